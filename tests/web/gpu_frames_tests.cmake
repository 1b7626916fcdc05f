# prt-gpu-frames (web/native) through this machine's EGL: Mesa's llvmpipe here and in CI.
# include()d from tests/CMakeLists.txt for native builds. Not under the sanitizers: the
# work happens inside the GL driver, which is not instrumented (and keeps allocations past
# exit); the client code it runs is the wasm build's, tested there and in the browser.
if(NOT PRT_SANITIZE)
  foreach(case IN ITEMS glossy errors)
    add_test(NAME gpu_frames_${case}
             COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/gpu_frames_test.sh ${case} $<TARGET_FILE:prt-gpu-frames>
                     $<TARGET_FILE:prt-bake> ${CMAKE_CURRENT_BINARY_DIR}/gpu_frames_work/${case})
    set_tests_properties(gpu_frames_${case} PROPERTIES TIMEOUT 900)
  endforeach()
endif()
