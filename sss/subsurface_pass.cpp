#include "sss/subsurface_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <variant>

#include <glm/gtc/type_ptr.hpp>
#include <glm/trigonometric.hpp>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/shaders.h"
#include "gl/shaders/frame_uniforms.h"
#include "sss/diffusion.h"
#include "sss/layers.h"
#include "sss/shaders/subsurface_interface.h"
#include "sss/surface_samples.h"

namespace sl::sss {

using gl::Framebuffer;
using gl::GL;
using gl::Texture;

namespace {

constexpr int kThicknessRows = 64;
constexpr int kFootprintLevels = 8;
constexpr float kZero[4] = {0.0f, 0.0f, 0.0f, 0.0f};

Texture create_profile_array(int width, int height, int layers) {
    GLuint id = 0;
    GL.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    GL.TextureStorage3D(id, 1, GL_RGBA32F, width, height, layers);
    GL.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    GL.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    GL.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    GL.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return Texture(id);
}

void upload_layer(const Texture& texture, int width, int height, int layer,
                  const std::vector<glm::vec3>& rows) {
    GL.TextureSubImage3D(texture.id(), 0, 0, 0, layer, width, height, 1, GL_RGB, GL_FLOAT,
                         rows.data());
}

void attach(const Framebuffer& framebuffer, std::initializer_list<GLuint> colours, GLuint depth,
            const char* what) {
    std::vector<GLenum> buffers;
    for (const GLuint texture : colours) {
        const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + buffers.size());
        GL.NamedFramebufferTexture(framebuffer.id(), attachment, texture, 0);
        buffers.push_back(attachment);
    }
    if (depth) {
        GL.NamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth, 0);
    }
    GL.NamedFramebufferDrawBuffers(framebuffer.id(), GLsizei(buffers.size()), buffers.data());
    const GLenum status = GL.CheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        fail("{} framebuffer is incomplete (status {:#x})", what, status);
    }
}

// Every light the translucent objects take: the scene's (its `[light]`, or every spot light and
// point-light face of its `[[lights]]`), then [sss]'s own.
std::vector<SpotLight> lights_of(const Scene& scene) {
    std::vector<SpotLight> lights = scene.spot_lights();
    lights.insert(lights.end(), scene.subsurface.lights.begin(), scene.subsurface.lights.end());
    return lights;
}

// One translucent material's profiles, tabulated before the first frame (§5.1): R (and T for
// the multipole) as kThicknessRows rows of `texels` radii.
struct TabulatedMaterial {
    SubsurfaceMaterial material;
    std::vector<glm::vec3> R, T;
};

TabulatedMaterial tabulate(const Translucency& t, const Subsurface& settings) {
    const int texels = settings.profile_texels;
    TabulatedMaterial out;
    SubsurfaceMaterial& sm = out.material;
    const RgbDiffusion d = RgbDiffusion::of(t.medium);
    sm.r_max_mm = splat_radius(d, settings.epsilon, settings.flux_radius);
    const double sigma_t_mean =
        (d[0].sigma_t_reduced + d[1].sigma_t_reduced + d[2].sigma_t_reduced) / 3.0;
    sm.d_min_mm = 4.0 / sigma_t_mean;
    sm.d_max_mm = 64.0 / sigma_t_mean;
    std::vector<glm::vec3>& R = out.R;
    R.assign(size_t(texels * kThicknessRows), glm::vec3(0.0f));
    out.T.assign(R.size(), glm::vec3(0.0f));
    if (!t.coats.empty()) {
        // Coats over a semi-infinite base, combined in frequency space (§5.1.2).
        std::vector<Layer> layers = t.coats;
        layers.push_back({t.medium, 0.0});
        for (const Layer& layer : layers) {
            sm.r_max_mm =
                std::max(sm.r_max_mm, splat_radius(RgbDiffusion::of(layer.material),
                                                   settings.epsilon, settings.flux_radius));
        }
        const LayeredProfile p = layered_profile(layers, sm.r_max_mm, 256, texels);
        for (int row = 0; row < kThicknessRows; ++row) {
            std::copy(p.reflectance.texels.begin(), p.reflectance.texels.end(),
                      R.begin() + row * texels);
        }
        sm.total_reflectance = glm::vec3(p.total_R);
        return out;
    }
    if (t.model == DiffusionModel::multipole) {
        SlabProfiles p =
            tabulate_multipole(d, sm.r_max_mm, sm.d_min_mm, sm.d_max_mm, texels, kThicknessRows);
        R = std::move(p.R);
        out.T = std::move(p.T);
        sm.multipole = true;
    } else {
        const RadialProfile p = tabulate_dipole(d, sm.r_max_mm, texels);
        for (int row = 0; row < kThicknessRows; ++row) {
            std::copy(p.texels.begin(), p.texels.end(), R.begin() + row * texels);
        }
    }
    for (int c = 0; c < 3; ++c) {
        sm.total_reflectance[c] = float(total_diffuse_reflectance(d[c]));
    }
    return out;
}

