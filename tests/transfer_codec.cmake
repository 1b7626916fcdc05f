# The transfer codec's tests (shared/prt/transfer_codec.h): gtest in both toolchains, and
# a libFuzzer target for the decoder when the compiler is Clang and PRT_FUZZ is on.
# include()d from tests/CMakeLists.txt; paths are relative to this file.

add_executable(prt_transfer_codec_tests ${CMAKE_CURRENT_LIST_DIR}/shared/transfer_codec_test.cpp
                                        ${CMAKE_CURRENT_LIST_DIR}/shared/transfer_codec_matrix_test.cpp
                                        ${CMAKE_CURRENT_LIST_DIR}/shared/transfer_codec_matrix_weights_test.cpp
                                        ${CMAKE_CURRENT_LIST_DIR}/shared/transfer_codec_matrix_basis8_test.cpp)
target_link_libraries(prt_transfer_codec_tests PRIVATE prt_test_support ${PRT_GTEST_MAIN})
# The tests check the codec's internals (streams, half floats, k-means, eigen) too.
target_include_directories(prt_transfer_codec_tests PRIVATE ${PROJECT_SOURCE_DIR}/shared/prt/codec)
target_compile_options(prt_transfer_codec_tests PRIVATE ${PRT_STRICT_WARNINGS})
if(EMSCRIPTEN)
  target_link_options(prt_transfer_codec_tests PRIVATE -sENVIRONMENT=node -sEXIT_RUNTIME=1 -sALLOW_MEMORY_GROWTH=1)
endif()
add_test(NAME transfer_codec_tests${PRT_TEST_SUFFIX} COMMAND prt_transfer_codec_tests)
set_tests_properties(transfer_codec_tests${PRT_TEST_SUFFIX} PROPERTIES TIMEOUT 600)

# libFuzzer needs Clang: configure a separate tree with
#   CC=clang CXX=clang++ cmake --preset native -B build/fuzz -DPRT_FUZZ=ON
#   cmake --build build/fuzz --target prt_transfer_codec_fuzz
#   build/fuzz/tests/prt_transfer_codec_fuzz -max_total_time=120 CORPUS_DIR
# The target compiles the shared sources itself, with the fuzzer's instrumentation, and a
# short smoke run (fixed seed, 20000 inputs) is registered as a test.
option(PRT_FUZZ "Build the libFuzzer targets (Clang only)" OFF)
if(PRT_FUZZ AND NOT EMSCRIPTEN)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "PRT_FUZZ needs Clang (CXX=clang++); the compiler is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  get_target_property(prt_shared_sources prt_shared SOURCES)
  get_target_property(prt_shared_dir prt_shared SOURCE_DIR)
  list(TRANSFORM prt_shared_sources PREPEND "${prt_shared_dir}/" REGEX "^[^/]")
  add_executable(prt_transfer_codec_fuzz ${CMAKE_CURRENT_LIST_DIR}/fuzz/transfer_codec_fuzz.cpp ${prt_shared_sources})
  target_include_directories(prt_transfer_codec_fuzz PRIVATE ${prt_shared_dir} ${prt_shared_dir}/prt/codec)
  target_compile_options(prt_transfer_codec_fuzz PRIVATE -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
                                                         -ffp-contract=off ${PRT_STRICT_WARNINGS})
  target_link_options(prt_transfer_codec_fuzz PRIVATE -fsanitize=fuzzer,address,undefined)
  add_test(NAME transfer_codec_fuzz_smoke COMMAND prt_transfer_codec_fuzz -seed=1 -runs=5000 -max_len=4096)
endif()

# `prt-bake compress-report` end to end (native only: the baker is).
if(NOT EMSCRIPTEN)
  set(PRT_CODEC_ENV_DIR /usr/share/blender/datafiles/studiolights/world
      CACHE PATH "Directory of .exr environment maps for the compress-report test")
  add_test(NAME transfer_codec_cli
           COMMAND ${CMAKE_COMMAND} -DPRT_BAKE=$<TARGET_FILE:prt-bake> -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/transfer_codec_cli
                   -DENV_DIR=${PRT_CODEC_ENV_DIR} -P ${CMAKE_CURRENT_LIST_DIR}/transfer_codec_cli.cmake)
  set_tests_properties(transfer_codec_cli PROPERTIES TIMEOUT 600)
endif()
