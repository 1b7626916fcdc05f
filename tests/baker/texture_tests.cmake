# Tests of prt_texture (native only): texel rasterisation against a clipping reference and
# gutter dilation. include()d from tests/CMakeLists.txt; paths are relative to this file.
add_executable(prt_texture_tests
  ${CMAKE_CURRENT_LIST_DIR}/texel_raster_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/texel_dilate_test.cpp
)
target_link_libraries(prt_texture_tests PRIVATE prt_texture GTest::gtest_main)
target_compile_options(prt_texture_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME texture_tests COMMAND prt_texture_tests)