// Row `row` of a tabulated profile as a function of r, linearly interpolated, zero beyond r_max.
std::function<glm::vec3(double)> profile_row(const std::vector<glm::vec3>& table, int row,
                                             int texels, double r_max_mm) {
    return [texels, r_max_mm, values = table.data() + size_t(row * texels)](double r) {
        const double x = r / r_max_mm * (texels - 1);
        if (x >= texels - 1) {
            return glm::vec3(0.0f);
        }
        const int j = int(x);
        const float f = float(x - j);
        return values[j] * (1.0f - f) + values[j + 1] * f;
    };
}

// The profiles averaged over a disk of radius rho (FootprintLevels): every row of a multipole,
// else the one row every thickness shares.
void average_over_disk(const TabulatedMaterial& tabulated, int texels, double rho,
                       std::vector<glm::vec3>& R, std::vector<glm::vec3>& T) {
    const SubsurfaceMaterial& sm = tabulated.material;
    const bool rows_differ = sm.multipole;
    for (int row = 0; row < (rows_differ ? kThicknessRows : 1); ++row) {
        const std::vector<glm::vec3> r_row = disk_average(
            profile_row(tabulated.R, row, texels, sm.r_max_mm), sm.r_max_mm, texels, rho);
        std::copy(r_row.begin(), r_row.end(), R.begin() + row * texels);
        if (rows_differ) {
            const std::vector<glm::vec3> t_row = disk_average(
                profile_row(tabulated.T, row, texels, sm.r_max_mm), sm.r_max_mm, texels, rho);
            std::copy(t_row.begin(), t_row.end(), T.begin() + row * texels);
        }
    }
    if (!rows_differ) {
        for (int row = 1; row < kThicknessRows; ++row) {
            std::copy(R.begin(), R.begin() + texels, R.begin() + row * texels);
        }
    }
}

}  // namespace

SubsurfacePass::SubsurfacePass(const Scene& scene, int width, int height)
    : scene_(scene), width_(width), height_(height) {
    for (const LightSource& light : scene.lights) {
        if (std::holds_alternative<DirectionalLight>(light)) {
            fail(
                "scene '{}': translucent objects (sss) take spot and point lights; its "
                "[[lights]] has a directional light, whose parallel beams the splats do not "
                "model: light it with spot or point lights, or use no translucent material",
                scene.name);
        }
    }
    upload_profiles();
    if (scene.environment.enabled() && scene.subsurface.environment_samples > 0) {
        build_environment_samples();
    }
    create_programs();
    create_targets();
    gl::check_errors("creating the subsurface pass");
}

