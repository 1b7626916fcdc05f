# Unit tests of native/ (native only): the image loaders on files written at test time
# with OpenEXR, stb_image_write and hand-built bytes (valid and malformed), JSON text
# against nlohmann_json's parser, the strict flag parser, the exit-status table and the
# file reader's refusals.
# include()d from tests/CMakeLists.txt; paths are relative to this file.

if(NOT TARGET OpenEXR::OpenEXR)  # native/ finds it GLOBAL
  find_package(OpenEXR CONFIG REQUIRED)
endif()
# Debian's nlohmann-json3-dev: an independent JSON parser to check json_text's output with.
find_package(nlohmann_json CONFIG REQUIRED)

add_executable(prt_native_tests
  ${CMAKE_CURRENT_LIST_DIR}/image_io_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/radiance_hdr_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/json_text_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_args_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exit_status_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/file_io_test.cpp
)
# OpenEXR and prt_stb (stb_image_write, and stb_image as a second HDR decoder) write and
# cross-check the test images.
target_link_libraries(prt_native_tests PRIVATE
  prt_image_io prt_json_text prt_cli_args prt_exit_status prt_file_io
  OpenEXR::OpenEXR prt_stb nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_options(prt_native_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME native_tests COMMAND prt_native_tests)
# A loader that spins on a malformed file must fail the test, not stall the run.
set_tests_properties(native_tests PROPERTIES TIMEOUT 300)
