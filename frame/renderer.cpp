#include "frame/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/trigonometric.hpp>

#include "core/check.h"
#include "core/error.h"
#include "frame/shaders/frame_interface.h"
#include "frame/shadow_fit.h"
#include "gl/debug.h"
#include "gl/shaders.h"
#include "gl/shaders/object_uniforms.h"

namespace sl::frame {

using gl::GL;

namespace {

// Normal offset of shadow lookups, in shadow-map texels at the receiver's distance.
constexpr float kShadowNormalOffsetTexels = 1.5f;

// A framebuffer of `size` x `size` (or width x height) texels whose targets the GL must have
// allocated: an incompleteness here is a size the driver could not give memory to (llvmpipe
// refuses any texture over 1 GiB: 16384² RGBA32F is 4 GiB), said as such.
void require_complete(GLuint framebuffer, const char* what, int width, int height) {
    const GLenum status = GL.CheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        const auto* renderer = reinterpret_cast<const char*>(GL.GetString(GL_RENDERER));
        fail(
            "the {} targets of {}x{} ({:.0f} MiB for each RGBA32F one) could not be allocated "
            "by {} (framebuffer status {:#x}): use a smaller size",
            what, width, height, double(width) * height * 16.0 / (1 << 20),
            renderer ? renderer : "the GL", status);
    }
}

// The largest texture and framebuffer side this GL takes.
int max_target_side() {
    GLint texture = 0, width = 0, height = 0;
    GL.GetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
    GL.GetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &width);
    GL.GetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &height);
    return std::min({texture, width, height});
}

// The frame's options, or a method's own `shadow` parameters.
void require_valid(const ShadowSettings& settings) {
    if (settings.map_size < 16 || settings.map_size > 16384) {
        fail("shadow map size {} must be in 16..16384", settings.map_size);
    }
    if (settings.radius < 0 || settings.radius > 8) {
        fail("shadow filter radius {} must be in 0..8", settings.radius);
    }
}

}  // namespace

gl::shared::FrameUniforms make_frame_uniforms(const Scene& scene, const RenderOptions& options) {
    const float aspect = options.aspect();
    const glm::mat4 view_projection = scene.camera.projection(aspect) * scene.camera.view();
    const SpotLight& light = scene.light;
    const Medium& medium = scene.medium;
    gl::shared::FrameUniforms u{};
    u.view_projection = view_projection;
    u.inverse_view_projection = glm::inverse(view_projection);
    u.light_view_projection = shadow_view_projection(light, scene.camera, aspect);
    u.camera_position = glm::vec4(scene.camera.position, 1.0f);
    u.camera_forward = glm::vec4(glm::normalize(scene.camera.target - scene.camera.position), 0.0f);
    u.light_position = glm::vec4(light.position, light.near);
    u.light_direction = glm::vec4(light.direction(), light.far);
    u.light_intensity = glm::vec4(light.intensity, 0.0f);
    u.light_cone = glm::vec4(glm::radians(light.cone_half_angle_degrees),
                             light.smooth_edge() ? glm::radians(light.falloff_degrees) : 0.0f,
                             light.shape == SpotShape::pyramid ? 1.0f : 0.0f, light.half_width);
    u.medium_sigma_s = glm::vec4(medium.sigma_s, float(int(medium.phase)));
    u.medium_sigma_t =
        glm::vec4(medium.sigma_t(), medium.model == MediumModel::physical ? 1.0f : 0.0f);
    u.medium_attenuation = glm::vec4(
        medium.a0, medium.a1, medium.phase == PhaseFunction::isotropic ? 0.0f : 1.0f, medium.g);
    u.ambient = glm::vec4(scene.ambient, 0.0f);
    u.shadow = shadow_uniform(options.shadow);
    u.display = glm::vec4(scene.camera.exposure, float(options.width), float(options.height), 0.0f);
    return u;
}

