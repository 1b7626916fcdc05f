# Fails when code outside the transfer codec includes one of its private headers
# (shared/prt/codec/): the codec's public interface is prt/transfer_codec.h alone. Its own
# tests (tests/shared/transfer_codec_test.cpp, tests/fuzz/) may look inside.
# Usage: cmake -DSOURCE_DIR=<repo root> -P codec_private_check.cmake
file(GLOB_RECURSE files
     ${SOURCE_DIR}/shared/*.h ${SOURCE_DIR}/shared/*.cpp ${SOURCE_DIR}/baker/*.h ${SOURCE_DIR}/baker/*.cpp ${SOURCE_DIR}/native/*.h ${SOURCE_DIR}/native/*.cpp ${SOURCE_DIR}/native/*.h ${SOURCE_DIR}/native/*.cpp
     ${SOURCE_DIR}/server/*.h ${SOURCE_DIR}/server/*.cpp ${SOURCE_DIR}/web/src/*.h ${SOURCE_DIR}/web/src/*.cpp
     ${SOURCE_DIR}/bench/*.h ${SOURCE_DIR}/bench/*.cpp ${SOURCE_DIR}/tests/*.h ${SOURCE_DIR}/tests/*.cpp)
file(GLOB private_headers RELATIVE ${SOURCE_DIR}/shared/prt/codec ${SOURCE_DIR}/shared/prt/codec/*.h)
list(LENGTH private_headers header_count)
if(header_count EQUAL 0)
  message(FATAL_ERROR "no private codec headers found under ${SOURCE_DIR}/shared/prt/codec")
endif()
list(FILTER files EXCLUDE REGEX "/shared/prt/codec/|/tests/shared/transfer_codec_test\\.cpp$|/tests/fuzz/")
include(${CMAKE_CURRENT_LIST_DIR}/include_scan.cmake)
set(bad "")
scan_includes(bad "${files}" "${private_headers};codec/")
if(bad)
  string(REPLACE ";" "\n  " text "${bad}")
  message(FATAL_ERROR "only the codec and its tests may include shared/prt/codec/ headers (use prt/transfer_codec.h):\n  ${text}")
endif()
message(STATUS "${header_count} private codec headers, included by nothing outside the codec")
