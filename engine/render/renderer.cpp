#include "render/renderer.h"

#include "render/gpu_mesh.h"
#include "render/mesh_builders.h"
#include "render/shader_program.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace substep::render {
namespace {

Vec3f toLinear(const Colour& srgb) {
    return Vec3f(std::pow(srgb.x(), 2.2f), std::pow(srgb.y(), 2.2f), std::pow(srgb.z(), 2.2f));
}

/// Bounding radius of an instance about its position, for the scene bounds.
float instanceRadius(const RenderInstance& instance, float meshRadius) {
    switch (instance.kind) {
        case ShapeKind::Sphere: return instance.dimensions.x();
        case ShapeKind::Box: return instance.dimensions.norm() / 2.0f;
        case ShapeKind::Capsule: return instance.dimensions.x() + instance.dimensions.y() / 2.0f;
        case ShapeKind::Cylinder: return std::hypot(instance.dimensions.x(), instance.dimensions.y() / 2.0f);
        case ShapeKind::Mesh: return meshRadius;
    }
    return 0.0f;
}

/// The scale applied to the cached mesh: the unit primitives scale, the others are built to size.
Vec3f instanceScale(const RenderInstance& instance) {
    switch (instance.kind) {
        case ShapeKind::Sphere: return Vec3f::Constant(instance.dimensions.x());
        case ShapeKind::Box: return instance.dimensions;
        case ShapeKind::Cylinder:
            return Vec3f(instance.dimensions.x(), instance.dimensions.y(), instance.dimensions.x());
        default: return Vec3f::Ones();
    }
}

/// Two unit vectors spanning the plane with normal `normal`.
std::pair<Vec3f, Vec3f> planeBasis(const Vec3f& normal) {
    // Prefer the world x axis on the plane, so a horizontal ground's grid runs along x and z.
    Vec3f tangent = Vec3f::UnitX() - normal * normal.x();
    if (tangent.squaredNorm() < 1e-6f) tangent = Vec3f::UnitZ() - normal * normal.z();
    tangent.normalize();
    return {tangent, normal.cross(tangent)};
}

/// The shader's shadow filter (lighting.glsl's uShadowFilter): 0 the 4 x 4 filter, 1 one tap,
/// 2 none.
int shadowFilter(ShadowMode mode) {
    switch (mode) {
        case ShadowMode::Soft: return 0;
        case ShadowMode::Hard: return 1;
        case ShadowMode::Off: return 2;
    }
    return 0;
}

/// Orders `batch` nearest first by `depths` (squared distances, one per instance), so hidden
/// fragments of a pile fail the depth test before they are shaded.
void sortFrontToBack(std::vector<InstanceData>& batch, const std::vector<float>& depths) {
    std::vector<std::size_t> order(batch.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depths[a] < depths[b]; });
    std::vector<InstanceData> sorted;
    sorted.reserve(batch.size());
    for (const std::size_t i : order) sorted.push_back(batch[i]);
    batch.swap(sorted);
}

}  // namespace

RendererSettings rendererSettings(const RenderQuality& quality) {
    return {.shadowMapSize = quality.shadowMapSize,
            .shadows = quality.shadows,
            .sphereRings = quality.sphereRings,
            .sphereSegments = quality.sphereSegments,
            .coarseSphereBelowPixels = quality.coarseSphereBelowPixels,
            .frontToBack = quality.frontToBack};
}