glm::vec4 shadow_uniform(const ShadowSettings& settings) {
    const int radius = settings.filter == ShadowFilter::pcf ? settings.radius : 0;
    return glm::vec4(1.0f / float(settings.map_size), float(radius), kShadowNormalOffsetTexels,
                     settings.filter == ShadowFilter::vsm ? 1.0f : 0.0f);
}

// The volume pass's sections, one GL_TIME_ELAPSED query each (queries are reused across frames).
class SceneRenderer::Timeline final : public PassTimeline {
public:
    // A new frame: no section open yet.
    void begin() {
        used_ = 0;
        names_.clear();
    }
    void begin(const std::string& first) {
        begin();
        section(first.c_str());
    }
    void section(const char* name) override {
        end();
        if (used_ == queries_.size())
            queries_.push_back(gl::create_query(GL_TIME_ELAPSED));
        names_.emplace_back(name);
        GL.BeginQuery(GL_TIME_ELAPSED, queries_[used_++].id());
        open_ = true;
    }
    void end() {
        if (open_)
            GL.EndQuery(GL_TIME_ELAPSED);
        open_ = false;
    }
    // Waits for the results; sections of the same name are summed.
    std::vector<std::pair<std::string, double>> results() const {
        std::vector<std::pair<std::string, double>> sections;
        for (size_t i = 0; i < used_; ++i) {
            GLuint64 ns = 0;
            GL.GetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &ns);
            auto same = std::find_if(sections.begin(), sections.end(),
                                     [&](const auto& s) { return s.first == names_[i]; });
            if (same == sections.end())
                sections.emplace_back(names_[i], double(ns) * 1e-6);
            else
                same->second += double(ns) * 1e-6;
        }
        return sections;
    }

private:
    std::vector<gl::Query> queries_;
    std::vector<std::string> names_;
    size_t used_ = 0;
    bool open_ = false;
};

// Times one pass with a GL_TIME_ELAPSED query; the result is read after the frame.
class SceneRenderer::PassTimer {
public:
    PassTimer(const gl::Query& query, const char* name) {
        GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
        GL.BeginQuery(GL_TIME_ELAPSED, query.id());
    }
    ~PassTimer() {
        GL.EndQuery(GL_TIME_ELAPSED);
        GL.PopDebugGroup();
    }
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;
};

// One pass of the frame, once per light: a section of its timeline (summed over the lights) and a
// debug group.
class SceneRenderer::GroupTimer {
public:
    GroupTimer(Timeline& timeline, const char* name) : timeline_(timeline) {
        GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
        timeline_.section(name);
    }
    ~GroupTimer() {
        timeline_.end();
        GL.PopDebugGroup();
    }
    GroupTimer(const GroupTimer&) = delete;
    GroupTimer& operator=(const GroupTimer&) = delete;

private:
    Timeline& timeline_;
};

SceneRenderer::SceneRenderer(const Scene& scene, const RenderOptions& options)
    : scene_(scene), options_(options) {
    if (options.width <= 0 || options.height <= 0 || options.width > 16384 ||
        options.height > 16384) {
        fail("render size {}x{} must be in 1..16384", options.width, options.height);
    }
    if (const int side = max_target_side(); options.width > side || options.height > side) {
        fail("render size {}x{} is beyond this GL's largest texture and framebuffer side, {}",
             options.width, options.height, side);
    }
    require_valid(options.shadow);  // before any GL work
    uniforms_ = make_frame_uniforms(scene, options);
    uniform_buffer_ = gl::create_buffer(&uniforms_, sizeof(uniforms_), GL_DYNAMIC_STORAGE_BIT);
    uniform_buffer_.label("frame uniforms");
    upload_meshes();
    create_programs();
    environment_ = std::make_unique<ibl::EnvironmentTextures>(scene);
    environment_->set_uniforms(uniforms_, scene.environment);
    if (scene.has_translucent_objects()) {
        subsurface_ = std::make_unique<sss::SubsurfacePass>(scene, options.width, options.height);
    }
    allocate_shadow(options.shadow);
    create_targets();
    create_timers();
    gl::check_errors("creating the scene renderer");
}

