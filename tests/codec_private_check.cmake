# Fails when code outside the transfer codec includes one of its private headers
# (shared/prt/codec/): the codec's public interface is prt/transfer_codec.h alone. Its own
# tests (tests/shared/transfer_codec_test.cpp, tests/fuzz/) may look inside.
# Usage: cmake -DSOURCE_DIR=<repo root> -P codec_private_check.cmake
file(GLOB_RECURSE files
     ${SOURCE_DIR}/shared/*.h ${SOURCE_DIR}/shared/*.cpp ${SOURCE_DIR}/baker/*.h ${SOURCE_DIR}/baker/*.cpp
     ${SOURCE_DIR}/server/*.h ${SOURCE_DIR}/server/*.cpp ${SOURCE_DIR}/web/src/*.h ${SOURCE_DIR}/web/src/*.cpp
     ${SOURCE_DIR}/bench/*.h ${SOURCE_DIR}/bench/*.cpp ${SOURCE_DIR}/tests/*.h ${SOURCE_DIR}/tests/*.cpp)
file(GLOB private_headers RELATIVE ${SOURCE_DIR}/shared/prt/codec ${SOURCE_DIR}/shared/prt/codec/*.h)
list(LENGTH private_headers header_count)
if(header_count EQUAL 0)
  message(FATAL_ERROR "no private codec headers found under ${SOURCE_DIR}/shared/prt/codec")
endif()
set(bad "")
foreach(f ${files})
  if(f MATCHES "/shared/prt/codec/" OR f MATCHES "/tests/shared/transfer_codec_test.cpp$" OR f MATCHES "/tests/fuzz/")
    continue()
  endif()
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${lines})
    foreach(header ${private_headers} "codec/")
      string(FIND "${line}" "${header}" pos)
      if(NOT pos EQUAL -1)
        list(APPEND bad "${f}: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(bad)
  string(REPLACE ";" "\n  " text "${bad}")
  message(FATAL_ERROR "only the codec and its tests may include shared/prt/codec/ headers (use prt/transfer_codec.h):\n  ${text}")
endif()
message(STATUS "${header_count} private codec headers, included by nothing outside the codec")