Renderer::Renderer(const GlApi& gl, const RendererSettings& settings) : gl_(gl), settings_(settings) {
    meshProgram_ = std::make_unique<ShaderProgram>(gl, std::initializer_list<std::string_view>{"mesh.vert"},
                                                   std::initializer_list<std::string_view>{"lighting.glsl", "mesh.frag"});
    shadowProgram_ = std::make_unique<ShaderProgram>(gl, std::initializer_list<std::string_view>{"shadow.vert"},
                                                     std::initializer_list<std::string_view>{"shadow.frag"});
    groundProgram_ = std::make_unique<ShaderProgram>(gl, std::initializer_list<std::string_view>{"ground.vert"},
                                                     std::initializer_list<std::string_view>{"lighting.glsl", "ground.frag"});
    skyProgram_ = std::make_unique<ShaderProgram>(gl, std::initializer_list<std::string_view>{"sky.vert"},
                                                  std::initializer_list<std::string_view>{"sky.frag"});
    lineProgram_ = std::make_unique<ShaderProgram>(gl, std::initializer_list<std::string_view>{"line.vert"},
                                                   std::initializer_list<std::string_view>{"line.frag"});

    // Shadow map: a depth texture compared in hardware (sampler2DShadow), lit outside its area.
    gl_.GenTextures(1, &shadowTexture_);
    allocateShadowMap();
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float farDepth[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    gl_.TexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, farDepth);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl_.GenFramebuffers(1, &shadowFramebuffer_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTexture_, 0);
    gl_.DrawBuffer(GL_NONE);
    gl_.ReadBuffer(GL_NONE);
    const GLenum shadowStatus = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (shadowStatus != GL_FRAMEBUFFER_COMPLETE) throw std::runtime_error("shadow map framebuffer is incomplete");

    gl_.GenVertexArrays(1, &emptyVertexArray_);

    gl_.GenVertexArrays(1, &groundVertexArray_);
    gl_.BindVertexArray(groundVertexArray_);
    gl_.GenBuffers(1, &groundBuffer_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, groundBuffer_);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);

    gl_.GenVertexArrays(1, &lineVertexArray_);
    gl_.BindVertexArray(lineVertexArray_);
    gl_.GenBuffers(1, &lineBuffer_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    gl_.EnableVertexAttribArray(1);
    gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                            reinterpret_cast<const void*>(3 * sizeof(float)));
    gl_.BindVertexArray(0);

    const GLenum error = gl_.GetError();
    if (error != GL_NO_ERROR) throw std::runtime_error("renderer set-up: " + glErrorName(error));
}

void Renderer::allocateShadowMap() {
    gl_.BindTexture(GL_TEXTURE_2D, shadowTexture_);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, settings_.shadowMapSize, settings_.shadowMapSize, 0,
                   GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
}

void Renderer::setSettings(const RendererSettings& settings) {
    if (settings == settings_) return;
    const bool resize = settings.shadowMapSize != settings_.shadowMapSize;
    const bool retessellate =
        settings.sphereRings != settings_.sphereRings || settings.sphereSegments != settings_.sphereSegments;
    settings_ = settings;
    if (resize) allocateShadowMap();
    // The shared unit sphere is built again at the new tessellation on its next use.
    if (retessellate) meshes_.erase(MeshKey{ShapeKind::Sphere, 0.0f, 0.0f, nullptr});
    if (settings_.coarseSphereBelowPixels <= 0.0f) meshes_.erase(MeshKey{ShapeKind::Sphere, 1.0f, 0.0f, nullptr});
}

Renderer::~Renderer() {
    meshes_.clear();
    gl_.DeleteTextures(1, &shadowTexture_);
    gl_.DeleteFramebuffers(1, &shadowFramebuffer_);
    gl_.DeleteVertexArrays(1, &emptyVertexArray_);
    gl_.DeleteVertexArrays(1, &groundVertexArray_);
    gl_.DeleteBuffers(1, &groundBuffer_);
    gl_.DeleteVertexArrays(1, &lineVertexArray_);
    gl_.DeleteBuffers(1, &lineBuffer_);
}

GpuMesh& Renderer::meshFor(const RenderInstance& instance, bool coarse, MeshKey& key) {
    switch (instance.kind) {
        case ShapeKind::Sphere: key = {instance.kind, coarse ? 1.0f : 0.0f, 0.0f, nullptr}; break;
        case ShapeKind::Box:
        case ShapeKind::Cylinder: key = {instance.kind, 0.0f, 0.0f, nullptr}; break;
        case ShapeKind::Capsule: key = {instance.kind, instance.dimensions.x(), instance.dimensions.y(), nullptr}; break;
        case ShapeKind::Mesh: key = {instance.kind, 0.0f, 0.0f, instance.mesh.get()}; break;
    }
    auto found = meshes_.find(key);
    if (found == meshes_.end()) {
        CachedMesh cached;
        switch (instance.kind) {
            case ShapeKind::Sphere:
                cached.mesh = std::make_unique<GpuMesh>(
                    gl_, coarse ? unitSphereMesh(6, 12) : unitSphereMesh(settings_.sphereRings, settings_.sphereSegments));
                break;
            case ShapeKind::Box: cached.mesh = std::make_unique<GpuMesh>(gl_, unitBoxMesh()); break;
            case ShapeKind::Cylinder: cached.mesh = std::make_unique<GpuMesh>(gl_, unitCylinderMesh()); break;
            case ShapeKind::Capsule:
                cached.mesh = std::make_unique<GpuMesh>(gl_, capsuleMesh(instance.dimensions.x(), instance.dimensions.y()));
                break;
            case ShapeKind::Mesh:
                cached.mesh = std::make_unique<GpuMesh>(gl_, instance.mesh ? *instance.mesh : MeshData{});
                cached.source = instance.mesh;
                // Triangle meshes, heightfields and open tubes may be seen from behind.
                cached.closed = false;
                break;
        }
        found = meshes_.emplace(key, std::move(cached)).first;
    }
    found->second.used = true;
    return *found->second.mesh;
}