void SubsurfacePass::upload_profiles() {
    const Subsurface& settings = scene_.subsurface;
    const int texels = settings.profile_texels;
    // The profiles of every translucent material in use (§5.1: tabulated once, before the first
    // frame).
    std::vector<TabulatedMaterial> tabulated;
    for (size_t m = 0; m < scene_.materials.size(); ++m) {
        const std::optional<Translucency>& t = scene_.materials[m].translucency;
        const bool used = std::any_of(scene_.objects.begin(), scene_.objects.end(),
                                      [&](const Object& o) { return size_t(o.material) == m; });
        if (!t || !used) {
            continue;
        }
        tabulated.push_back(tabulate(*t, settings));
        SubsurfaceMaterial& sm = tabulated.back().material;
        sm.material = int(m);
        sm.layer = int(materials_.size());
        any_multipole_ = any_multipole_ || sm.multipole;
        materials_.push_back(sm);
    }
    if (materials_.empty()) {
        fail("subsurface pass: the scene has no translucent object");
    }
    // Footprint levels (FootprintLevels): each material's rows averaged over disks of
    // growing radius, layer = material layer x levels + level.
    const int levels = settings.footprint ? kFootprintLevels : 1;
    profile_R_ = create_profile_array(texels, kThicknessRows, int(materials_.size()) * levels);
    profile_T_ = create_profile_array(texels, kThicknessRows, int(materials_.size()) * levels);
    for (size_t i = 0; i < materials_.size(); ++i) {
        const FootprintLevels footprint{levels, materials_[i].r_max_mm / 4.0};
        for (int k = 0; k < levels; ++k) {
            const double rho = footprint.radius(k);
            std::vector<glm::vec3> R = tabulated[i].R, T = tabulated[i].T;
            if (rho > 0.0) {
                average_over_disk(tabulated[i], texels, rho, R, T);
            }
            upload_layer(profile_R_, texels, kThicknessRows, int(i) * levels + k, R);
            upload_layer(profile_T_, texels, kThicknessRows, int(i) * levels + k, T);
        }
    }
    profile_R_.label("subsurface R profiles");
    profile_T_.label("subsurface T profiles");
}

void SubsurfacePass::build_environment_samples() {
    // Uniform samples for the environment (§5.3.1): 5x random candidates, eliminated to N.
    const auto start = std::chrono::steady_clock::now();
    for (size_t i = 0; i < scene_.objects.size(); ++i) {
        const Object& object = scene_.objects[i];
        if (!scene_.materials[size_t(object.material)].translucency) {
            continue;
        }
        const size_t n = size_t(scene_.subsurface.environment_samples);
        const SurfaceSamples samples = eliminate_samples(
            random_surface_points(*object.mesh, object.transform, 5 * n, 1 + i), n);
        std::vector<float> interleaved;
        for (size_t k = 0; k < samples.positions.size(); ++k) {
            const glm::vec3 p = samples.positions[k], nn = samples.normals[k];
            interleaved.insert(interleaved.end(), {p.x, p.y, p.z, nn.x, nn.y, nn.z});
        }
        EnvironmentSamples e;
        e.object = i;
        e.count = GLsizei(samples.positions.size());
        e.area_per_sample = float(samples.area / double(e.count));
        e.vertices = gl::create_buffer(interleaved.data(), interleaved.size() * sizeof(float));
        e.vertex_array = gl::create_vertex_array();
        GL.VertexArrayVertexBuffer(e.vertex_array.id(), 0, e.vertices.id(), 0, 6 * sizeof(float));
        for (GLuint a = 0; a < 2; ++a) {
            GL.EnableVertexArrayAttrib(e.vertex_array.id(), a);
            GL.VertexArrayAttribFormat(e.vertex_array.id(), a, 3, GL_FLOAT, GL_FALSE,
                                       a * 3 * sizeof(float));
            GL.VertexArrayAttribBinding(e.vertex_array.id(), a, 0);
        }
        stats_.environment_samples += size_t(e.count);
        environment_.push_back(std::move(e));
    }
    stats_.sample_elimination_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void SubsurfacePass::create_programs() {
    gbuffer_program_ = gl::create_program({{GL_VERTEX_SHADER, "sss/shaders/gbuffer.vert"},
                                           {GL_FRAGMENT_SHADER, "sss/shaders/gbuffer.frag"}});
    splat_program_ = gl::create_program({{GL_VERTEX_SHADER, "sss/shaders/splat_light.vert"},
                                         {GL_GEOMETRY_SHADER, "sss/shaders/splat.geom"},
                                         {GL_FRAGMENT_SHADER, "sss/shaders/splat.frag"}});
    points_program_ = gl::create_program({{GL_VERTEX_SHADER, "sss/shaders/splat_points.vert"},
                                          {GL_GEOMETRY_SHADER, "sss/shaders/splat.geom"},
                                          {GL_FRAGMENT_SHADER, "sss/shaders/splat.frag"}});
    area_program_ = gl::create_program({{GL_VERTEX_SHADER, "sss/shaders/splat_light.vert"},
                                        {GL_GEOMETRY_SHADER, "sss/shaders/visible_area.geom"},
                                        {GL_FRAGMENT_SHADER, "sss/shaders/visible_area.frag"}});
    combine_program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                           {GL_FRAGMENT_SHADER, "sss/shaders/combine.frag"}});
    empty_vertex_array_ = gl::create_vertex_array();
}

