#include "sampling/march.h"

#include <chrono>
#include <cmath>

#include "analytic/region_pass.h"
#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/shaders.h"

namespace sl::sampling {

namespace {

using gl::GL;
using gl::Parameter;

// Uniform locations of sampling/shaders/march.frag and march_resolve.frag.
namespace march_uniform {
constexpr GLint samples = 0, jitter = 1, clip_mode = 2, buffer_scale = 3, attenuation = 4,
                optical_thickness = 5, animate_phase = 6, time = 7, interval_mode = 8,
                clip_planes = 10;
}
namespace resolve_uniform {
constexpr GLint buffer_scale = 0, blur = 1;
}

constexpr double kScales[] = {1.0, 0.5, 0.25};

class MarchMethod final : public gl::VolumeMethod {
public:
    explicit MarchMethod(MarchVariant variant) : variant_(variant) {
        declare({.name = "samples",
                 .type = Parameter::Type::integer,
                 .default_value = 64,
                 .min = 1,
                 .max = 4096,
                 .description = variant == MarchVariant::march
                                    ? "samples per eye ray over its clipped trace"
                                    : "samples per eye ray over its uncertain interval"});
        declare({.name = "resolution_scale",
                 .type = Parameter::Type::choice,
                 .default_value = 0,
                 .description = "size of the marching buffer relative to the frame",
                 .choices = {"1", "0.5", "0.25"}});
        declare({.name = "blur",
                 .type = Parameter::Type::choice,
                 .default_value = 0,
                 .description = "none; gauss5 (Moschos alg. 3); depth_aware (no bleeding)",
                 .choices = {"none", "gauss5", "depth_aware"}});
        declare({.name = "jitter",
                 .type = Parameter::Type::integer,
                 .default_value = 0,
                 .min = 0,
                 .max = 1,
                 .description = "1: per-pixel offset of the samples (interleaved gradient noise)"});
        declare_shadow_parameters();
        if (variant == MarchVariant::march) {
            declare({.name = "clip",
                     .type = Parameter::Type::choice,
                     .default_value = 2,
                     .description = "off; pyramid (Moschos alg. 4); cone (exact cone and range)",
                     .choices = {"off", "pyramid", "cone"}});
            declare({.name = "attenuation",
                     .type = Parameter::Type::choice,
                     .default_value = 0,
                     .description = "model (the reference's); moschos (eq. 3.1, does NOT match "
                                    "the reference)",
                     .choices = {"model", "moschos"}});
            declare({.name = "optical_thickness",
                     .default_value = 15.0,
                     .min = 1e-3,
                     .max = 1e6,
                     .description = "metres: l of Moschos eq. 3.1 (attenuation=moschos)"});
            declare({.name = "animate_phase",
                     .type = Parameter::Type::integer,
                     .default_value = 0,
                     .min = 0,
                     .max = 1,
                     .description = "1: the phase function's g drifts with time and place"});
        }
    }

    std::string name() const override {
        return variant_ == MarchVariant::march ? "march" : "hybrid3";
    }