Renderer::Bounds Renderer::batchInstances(const RenderScene& scene, float pixelsPerRadian) {
    for (auto& [key, cached] : meshes_) cached.used = false;
    std::map<MeshKey, std::vector<InstanceData>> batches;
    Eigen::AlignedBox3f box;
    const float coarseBelow = settings_.coarseSphereBelowPixels;
    std::map<MeshKey, std::vector<float>> depths;  // squared distances from the camera, frontToBack only
    for (const RenderInstance& instance : scene.instances) {
        MeshKey key;
        // Apparent radius ≈ r / distance radians, in pixels of the target's height.
        const bool coarse = coarseBelow > 0.0f && instance.kind == ShapeKind::Sphere &&
                            instance.dimensions.x() * pixelsPerRadian <
                                coarseBelow * (instance.position - scene.camera.position).norm();
        const GpuMesh& mesh = meshFor(instance, coarse, key);
        InstanceData data{};
        const Mat4f model = modelMatrix(instance.position, instance.orientation, instanceScale(instance));
        std::copy(model.data(), model.data() + 16, data.model);
        data.colour[0] = instance.colour.x();
        data.colour[1] = instance.colour.y();
        data.colour[2] = instance.colour.z();
        data.colour[3] = 1.0f;
        batches[key].push_back(data);
        if (settings_.frontToBack) depths[key].push_back((instance.position - scene.camera.position).squaredNorm());
        const float radius = instanceRadius(instance, mesh.boundingRadius());
        box.extend(instance.position - Vec3f::Constant(radius));
        box.extend(instance.position + Vec3f::Constant(radius));
    }
    // Meshes no instance uses any more are freed; the shared primitives stay.
    for (auto it = meshes_.begin(); it != meshes_.end();) {
        const ShapeKind kind = std::get<0>(it->first);
        const bool shared = kind == ShapeKind::Sphere || kind == ShapeKind::Box || kind == ShapeKind::Cylinder;
        if (!it->second.used && !shared) {
            it = meshes_.erase(it);
        } else {
            std::vector<InstanceData>& batch = batches[it->first];
            if (settings_.frontToBack && batch.size() > 1) sortFrontToBack(batch, depths[it->first]);
            it->second.mesh->setInstances(batch);
            ++it;
        }
    }
    if (box.isEmpty()) return {.centre = scene.camera.target, .radius = 1.0f};
    return {.centre = box.center(), .radius = std::max(box.diagonal().norm() / 2.0f, 1e-3f)};
}

void Renderer::drawShadowMap(const Mat4f& lightViewProjection) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
    gl_.Viewport(0, 0, settings_.shadowMapSize, settings_.shadowMapSize);
    gl_.ClearDepth(1.0);
    gl_.Clear(GL_DEPTH_BUFFER_BIT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LEQUAL);
    gl_.Disable(GL_CULL_FACE);
    // Slope-scaled offset keeps lit faces from shadowing themselves (acne).
    gl_.Enable(GL_POLYGON_OFFSET_FILL);
    gl_.PolygonOffset(2.0f, 4.0f);
    shadowProgram_->use();
    shadowProgram_->set("uLightViewProjection", lightViewProjection);
    for (const auto& [key, cached] : meshes_) cached.mesh->draw();
    gl_.Disable(GL_POLYGON_OFFSET_FILL);
}