void SubsurfacePass::create_targets() {
    eye_positions_ = gl::create_texture_2d(GL_RGBA32F, width_, height_, GL_NEAREST);
    eye_normals_ = gl::create_texture_2d(GL_RGBA32F, width_, height_, GL_NEAREST);
    eye_framebuffer_ = gl::create_framebuffer();
    const int size = scene_.subsurface.map_size;
    light_positions_ = gl::create_texture_2d(GL_RGBA32F, size, size, GL_NEAREST);
    light_normals_ = gl::create_texture_2d(GL_RGBA32F, size, size, GL_NEAREST);
    light_depth_ = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, size, size, GL_NEAREST);
    light_framebuffer_ = gl::create_framebuffer();
    attach(light_framebuffer_, {light_positions_.id(), light_normals_.id()}, light_depth_.id(),
           "subsurface light map");
    back_positions_ = gl::create_texture_2d(GL_RGBA32F, any_multipole_ ? size : 1,
                                            any_multipole_ ? size : 1, GL_NEAREST);
    if (any_multipole_) {
        back_scratch_ = gl::create_texture_2d(GL_RGBA32F, size, size, GL_NEAREST);
        back_depth_ = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, size, size, GL_NEAREST);
        back_framebuffer_ = gl::create_framebuffer();
        attach(back_framebuffer_, {back_positions_.id(), back_scratch_.id()}, back_depth_.id(),
               "subsurface thickness");
    }
    area_sums_ = gl::create_texture_2d(GL_RGBA32F, 1, 1, GL_NEAREST);
    area_framebuffer_ = gl::create_framebuffer();
    attach(area_framebuffer_, {area_sums_.id()}, 0, "subsurface visible area");
    scatter_ = gl::create_texture_2d(GL_RGBA32F, width_, height_, GL_NEAREST);
    scatter_framebuffer_ = gl::create_framebuffer();
    attach(scatter_framebuffer_, {scatter_.id()}, 0, "subsurface scatter");
}

SubsurfacePass::~SubsurfacePass() = default;

const SubsurfaceMaterial* SubsurfacePass::material_of(int scene_material) const {
    for (const SubsurfaceMaterial& m : materials_) {
        if (m.material == scene_material) {
            return &m;
        }
    }
    return nullptr;
}

glm::vec4 SubsurfacePass::region_of_interest(size_t index, const SpotLight& light) const {
    // The object's bounding box projected into the light's map; the whole map when a corner is
    // behind the light (§5.1, figure 5.3).
    const Object& object = scene_.objects[index];
    const Bounds b = object.mesh->bounds();
    const glm::mat4 view_projection = light.projection() * light.view();
    glm::vec2 lo(1.0f), hi(0.0f);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 local((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                              (k & 4) ? b.max.z : b.min.z);
        const glm::vec4 clip = view_projection * object.transform * glm::vec4(local, 1.0f);
        if (clip.w <= 1e-6f) {
            return {0.0f, 0.0f, 1.0f, 1.0f};
        }
        const glm::vec2 uv = 0.5f * (glm::vec2(clip) / clip.w) + 0.5f;
        lo = glm::min(lo, uv);
        hi = glm::max(hi, uv);
    }
    lo = glm::clamp(lo, 0.0f, 1.0f);
    hi = glm::clamp(hi, 0.0f, 1.0f);
    return {lo, glm::max(hi - lo, glm::vec2(0.0f))};
}

