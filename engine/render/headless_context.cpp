#include "render/headless_context.h"

#include "render/egl_context.h"
#include "render/osmesa_context.h"

#include <cstdlib>
#include <string>

namespace substep::render {

std::unique_ptr<GlContext> createHeadlessContext() {
    const char* choice = std::getenv("SUBSTEP_GL_BACKEND");
    const std::string backend = choice != nullptr ? choice : "";
    if (!backend.empty() && backend != "egl" && backend != "osmesa") {
        throw ContextError("SUBSTEP_GL_BACKEND=" + backend + ": expected egl or osmesa");
    }

    std::string failures;
    if (backend != "osmesa") {
        try {
            return createEglContext();
        } catch (const ContextError& error) {
            failures = error.what();
        }
    }
    if (backend != "egl") {
        try {
            return createOsMesaContext();
        } catch (const ContextError& error) {
            failures += (failures.empty() ? "" : "; ") + std::string(error.what());
        }
    }
    throw ContextError("no headless OpenGL 3.3 context: " + failures);
}

}  // namespace substep::render
