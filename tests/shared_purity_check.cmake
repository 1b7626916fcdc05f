# Fails when a file under shared/ includes something shared/ must not depend on:
# file or console I/O, threads, GL, Embree, Boost (shared/ must build unchanged for wasm).
file(GLOB_RECURSE files ${SHARED_DIR}/*.h ${SHARED_DIR}/*.cpp)
set(forbidden "<fstream>" "<iostream>" "<cstdio>" "<stdio.h>" "<thread>" "<mutex>" "<atomic>" "<filesystem>"
              "<GL" "<GLES" "<emscripten" "<embree" "<boost/" "<tiny_gltf" "<Imf" "<OpenEXR")
include(${CMAKE_CURRENT_LIST_DIR}/include_scan.cmake)
set(bad "")
scan_includes(bad "${files}" "${forbidden}")
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no sources found under ${SHARED_DIR}")
endif()
if(bad)
  string(REPLACE ";" "\n  " text "${bad}")
  message(FATAL_ERROR "shared/ must not include I/O, threads, GL, Embree or Boost:\n  ${text}")
endif()
message(STATUS "${count} files under shared/ are free of I/O, threads, GL, Embree and Boost")
