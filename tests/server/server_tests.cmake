# prt-serve end to end (native only): a real server on a loopback port the kernel picks,
# a real HTTP client (Boost.Beast, blocking) and raw sockets for hostile input.
# include()d from tests/CMakeLists.txt; paths are relative to this file.

find_package(ZLIB REQUIRED)  # prt_zstd and prt_brotlidec come from native/CMakeLists.txt
# The tests read the server's JSON documents with nlohmann-json3-dev (header-only).
find_package(nlohmann_json CONFIG REQUIRED)

set(PRT_SERVE_TEST_DIR ${CMAKE_CURRENT_LIST_DIR})
set(PRT_SERVE_WORK_DIR ${CMAKE_CURRENT_BINARY_DIR}/server_work)
set(PRT_BLENDER_STUDIO_EXR /usr/share/blender/datafiles/studiolights/world/studio.exr
    CACHE FILEPATH "blender-data EXR the server tests copy in as an environment map (used when present)")

add_library(prt_serve_test_support STATIC
  ${PRT_SERVE_TEST_DIR}/encoded_asset.cpp
  ${PRT_SERVE_TEST_DIR}/http_client.cpp
  ${PRT_SERVE_TEST_DIR}/serve_env.cpp
  ${PRT_SERVE_TEST_DIR}/server_process.cpp
  ${PRT_SERVE_TEST_DIR}/test_tree.cpp
)
target_include_directories(prt_serve_test_support PUBLIC ${PRT_SERVE_TEST_DIR})
target_link_libraries(prt_serve_test_support
  PUBLIC prt_serve prt_shared GTest::gtest nlohmann_json::nlohmann_json ZLIB::ZLIB prt_zstd prt_brotlidec)
target_compile_definitions(prt_serve_test_support PRIVATE
  PRT_SERVE_EXE="$<TARGET_FILE:prt-serve>"
  PRT_SERVE_WORK_DIR="${PRT_SERVE_WORK_DIR}"
  PRT_BLENDER_STUDIO_EXR="${PRT_BLENDER_STUDIO_EXR}")
target_compile_options(prt_serve_test_support PRIVATE ${PRT_STRICT_WARNINGS})

add_executable(prt_server_tests
  ${PRT_SERVE_TEST_DIR}/unit_test.cpp
  ${PRT_SERVE_TEST_DIR}/asset_parts_test.cpp
  ${PRT_SERVE_TEST_DIR}/http_test.cpp
  ${PRT_SERVE_TEST_DIR}/parts_test.cpp
  ${PRT_SERVE_TEST_DIR}/hostile_test.cpp
  ${PRT_SERVE_TEST_DIR}/load_test.cpp
  ${PRT_SERVE_TEST_DIR}/cli_test.cpp
  ${PRT_SERVE_TEST_DIR}/thumbnail_test.cpp
)
# stb_image decodes the thumbnails' PNGs (thumbnail_test.cpp, http_test.cpp).
target_link_libraries(prt_server_tests PRIVATE prt_serve_test_support prt_stb GTest::gtest_main)
target_compile_options(prt_server_tests PRIVATE ${PRT_STRICT_WARNINGS})
add_dependencies(prt_server_tests prt-serve)

# One ctest test per group, each its own process with its own servers.
foreach(group IN ITEMS unit http parts hostile load cli)
  if(group STREQUAL "unit")
    set(filter "ContentHash.*:RequestTarget.*:RequestHead.*:PublicError.*:Negotiation.*:AccessLog.Escapes*:MimeTypes.*:AssetParts.*:ServeOptions.*:OsError.*:BackgroundTexture.*:MeshRaster.*:Thumbnail.*")
  elseif(group STREQUAL "parts")
    set(filter "Parts.*")
  elseif(group STREQUAL "http")
    set(filter "Scenes.*:Assets.*:Conditional.*:Ranges.*:Head.*:KeepAlive.*:StaticFiles.*:Lights.*:Api.*:AccessLog.OneLine*:AccessLog.Quiet*:AccessLog.Slow*:Rescan.*")
  elseif(group STREQUAL "hostile")
    set(filter "Hostile.*")
  elseif(group STREQUAL "load")
    set(filter "Load.*:Lifecycle.*")
  else()
    set(filter "Cli.*")
  endif()
  add_test(NAME server_${group} COMMAND prt_server_tests --gtest_filter=${filter})
  set_tests_properties(server_${group} PROPERTIES TIMEOUT 600)
endforeach()

# The benchmark's asset generator (scripts/bench-serve.sh).
add_executable(prt_serve_make_asset ${PRT_SERVE_TEST_DIR}/make_asset_tool.cpp)
target_link_libraries(prt_serve_make_asset PRIVATE prt_serve_test_support)
target_compile_options(prt_serve_make_asset PRIVATE ${PRT_STRICT_WARNINGS})
