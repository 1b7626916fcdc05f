# Tests of prt_scene (native only): the glTF loader on files written at test time (valid
# ones and a malformed corpus, gltf_test_files.h), its geometry and texture helpers, and the
# built-in default scene. include()d from tests/CMakeLists.txt; paths are relative to this
# file. prt_stb provides stb_image_write, used to make PNG textures for the tests.
add_executable(prt_scene_tests
  ${CMAKE_CURRENT_LIST_DIR}/scene_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_malformed_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_corpus_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_geometry_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/default_scene_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/glossy_materials_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/uv_atlas_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/uv_texcoord_load_test.cpp
)
target_link_libraries(prt_scene_tests PRIVATE prt_scene prt_stb GTest::gtest_main)
target_compile_options(prt_scene_tests PRIVATE ${PRT_STRICT_WARNINGS})
# Debian's assimp-testmodels: real glTF 1.0/2.0 files, valid and malformed (gltf_corpus_test.cpp).
set(PRT_ASSIMP_MODELS_DIR /usr/share/assimp/models CACHE PATH "assimp-testmodels' model directory (tests/baker)")
target_compile_definitions(prt_scene_tests PRIVATE PRT_ASSIMP_MODELS_DIR="${PRT_ASSIMP_MODELS_DIR}")
add_test(NAME scene_tests COMMAND prt_scene_tests)
