# The client's sources, shared by the Emscripten build (web/CMakeLists.txt) and the native
# OpenGL ES build of the same renderer for GPU benchmarks (web/native/CMakeLists.txt).
set(PRT_WEB_DIR ${CMAKE_CURRENT_LIST_DIR})

# GL-free: decoding, packing, emitters (also the Node test module's).
set(PRT_WEB_CORE_SOURCES
  ${PRT_WEB_DIR}/src/transfer_texture.cpp ${PRT_WEB_DIR}/src/texel_texture.cpp ${PRT_WEB_DIR}/src/texel_glossy.cpp
  ${PRT_WEB_DIR}/src/cpca_texture.cpp ${PRT_WEB_DIR}/src/glossy_texture.cpp ${PRT_WEB_DIR}/src/glossy_fused.cpp ${PRT_WEB_DIR}/src/rtt_texture.cpp ${PRT_WEB_DIR}/src/bi_scale_texture.cpp ${PRT_WEB_DIR}/src/glossy_synthetic.cpp
  ${PRT_WEB_DIR}/src/asset_stream.cpp ${PRT_WEB_DIR}/src/emitters.cpp ${PRT_WEB_DIR}/src/analytic_lights.cpp
  ${PRT_WEB_DIR}/src/cube_faces.cpp)

# The renderer and the client's state: OpenGL ES 3 / WebGL2 calls, no bindings and no context
# creation (gl_context.h has one implementation per platform).
set(PRT_WEB_GL_SOURCES
  ${PRT_WEB_DIR}/src/client_app.cpp ${PRT_WEB_DIR}/src/orbit_camera.cpp ${PRT_WEB_DIR}/src/gl_renderer.cpp ${PRT_WEB_DIR}/src/gl_renderer_bi_scale.cpp
  ${PRT_WEB_DIR}/src/texel_renderer.cpp ${PRT_WEB_DIR}/src/gl_program.cpp ${PRT_WEB_DIR}/src/emitter_renderer.cpp
  ${PRT_WEB_DIR}/src/light_cube.cpp ${PRT_WEB_DIR}/src/cube_sh_reduction.cpp ${PRT_WEB_DIR}/src/lighting_block.cpp
  ${PRT_WEB_DIR}/src/dynamic_lighting.cpp)

set(PRT_SHADERS
  ${PRT_WEB_DIR}/shaders/prt.vert
  ${PRT_WEB_DIR}/shaders/cpca.vert
  ${PRT_WEB_DIR}/shaders/texel_prt.vert
  ${PRT_WEB_DIR}/shaders/texel_prt.frag
  ${PRT_WEB_DIR}/shaders/depth_only.frag
  ${PRT_WEB_DIR}/shaders/glossy_table.vert
  ${PRT_WEB_DIR}/shaders/glossy_transfer.vert
  ${PRT_WEB_DIR}/shaders/glossy.vert
  ${PRT_WEB_DIR}/shaders/glossy_gather.vert
  ${PRT_WEB_DIR}/shaders/biscale_rotate.vert
  ${PRT_WEB_DIR}/shaders/biscale.vert
  ${PRT_WEB_DIR}/shaders/biscale.frag
  ${PRT_WEB_DIR}/shaders/lambert.vert
  ${PRT_WEB_DIR}/shaders/shade.frag
  ${PRT_WEB_DIR}/shaders/background.vert
  ${PRT_WEB_DIR}/shaders/background.frag
  ${PRT_WEB_DIR}/shaders/radiance.vert
  ${PRT_WEB_DIR}/shaders/discard.frag
  ${PRT_WEB_DIR}/shaders/emitter.vert
  ${PRT_WEB_DIR}/shaders/emitter.frag
  ${PRT_WEB_DIR}/shaders/fullscreen.vert
  ${PRT_WEB_DIR}/shaders/cube_project.frag
  ${PRT_WEB_DIR}/shaders/cube_sum.frag
  ${PRT_WEB_DIR}/shaders/lighting_combine.vert)

# Adds the command that embeds the shaders as string constants in <build dir>/generated/
# web_shaders.h and sets `out_var` to that header's path.
function(prt_embed_shaders out_var)
  set(header ${CMAKE_CURRENT_BINARY_DIR}/generated/web_shaders.h)
  add_custom_command(OUTPUT ${header}
    COMMAND ${CMAKE_COMMAND} -DOUT=${header} "-DFILES=${PRT_SHADERS}" -P ${PRT_WEB_DIR}/embed_shaders.cmake
    DEPENDS ${PRT_SHADERS} ${PRT_WEB_DIR}/embed_shaders.cmake
    COMMENT "Embedding GLSL shaders"
    VERBATIM)
  set(${out_var} ${header} PARENT_SCOPE)
endfunction()
