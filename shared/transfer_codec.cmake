# The transfer codec (prt/transfer_codec.h, docs/transfer-codec.md): part of prt_shared.
# include()d from shared/CMakeLists.txt; paths are relative to this file.
target_sources(prt_shared PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_half.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_streams.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_container.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_settings.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_encode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_decode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_decode_util.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_kmeans.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_eigen.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_cpca_fit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_cpca_search.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/transfer_codec_cpca_decode.cpp
)