    void prepare(const Scene& scene) override {
        if (variant_ == MarchVariant::hybrid3) {
            analytic::AnalyticRegionPass::require_closed_form(scene, name());
            const auto start = std::chrono::steady_clock::now();
            const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
            const bt::Regions regions = bt::extract_regions(tree);
            const bt::RegionMesh lit = regions.mesh(bt::Region::lit);
            const bt::RegionMesh uncertain = regions.mesh(bt::Region::uncertain);
            beamtree_ms_ =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
            analytic_.upload(scene, lit.positions, lit.triangles);
            upload_uncertain(uncertain);
        }
        clip_planes_.clear();
        for (const bt::Plane& plane : bt::influence_planes(scene.light)) {
            clip_planes_.insert(clip_planes_.end(), {float(plane.normal.x), float(plane.normal.y),
                                                     float(plane.normal.z), float(plane.offset)});
        }
        if (!march_program_) {
            march_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                    {GL_FRAGMENT_SHADER, "sampling/shaders/march.frag"}});
            resolve_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                    {GL_FRAGMENT_SHADER, "sampling/shaders/march_resolve.frag"}});
            empty_vertex_array_ = gl::create_vertex_array();
        }
        frame_index_ = 0;
    }

    void render(const gl::VolumeInputs& inputs) override {
        GLint target = 0;
        GL.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
        const double scale = kScales[int(parameter("resolution_scale"))];
        allocate(inputs.width, inputs.height, scale);
        const bool hybrid = variant_ == MarchVariant::hybrid3;
        if (hybrid) {
            inputs.timeline.section("intervals");
            draw_intervals(inputs);
            for (GLuint unit = 1; unit <= 3; ++unit)
                GL.BindTextureUnit(unit, interval_textures_[unit - 1].id());
            GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
            GL.Viewport(0, 0, inputs.width, inputs.height);
            inputs.timeline.section("analytic");
            analytic_.draw(inputs, true);  // leaves units 1-3 (the intervals) bound
        }

        inputs.timeline.section("march");
        GL.BindFramebuffer(GL_FRAMEBUFFER, march_framebuffer_.id());
        GL.Viewport(0, 0, buffer_width_, buffer_height_);
        const float zero[4] = {0, 0, 0, 0};
        GL.ClearNamedFramebufferfv(march_framebuffer_.id(), GL_COLOR, 0, zero);
        GL.Disable(GL_BLEND);
        const GLuint program = march_program_.id();
        GL.UseProgram(program);
        GL.ProgramUniform1i(program, march_uniform::samples, int(parameter("samples")));
        GL.ProgramUniform1i(program, march_uniform::jitter, int(parameter("jitter")));
        GL.ProgramUniform1i(program, march_uniform::clip_mode, hybrid ? 2 : int(parameter("clip")));
        GL.ProgramUniform1f(program, march_uniform::buffer_scale, float(scale));
        GL.ProgramUniform1i(program, march_uniform::attenuation,
                            hybrid ? 0 : int(parameter("attenuation")));
        GL.ProgramUniform1f(program, march_uniform::optical_thickness,
                            hybrid ? 1.0f : float(parameter("optical_thickness")));
        GL.ProgramUniform1i(program, march_uniform::animate_phase,
                            hybrid ? 0 : int(parameter("animate_phase")));
        GL.ProgramUniform1f(program, march_uniform::time, float(frame_index_++) / 60.0f);
        GL.ProgramUniform1i(program, march_uniform::interval_mode, hybrid ? 1 : 0);
        GL.ProgramUniform4fv(program, march_uniform::clip_planes, 6, clip_planes_.data());
        GL.BindTextureUnit(0, inputs.surface_depth);
        GL.BindVertexArray(empty_vertex_array_.id());
        GL.DrawArrays(GL_TRIANGLES, 0, 3);

        inputs.timeline.section("resolve");
        GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
        GL.Viewport(0, 0, inputs.width, inputs.height);
        GL.UseProgram(resolve_program_.id());
        GL.ProgramUniform1f(resolve_program_.id(), resolve_uniform::buffer_scale, float(scale));
        GL.ProgramUniform1i(resolve_program_.id(), resolve_uniform::blur, int(parameter("blur")));
        GL.BindTextureUnit(0, inputs.surface_depth);
        GL.BindTextureUnit(1, march_target_.id());
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
        GL.Disable(GL_BLEND);
    }

    gl::MethodStatistics statistics() const override {
        // Samples evaluated: the marching buffer's alpha, summed (read back here, not timed).
        std::vector<float> rgba(size_t(buffer_width_) * buffer_height_ * 4);
        GL.GetTextureImage(march_target_.id(), 0, GL_RGBA, GL_FLOAT,
                           GLsizei(rgba.size() * sizeof(float)), rgba.data());
        double samples = 0.0;
        for (size_t i = 3; i < rgba.size(); i += 4)
            samples += rgba[i];
        gl::MethodStatistics stats = {{"samples_evaluated", samples},
                                      {"buffer_width", double(buffer_width_)},
                                      {"buffer_height", double(buffer_height_)}};
        if (variant_ == MarchVariant::hybrid3) {
            stats.insert(stats.end(), {{"cpu_ms_beamtree", beamtree_ms_},
                                       {"region_faces", double(analytic_.triangle_count())},
                                       {"uncertain_faces", double(uncertain_count_ / 3)},
                                       {"fragments_analytic", analytic_.fragments()}});
        }
        return stats;
    }

    gl::TextureViews textures() const override {
        if (!march_target_) {
            return {};
        }
        gl::TextureViews views = {
            {name() + "/marching buffer (rgb I_s, a samples)", march_target_.id()}};
        if (variant_ == MarchVariant::hybrid3) {
            const char* names[3] = {"uncertain entry", "uncertain exit", "camera inside"};
            for (int i = 0; i < 3; ++i) {
                views.push_back({name() + "/interval " + names[i], interval_textures_[i].id()});
            }
            for (gl::TextureView& view : analytic_.textures(name())) {
                views.push_back(std::move(view));
            }
        }
        return views;
    }

