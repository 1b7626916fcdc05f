# Baker tests (native only): real Embree on scenes built in code.
add_executable(prt_bake_tests ${CMAKE_CURRENT_LIST_DIR}/transfer_test.cpp ${CMAKE_CURRENT_LIST_DIR}/bake_asset_test.cpp ${CMAKE_CURRENT_LIST_DIR}/sh_accumulate_test.cpp ${CMAKE_CURRENT_LIST_DIR}/bounce_gather_test.cpp)
target_include_directories(prt_bake_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_bake_tests PRIVATE prt_transfer GTest::gtest_main)
add_test(NAME bake_tests COMMAND prt_bake_tests)

# Spatially-varying lighting (docs/spatially-varying.md): against limits and a brute-force
# area integral over an emitter on the lighting sphere.
add_executable(prt_local_lighting_tests ${CMAKE_CURRENT_LIST_DIR}/local_lighting_test.cpp)
target_include_directories(prt_local_lighting_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_local_lighting_tests PRIVATE prt_transfer GTest::gtest_main)
add_test(NAME local_lighting_tests COMMAND prt_local_lighting_tests)

# Glossy transfer matrices (docs/glossy.md): closed forms, exact quadratures and the
# brute-force glossy reference.
add_executable(prt_glossy_bake_tests ${CMAKE_CURRENT_LIST_DIR}/glossy_test.cpp)
target_include_directories(prt_glossy_bake_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_glossy_bake_tests PRIVATE prt_transfer prt_test_support GTest::gtest_main)
add_test(NAME glossy_bake_tests COMMAND prt_glossy_bake_tests)

# Transfer textures (docs/transfer-textures.md): closed forms, the vertex bake, light leaks
# under touching geometry, and seams under bilinear filtering.
add_executable(prt_texel_bake_tests ${CMAKE_CURRENT_LIST_DIR}/texel_bake_test.cpp)
target_include_directories(prt_texel_bake_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_texel_bake_tests PRIVATE prt_transfer GTest::gtest_main)
target_compile_options(prt_texel_bake_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME texel_bake_tests COMMAND prt_texel_bake_tests)

# Normal maps (docs/transfer-textures.md, "Normal maps"): the loader's normalTexture and
# TANGENT, computed tangents, and a normal-mapped flat quad against the tessellated bumps.
add_executable(prt_normal_map_tests ${CMAKE_CURRENT_LIST_DIR}/normal_map_test.cpp)
target_include_directories(prt_normal_map_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_normal_map_tests PRIVATE prt_transfer prt_stb GTest::gtest_main)
target_compile_options(prt_normal_map_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME normal_map_tests COMMAND prt_normal_map_tests)

# prt-bake's progress bar (elapsed time, the remaining-time estimate) and the
# rate-distortion plot's axes (compress-report --svg): formatting and arithmetic.
add_executable(prt_bake_cli_output_tests ${CMAKE_CURRENT_LIST_DIR}/cli_output_test.cpp)
target_link_libraries(prt_bake_cli_output_tests PRIVATE prt_bake_cli GTest::gtest_main)
target_compile_options(prt_bake_cli_output_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME bake_cli_output_tests COMMAND prt_bake_cli_output_tests)

# Radiance transfer textures (docs/bi-scale.md): a flat patch's closed form, the white
# furnace, a brute-force integral over a patch with pits.
add_executable(prt_rtt_bake_tests ${CMAKE_CURRENT_LIST_DIR}/rtt_bake_test.cpp)
target_include_directories(prt_rtt_bake_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_rtt_bake_tests PRIVATE prt_rtt GTest::gtest_main)
target_compile_options(prt_rtt_bake_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME rtt_bake_tests COMMAND prt_rtt_bake_tests)

# Bi-scale in the baker: the parametric id map, the asset's bi-scale sections, the reduction
# through the stored frames (docs/bi-scale.md).
add_executable(prt_bi_scale_bake_tests ${CMAKE_CURRENT_LIST_DIR}/bi_scale_bake_test.cpp)
target_include_directories(prt_bi_scale_bake_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_bi_scale_bake_tests PRIVATE prt_rtt GTest::gtest_main)
target_compile_options(prt_bi_scale_bake_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME bi_scale_bake_tests COMMAND prt_bi_scale_bake_tests)

# The synthesised id map of bi-scale transfer (baker/biscale/, docs/bi-scale.md): coverage,
# gutters, q inside a cell, frames, cell size, phases, determinism, refusals; time printed.
add_executable(prt_id_map_synthesis_tests ${CMAKE_CURRENT_LIST_DIR}/id_map_synthesis_test.cpp)
target_include_directories(prt_id_map_synthesis_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_id_map_synthesis_tests PRIVATE prt_biscale prt_scene GTest::gtest_main)
target_compile_options(prt_id_map_synthesis_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME id_map_synthesis_tests COMMAND prt_id_map_synthesis_tests)
