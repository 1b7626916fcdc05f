# Sharded bakes (docs/scale-out.md): plan, bake-shard and merge through the real prt-bake
# (shard_cli_test.sh, one ctest test per case), and the same on a real single-node Slurm
# cluster (slurm_bake_test.sh, which starts and stops its own through scripts/slurm-local.sh).
# include()d from tests/CMakeLists.txt for native builds.

# The plan, shard and merged-pass files on damaged and hostile bytes.
add_executable(prt_shard_format_tests ${CMAKE_CURRENT_LIST_DIR}/shard_format_test.cpp)
target_link_libraries(prt_shard_format_tests PRIVATE prt_shard GTest::gtest_main)
target_compile_options(prt_shard_format_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_test(NAME shard_format_tests COMMAND prt_shard_format_tests)
set(PRT_SHARD_CASES identical glossy texels texels_damaged missing corrupt mismatched changed_scene prepared_scene usage)
foreach(case IN LISTS PRT_SHARD_CASES)
  add_test(NAME shard_cli_${case}
           COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/shard_cli_test.sh ${case} $<TARGET_FILE:prt-bake>
                   ${CMAKE_CURRENT_BINARY_DIR}/shard_work/${case})
  set_tests_properties(shard_cli_${case} PROPERTIES TIMEOUT 900)
endforeach()

# Real Slurm (Debian's slurm-wlm and munge, from scripts/install-deps.sh; without them the
# tests fail, naming what is missing). Each case starts its own single-node cluster, so they
# take turns (one set of ports), and each has a time limit so a stuck job fails the test.
# Not under the sanitizers: the time goes to Slurm's scheduling, and the code the jobs run is
# the shard_cli cases' (which the sanitizer build runs).
set(PRT_SLURM_CASES identical texels requeue failure)
if(PRT_SANITIZE)
  set(PRT_SLURM_CASES)
endif()
foreach(case IN LISTS PRT_SLURM_CASES)
  add_test(NAME slurm_bake_${case}
           COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/slurm_bake_test.sh ${case} $<TARGET_FILE:prt-bake>
                   ${CMAKE_CURRENT_BINARY_DIR}/slurm_work/${case})
  set_tests_properties(slurm_bake_${case} PROPERTIES TIMEOUT 900 RESOURCE_LOCK prt_slurm_local)
endforeach()
