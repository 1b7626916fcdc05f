# Fails when prt-serve depends on the baker: configures the tree with the baker switched off
# and the baker's packages (Embree, TinyGLTF, GLM, meshoptimizer) disabled, so any
# find_package of them fails, then checks that prt-serve's build compiles nothing under
# baker/ and that no baker target exists. Also fails if a server source includes a baker
# header. Usage: cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<scratch> -P server_alone_check.cmake
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G Ninja -DCMAKE_BUILD_TYPE=Release
          -DPRT_BUILD_BAKER=OFF -DPRT_BUILD_TESTS=OFF
          -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON
          -DCMAKE_DISABLE_FIND_PACKAGE_glm=ON -DCMAKE_DISABLE_FIND_PACKAGE_meshoptimizer=ON
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the server alone does not configure without the baker's packages:\n${err}")
endif()

execute_process(COMMAND ninja -C ${WORK_DIR} -t commands prt-serve RESULT_VARIABLE rc OUTPUT_VARIABLE commands ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ninja cannot list prt-serve's build commands: ${err}")
endif()
string(FIND "${commands}" "${SOURCE_DIR}/server/main.cpp" has_main)
if(has_main EQUAL -1)
  message(FATAL_ERROR "prt-serve's build commands do not compile server/main.cpp; the check is looking at the wrong thing:\n${commands}")
endif()
string(REGEX MATCHALL "[^ ]*/baker/[^ ]*" baker_inputs "${commands}")
if(baker_inputs)
  string(REPLACE ";" "\n  " text "${baker_inputs}")
  message(FATAL_ERROR "prt-serve's build uses baker/ files:\n  ${text}")
endif()

# A baker library named in server/CMakeLists.txt would not exist here and would reach the
# link line as -l<name>: look for the names too.
execute_process(COMMAND ninja -C ${WORK_DIR} -t targets all OUTPUT_VARIABLE targets)
foreach(baker_target IN ITEMS prt-bake prt_bake_cli prt_transfer prt_scene)
  string(REGEX MATCH "(^|\n)[^\n]*${baker_target}[:.][^\n]*" found "${targets}")
  if(found)
    message(FATAL_ERROR "the server-only build still defines the baker target ${baker_target}: ${found}")
  endif()
  string(REGEX MATCH "[^ ]*${baker_target}[^ ]*" linked "${commands}")
  if(linked)
    message(FATAL_ERROR "prt-serve's build names the baker library ${baker_target}: ${linked}")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/include_scan.cmake)
file(GLOB_RECURSE server_files ${SOURCE_DIR}/server/*.h ${SOURCE_DIR}/server/*.cpp)
file(GLOB_RECURSE baker_headers RELATIVE ${SOURCE_DIR}/baker ${SOURCE_DIR}/baker/*.h)
set(tokens "\"baker/")
foreach(h ${baker_headers})
  get_filename_component(name ${h} NAME)
  list(APPEND tokens "\"${name}\"")
endforeach()
set(bad "")
scan_includes(bad "${server_files}" "${tokens}")
if(bad)
  string(REPLACE ";" "\n  " text "${bad}")
  message(FATAL_ERROR "server/ includes baker headers:\n  ${text}")
endif()
list(LENGTH server_files count)
message(STATUS "prt-serve configures without the baker's packages, compiles no baker/ file, and its ${count} sources include no baker header")
file(REMOVE_RECURSE ${WORK_DIR})
