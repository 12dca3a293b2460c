#include "render/shader_program.h"

#include "render/shader_sources.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace substep::render {
namespace {

GLuint compileStage(const GlApi& gl, GLenum stage, std::initializer_list<std::string_view> files) {
    std::vector<const GLchar*> texts{"#version 330 core\n"};
    std::vector<GLint> lengths{-1};
    std::string names;
    for (const std::string_view file : files) {
        const std::string_view text = shaderSource(file);
        texts.push_back(text.data());
        lengths.push_back(static_cast<GLint>(text.size()));
        names += (names.empty() ? "" : " + ") + std::string(file);
    }
    const GLuint shader = gl.CreateShader(stage);
    gl.ShaderSource(shader, static_cast<GLsizei>(texts.size()), texts.data(), lengths.data());
    gl.CompileShader(shader);
    GLint compiled = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (compiled != GL_TRUE) {
        char log[4096] = {};
        gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
        gl.DeleteShader(shader);
        throw std::runtime_error("shader " + names + " does not compile:\n" + log);
    }
    return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(const GlApi& gl, std::initializer_list<std::string_view> vertexFiles,
                             std::initializer_list<std::string_view> fragmentFiles)
    : gl_(gl) {
    const GLuint vertex = compileStage(gl, GL_VERTEX_SHADER, vertexFiles);
    GLuint fragment = 0;
    try {
        fragment = compileStage(gl, GL_FRAGMENT_SHADER, fragmentFiles);
    } catch (...) {
        gl.DeleteShader(vertex);
        throw;
    }
    program_ = gl.CreateProgram();
    gl.AttachShader(program_, vertex);
    gl.AttachShader(program_, fragment);
    gl.LinkProgram(program_);
    gl.DeleteShader(vertex);
    gl.DeleteShader(fragment);
    GLint linked = GL_FALSE;
    gl.GetProgramiv(program_, GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        char log[4096] = {};
        gl.GetProgramInfoLog(program_, sizeof log, nullptr, log);
        gl.DeleteProgram(program_);
        throw std::runtime_error(std::string("shader program does not link:\n") + log);
    }
}

ShaderProgram::~ShaderProgram() { gl_.DeleteProgram(program_); }

void ShaderProgram::use() const { gl_.UseProgram(program_); }

void ShaderProgram::set(const char* name, int value) const {
    gl_.Uniform1i(gl_.GetUniformLocation(program_, name), value);
}

void ShaderProgram::set(const char* name, float value) const {
    gl_.Uniform1f(gl_.GetUniformLocation(program_, name), value);
}

void ShaderProgram::set(const char* name, const Vec3f& value) const {
    gl_.Uniform3fv(gl_.GetUniformLocation(program_, name), 1, value.data());
}

void ShaderProgram::set(const char* name, const Mat4f& value) const {
    // Eigen stores column-major, as GL expects.
    gl_.UniformMatrix4fv(gl_.GetUniformLocation(program_, name), 1, GL_FALSE, value.data());
}

}  // namespace substep::render
