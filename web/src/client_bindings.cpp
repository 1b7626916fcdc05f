// Embind bindings of the browser client (ClientApp): what web/shell/app.js calls.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include "client_app.h"

using emscripten::val;
using prt::web::ClientApp;

namespace {

// new Module.ClientApp("#canvas"): the WebGL2 context on that canvas.
ClientApp* makeClientApp(const std::string& canvas) { return new ClientApp(prt::web::GlContextOptions{canvas, 0, 0}); }

// A Uint8Array over the reserved asset memory, for fetch() to stream into; null when the
// allocation failed (out of memory). Re-take it after any other call into the module:
// memory growth detaches old views.
val reserveAsset(ClientApp& app, double bytes) {
  if (!(bytes >= 0) || bytes > 2147483647.0) return val::null();
  std::uint8_t* p = app.reserveAsset(static_cast<std::size_t>(bytes));
  if (!p) return val::null();
  return val(emscripten::typed_memory_view(static_cast<std::size_t>(bytes), p));
}

// The progressive-loading buffer (zeroed, the catalogue's file size) as a Uint8Array, or
// null when it cannot be allocated; streamBuffer re-takes the view (memory growth detaches it).
val reserveStream(ClientApp& app, double bytes) {
  if (!(bytes >= 0) || bytes > 2147483647.0) return val::null();
  std::uint8_t* p = app.reserveStream(static_cast<std::size_t>(bytes));
  if (!p) return val::null();
  return val(emscripten::typed_memory_view(static_cast<std::size_t>(bytes), p));
}
val streamBuffer(ClientApp& app) {
  if (app.streamSize() == 0) return val::null();
  return val(emscripten::typed_memory_view(app.streamSize(), app.streamBuffer()));
}

std::string setEnvironment(ClientApp& app, const val& flat, int order) {
  return app.setEnvironment(emscripten::convertJSArrayToNumberVector<float>(flat), order);
}

val lightSH(ClientApp& app) { return val::array(app.lightSH()); }
val cubeSH(ClientApp& app) { return val::array(app.cubeSH()); }

// Float32Array or array of numbers.
std::string setLights(ClientApp& app, const val& flat) {
  return app.setLights(emscripten::convertJSArrayToNumberVector<float>(flat));
}

int addLightMesh(ClientApp& app, const val& positions, const val& indices) {
  if (positions.isNull() || positions.isUndefined() || indices.isNull() || indices.isUndefined()) return -1;
  // Doubles first: a negative, fractional or huge index must be rejected, not wrapped.
  const std::vector<double> raw = emscripten::convertJSArrayToNumberVector<double>(indices);
  std::vector<std::uint32_t> idx;
  idx.reserve(raw.size());
  for (double v : raw) {
    if (!(v >= 0.0) || v > 4294967295.0 || v != static_cast<double>(static_cast<std::uint32_t>(v))) return -1;
    idx.push_back(static_cast<std::uint32_t>(v));
  }
  return app.addLightMesh(emscripten::convertJSArrayToNumberVector<float>(positions), std::move(idx));
}

val lightCenter(const ClientApp& app) {
  const prt::Vec3 c = app.lightCenter();
  return val::array(std::vector<float>{c.x, c.y, c.z});
}

val rayFromScreen(const ClientApp& app, float x, float y) { return val::array(app.rayFromScreen(x, y)); }
double weightTableBytes(const ClientApp& app) { return static_cast<double>(app.weightTableBytes()); }

val cpcaShape(const ClientApp& app, prt::web::ShadingMode kind) { return val::array(app.cpcaShape(kind)); }
val vertexRadiance(const ClientApp& app) { return val::array(app.vertexRadiance()); }
val vertexGlossy(const ClientApp& app) { return val::array(app.vertexGlossy()); }
val glossyReference(ClientApp& app, prt::web::ShadingMode kind) { return val::array(app.glossyReference(kind)); }
// Float32Array copies: a scene's rotated transferred radiance is 3 x vertices x 28 floats.
val float32Array(const std::vector<float>& v) {
  val out = val::global("Float32Array").new_(v.size());
  out.call<void>("set", val(emscripten::typed_memory_view(v.size(), v.data())));
  return out;
}
val biScaleRotated(const ClientApp& app) { return float32Array(app.biScaleRotated()); }
val biScaleRotatedReference(ClientApp& app) { return float32Array(app.biScaleRotatedReference()); }
val glossyShape(const ClientApp& app, prt::web::ShadingMode kind) { return val::array(app.glossyShape(kind)); }

val atlasSizes(const ClientApp& app) { return val::array(app.atlasSizes()); }

// Atlas `atlas` of texel pass `kind` read back in UV space (ClientApp::texelAtlasRadiance): a
// Float32Array of width x height x 4 linear RGBA floats, or a string naming the error.
// With `positions` (tests) the fragments' world positions instead of radiance (alpha as before).
val texelAtlasRadiance(ClientApp& app, prt::web::ShadingMode kind, int atlas, bool positions) {
  std::vector<float> rgba;
  if (std::string e = app.texelAtlasRadiance(kind, atlas, &rgba, positions); !e.empty()) return val(e);
  return val(emscripten::typed_memory_view(rgba.size(), rgba.data())).call<val>("slice");  // a copy: rgba dies here
}

val project(const ClientApp& app, float x, float y, float z) { return val::array(app.project(x, y, z)); }
val viewProjection(const ClientApp& app) { return val::array(app.viewProjection()); }
val sceneCenter(const ClientApp& app) {
  const prt::Vec3 c = app.sceneCenter();
  return val::array(std::vector<float>{c.x, c.y, c.z});
}

// The image background's texels: a Uint32Array (or array) of width x height RGB9E5 values.
std::string setBackgroundImage(ClientApp& app, int width, int height, const val& texels) {
  if (texels.isNull() || texels.isUndefined()) return app.setBackgroundImage(0, 0, {});
  const std::vector<std::uint32_t> data = emscripten::convertJSArrayToNumberVector<std::uint32_t>(texels);
  return app.setBackgroundImage(width, height, data);
}

val cameraPose(const ClientApp& app) { return val::array(app.cameraPose()); }
bool setCameraPose(ClientApp& app, const val& pose) {
  if (!pose.isArray()) return false;
  return app.setCameraPose(emscripten::convertJSArrayToNumberVector<float>(pose));
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_client) {
  // Module.ShadingMode.interreflected etc.: what setMode / mode() take and give, and the pass
  // kinds (its first three values) of streamPass, loadedBands, passForm and cpcaShape.
  emscripten::enum_<prt::web::ShadingMode>("ShadingMode")
      .value("unshadowed", prt::web::ShadingMode::kUnshadowed)
      .value("shadowed", prt::web::ShadingMode::kShadowed)
      .value("interreflected", prt::web::ShadingMode::kInterreflected)
      .value("lambert", prt::web::ShadingMode::kLambert);
  // Module.PassForm.absent / expanded / cpca: what passForm gives.
  emscripten::enum_<prt::web::PassForm>("PassForm")
      .value("absent", prt::web::PassForm::kAbsent)
      .value("expanded", prt::web::PassForm::kExpanded)
      .value("cpca", prt::web::PassForm::kCpca);
  // Module.GlossyMix.diffuse / glossy / both: which terms a pass draws (setGlossyMix).
  emscripten::enum_<prt::web::GlossyMix>("GlossyMix")
      .value("diffuse", prt::web::GlossyMix::kDiffuse)
      .value("glossy", prt::web::GlossyMix::kGlossy)
      .value("both", prt::web::GlossyMix::kBoth);
  // Module.TransferDomain.vertex / texel: which passes are drawn (setSource, source, hasSource).
  emscripten::enum_<prt::web::BackgroundMode>("BackgroundMode")
      .value("none", prt::web::BackgroundMode::kNone)
      .value("colour", prt::web::BackgroundMode::kColour)
      .value("blurred", prt::web::BackgroundMode::kBlurred)
      .value("image", prt::web::BackgroundMode::kImage);

  emscripten::enum_<prt::TransferDomain>("TransferDomain")
      .value("vertex", prt::TransferDomain::kVertex)
      .value("texel", prt::TransferDomain::kTexel);
  emscripten::class_<ClientApp>("ClientApp")
      .constructor(&makeClientApp, emscripten::allow_raw_pointers())
      .function("error", &ClientApp::error)
      .function("reserveAsset", &reserveAsset)
      .function("loadAsset", &ClientApp::loadAsset)
      .function("reserveStream", &reserveStream)
      .function("streamBuffer", &streamBuffer)
      .function("streamGeometry", &ClientApp::streamGeometry)
      .function("streamPass", &ClientApp::streamPass)
      .function("endStream", &ClientApp::endStream)
      .function("loadedBands", &ClientApp::loadedBands)
      .function("setCpcaDirect", &ClientApp::setCpcaDirect)
      .function("cpcaDirect", &ClientApp::cpcaDirect)
      .function("passForm", &ClientApp::passForm)
      .function("cpcaShape", &cpcaShape)
      .function("vertexRadiance", &vertexRadiance)
      .function("setSource", &ClientApp::setSource)
      .function("source", &ClientApp::source)
      .function("hasSource", &ClientApp::hasSource)
      .function("streamTexelPass", &ClientApp::streamTexelPass)
      .function("texelBands", &ClientApp::texelBands)
      .function("streamVisibilityPass", &ClientApp::streamVisibilityPass)
      .function("hasTexelGlossy", &ClientApp::hasTexelGlossy)
      .function("texelGlossyBands", &ClientApp::texelGlossyBands)
      .function("texelGlossyError", &ClientApp::texelGlossyError)
      .function("atlasSizes", &atlasSizes)
      .function("texelAtlasRadiance", &texelAtlasRadiance)
      .function("setGlossyMix", &ClientApp::setGlossyMix)
      .function("glossyMix", &ClientApp::glossyMix)
      .function("hasGlossy", &ClientApp::hasGlossy)
      .function("hasAnyPass", &ClientApp::hasAnyPass)
      .function("glossyBands", &ClientApp::glossyBands)
      .function("glossyShape", &glossyShape)
      .function("streamGlossyPass", &ClientApp::streamGlossyPass)
      .function("setFresnel", &ClientApp::setFresnel)
      .function("vertexGlossy", &vertexGlossy)
      .function("lastGlossyStep", &ClientApp::lastGlossyStep)
      .function("glossyReference", &glossyReference)
      .function("useSyntheticGlossy", &ClientApp::useSyntheticGlossy)
      .function("setBiScale", &ClientApp::setBiScale)
      .function("biScale", &ClientApp::biScale)
      .function("biScaleOrder", &ClientApp::biScaleOrder)
      .function("setViewDependence", &ClientApp::setViewDependence)
      .function("viewDependence", &ClientApp::viewDependence)
      .function("drewBiScale", &ClientApp::drewBiScale)
      .function("biScaleRotated", &biScaleRotated)
      .function("biScaleRotatedReference", &biScaleRotatedReference)
      .function("shadeGlossyVertices", &ClientApp::shadeGlossyVertices)
      .function("finishGlossy", &ClientApp::finishGlossy)
      .function("touchLighting", &ClientApp::touchLighting)
      .function("setEnvironment", &setEnvironment)
      .function("setWhiteFurnace", &ClientApp::setWhiteFurnace)
      .function("setEnvRotation", &ClientApp::setEnvRotation)
      .function("setLightColor", &ClientApp::setLightColor)
      .function("setMode", &ClientApp::setMode)
      .function("setDisplayOrder", &ClientApp::setDisplayOrder)
      .function("setExposure", &ClientApp::setExposure)
      .function("setBackgroundMode", &ClientApp::setBackgroundMode)
      .function("setBackgroundColour", &ClientApp::setBackgroundColour)
      .function("setBackgroundImage", &setBackgroundImage)
      .function("hasBackgroundImage", &ClientApp::hasBackgroundImage)
      .function("orbit", &ClientApp::orbit)
      .function("pan", &ClientApp::pan)
      .function("zoom", &ClientApp::zoom)
      .function("frameScene", &ClientApp::frameScene)
      .function("cameraPose", &cameraPose)
      .function("setCameraPose", &setCameraPose)
      .function("sceneRadius", &ClientApp::sceneRadius)
      .function("sceneCenter", &sceneCenter)
      .function("viewProjection", &viewProjection)
      .function("render", &ClientApp::render)
      .function("lightSH", &lightSH)
      .function("project", &project)
      .function("vertexCount", &ClientApp::vertexCount)
      .function("triangleCount", &ClientApp::triangleCount)
      .function("bakedOrder", &ClientApp::bakedOrder)
      .function("displayOrder", &ClientApp::displayOrder)
      .function("mode", &ClientApp::mode)
      .function("hasPass", &ClientApp::hasPass)
      .function("setLights", &setLights)
      .function("addLightMesh", &addLightMesh)
      .function("setEnvironmentEnabled", &ClientApp::setEnvironmentEnabled)
      .function("setProjection", &ClientApp::setProjection)
      .function("projectionMode", &ClientApp::projectionMode)
      .function("gpuProjectionSupported", &ClientApp::gpuProjectionSupported)
      .function("setCubeSize", &ClientApp::setCubeSize)
      .function("cubeSize", &ClientApp::cubeSize)
      .function("simulateNoFloatTargets", &ClientApp::simulateNoFloatTargets)
      .function("lightCenter", &lightCenter)
      .function("lightingModel", &ClientApp::lightingModel)
      .function("lightingRadius", &ClientApp::lightingRadius)
      .function("cubeSH", &cubeSH)
      .function("projectLightsNow", &ClientApp::projectLightsNow)
      .function("finishGpu", &ClientApp::finishGpu)
      .function("shadeVertices", &ClientApp::shadeVertices)
      .function("finishShading", &ClientApp::finishShading)
      .function("weightTableBytes", &weightTableBytes)
      .function("projectionError", &ClientApp::projectionError)
      .function("rayFromScreen", &rayFromScreen);
}
