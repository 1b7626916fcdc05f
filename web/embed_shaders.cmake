# Writes a C++ header holding each GLSL file as a raw string literal, so the shaders stay
# editable .vert/.frag files and still ship inside the wasm (no extra fetches).
# Usage: cmake -DOUT=header.h -DFILES="a.vert;b.frag" -P embed_shaders.cmake
set(text "// Generated from web/shaders by web/embed_shaders.cmake. Do not edit.\n#pragma once\n\nnamespace prt::web::shaders {\n")
foreach(file IN LISTS FILES)
  get_filename_component(name ${file} NAME)
  string(MAKE_C_IDENTIFIER ${name} id)
  file(READ ${file} source)
  string(APPEND text "inline constexpr const char* k_${id} = R\"glsl(${source})glsl\";\n")
endforeach()
string(APPEND text "}  // namespace prt::web::shaders\n")
file(WRITE ${OUT}.tmp "${text}")
file(RENAME ${OUT}.tmp ${OUT})