void SubsurfacePass::set_light(GLuint program, const SpotLight& light) const {
    const float half_angle = glm::radians(light.cone_half_angle_degrees);
    GL.ProgramUniform4fv(program, SL_SSS_LIGHT_POSITION, 1,
                         glm::value_ptr(glm::vec4(light.position, std::tan(half_angle))));
    GL.ProgramUniform4fv(program, SL_SSS_LIGHT_DIRECTION, 1,
                         glm::value_ptr(glm::vec4(light.direction(), half_angle)));
    GL.ProgramUniform4fv(
        program, SL_SSS_LIGHT_INTENSITY, 1,
        glm::value_ptr(glm::vec4(
            light.intensity, light.smooth_edge() ? glm::radians(light.falloff_degrees) : 0.0f)));
    GL.ProgramUniform4fv(
        program, SL_SSS_LIGHT_RANGE, 1,
        glm::value_ptr(glm::vec4(light.near, light.far,
                                 light.shape == SpotShape::pyramid ? 1.0f : 0.0f, 0.0f)));
}

void SubsurfacePass::set_material(GLuint program, size_t object) const {
    const Object& o = scene_.objects[object];
    const SubsurfaceMaterial& m = *material_of(o.material);
    const Translucency& t = *scene_.materials[size_t(o.material)].translucency;
    const float mm = scene_.subsurface.mm_per_unit;
    GL.ProgramUniform4fv(program, SL_SSS_MATERIAL, 1,
                         glm::value_ptr(glm::vec4(float(m.r_max_mm) / mm, mm, float(t.medium.eta),
                                                  m.multipole ? 1.0f : 0.0f)));
    const float weighting = scene_.subsurface.weighting == SplatWeighting::seed ? 1.0f : 0.0f;
    const int levels = scene_.subsurface.footprint ? kFootprintLevels : 1;
    GL.ProgramUniform4fv(program, SL_SSS_SLAB, 1,
                         glm::value_ptr(glm::vec4(float(m.d_min_mm), float(m.d_max_mm),
                                                  float(m.layer * levels), weighting)));
    GL.ProgramUniform4fv(
        program, SL_SSS_FOOTPRINT, 1,
        glm::value_ptr(glm::vec4(float(m.r_max_mm / 4.0), float(levels), 0.0f, 0.0f)));
    GL.ProgramUniform1f(program, SL_SSS_OBJECT, float(object + 1));
}

std::vector<size_t> SubsurfacePass::translucent_objects() const {
    std::vector<size_t> translucent;
    for (size_t i = 0; i < scene_.objects.size(); ++i) {
        if (scene_.materials[size_t(scene_.objects[i].material)].translucency) {
            translucent.push_back(i);
        }
    }
    return translucent;
}

void SubsurfacePass::render(const DrawObject& draw, const glm::mat4& view_projection,
                            GLuint surface_depth, GLuint surface_framebuffer, uint32_t frame) {
    stats_.lights = 0;
    stats_.splat_draws = 0;
    stats_.grid_samples = 0;
    const std::vector<size_t> translucent = translucent_objects();
    draw_eye_gbuffer(draw, view_projection, surface_depth, translucent);

    GL.ClearNamedFramebufferfv(scatter_framebuffer_.id(), GL_COLOR, 0, kZero);
    GL.BindTextureUnit(SL_SSS_LIGHT_POSITIONS_UNIT, light_positions_.id());
    GL.BindTextureUnit(SL_SSS_LIGHT_NORMALS_UNIT, light_normals_.id());
    GL.BindTextureUnit(SL_SSS_BACK_POSITIONS_UNIT, back_positions_.id());
    GL.BindTextureUnit(SL_SSS_EYE_POSITIONS_UNIT, eye_positions_.id());
    GL.BindTextureUnit(SL_SSS_EYE_NORMALS_UNIT, eye_normals_.id());
    GL.BindTextureUnit(SL_SSS_PROFILE_R_UNIT, profile_R_.id());
    GL.BindTextureUnit(SL_SSS_PROFILE_T_UNIT, profile_T_.id());
    GL.BindTextureUnit(SL_SSS_VISIBLE_AREA_UNIT, area_sums_.id());
    for (const SpotLight& light : lights_of(scene_)) {
        ++stats_.lights;
        draw_light_maps(draw, light, translucent);
        splat_light(light, translucent, frame);
    }
    if (!environment_.empty()) {
        splat_environment();
    }
    composite(surface_framebuffer);
}