void SceneRenderer::upload_meshes() {
    for (const Object& object : scene_.objects) {
        const Mesh& mesh = *object.mesh;
        if (meshes_.contains(&mesh)) {
            continue;
        }
        std::vector<float> interleaved;
        interleaved.reserve(mesh.positions.size() * 6);
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::vec3 p = mesh.positions[i], n = mesh.normals[i];
            interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
        }
        GpuMesh gpu;
        gpu.vertices = gl::create_buffer(interleaved.data(), interleaved.size() * sizeof(float));
        gpu.indices =
            gl::create_buffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
        gpu.index_count = GLsizei(mesh.triangles.size() * 3);
        gpu.vertex_array = gl::create_vertex_array();
        const GLuint vao = gpu.vertex_array.id();
        GL.VertexArrayVertexBuffer(vao, 0, gpu.vertices.id(), 0, 6 * sizeof(float));
        GL.VertexArrayElementBuffer(vao, gpu.indices.id());
        for (GLuint attribute = 0; attribute < 2; ++attribute) {
            GL.EnableVertexArrayAttrib(vao, attribute);
            GL.VertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE,
                                       attribute * 3 * sizeof(float));
            GL.VertexArrayAttribBinding(vao, attribute, 0);
        }
        gpu.vertex_array.label(object.name);
        meshes_.emplace(&mesh, std::move(gpu));
    }
}

void SceneRenderer::create_programs() {
    shadow_program_ = gl::create_program({{GL_VERTEX_SHADER, "frame/shaders/shadow.vert"},
                                          {GL_FRAGMENT_SHADER, "frame/shaders/shadow.frag"}});
    shadow_moments_program_ =
        gl::create_program({{GL_VERTEX_SHADER, "frame/shaders/shadow.vert"},
                            {GL_FRAGMENT_SHADER, "frame/shaders/shadow_moments.frag"}});
    shadow_blur_program_ =
        gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                            {GL_FRAGMENT_SHADER, "frame/shaders/shadow_blur.frag"}});
    surface_program_ = gl::create_program({{GL_VERTEX_SHADER, "frame/shaders/surface.vert"},
                                           {GL_FRAGMENT_SHADER, "frame/shaders/surface.frag"}});
    composite_program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "frame/shaders/composite.frag"}});
    empty_vertex_array_ = gl::create_vertex_array();
}

void SceneRenderer::create_targets() {
    const int w = options_.width, h = options_.height;
    surface_color_ = gl::create_texture_2d(GL_RGBA32F, w, h, GL_NEAREST);
    surface_depth_ = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
    surface_framebuffer_ = gl::create_framebuffer();
    GL.NamedFramebufferTexture(surface_framebuffer_.id(), GL_COLOR_ATTACHMENT0, surface_color_.id(),
                               0);
    GL.NamedFramebufferTexture(surface_framebuffer_.id(), GL_DEPTH_ATTACHMENT, surface_depth_.id(),
                               0);
    require_complete(surface_framebuffer_.id(), "surface", w, h);

    in_scattering_ = gl::create_texture_2d(GL_RGBA32F, w, h, GL_NEAREST);
    volume_framebuffer_ = gl::create_framebuffer();
    GL.NamedFramebufferTexture(volume_framebuffer_.id(), GL_COLOR_ATTACHMENT0, in_scattering_.id(),
                               0);
    require_complete(volume_framebuffer_.id(), "in-scattering", w, h);

    hdr_ = gl::create_texture_2d(GL_RGBA32F, w, h, GL_NEAREST);
    display_ = gl::create_texture_2d(GL_RGBA8, w, h, GL_NEAREST);
    composite_framebuffer_ = gl::create_framebuffer();
    GL.NamedFramebufferTexture(composite_framebuffer_.id(), GL_COLOR_ATTACHMENT0, hdr_.id(), 0);
    GL.NamedFramebufferTexture(composite_framebuffer_.id(), GL_COLOR_ATTACHMENT1, display_.id(), 0);
    const GLenum attachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    GL.NamedFramebufferDrawBuffers(composite_framebuffer_.id(), 2, attachments);
    require_complete(composite_framebuffer_.id(), "composite", w, h);
}

