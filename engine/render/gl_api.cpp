#include "render/gl_api.h"

#include <stdexcept>

namespace substep::render {

GlApi loadGlApi(GlProcLoader loader, void* user) {
    GlApi api;
#define SUBSTEP_GL_LOAD(type, name)                                                          \
    api.name = reinterpret_cast<type>(loader("gl" #name, user));                             \
    if (api.name == nullptr) {                                                               \
        throw std::runtime_error("OpenGL function gl" #name                                  \
                                 " is missing: the context is not OpenGL 3.3 core capable"); \
    }
    SUBSTEP_GL_FUNCTIONS(SUBSTEP_GL_LOAD)
#undef SUBSTEP_GL_LOAD
    return api;
}

std::string glErrorName(GLenum error) {
    switch (error) {
        case GL_NO_ERROR: return "GL_NO_ERROR";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return "GL error " + std::to_string(error);
    }
}

}  // namespace substep::render