void SubsurfacePass::draw_eye_gbuffer(const DrawObject& draw, const glm::mat4& view_projection,
                                      GLuint surface_depth,
                                      const std::vector<size_t>& translucent) {
    // The eye G-buffer of the translucent objects, where the surface pass saw them.
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "subsurface eye");
    attach(eye_framebuffer_, {eye_positions_.id(), eye_normals_.id()}, surface_depth,
           "subsurface eye");
    GL.BindFramebuffer(GL_FRAMEBUFFER, eye_framebuffer_.id());
    GL.Viewport(0, 0, width_, height_);
    GL.ClearNamedFramebufferfv(eye_framebuffer_.id(), GL_COLOR, 0, kZero);
    GL.ClearNamedFramebufferfv(eye_framebuffer_.id(), GL_COLOR, 1, kZero);
    GL.Enable(GL_DEPTH_TEST);
    GL.DepthFunc(GL_LEQUAL);
    GL.DepthMask(GL_FALSE);
    const GLuint gbuffer = gbuffer_program_.id();
    GL.UseProgram(gbuffer);
    GL.ProgramUniformMatrix4fv(gbuffer, SL_SSS_VIEW_PROJECTION, 1, GL_FALSE,
                               glm::value_ptr(view_projection));
    for (const size_t i : translucent) {
        GL.ProgramUniform1f(gbuffer, SL_SSS_GBUFFER_OBJECT, float(i + 1));
        draw(i, gbuffer);
    }
    GL.DepthMask(GL_TRUE);
    GL.DepthFunc(GL_LESS);
    GL.PopDebugGroup();
}

void SubsurfacePass::draw_light_maps(const DrawObject& draw, const SpotLight& light,
                                     const std::vector<size_t>& translucent) {
    // Light-view positions and normals of everything (occluders too: their ids differ).
    const int size = scene_.subsurface.map_size;
    const float one = 1.0f;
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "subsurface light map");
    GL.BindFramebuffer(GL_FRAMEBUFFER, light_framebuffer_.id());
    GL.Viewport(0, 0, size, size);
    GL.ClearNamedFramebufferfv(light_framebuffer_.id(), GL_COLOR, 0, kZero);
    GL.ClearNamedFramebufferfv(light_framebuffer_.id(), GL_COLOR, 1, kZero);
    GL.ClearNamedFramebufferfv(light_framebuffer_.id(), GL_DEPTH, 0, &one);
    GL.Enable(GL_DEPTH_TEST);
    const GLuint gbuffer = gbuffer_program_.id();
    GL.UseProgram(gbuffer);
    GL.ProgramUniformMatrix4fv(gbuffer, SL_SSS_VIEW_PROJECTION, 1, GL_FALSE,
                               glm::value_ptr(light.projection() * light.view()));
    // As the frame's shadow map: what lies between the light and its near plane still
    // occludes (clamped to the map's near plane, its positions kept), not clipped away.
    GL.Enable(GL_DEPTH_CLAMP);
    for (size_t i = 0; i < scene_.objects.size(); ++i) {
        if (scene_.casts_shadow(scene_.objects[i])) {  // glass lets the light through
            GL.ProgramUniform1f(gbuffer, SL_SSS_GBUFFER_OBJECT, float(i + 1));
            draw(i, gbuffer);
        }
    }
    GL.Disable(GL_DEPTH_CLAMP);
    if (any_multipole_) {
        // The far side of each translucent object: its back faces, farthest first (§5.1.2).
        const float nothing = 0.0f;
        GL.BindFramebuffer(GL_FRAMEBUFFER, back_framebuffer_.id());
        GL.ClearNamedFramebufferfv(back_framebuffer_.id(), GL_COLOR, 0, kZero);
        GL.ClearNamedFramebufferfv(back_framebuffer_.id(), GL_DEPTH, 0, &nothing);
        GL.DepthFunc(GL_GREATER);
        GL.Enable(GL_CULL_FACE);
        GL.CullFace(GL_FRONT);
        for (const size_t i : translucent) {
            GL.ProgramUniform1f(gbuffer, SL_SSS_GBUFFER_OBJECT, float(i + 1));
            draw(i, gbuffer);
        }
        GL.Disable(GL_CULL_FACE);
        GL.CullFace(GL_BACK);
        GL.DepthFunc(GL_LESS);
    }
    GL.Disable(GL_DEPTH_TEST);
    GL.PopDebugGroup();
}

