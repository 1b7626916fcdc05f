# Tests of prt_unwrap (native only): the lightmap-atlas generator with the real Blender
# (Debian's blender package, installed by scripts/install-deps.sh: the test fails, rather than
# skips, without it) and seam splitting. include()d from tests/CMakeLists.txt.
add_executable(prt_unwrap_tests ${CMAKE_CURRENT_LIST_DIR}/uv_unwrap_test.cpp)
target_link_libraries(prt_unwrap_tests PRIVATE prt_unwrap GTest::gtest_main)
target_compile_options(prt_unwrap_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME unwrap_tests COMMAND prt_unwrap_tests)
set_tests_properties(unwrap_tests PROPERTIES TIMEOUT 300)
