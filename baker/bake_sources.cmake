# The Embree transfer baker as a library (prt_bake), shared by prt-bake and the tests.
find_package(embree 3 REQUIRED)
find_package(Threads REQUIRED)
add_library(prt_bake STATIC
  ${CMAKE_CURRENT_LIST_DIR}/embree_scene.cpp
  ${CMAKE_CURRENT_LIST_DIR}/transfer_bake.cpp
  ${CMAKE_CURRENT_LIST_DIR}/local_sphere.cpp
  ${CMAKE_CURRENT_LIST_DIR}/direct_reference.cpp
)
target_include_directories(prt_bake PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(prt_bake PUBLIC prt_shared embree Threads::Threads)
target_compile_options(prt_bake PRIVATE ${PRT_STRICT_WARNINGS})
