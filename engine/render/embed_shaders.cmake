# Writes OUTPUT, a C++ source holding every GLSL file of SHADER_DIR as a string, so the program
# finds its shaders wherever it is installed or run from. Run by the build (cmake -P) whenever a
# shader changes.
file(GLOB shader_files RELATIVE "${SHADER_DIR}" "${SHADER_DIR}/*.glsl" "${SHADER_DIR}/*.vert"
     "${SHADER_DIR}/*.frag")
list(SORT shader_files)
set(entries "")
foreach(name IN LISTS shader_files)
  file(READ "${SHADER_DIR}/${name}" text)
  string(APPEND entries "    {\"${name}\", R\"glsl(${text})glsl\"},\n")
endforeach()
set(content "// Generated from shaders/ by engine/render/embed_shaders.cmake: do not edit.\n\
#include \"render/shader_sources.h\"\n\
\n\
#include <stdexcept>\n\
#include <string>\n\
\n\
namespace substep::render {\n\
namespace {\n\
\n\
struct ShaderFile {\n\
    std::string_view name;\n\
    std::string_view text;\n\
};\n\
\n\
constexpr ShaderFile kShaderFiles[] = {\n\
${entries}};\n\
\n\
}  // namespace\n\
\n\
std::string_view shaderSource(std::string_view name) {\n\
    for (const ShaderFile& file : kShaderFiles) {\n\
        if (file.name == name) return file.text;\n\
    }\n\
    throw std::runtime_error(\"no shader named \" + std::string(name) + \" in shaders/\");\n\
}\n\
\n\
}  // namespace substep::render\n")
# Only touch the output when it changes, so unrelated edits rebuild nothing.
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" previous)
  if(previous STREQUAL content)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${content}")
