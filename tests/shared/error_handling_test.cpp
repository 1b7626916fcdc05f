// Every entry point of the shared SH library rejects bad input with a named error instead
// of reading or writing out of bounds (run under ASan/UBSan by the sanitizer preset).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "prt/cubemap.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "prt/sh_rotation.h"
#include "prt/sh_window.h"
#include "prt/sh_zonal.h"
#include "prt/status.h"

namespace prt {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

void expectError(const Status& s, StatusCode code, const char* fragment) {
  EXPECT_FALSE(s.isOk());
  EXPECT_EQ(s.code(), code) << s.toString();
  EXPECT_NE(s.message().find(fragment), std::string::npos) << "message '" << s.message() << "' lacks '" << fragment << "'";
}

TEST(Errors, BasisRejectsBadOrderDirectionAndBuffer) {
  std::vector<float> out(400);
  expectError(evalShBasis(0, {0, 0, 1}, out), StatusCode::kInvalidArgument, "order 0");
  expectError(evalShBasis(kMaxShOrder + 1, {0, 0, 1}, out), StatusCode::kInvalidArgument, "outside");
  expectError(evalShBasis(-3, {0, 0, 1}, out), StatusCode::kInvalidArgument, "-3");
  expectError(evalShBasis(3, {kNan, 0, 1}, out), StatusCode::kNotFinite, "direction");
  expectError(evalShBasis(3, {kInf, 0, 1}, out), StatusCode::kNotFinite, "direction");
  expectError(evalShBasis(3, {0, 0, 0}, out), StatusCode::kInvalidArgument, "zero length");
  expectError(evalShBasis(3, {0, 0, 1}, std::span<float>(out.data(), 8)), StatusCode::kSizeMismatch, "needs 9");
  EXPECT_TRUE(evalShBasis(3, {0, 0, 1}, std::span<float>(out.data(), 9)).isOk());
  // Denormal-length directions still normalise.
  EXPECT_TRUE(evalShBasis(3, {1e-30f, 0, 0}, out).isOk());
}

TEST(Errors, BatchRejectsMismatchedArraysAndNonUnitDirections) {
  std::vector<float> x = {1, 0}, y = {0, 1}, z = {0, 0}, out(18);
  EXPECT_TRUE(evalShBasisBatch(3, x, y, z, out).isOk());
  expectError(evalShBasisBatch(3, x, y, std::span<const float>(z.data(), 1), out), StatusCode::kSizeMismatch, "differ");
  expectError(evalShBasisBatch(3, x, y, z, std::span<float>(out.data(), 17)), StatusCode::kSizeMismatch, "18 needed");
  x[1] = 2;
  expectError(evalShBasisBatch(3, x, y, z, out), StatusCode::kInvalidArgument, "direction 1");
  x[1] = kNan;
  expectError(evalShBasisBatch(3, x, y, z, out), StatusCode::kNotFinite, "direction 1");
  expectError(evalShBasisBatch(13 + kMaxShOrder, x, y, z, out), StatusCode::kInvalidArgument, "order");
  // Zero directions is fine and writes nothing.
  EXPECT_TRUE(evalShBasisBatch(3, {}, {}, {}, {}).isOk());
}

TEST(Errors, ZonalFunctionsCheckRangesAndSizes) {
  std::vector<float> z(4), full(16);
  expectError(zonalClampedCosine(5, z), StatusCode::kSizeMismatch, "5 needed");
  expectError(zonalCircularLight(4, 0.0f, 1.0f, z), StatusCode::kInvalidArgument, "radius");
  expectError(zonalCircularLight(4, 4.0f, 1.0f, z), StatusCode::kInvalidArgument, "radius");
  expectError(zonalCircularLight(4, kNan, 1.0f, z), StatusCode::kInvalidArgument, "radius");
  expectError(zonalCircularLight(4, 0.5f, kInf, z), StatusCode::kNotFinite, "radiance");
  ASSERT_TRUE(zonalClampedCosine(4, z).isOk());
  expectError(placeZonal(4, z, {0, 0, 0}, full), StatusCode::kInvalidArgument, "zero length");
  expectError(placeZonal(4, z, {0, 0, 1}, std::span<float>(full.data(), 15)), StatusCode::kSizeMismatch, "16 needed");
  expectError(placeZonal(5, z, {0, 0, 1}, full), StatusCode::kSizeMismatch, "zonal");
  expectError(convolveZonal(4, z, std::span<float>(full.data(), 3)), StatusCode::kSizeMismatch, "coefficients");
}

TEST(Errors, RotationRejectsNonRotations) {
  ShRotation rot;
  Mat3 scale;
  scale.m[0][0] = 2.0f;
  expectError(ShRotation::make(3, scale, &rot), StatusCode::kInvalidArgument, "not a rotation");
  Mat3 mirror;
  mirror.m[2][2] = -1.0f;
  expectError(ShRotation::make(3, mirror, &rot), StatusCode::kInvalidArgument, "det");
  Mat3 nan;
  nan.m[1][1] = kNan;
  expectError(ShRotation::make(3, nan, &rot), StatusCode::kNotFinite, "not finite");
  expectError(ShRotation::make(0, Mat3{}, &rot), StatusCode::kInvalidArgument, "order");
  std::vector<float> in(9), out(9);
  expectError(rot.apply(in, out), StatusCode::kInvalidArgument, "not built");
  ASSERT_TRUE(ShRotation::make(3, Mat3{}, &rot).isOk());
  expectError(rot.apply(std::span<const float>(in.data(), 8), out), StatusCode::kSizeMismatch, "9");
}

TEST(Errors, ImagesAreValidatedBeforeUse) {
  std::vector<Rgb> c;
  RgbImage empty;
  expectError(projectEquirect(3, empty, &c), StatusCode::kInvalidArgument, "0x0");
  RgbImage shortData;
  shortData.width = 4;
  shortData.height = 2;
  shortData.rgb.resize(23);
  expectError(projectEquirect(3, shortData, &c), StatusCode::kSizeMismatch, "24 expected");
  RgbImage nanImage = shortData;
  nanImage.rgb.assign(24, 1.0f);
  nanImage.rgb[13] = kNan;
  expectError(projectEquirect(3, nanImage, &c), StatusCode::kNotFinite, "pixel (0, 1)");
  RgbImage huge;
  huge.width = kMaxImageSide + 1;
  huge.height = 1;
  expectError(projectEquirect(3, huge, &c), StatusCode::kInvalidArgument, "each side");
  expectError(projectAngularMap(3, nanImage, &c), StatusCode::kNotFinite, "angular");
  nanImage.rgb[13] = 0.0f;
  expectError(projectAngularMap(3, nanImage, &c), StatusCode::kInvalidArgument, "square");
  expectError(projectEquirect(99, nanImage, &c), StatusCode::kInvalidArgument, "order 99");
}

TEST(Errors, CubeMapsAndCrossesAreValidated) {
  std::vector<Rgb> c;
  CubeMap cube;
  expectError(projectCubeMap(3, cube, &c), StatusCode::kInvalidArgument, "face size 0");
  cube.size = 2;
  for (auto& f : cube.faces) f.assign(12, 0.5f);
  cube.faces[3].resize(11);
  expectError(projectCubeMap(3, cube, &c), StatusCode::kSizeMismatch, "face 3");
  cube.faces[3].assign(12, kInf);
  expectError(projectCubeMap(3, cube, &c), StatusCode::kNotFinite, "face 3");
  RgbImage notCross;
  notCross.width = 5;
  notCross.height = 3;
  notCross.rgb.assign(45, 0.0f);
  CubeMap out;
  expectError(cubeMapFromCross(notCross, &out), StatusCode::kInvalidArgument, "4:3");
}

TEST(Errors, ProjectSamplesChecksSizes) {
  DirectionSet s;
  ASSERT_TRUE(hammersleySphere(16, &s).isOk());
  std::vector<Rgb> values(15), c;
  expectError(projectSamples(3, s, values, &c), StatusCode::kSizeMismatch, "16 directions");
  values.resize(16);
  s.x[4] = 3.0f;
  expectError(projectSamples(3, s, values, &c), StatusCode::kInvalidArgument, "direction 4");
  expectError(hammersleySphere(0, &s), StatusCode::kInvalidArgument, "count 0");
  expectError(stratifiedSphere(0, 1, &s), StatusCode::kInvalidArgument, "side 0");
}

TEST(Errors, WindowChecks) {
  std::vector<Rgb> coeffs(8);
  expectError(applyShWindow(ShWindow::kHanning, 3, 0.0f, coeffs), StatusCode::kSizeMismatch, "order*order");
  std::vector<float> w(3);
  expectError(shWindowWeights(ShWindow::kLanczos, 3, kNan, w), StatusCode::kNotFinite, "width");
  expectError(shWindowWeights(ShWindow::kLanczos, 4, 0.0f, w), StatusCode::kSizeMismatch, "4 values");
}


int g_evaluations = 0;
Status countedStatus(StatusCode code) {
  ++g_evaluations;
  return code == StatusCode::kOk ? Status::ok() : Status::error(code, "from countedStatus");
}
Status twoSteps(StatusCode first, StatusCode second, bool* reachedEnd) {
  PRT_RETURN_IF_ERROR(countedStatus(first));
  PRT_RETURN_IF_ERROR(countedStatus(second));
  *reachedEnd = true;
  return Status::ok();
}

TEST(ErrorHandling, ReturnIfErrorStopsAtTheFirstFailureAndEvaluatesOnce) {
  bool reachedEnd = false;
  g_evaluations = 0;
  Status s = twoSteps(StatusCode::kNotFound, StatusCode::kInternal, &reachedEnd);
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_EQ(s.message(), "from countedStatus");
  EXPECT_EQ(g_evaluations, 1);
  EXPECT_FALSE(reachedEnd);

  g_evaluations = 0;
  s = twoSteps(StatusCode::kOk, StatusCode::kOk, &reachedEnd);
  EXPECT_TRUE(s.isOk());
  EXPECT_EQ(g_evaluations, 2);
  EXPECT_TRUE(reachedEnd);
}

TEST(ErrorHandling, EveryCodeHasItsOwnName) {
  std::set<std::string> names;
  for (int c = 0; c <= static_cast<int>(StatusCode::kInternal); ++c) {
    std::string name = statusCodeName(static_cast<StatusCode>(c));
    EXPECT_NE(name, "unknown") << c;
    EXPECT_TRUE(names.insert(name).second) << "repeated name " << name;
  }
}

}  // namespace
}  // namespace prt
