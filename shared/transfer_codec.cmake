# The transfer codec (prt/transfer_codec.h, docs/transfer-codec.md): part of prt_shared.
# include()d from shared/CMakeLists.txt; paths are relative to this file. Its sources and
# internal headers live in prt/codec/, on prt_shared's PRIVATE include path (included by
# bare name): only prt/transfer_codec.h is public. Tests of the internals add the path
# themselves; tests/codec_private_check.cmake keeps everyone else out.
target_sources(prt_shared PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/prt/half_float.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_streams.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_container.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_settings.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_encode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_decode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_decode_util.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_kmeans.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_eigen.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_cpca_fit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_cpca_search.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_cpca_decode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_matrix.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_basis8.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_matrix_cpca.cpp
  ${CMAKE_CURRENT_LIST_DIR}/prt/codec/transfer_codec_matrix_cpca_decode.cpp
)
target_include_directories(prt_shared PRIVATE ${CMAKE_CURRENT_LIST_DIR}/prt/codec)
