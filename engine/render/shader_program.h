#pragma once
/// A linked GLSL program built from the embedded shader files, with uniform setters that look
/// locations up by name (a handful per draw: not worth caching).

#include "render/gl_api.h"
#include "render/render_math.h"

#include <initializer_list>
#include <string_view>

namespace substep::render {

class ShaderProgram {
  public:
    /// Compiles each stage from the named files of shaders/, concatenated in order after the
    /// `#version 330 core` line, and links them. Throws std::runtime_error with the compiler's
    /// log naming the files.
    ShaderProgram(const GlApi& gl, std::initializer_list<std::string_view> vertexFiles,
                  std::initializer_list<std::string_view> fragmentFiles);
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    void use() const;
    void set(const char* name, int value) const;
    void set(const char* name, float value) const;
    void set(const char* name, const Vec3f& value) const;
    void set(const char* name, const Mat4f& value) const;

  private:
    const GlApi& gl_;
    GLuint program_ = 0;
};

}  // namespace substep::render
