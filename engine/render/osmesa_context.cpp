#include "render/osmesa_context.h"

#include <dlfcn.h>

#include <string>
#include <vector>

namespace substep::render {
namespace {

// The few declarations of GL/osmesa.h this file needs. That header pulls in GL/gl.h, whose
// prototypes clash with glcorearb.h's, and the library is opened with dlopen anyway.
using OsMesaContextHandle = struct osmesa_context*;
using CreateContextAttribs = OsMesaContextHandle (*)(const int* attributes, OsMesaContextHandle share);
using DestroyContext = void (*)(OsMesaContextHandle);
using MakeCurrent = unsigned char (*)(OsMesaContextHandle, void* buffer, unsigned type, int width,
                                      int height);
using GetProcAddress = GlProcAddress (*)(const char* name);
constexpr int kOsMesaFormat = 0x22;
constexpr int kOsMesaDepthBits = 0x30;
constexpr int kOsMesaProfile = 0x33;
constexpr int kOsMesaCoreProfile = 0x34;
constexpr int kOsMesaMajorVersion = 0x36;
constexpr int kOsMesaMinorVersion = 0x37;
constexpr int kRgba = 0x1908;          // GL_RGBA
constexpr unsigned kUnsignedByte = 0x1401;  // GL_UNSIGNED_BYTE

class OsMesaContext final : public GlContext {
  public:
    OsMesaContext() {
        for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
            library_ = dlopen(name, RTLD_NOW | RTLD_LOCAL);
            if (library_ != nullptr) break;
        }
        if (library_ == nullptr) {
            throw ContextError("OSMesa: libOSMesa is not installed (Debian: libosmesa6)");
        }
        createContext_ = reinterpret_cast<CreateContextAttribs>(dlsym(library_, "OSMesaCreateContextAttribs"));
        destroyContext_ = reinterpret_cast<DestroyContext>(dlsym(library_, "OSMesaDestroyContext"));
        makeCurrent_ = reinterpret_cast<MakeCurrent>(dlsym(library_, "OSMesaMakeCurrent"));
        getProcAddress_ = reinterpret_cast<GetProcAddress>(dlsym(library_, "OSMesaGetProcAddress"));
        if (!createContext_ || !destroyContext_ || !makeCurrent_ || !getProcAddress_) {
            dlclose(library_);
            throw ContextError("OSMesa: libOSMesa lacks OSMesaCreateContextAttribs (too old)");
        }
        const int attributes[] = {kOsMesaFormat, kRgba,
                                  kOsMesaDepthBits, 24,
                                  kOsMesaProfile, kOsMesaCoreProfile,
                                  kOsMesaMajorVersion, 3,
                                  kOsMesaMinorVersion, 3,
                                  0};
        context_ = createContext_(attributes, nullptr);
        if (context_ == nullptr) {
            dlclose(library_);
            throw ContextError("OSMesa: OSMesaCreateContextAttribs (OpenGL 3.3 core) failed");
        }
        try {
            makeCurrent();
        } catch (...) {
            destroyContext_(context_);
            dlclose(library_);
            throw;
        }
    }

    // The library stays loaded: Mesa registers thread-exit handlers that must outlive the
    // context, and unloading it mid-process has crashed on exit.
    ~OsMesaContext() override { destroyContext_(context_); }

    void makeCurrent() override {
        if (makeCurrent_(context_, surface_.data(), kUnsignedByte, 1, 1) == 0) {
            throw ContextError("OSMesa: OSMesaMakeCurrent failed");
        }
    }

    GlProcAddress procAddress(const char* name) const override { return getProcAddress_(name); }
    PixelSize framebufferSize() const override { return {}; }
    std::string backendName() const override { return "OSMesa"; }

  private:
    void* library_ = nullptr;
    CreateContextAttribs createContext_ = nullptr;
    DestroyContext destroyContext_ = nullptr;
    MakeCurrent makeCurrent_ = nullptr;
    GetProcAddress getProcAddress_ = nullptr;
    OsMesaContextHandle context_ = nullptr;
    std::vector<unsigned char> surface_ = std::vector<unsigned char>(4);  ///< the 1x1 RGBA buffer
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() { return std::make_unique<OsMesaContext>(); }

}  // namespace substep::render
