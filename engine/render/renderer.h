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
#include "render/render_quality.h"
#include "render/render_scene.h"
#include "render/render_target.h"

#include <map>
#include <memory>
#include <tuple>

namespace substep::render {

class GpuMesh;
class ShaderProgram;

/// What the renderer itself draws at a quality level (render_quality.h); multisampling belongs
/// to the framebuffer drawn into. The defaults are the full level, which headless renders use.
struct RendererSettings {
    int shadowMapSize = 2048;  ///< texels per side
    ShadowMode shadows = ShadowMode::Soft;
    int sphereRings = 24;      ///< the unit sphere's latitude bands
    int sphereSegments = 48;   ///< and longitude slices
    /// Spheres that look smaller than this radius (pixels of the target) are drawn with a coarse
    /// mesh of 6 x 12 (a thousand small balls are otherwise mostly triangles smaller than a
    /// pixel, which a software rasteriser sets up one by one); 0 never.
    float coarseSphereBelowPixels = 0.0f;
    /// Instances of a mesh drawn nearest first, so a pile's hidden fragments are rejected by the
    /// depth test before shading (the same picture up to ties in depth).
    bool frontToBack = false;
    friend bool operator==(const RendererSettings&, const RendererSettings&) = default;
};

/// The renderer's part of a quality level.
RendererSettings rendererSettings(const RenderQuality& quality);

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

    /// Switches shadow map size, shadow filter and sphere tessellation from the next frame on
    /// (the interactive app's quality levels); does nothing when they are the same.
    void setSettings(const RendererSettings& settings);
    const RendererSettings& settings() const { return settings_; }
    /// Triangles drawn by the last render() call in the view pass (the shadow pass draws as many
    /// again): what instancing submits, for the panel's readout.
    long long lastTriangleCount() const { return lastTriangles_; }

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

    void allocateShadowMap();
    /// `coarse`: a sphere's coarse level of detail.
    GpuMesh& meshFor(const RenderInstance& instance, bool coarse, MeshKey& key);
    /// `pixelsPerRadian` of the target's height: a sphere's apparent size picks its detail.
    Bounds batchInstances(const RenderScene& scene, float pixelsPerRadian);
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
    long long lastTriangles_ = 0;
};

}  // namespace substep::render