void Renderer::drawSky(const RenderScene& scene, const Mat4f& viewProjection) {
    // Drawn after the opaque geometry, at the far plane with the depth test: only the pixels
    // nothing covers run its shader (a software rasteriser otherwise shades the whole view
    // twice where the ground lies), and the picture is the same.
    gl_.DepthFunc(GL_LEQUAL);
    gl_.DepthMask(GL_FALSE);
    skyProgram_->use();
    skyProgram_->set("uInverseViewProjection", Mat4f(viewProjection.inverse()));
    skyProgram_->set("uSkyZenith", scene.sky.zenith);
    skyProgram_->set("uSkyHorizon", scene.sky.horizon);
    skyProgram_->set("uSunDirection", scene.sun.direction.normalized());
    gl_.BindVertexArray(emptyVertexArray_);
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
    gl_.BindVertexArray(0);
    gl_.DepthMask(GL_TRUE);
}

void Renderer::setLighting(const ShaderProgram& program, const RenderScene& scene, const Mat4f& viewProjection,
                           const Mat4f& lightViewProjection, float fogDistance, float normalOffset) {
    program.use();
    program.set("uViewProjection", viewProjection);
    program.set("uSunDirection", Vec3f(scene.sun.direction.normalized()));
    program.set("uSunColour", Vec3f(toLinear(scene.sun.colour) * scene.sun.intensity));
    // Soft ambient: the sky from above, a dimmer bounce from the ground below.
    const Colour groundColour = scene.ground ? scene.ground->colour : Colour(0.5f, 0.5f, 0.5f);
    program.set("uSkyAmbient", Vec3f(toLinear(scene.sky.zenith) * 0.55f + Vec3f::Constant(0.06f)));
    program.set("uGroundAmbient", Vec3f(toLinear(groundColour) * 0.3f));
    program.set("uHorizonColour", toLinear(scene.sky.horizon));
    program.set("uCameraPosition", scene.camera.position);
    program.set("uFogDistance", fogDistance);
    program.set("uLightViewProjection", lightViewProjection);
    program.set("uShadowTexel", 1.0f / static_cast<float>(settings_.shadowMapSize));
    program.set("uShadowNormalOffset", normalOffset);
    program.set("uShadowMap", 0);
    program.set("uShadowFilter", shadowFilter(settings_.shadows));
}

void Renderer::drawGround(const RenderScene& scene, const Ground& ground, float halfExtent) {
    const Vec3f normal = ground.normal.normalized();
    const auto [tangent, bitangent] = planeBasis(normal);
    // Centred under the camera's target, so the visible part is always covered.
    const Vec3f target = scene.camera.target;
    const Vec3f centre = target - normal * (normal.dot(target) - ground.offset);
    const Vec3f corners[4] = {centre + halfExtent * (-tangent - bitangent), centre + halfExtent * (tangent - bitangent),
                              centre + halfExtent * (-tangent + bitangent), centre + halfExtent * (tangent + bitangent)};
    gl_.BindVertexArray(groundVertexArray_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, groundBuffer_);
    gl_.BufferData(GL_ARRAY_BUFFER, sizeof corners, corners[0].data(), GL_STREAM_DRAW);
    groundProgram_->set("uGroundNormal", normal);
    groundProgram_->set("uGroundTangent", tangent);
    groundProgram_->set("uGroundBitangent", bitangent);
    groundProgram_->set("uGroundColour", ground.colour);
    groundProgram_->set("uGridSpacing", ground.gridSpacing);
    gl_.Disable(GL_CULL_FACE);
    gl_.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    gl_.BindVertexArray(0);
}

void Renderer::drawMeshes() {
    lastTriangles_ = 0;
    for (const auto& [key, cached] : meshes_) {
        lastTriangles_ += cached.mesh->triangleCount() * cached.mesh->instanceCount();
        if (cached.closed)
            gl_.Enable(GL_CULL_FACE);
        else
            gl_.Disable(GL_CULL_FACE);
        cached.mesh->draw();
    }
    gl_.Disable(GL_CULL_FACE);
}

