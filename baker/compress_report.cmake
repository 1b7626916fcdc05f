# `prt-bake compress-report` (compress_command.cpp): its sources and the zstd and brotli
# libraries it measures with. include()d from baker/CMakeLists.txt after prt-bake is defined.
find_library(PRT_BAKE_ZSTD_LIBRARY zstd REQUIRED)
find_library(PRT_BAKE_BROTLIENC_LIBRARY brotlienc REQUIRED)
find_library(PRT_BAKE_BROTLIDEC_LIBRARY brotlidec REQUIRED)
find_path(PRT_BAKE_ZSTD_INCLUDE_DIR zstd.h REQUIRED)
find_path(PRT_BAKE_BROTLI_INCLUDE_DIR brotli/encode.h REQUIRED)
target_sources(prt-bake PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/compress_command.cpp
  ${CMAKE_CURRENT_LIST_DIR}/compress_lightings.cpp
  ${CMAKE_CURRENT_LIST_DIR}/byte_compressors.cpp
)
target_include_directories(prt-bake SYSTEM PRIVATE ${PRT_BAKE_ZSTD_INCLUDE_DIR} ${PRT_BAKE_BROTLI_INCLUDE_DIR})
target_link_libraries(prt-bake PRIVATE ${PRT_BAKE_ZSTD_LIBRARY} ${PRT_BAKE_BROTLIENC_LIBRARY} ${PRT_BAKE_BROTLIDEC_LIBRARY})
