#pragma once
/// The OpenGL 3.3 core renderer: draws a RenderScene into a RenderTarget of the current context.
///
/// A frame is: a shadow map from the sun (depth of every instance, orthographic around the
/// scene's bounds), the sky gradient, the ground with its grid, the instances batched by mesh
/// (one instanced draw per mesh), then the debug lines (faint where hidden, full where visible).
/// Nothing depends on time or on earlier frames, so the same scene gives the same pixels.
/// It draws into whatever framebuffer it is given: an OffscreenTarget headless, a window's
/// default framebuffer (0) in the interactive app.

#include "render/gl_api.h"
#include "render/render_scene.h"
#include "render/render_target.h"

#include <map>
#include <memory>
#include <tuple>

namespace substep::render {

class GpuMesh;
class ShaderProgram;

struct RendererSettings {
    int shadowMapSize = 2048;  ///< texels per side
};

class Renderer {
  public:
    /// Compiles the shaders and builds the shared meshes on the current context. Throws
    /// std::runtime_error when a shader does not compile (a driver without GLSL 3.30).
    explicit Renderer(const GlApi& gl, const RendererSettings& settings = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Draws `scene` into `target`, covering every pixel of its area. Throws std::runtime_error on a
    /// GL error.
    void render(const RenderScene& scene, const RenderTarget& target);

  private:
    /// Which GPU mesh an instance uses: the shared unit sphere and box, a capsule per size, or
    /// the instance's own MeshData.
    using MeshKey = std::tuple<ShapeKind, float, float, const MeshData*>;
    struct CachedMesh {
        std::unique_ptr<GpuMesh> mesh;
        std::shared_ptr<const MeshData> source;  ///< keeps a ShapeKind::Mesh key's address valid
        bool closed = true;                      ///< back faces may be culled
        bool used = false;                       ///< by the frame being drawn
    };
    struct Bounds {
        Vec3f centre = Vec3f::Zero();
        float radius = 1.0f;
    };

    GpuMesh& meshFor(const RenderInstance& instance, MeshKey& key);
    Bounds batchInstances(const RenderScene& scene);
    void drawShadowMap(const Mat4f& lightViewProjection);
    void drawSky(const RenderScene& scene, const Mat4f& viewProjection);
    void setLighting(const ShaderProgram& program, const RenderScene& scene, const Mat4f& viewProjection,
                     const Mat4f& lightViewProjection, float fogDistance, float normalOffset);
    void drawGround(const RenderScene& scene, const Ground& ground, float halfExtent);
    void drawMeshes();
    void drawLines(const RenderScene& scene, const Mat4f& viewProjection);

    const GlApi& gl_;
    RendererSettings settings_;
    std::unique_ptr<ShaderProgram> meshProgram_;
    std::unique_ptr<ShaderProgram> shadowProgram_;
    std::unique_ptr<ShaderProgram> groundProgram_;
    std::unique_ptr<ShaderProgram> skyProgram_;
    std::unique_ptr<ShaderProgram> lineProgram_;
    std::map<MeshKey, CachedMesh> meshes_;
    GLuint shadowTexture_ = 0;
    GLuint shadowFramebuffer_ = 0;
    GLuint emptyVertexArray_ = 0;  ///< the sky's triangle needs no attributes, but core GL needs a VAO
    GLuint groundVertexArray_ = 0;
    GLuint groundBuffer_ = 0;
    GLuint lineVertexArray_ = 0;
    GLuint lineBuffer_ = 0;
};

}  // namespace substep::render
