# prt_scene: where the baker's Scene comes from — the glTF loader and the built-in default
# scene — with the mesh clean-up and normal routines they share. include()d from
# baker/CMakeLists.txt; paths are relative to this file.

# Debian ships TinyGLTF compiled, as libtinygltf.so (see
# /usr/share/doc/libtinygltf-dev/README.Debian), so no file here defines
# TINYGLTF_IMPLEMENTATION: compiling it would also need nlohmann-json3-dev, which
# libtinygltf-dev does not pull in. The library's image decoding is replaced at run time
# (gltf_texture.cpp) by stb_image from libstb-dev.
find_package(TinyGLTF CONFIG REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)
# nlohmann-json3-dev (header-only) for the checks tinygltf does not make (gltf_json_check.h).
find_package(nlohmann_json CONFIG REQUIRED)

# prt_stb (Debian's prebuilt stb_image) is defined by baker/CMakeLists.txt before this file.

add_library(prt_scene STATIC
  ${CMAKE_CURRENT_LIST_DIR}/gltf_loader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_accessor.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_json_check.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gltf_texture.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_normals.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_cleanup.cpp
  ${CMAKE_CURRENT_LIST_DIR}/default_scene.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_order.cpp
)
target_include_directories(prt_scene PUBLIC ${CMAKE_CURRENT_LIST_DIR})
# tiny_gltf.h, GLM and stb live under /usr/include, which GCC and Clang treat as system
# headers, so their warnings stay out of -Werror.
target_link_libraries(prt_scene PUBLIC prt_shared PRIVATE TinyGLTF::TinyGLTF nlohmann_json::nlohmann_json glm::glm prt_stb meshoptimizer::meshoptimizer)
target_compile_options(prt_scene PRIVATE ${PRT_STRICT_WARNINGS})
