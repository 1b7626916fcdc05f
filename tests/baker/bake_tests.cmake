# Baker tests (native only): real Embree on scenes built in code.
add_executable(prt_bake_tests ${CMAKE_CURRENT_LIST_DIR}/transfer_test.cpp ${CMAKE_CURRENT_LIST_DIR}/bake_asset_test.cpp)
target_include_directories(prt_bake_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_bake_tests PRIVATE prt_transfer GTest::gtest_main)
add_test(NAME bake_tests COMMAND prt_bake_tests)

# Spatially-varying lighting (docs/spatially-varying.md): against limits and a brute-force
# area integral over an emitter on the lighting sphere.
add_executable(prt_local_lighting_tests ${CMAKE_CURRENT_LIST_DIR}/local_lighting_test.cpp)
target_include_directories(prt_local_lighting_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/..)
target_link_libraries(prt_local_lighting_tests PRIVATE prt_transfer GTest::gtest_main)
add_test(NAME local_lighting_tests COMMAND prt_local_lighting_tests)