void Renderer::drawLines(const RenderScene& scene, const Mat4f& viewProjection) {
    if (scene.lines.empty()) return;
    std::vector<float> vertices;
    vertices.reserve(scene.lines.size() * 12);
    for (const DebugLine& line : scene.lines) {
        for (const Vec3f& point : {line.from, line.to}) {
            vertices.insert(vertices.end(), {point.x(), point.y(), point.z(), line.colour.x(), line.colour.y(),
                                             line.colour.z()});
        }
    }
    gl_.BindVertexArray(lineVertexArray_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(),
                   GL_STREAM_DRAW);
    lineProgram_->use();
    lineProgram_->set("uViewProjection", viewProjection);
    gl_.Enable(GL_BLEND);
    gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl_.DepthMask(GL_FALSE);
    // Joint frames sit inside bodies: show them faintly through the surface, fully where visible.
    const auto count = static_cast<GLsizei>(scene.lines.size() * 2);
    gl_.DepthFunc(GL_GREATER);
    lineProgram_->set("uOpacity", 0.2f);
    gl_.DrawArrays(GL_LINES, 0, count);
    gl_.DepthFunc(GL_LEQUAL);
    lineProgram_->set("uOpacity", 1.0f);
    gl_.DrawArrays(GL_LINES, 0, count);
    gl_.DepthMask(GL_TRUE);
    gl_.Disable(GL_BLEND);
    gl_.BindVertexArray(0);
}

void Renderer::render(const RenderScene& scene, const RenderTarget& target) {
    const float pixelsPerRadian =
        static_cast<float>(target.size.height) / (2.0f * std::tan(std::max(scene.camera.fovY, 1e-3f) / 2.0f));
    const Bounds bounds = batchInstances(scene, pixelsPerRadian);

    // The sun's view: an orthographic box around the scene's bounding sphere.
    const Vec3f sunDirection = scene.sun.direction.normalized();
    const Vec3f sunUp = std::abs(sunDirection.y()) > 0.99f ? Vec3f::UnitZ() : Vec3f::UnitY();
    const float r = bounds.radius;
    const Mat4f lightView = lookAt(bounds.centre + sunDirection * 2.0f * r, bounds.centre, sunUp);
    const Mat4f lightViewProjection = orthographic(-r, r, -r, r, 0.5f * r, 3.5f * r) * lightView;
    // Without shadows the pass is skipped: the shader then never reads the map.
    if (settings_.shadows != ShadowMode::Off) drawShadowMap(lightViewProjection);

    // The camera: near and far from the distance to the target, wide enough for the ground.
    const Camera& camera = scene.camera;
    const float viewDistance = std::max((camera.target - camera.position).norm(), 1e-3f);
    const float groundHalfExtent = std::max({50.0f, 30.0f * r, 4.0f * viewDistance});
    const float nearPlane = std::max(0.02f * viewDistance, 1e-3f);
    const float farPlane = 2.0f * groundHalfExtent + (camera.position - bounds.centre).norm() + r;
    const float aspect = static_cast<float>(target.size.width) / static_cast<float>(std::max(target.size.height, 1));
    const Mat4f viewProjection = perspective(camera.fovY, aspect, nearPlane, farPlane) *
                                 lookAt(camera.position, camera.target, camera.up);

    gl_.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    gl_.Viewport(target.originX, target.originY, target.size.width, target.size.height);
    // The clear is scissored to the target's area: a part of a window leaves the rest as drawn.
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(target.originX, target.originY, target.size.width, target.size.height);
    gl_.ClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    gl_.ClearDepth(1.0);
    gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_.Disable(GL_SCISSOR_TEST);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LEQUAL);

    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, shadowTexture_);
    const float fogDistance = 0.6f * groundHalfExtent;
    const float normalOffset = 3.0f * (2.0f * r / static_cast<float>(settings_.shadowMapSize));
    if (scene.ground) {
        setLighting(*groundProgram_, scene, viewProjection, lightViewProjection, fogDistance, normalOffset);
        drawGround(scene, *scene.ground, groundHalfExtent);
    }
    setLighting(*meshProgram_, scene, viewProjection, lightViewProjection, fogDistance, normalOffset);
    drawMeshes();
    drawSky(scene, viewProjection);
    drawLines(scene, viewProjection);

    const GLenum error = gl_.GetError();
    if (error != GL_NO_ERROR) throw std::runtime_error("rendering a frame: " + glErrorName(error));
}

}  // namespace substep::render