void SubsurfacePass::splat_light(const SpotLight& light, const std::vector<size_t>& translucent,
                                 uint32_t frame) {
    const Subsurface& settings = scene_.subsurface;
    const GLsizei grid_count = settings.grid_x * settings.grid_y;
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "subsurface splats");
    GL.Enable(GL_BLEND);
    GL.BlendEquation(GL_FUNC_ADD);
    GL.BlendFunc(GL_ONE, GL_ONE);
    GL.BindVertexArray(empty_vertex_array_.id());
    for (const size_t i : translucent) {
        const glm::vec4 roi = region_of_interest(i, light);
        if (roi.z <= 0.0f || roi.w <= 0.0f) {
            continue;
        }
        const glm::ivec4 grid(settings.grid_x, settings.grid_y, int(frame * 7919u + i),
                              settings.jitter ? 1 : 0);
        for (const GLuint program : {area_program_.id(), splat_program_.id()}) {
            set_light(program, light);
            set_material(program, i);
            GL.ProgramUniform4fv(program, SL_SSS_ROI, 1, glm::value_ptr(roi));
            GL.ProgramUniform4i(program, SL_SSS_GRID, grid.x, grid.y, grid.z, grid.w);
        }
        if (settings.weighting == SplatWeighting::seed) {
            // Σ ΔA and N_s of this light's valid samples for A_vis / N_s.
            const GLuint area = area_program_.id();
            GL.ProgramUniform4fv(area, SL_SSS_SLAB, 1,
                                 glm::value_ptr(glm::vec4(0.0f, 0.0f, 0.0f, 2.0f)));
            GL.BindFramebuffer(GL_FRAMEBUFFER, area_framebuffer_.id());
            GL.Viewport(0, 0, 1, 1);
            GL.ClearNamedFramebufferfv(area_framebuffer_.id(), GL_COLOR, 0, kZero);
            GL.UseProgram(area);
            GL.DrawArrays(GL_POINTS, 0, grid_count);
        }
        GL.BindFramebuffer(GL_FRAMEBUFFER, scatter_framebuffer_.id());
        GL.Viewport(0, 0, width_, height_);
        GL.UseProgram(splat_program_.id());
        GL.DrawArrays(GL_POINTS, 0, grid_count);
        ++stats_.splat_draws;
        stats_.grid_samples += size_t(grid_count);
    }
    GL.Disable(GL_BLEND);
    GL.PopDebugGroup();
}

void SubsurfacePass::splat_environment() {
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "subsurface environment");
    GL.BindFramebuffer(GL_FRAMEBUFFER, scatter_framebuffer_.id());
    GL.Viewport(0, 0, width_, height_);
    GL.Enable(GL_BLEND);
    GL.BlendFunc(GL_ONE, GL_ONE);
    const GLuint points = points_program_.id();
    GL.UseProgram(points);
    for (const EnvironmentSamples& e : environment_) {
        set_material(points, e.object);
        GL.ProgramUniform1f(points, SL_SSS_AREA_PER_SAMPLE, e.area_per_sample);
        GL.BindVertexArray(e.vertex_array.id());
        GL.DrawArrays(GL_POINTS, 0, e.count);
    }
    GL.Disable(GL_BLEND);
    GL.PopDebugGroup();
}

void SubsurfacePass::composite(GLuint surface_framebuffer) {
    // The deferred composite: scattered radiance onto the surface colour, attenuated to the eye.
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "subsurface composite");
    GL.BindFramebuffer(GL_FRAMEBUFFER, surface_framebuffer);
    GL.Viewport(0, 0, width_, height_);
    GL.Enable(GL_BLEND);
    GL.BlendFunc(GL_ONE, GL_ONE);
    GL.UseProgram(combine_program_.id());
    GL.BindTextureUnit(SL_SSS_SCATTER_UNIT, scatter_.id());
    GL.BindVertexArray(empty_vertex_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    GL.Disable(GL_BLEND);
    GL.PopDebugGroup();
}

}  // namespace sl::sss