void SceneRenderer::create_timers() {
    composite_timer_ = gl::create_query(GL_TIME_ELAPSED);
    subsurface_timer_ = gl::create_query(GL_TIME_ELAPSED);
    timeline_ = std::make_unique<Timeline>();
    shadow_timeline_ = std::make_unique<Timeline>();
    surface_timeline_ = std::make_unique<Timeline>();
    // llvmpipe reports its first GL_TIME_ELAPSED query of a context from time zero (since boot):
    // spend that first query here, on a clear, so that every frame's timings are real.
    const gl::Query priming = gl::create_query(GL_TIME_ELAPSED);
    GL.BeginQuery(GL_TIME_ELAPSED, priming.id());
    const float one = 1.0f;
    GL.DepthMask(GL_TRUE);  // depth clears obey the mask
    GL.ClearNamedFramebufferfv(shadow_framebuffer_.id(), GL_DEPTH, 0, &one);
    GL.EndQuery(GL_TIME_ELAPSED);
    GLuint64 ns = 0;
    GL.GetQueryObjectui64v(priming.id(), GL_QUERY_RESULT, &ns);
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::allocate_shadow(const ShadowSettings& settings) {
    require_valid(settings);
    const int size = settings.map_size;
    // The frame's map or a method's own: either must fit this GL.
    if (const int side = max_target_side(); size > side) {
        fail("shadow map size {} is beyond this GL's largest texture side, {}", size, side);
    }
    shadow_ = settings;
    // Depth compared in the sampler; linear filtering adds 2x2 PCF per tap, nearest keeps the
    // hard variant hard.
    shadow_map_ =
        gl::create_texture_2d(GL_DEPTH_COMPONENT32F, size, size,
                              settings.filter == ShadowFilter::pcf ? GL_LINEAR : GL_NEAREST);
    GL.TextureParameteri(shadow_map_.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    GL.TextureParameteri(shadow_map_.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    shadow_map_.label("shadow map");
    const bool vsm = settings.filter == ShadowFilter::vsm;
    shadow_moments_ = gl::create_texture_2d(GL_RG32F, vsm ? size : 1, vsm ? size : 1, GL_LINEAR);
    shadow_moments_.label("shadow moments");
    shadow_framebuffer_ = gl::create_framebuffer();
    GL.NamedFramebufferTexture(shadow_framebuffer_.id(), GL_DEPTH_ATTACHMENT, shadow_map_.id(), 0);
    if (vsm) {
        GL.NamedFramebufferTexture(shadow_framebuffer_.id(), GL_COLOR_ATTACHMENT0,
                                   shadow_moments_.id(), 0);
        GL.NamedFramebufferDrawBuffer(shadow_framebuffer_.id(), GL_COLOR_ATTACHMENT0);
        shadow_scratch_ = gl::create_texture_2d(GL_RG32F, size, size, GL_NEAREST);
        const GLuint targets[2] = {shadow_scratch_.id(), shadow_moments_.id()};
        for (int i = 0; i < 2; ++i) {
            shadow_blur_framebuffer_[i] = gl::create_framebuffer();
            GL.NamedFramebufferTexture(shadow_blur_framebuffer_[i].id(), GL_COLOR_ATTACHMENT0,
                                       targets[i], 0);
            require_complete(shadow_blur_framebuffer_[i].id(), "shadow blur", size, size);
        }
    } else {
        GL.NamedFramebufferDrawBuffer(shadow_framebuffer_.id(), GL_NONE);
        shadow_scratch_ = gl::Texture();
    }
    require_complete(shadow_framebuffer_.id(), "shadow map", size, size);
    uniforms_.shadow = shadow_uniform(settings);
}

void SceneRenderer::draw_objects(GLuint program, bool with_normals) {
    for (size_t i = 0; i < scene_.objects.size(); ++i) {
        draw_object(i, program, with_normals);
    }
}

void SceneRenderer::draw_object(size_t index, GLuint program, bool with_normals) {
    const Object& object = scene_.objects[index];
    GL.ProgramUniformMatrix4fv(program, SL_OBJECT_MODEL, 1, GL_FALSE,
                               glm::value_ptr(object.transform));
    if (with_normals) {
        const glm::mat4 normal_matrix = glm::inverseTranspose(object.transform);
        GL.ProgramUniformMatrix4fv(program, SL_OBJECT_NORMAL_MATRIX, 1, GL_FALSE,
                                   glm::value_ptr(normal_matrix));
    }
    if (program == surface_program_.id()) {
        const Material& material = scene_.materials[size_t(object.material)];
        GL.ProgramUniform1f(program, SL_SURFACE_ROUGHNESS, material.roughness);
        const sss::SubsurfaceMaterial* translucent =
            subsurface_ ? subsurface_->material_of(object.material) : nullptr;
        if (translucent) {
            // Subsurface scattering replaces the diffuse term (sss/subsurface_pass.h); the
            // surface keeps a dielectric specular with F0 from η and, under the ambient light,
            // the profile's total reflectance as its albedo.
            const double eta = material.translucency->medium.eta;
            const float f0 = float((eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0)));
            const glm::vec3 black(0.0f), f0s(f0);
            GL.ProgramUniform3fv(program, SL_SURFACE_ALBEDO, 1, glm::value_ptr(black));
            GL.ProgramUniform3fv(program, SL_SURFACE_F0, 1, glm::value_ptr(f0s));
            GL.ProgramUniform4fv(program, SL_SURFACE_TRANSLUCENT, 1,
                                 glm::value_ptr(glm::vec4(1.0f, translucent->total_reflectance)));
        } else {
            GL.ProgramUniform3fv(program, SL_SURFACE_ALBEDO, 1, glm::value_ptr(material.albedo));
            GL.ProgramUniform3fv(program, SL_SURFACE_F0, 1, glm::value_ptr(material.f0));
            GL.ProgramUniform4fv(program, SL_SURFACE_TRANSLUCENT, 1,
                                 glm::value_ptr(glm::vec4(0.0f)));
        }
    }
    const GpuMesh& mesh = meshes_.at(object.mesh.get());
    GL.BindVertexArray(mesh.vertex_array.id());
    GL.DrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
}

FrameTimings SceneRenderer::draw(VolumeMethod& method) {
    const auto start = std::chrono::steady_clock::now();
    // Several lights (docs/design.md §17): per light, its shadow map, its term on the surfaces
    // and its I_s, each added to the first light's; the method holds an instance per light.
    const size_t lights = scene_.lights.empty() ? 1 : scene_.spot_lights().size();
    const bool whole = method.takes_every_light();
    // Prepared (or updated) for this scene's lights.
    SL_CHECK(method.light_count() == (whole ? 1 : lights));
    if (const ShadowSettings wanted = method.shadow_settings(options_.shadow); wanted != shadow_) {
        allocate_shadow(wanted);
    }
    shadow_timeline_->begin();
    surface_timeline_->begin();
    timeline_->begin();
    for (size_t i = 0; i < lights; ++i) {
        const Scene light_scene = lights == 1 ? Scene() : scene_.for_light(i);
        const Scene& view = lights == 1 ? scene_ : light_scene;
        uniforms_ = make_frame_uniforms(view, options_);
        uniforms_.shadow = shadow_uniform(shadow_);
        environment_->set_uniforms(uniforms_, scene_.environment);
        GL.BindBufferBase(GL_UNIFORM_BUFFER, SL_FRAME_UNIFORMS_BINDING, uniform_buffer_.id());
        GL.NamedBufferSubData(uniform_buffer_.id(), 0, sizeof(uniforms_), &uniforms_);
        GL.Disable(GL_BLEND);
        GL.Disable(GL_CULL_FACE);  // open meshes (planes) must cast shadows from both sides
        {
            GroupTimer timer(*shadow_timeline_, "shadow map");
            draw_shadow_map();
        }
        {
            GroupTimer timer(*surface_timeline_, "surfaces");
            draw_surfaces(i > 0);
        }
        if (subsurface_ && i == 0) {  // once: it splats every light itself (sss/subsurface_pass.h)
            PassTimer timer(subsurface_timer_, "subsurface");
            subsurface_->render(
                [this](size_t index, GLuint program) { draw_object(index, program, true); },
                uniforms_.view_projection, surface_depth_.id(), surface_framebuffer_.id(),
                frame_index_++);
            // Its maps took texture units the methods share: give them back the shadow maps.
            GL.BindTextureUnit(SL_SHADOW_MAP_UNIT, shadow_map_.id());
            GL.BindTextureUnit(SL_SHADOW_MOMENTS_UNIT, shadow_moments_.id());
        }
        if (!whole) {
            draw_volume(method.for_light(i), view, i > 0);
        }
    }
    if (whole) {
        draw_volume(method, scene_, false);
    }
    {
        PassTimer timer(composite_timer_, "composite");
        draw_composite();
    }
    GL.DepthMask(GL_TRUE);
    FrameTimings timings = read_timings();
    gl::check_errors(("rendering with method " + method.name()).c_str());
    timings.cpu_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return timings;
}

void SceneRenderer::draw_shadow_map() {
    const int size = shadow_.map_size;
    GL.BindFramebuffer(GL_FRAMEBUFFER, shadow_framebuffer_.id());
    GL.Viewport(0, 0, size, size);
    const float one = 1.0f;
    GL.DepthMask(GL_TRUE);  // depth clears obey the mask
    GL.ClearNamedFramebufferfv(shadow_framebuffer_.id(), GL_DEPTH, 0, &one);
    const bool vsm = shadow_.filter == ShadowFilter::vsm;
    if (vsm) {
        const float far_moments[4] = {1.0f, 1.0f, 0.0f, 0.0f};
        GL.ClearNamedFramebufferfv(shadow_framebuffer_.id(), GL_COLOR, 0, far_moments);
    }
    GL.Enable(GL_DEPTH_TEST);
    GL.DepthFunc(GL_LESS);
    GL.DepthMask(GL_TRUE);
    GL.Enable(GL_POLYGON_OFFSET_FILL);
    GL.PolygonOffset(2.0f, 4.0f);  // slope-scaled bias against shadow acne
    // The light's range bounds where it scatters, not what casts shadows (the beam tree and
    // the reference see occluders from the light outward): an occluder between the light
    // and its near plane is clamped to depth 0 (and keeps its linear depth in the VSM
    // moments) instead of being clipped away, so it shadows everything in range behind it.
    GL.Enable(GL_DEPTH_CLAMP);
    const GLuint program = vsm ? shadow_moments_program_.id() : shadow_program_.id();
    GL.UseProgram(program);
    for (size_t i = 0; i < scene_.objects.size(); ++i) {
        if (scene_.casts_shadow(scene_.objects[i])) {  // glass lets the light through
            draw_object(i, program, false);
        }
    }
    GL.Disable(GL_DEPTH_CLAMP);
    GL.Disable(GL_POLYGON_OFFSET_FILL);
    if (vsm && shadow_.radius > 0) {
        blur_shadow_moments();
    }
}

void SceneRenderer::blur_shadow_moments() {
    // Separable Gaussian: moments -> scratch (x), scratch -> moments (y).
    GL.Disable(GL_DEPTH_TEST);
    GL.UseProgram(shadow_blur_program_.id());
    GL.ProgramUniform1i(shadow_blur_program_.id(), SL_SHADOW_BLUR_RADIUS, shadow_.radius);
    GL.BindVertexArray(empty_vertex_array_.id());
    const GLuint sources[2] = {shadow_moments_.id(), shadow_scratch_.id()};
    for (int i = 0; i < 2; ++i) {
        GL.BindFramebuffer(GL_FRAMEBUFFER, shadow_blur_framebuffer_[i].id());
        GL.ProgramUniform2i(shadow_blur_program_.id(), SL_SHADOW_BLUR_DIRECTION, i == 0, i == 1);
        GL.BindTextureUnit(SL_SHADOW_BLUR_SOURCE_UNIT, sources[i]);
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    GL.Enable(GL_DEPTH_TEST);
}

void SceneRenderer::draw_surfaces(bool add_light) {
    GL.BindFramebuffer(GL_FRAMEBUFFER, surface_framebuffer_.id());
    GL.Viewport(0, 0, options_.width, options_.height);
    GL.UseProgram(surface_program_.id());
    GL.BindTextureUnit(SL_SHADOW_MAP_UNIT, shadow_map_.id());
    GL.BindTextureUnit(SL_SHADOW_MOMENTS_UNIT, shadow_moments_.id());
    GL.Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    GL.ProgramUniform1i(surface_program_.id(), SL_SURFACE_LIGHT_ONLY, add_light ? 1 : 0);
    if (add_light) {
        // A further light: its term on the surfaces the first pass left in the depth buffer,
        // added (the alpha stays).
        GL.DepthFunc(GL_LEQUAL);
        GL.DepthMask(GL_FALSE);
        GL.Enable(GL_BLEND);
        GL.BlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
        draw_objects(surface_program_.id(), true);
        GL.Disable(GL_BLEND);
        GL.DepthMask(GL_TRUE);
        GL.DepthFunc(GL_LESS);
        return;
    }
    const float black[4] = {0, 0, 0, 0};
    const float far_depth = 1.0f;
    GL.ClearNamedFramebufferfv(surface_framebuffer_.id(), GL_COLOR, 0, black);
    GL.ClearNamedFramebufferfv(surface_framebuffer_.id(), GL_DEPTH, 0, &far_depth);
    environment_->bind();
    draw_objects(surface_program_.id(), true);
    if (environment_->enabled() && scene_.environment.skybox) {
        environment_->draw_skybox();  // the depth buffer stays as the methods expect
    }
}

void SceneRenderer::draw_volume(VolumeMethod& method, const Scene& scene, bool add_light) {
    // Timed by the method's timeline sections (queries of one target cannot nest). The
    // section's query and the debug group end with the scope, also when the method refuses its
    // parameters mid-frame (a froxel grid too large for the image).
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "volume");
    struct VolumePassEnd {
        Timeline& timeline;
        ~VolumePassEnd() {
            timeline.end();
            GL.PopDebugGroup();
        }
    } pass_end{*timeline_};
    timeline_->section(method.name().c_str());
    // Every method only adds into its target (VolumeMethod::render), so a further light's
    // instance adds its I_s straight onto the lights drawn before it: the target is cleared once.
    GL.BindFramebuffer(GL_FRAMEBUFFER, volume_framebuffer_.id());
    if (!add_light) {
        const float zero[4] = {0, 0, 0, 0};
        GL.ClearNamedFramebufferfv(volume_framebuffer_.id(), GL_COLOR, 0, zero);
    }
    GL.Disable(GL_DEPTH_TEST);
    GL.DepthMask(GL_FALSE);
    method.render(VolumeInputs{scene, uniforms_, surface_depth_.id(), shadow_map_.id(),
                               options_.width, options_.height, *timeline_});
}

void SceneRenderer::draw_composite() {
    GL.BindFramebuffer(GL_FRAMEBUFFER, composite_framebuffer_.id());
    GL.Viewport(0, 0, options_.width, options_.height);
    GL.Disable(GL_DEPTH_TEST);
    GL.Disable(GL_BLEND);
    GL.UseProgram(composite_program_.id());
    GL.BindTextureUnit(SL_COMPOSITE_SURFACE_UNIT, surface_color_.id());
    GL.BindTextureUnit(SL_COMPOSITE_IN_SCATTERING_UNIT, in_scattering_.id());
    GL.BindVertexArray(empty_vertex_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
}

FrameTimings SceneRenderer::read_timings() const {
    FrameTimings timings;
    {  // waits for the frame to finish
        GLuint64 ns = 0;
        GL.GetQueryObjectui64v(composite_timer_.id(), GL_QUERY_RESULT, &ns);
        timings.gpu.composite_ms = double(ns) * 1e-6;
    }
    for (const auto& [name, ms] : shadow_timeline_->results()) {
        timings.gpu.shadow_ms += ms;
    }
    for (const auto& [name, ms] : surface_timeline_->results()) {
        timings.gpu.surface_ms += ms;
    }
    if (subsurface_) {
        GLuint64 ns = 0;
        GL.GetQueryObjectui64v(subsurface_timer_.id(), GL_QUERY_RESULT, &ns);
        timings.gpu.subsurface_ms = double(ns) * 1e-6;
    }
    timings.gpu.volume_sections = timeline_->results();
    for (const auto& [name, ms] : timings.gpu.volume_sections) {
        timings.gpu.volume_ms += ms;
    }
    return timings;
}

gl::TextureViews SceneRenderer::textures() const {
    gl::TextureViews views = {{"frame/shadow map", shadow_map_.id()},
                              {"frame/surface depth", surface_depth_.id()},
                              {"frame/surface radiance", surface_color_.id()},
                              {"frame/in-scattering I_s", in_scattering_.id()},
                              {"frame/radiance (HDR)", hdr_.id()},
                              {"frame/display", display_.id()}};
    if (shadow_.filter == ShadowFilter::vsm) {
        views.insert(views.begin() + 1, {"frame/shadow moments", shadow_moments_.id()});
    }
    for (const gl::TextureView& view : environment_->textures()) {
        views.push_back(view);
    }
    return views;
}

Frame SceneRenderer::read_back() const {
    const int w = options_.width, h = options_.height;
    Frame frame;
    frame.radiance = read_rgb(hdr_.id());
    frame.in_scattering = read_rgb(in_scattering_.id());
    frame.surface = read_rgb(surface_color_.id());
    std::vector<uint8_t> rgba(size_t(w) * h * 4);
    GL.PixelStorei(GL_PACK_ALIGNMENT, 1);
    GL.GetTextureImage(display_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()),
                       rgba.data());
    frame.display_srgb8.resize(size_t(w) * h * 3);
    for (int y = 0; y < h; ++y) {  // GL rows run bottom to top
        for (int x = 0; x < w; ++x) {
            const size_t src = (size_t(h - 1 - y) * w + x) * 4, dst = (size_t(y) * w + x) * 3;
            std::copy_n(&rgba[src], 3, &frame.display_srgb8[dst]);
        }
    }
    std::vector<float> depth(size_t(w) * h);
    GL.GetTextureImage(surface_depth_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                       GLsizei(depth.size() * sizeof(float)), depth.data());
    frame.depth.resize(depth.size());
    for (int y = 0; y < h; ++y) {
        std::copy_n(&depth[size_t(h - 1 - y) * w], w, &frame.depth[size_t(y) * w]);
    }
    gl::check_errors("reading the frame back");
    // Before anything is written from it: a NaN or an infinity in any buffer is a failure of the
    // method or the input, never an output.
    require_finite(frame.in_scattering, "I_s (in-scattering)");
    require_finite(frame.surface, "surface radiance");
    require_finite(frame.radiance, "HDR radiance (I_eye)");
    return frame;
}

Frame SceneRenderer::render(VolumeMethod& method) {
    const FrameTimings timings = draw(method);
    Frame frame = read_back();
    frame.gpu = timings.gpu;
    frame.cpu_ms = timings.cpu_ms;
    return frame;
}

Image SceneRenderer::read_rgb(GLuint texture) const {
    const int w = options_.width, h = options_.height;
    std::vector<float> rgba(size_t(w) * h * 4);
    GL.GetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                       rgba.data());
    Image image(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t src = (size_t(h - 1 - y) * w + x) * 4;
            image.set(x, y, {rgba[src], rgba[src + 1], rgba[src + 2]});
        }
    }
    return image;
}

}  // namespace sl::frame