private:
    void allocate(int width, int height, double scale) {
        const int w = std::max(1, int(std::ceil(width * scale)));
        const int h = std::max(1, int(std::ceil(height * scale)));
        if (w == buffer_width_ && h == buffer_height_ && frame_width_ == width &&
            frame_height_ == height)
            return;
        buffer_width_ = w;
        buffer_height_ = h;
        frame_width_ = width;
        frame_height_ = height;
        march_target_ = gl::create_texture_2d(GL_RGBA32F, w, h, GL_NEAREST);
        march_target_.label("marching buffer");
        march_framebuffer_ = gl::create_framebuffer();
        GL.NamedFramebufferTexture(march_framebuffer_.id(), GL_COLOR_ATTACHMENT0,
                                   march_target_.id(), 0);
        if (variant_ == MarchVariant::hybrid3) {
            interval_framebuffer_ = gl::create_framebuffer();
            const GLenum attachments[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                           GL_COLOR_ATTACHMENT2};
            for (int i = 0; i < 3; ++i) {
                interval_textures_[i] = gl::create_texture_2d(GL_R32F, width, height, GL_NEAREST);
                GL.NamedFramebufferTexture(interval_framebuffer_.id(), attachments[i],
                                           interval_textures_[i].id(), 0);
            }
            GL.NamedFramebufferDrawBuffers(interval_framebuffer_.id(), 3, attachments);
        }
    }

    void upload_uncertain(const bt::RegionMesh& mesh) {
        uncertain_count_ = GLsizei(mesh.triangles.size() * 3);
        uncertain_vertices_ =
            gl::create_buffer(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
        uncertain_indices_ =
            gl::create_buffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
        uncertain_vertex_array_ = gl::create_vertex_array();
        const GLuint vao = uncertain_vertex_array_.id();
        GL.VertexArrayVertexBuffer(vao, 0, uncertain_vertices_.id(), 0, sizeof(glm::vec3));
        GL.VertexArrayElementBuffer(vao, uncertain_indices_.id());
        GL.EnableVertexArrayAttrib(vao, 0);
        GL.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        GL.VertexArrayAttribBinding(vao, 0, 0);
        if (!interval_program_) {
            interval_program_ = gl::create_program(
                {{GL_VERTEX_SHADER, "gl/shaders/world_position.vert"},
                 {GL_FRAGMENT_SHADER, "sampling/shaders/uncertain_interval.frag"}});
        }
    }

    // Nearest entry (MIN), farthest exit (MAX) and the camera-inside count (ADD) per pixel.
    void draw_intervals(const gl::VolumeInputs& inputs) {
        const GLuint fb = interval_framebuffer_.id();
        GL.BindFramebuffer(GL_FRAMEBUFFER, fb);
        GL.Viewport(0, 0, inputs.width, inputs.height);
        const float far_entry[4] = {1e30f, 0, 0, 0}, zero[4] = {0, 0, 0, 0};
        GL.ClearNamedFramebufferfv(fb, GL_COLOR, 0, far_entry);
        GL.ClearNamedFramebufferfv(fb, GL_COLOR, 1, zero);
        GL.ClearNamedFramebufferfv(fb, GL_COLOR, 2, zero);
        if (uncertain_count_ == 0)
            return;
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.BlendEquationi(0, GL_MIN);
        GL.BlendEquationi(1, GL_MAX);
        GL.BlendEquationi(2, GL_FUNC_ADD);
        GL.Enable(GL_DEPTH_CLAMP);
        GL.UseProgram(interval_program_.id());
        GL.BindVertexArray(uncertain_vertex_array_.id());
        GL.DrawElements(GL_TRIANGLES, uncertain_count_, GL_UNSIGNED_INT, nullptr);
        GL.Disable(GL_DEPTH_CLAMP);
        GL.BlendEquation(GL_FUNC_ADD);
        GL.Disable(GL_BLEND);
    }

    MarchVariant variant_;
    analytic::AnalyticRegionPass analytic_;
    gl::Program march_program_, resolve_program_, interval_program_;
    gl::VertexArray empty_vertex_array_;
    gl::Texture march_target_;
    gl::Framebuffer march_framebuffer_;
    gl::Texture interval_textures_[3];
    gl::Framebuffer interval_framebuffer_;
    gl::Buffer uncertain_vertices_, uncertain_indices_;
    gl::VertexArray uncertain_vertex_array_;
    GLsizei uncertain_count_ = 0;
    std::vector<float> clip_planes_;
    int buffer_width_ = 0, buffer_height_ = 0, frame_width_ = 0, frame_height_ = 0;
    int frame_index_ = 0;
    double beamtree_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<gl::VolumeMethod> create_march_method(MarchVariant variant) {
    return std::make_unique<MarchMethod>(variant);
}

}  // namespace sl::sampling
