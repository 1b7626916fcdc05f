# End-to-end tests of the prt-bake command line: they run the real binary on images written
# at test time (make_fixtures.cpp) and on blender-data's EXRs, and check exit statuses,
# error messages and JSON output (cli_test.mjs, one ctest test per case).
# include()d from tests/CMakeLists.txt for native builds; paths are relative to this file.

if(NOT TARGET OpenEXR::OpenEXR)  # baker/ finds it GLOBAL
  find_package(OpenEXR CONFIG REQUIRED)
endif()

add_executable(prt_cli_make_fixtures ${CMAKE_CURRENT_LIST_DIR}/make_fixtures.cpp)
target_link_libraries(prt_cli_make_fixtures PRIVATE OpenEXR::OpenEXR prt_stb)
target_compile_options(prt_cli_make_fixtures PRIVATE ${PRT_STRICT_WARNINGS})

set(PRT_CLI_FIXTURES_DIR ${CMAKE_CURRENT_BINARY_DIR}/cli_fixtures)
set(PRT_CLI_WORK_DIR ${CMAKE_CURRENT_BINARY_DIR}/cli_work)
# blender-data's CC0 studio-light EXRs (DWAB-compressed equirect maps). The project's
# install script installs the package; the test fails, rather than skips, without it.
set(PRT_BLENDER_WORLD_DIR /usr/share/blender/datafiles/studiolights/world
    CACHE PATH "Directory of blender-data's studio-light world EXRs (tests/cli)")

add_test(NAME cli_make_fixtures COMMAND prt_cli_make_fixtures ${PRT_CLI_FIXTURES_DIR})
set_tests_properties(cli_make_fixtures PROPERTIES FIXTURES_SETUP prt_cli_fixtures)

set(PRT_CLI_CASES
  help
  usage_errors
  builtin_sky
  table_output
  missing_file
  unknown_format
  truncated_png
  truncated_exr
  truncated_hdr_jpeg
  constant_radiance
  layouts
  orientation
  bad_content
  blender_exr
  fuzz
)

find_program(PRT_NODE NAMES node nodejs)
foreach(case IN LISTS PRT_CLI_CASES)
  if(PRT_NODE)
    add_test(NAME cli_${case}
             COMMAND ${PRT_NODE} ${CMAKE_CURRENT_LIST_DIR}/cli_test.mjs ${case} $<TARGET_FILE:prt-bake>
                     ${PRT_CLI_FIXTURES_DIR} ${PRT_CLI_WORK_DIR}/${case} ${PRT_BLENDER_WORLD_DIR})
  else()
    # A missing driver must show up as failing tests, not as fewer tests.
    add_test(NAME cli_${case}
             COMMAND ${CMAKE_COMMAND} -E echo "cli_${case}: node (Node.js >= 18) not found; it runs tests/cli/cli_test.mjs")
    set_tests_properties(cli_${case} PROPERTIES FAIL_REGULAR_EXPRESSION "not found")
  endif()
  set_tests_properties(cli_${case} PROPERTIES FIXTURES_REQUIRED prt_cli_fixtures TIMEOUT 300)
endforeach()

# Baking, `info` and `shade` end to end (bake_cli_test.mjs, one ctest test per case).
foreach(case IN ITEMS default_scene determinism bad_assets bad_scenes usage_errors interrupted local_lighting
                     lighting_usage_errors white_furnace output_safety durable_write signal_window glossy
                     glossy_usage_errors texels texel_usage_errors texel_unwrap texel_unwrap_errors texel_glossy
                     texel_normal_glossy
                     texture_sets texture_sets_density texture_sets_default texture_sets_limit compress_svg rtt rtt_usage_errors)
  add_test(NAME bake_cli_${case}
           COMMAND ${PRT_NODE} ${CMAKE_CURRENT_LIST_DIR}/bake_cli_test.mjs ${case} $<TARGET_FILE:prt-bake>
                   ${CMAKE_CURRENT_BINARY_DIR}/bake_cli_work/${case})
  set_tests_properties(bake_cli_${case} PROPERTIES TIMEOUT 600)
endforeach()

# `info` on an asset with transfer textures, written by a generator (no bake writes them yet).
add_executable(prt_cli_make_texel_asset ${CMAKE_CURRENT_LIST_DIR}/make_texel_asset.cpp)
target_link_libraries(prt_cli_make_texel_asset PRIVATE prt_shared)
target_compile_options(prt_cli_make_texel_asset PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME bake_cli_texel_info
         COMMAND ${PRT_NODE} ${CMAKE_CURRENT_LIST_DIR}/bake_cli_test.mjs texel_info $<TARGET_FILE:prt-bake>
                 ${CMAKE_CURRENT_BINARY_DIR}/bake_cli_work/texel_info $<TARGET_FILE:prt_cli_make_texel_asset>)
set_tests_properties(bake_cli_texel_info PROPERTIES TIMEOUT 120)

# The demo's bake (scripts/demo_bake_settings.sh) against an 8192-sample bake of the room: RMS
# and patch error bounds (demo_quality_test.mjs). Not under the sanitizers: it measures the
# bake's output, and the bakes it runs are the bake tests' code paths (about 20x slower there).
if(NOT PRT_SANITIZE)
  add_test(NAME demo_bake_quality
           COMMAND ${PRT_NODE} ${CMAKE_CURRENT_LIST_DIR}/demo_quality_test.mjs $<TARGET_FILE:prt-bake>
                   ${PROJECT_SOURCE_DIR}/scripts/demo_bake_settings.sh ${PRT_BLENDER_WORLD_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/demo_quality_work)
  set_tests_properties(demo_bake_quality PROPERTIES TIMEOUT 900)
endif()
