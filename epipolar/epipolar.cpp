#include "epipolar/epipolar.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "analytic/gpu_tables.h"
#include "analytic/region_pass.h"
#include "analytic/shaders/analytic_interface.h"
#include "core/error.h"
#include "epipolar/geometry.h"
#include "epipolar/shaders/epipolar_interface.h"
#include "frame/method_registry.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/shaders.h"

namespace sl::epipolar {

namespace {

using gl::GL;

// The choices, in the order declared.
enum class LitIntegral { closed_form, samples };

constexpr int kMaxStep = 256;
constexpr int kMaxSamples = 1 << 22;  // slices x samples_per_slice: 64 MiB per RGBA32F texture

// shaders/epipolar.glsl's Counters block: march.comp's indirect dispatch, then the statistics.
struct Counters {
    uint32_t march_groups = 0, march_groups_y = 1, march_groups_z = 1;
    uint32_t marched_samples = 0, lit_samples = 0, tree_lookups = 0, fixup_pixels = 0,
             fixup_samples = 0;
};

// The frame's light as the slice geometry takes it (Views::light): its position, or for parallel
// beams (light_cone.w > 0, a directional light) the point at infinity they come from.
glm::dvec4 light_point(const gl::shared::FrameUniforms& uniforms) {
    if (uniforms.light_cone.w > 0.0f) {
        return glm::dvec4(-glm::dvec3(uniforms.light_direction), 0.0);
    }
    return glm::dvec4(glm::dvec3(uniforms.light_position), 1.0);
}

class EpipolarMethod final : public frame::VolumeMethod {
public:
    EpipolarMethod() : VolumeMethod("epipolar") {
        slices_ = declare_integer("slices", 512, 1, 8192,
                                  "epipolar lines from the light's screen position to the border");
        samples_per_slice_ =
            declare_integer("samples_per_slice", 256, 2, 8192,
                            "samples on each line, evenly from its entry to its exit");
        max_step_ = declare_integer("max_step", 16, 1, kMaxStep,
                                    "samples between two marched ones at most (more are marched "
                                    "at depth discontinuities)");
        depth_threshold_ = declare_real("depth_threshold", 0.03, 0.0, 1e3,
                                        "view depths further apart than this fraction of the "
                                        "nearer are a discontinuity (refinement and the bilateral "
                                        "unwarp)");
        samples_ = declare_integer("samples", 64, 1, 4096,
                                   "steps per marched eye ray over its interval in the cone");
        lit_integral_ =
            declare_choice("lit_integral", {"closed_form", "samples"}, LitIntegral::closed_form,
                           "closed_form: a lit run of steps adds G(z1) - G(z0) (Chen "
                           "et al.); samples: its steps' densities (any medium)");
        minmax_ = declare_flag("minmax", true,
                               "on: the 1D min-max tree skips lit and dark runs; off: every step "
                               "tests the rectified line");
        interpolation_ =
            declare_flag("interpolation", true,
                         "off: every pixel is marched directly through the shadow map (= march)");
        declare_shadow_parameters(frame::ShadowFilter::hard);
    }
    void validate() const override {
        const double samples = double(*slices_) * double(*samples_per_slice_);
        if (samples > double(kMaxSamples)) {
            fail(
                "epipolar: slices x samples_per_slice = {} x {} = {} samples, more than the {} "
                "it keeps (four RGBA32F textures of that size); lower slices or "
                "samples_per_slice",
                *slices_, *samples_per_slice_, samples, kMaxSamples);
        }
    }

    std::string accepts() const override {
        return "every light type (a sun's lines meet at its point on screen, or at the "
               "anti-solar point); every medium with lit_integral = samples; with closed_form "
               "(the default): " +
               analytic::AnalyticRegionPass::accepts();
    }

    void prepare_light(const Scene& scene) override {
        if (!coordinates_program_) {
            const auto compute = [](const char* path) {
                return gl::create_program({{GL_COMPUTE_SHADER, path}});
            };
            coordinates_program_ = compute("epipolar/shaders/coordinates.comp");
            refine_program_ = compute("epipolar/shaders/refine.comp");
            rectify_program_ = compute("epipolar/shaders/rectify.comp");
            minmax_program_ = compute("epipolar/shaders/minmax.comp");
            interpolate_program_ = compute("epipolar/shaders/interpolate.comp");
            apply_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                    {GL_FRAGMENT_SHADER, "epipolar/shaders/apply.frag"}});
            overlay_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "epipolar/shaders/overlay.vert"},
                                    {GL_FRAGMENT_SHADER, "epipolar/shaders/overlay.frag"}});
            empty_vertex_array_ = gl::create_vertex_array();
            plain_sampler_ = gl::create_plain_sampler(GL_NEAREST);
            slices_buffer_ = gl::create_mutable_buffer();
            const Counters zero;
            counters_ = gl::create_buffer(&zero, sizeof(zero), GL_DYNAMIC_STORAGE_BIT);
        }
        update_light(scene, SceneChange::everything(scene));
    }

    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene& scene,
                                                       const SceneChange&) const override {
        if (*lit_integral_ == LitIntegral::closed_form) {
            analytic::AnalyticRegionPass::require_closed_form(scene, name());
        }
        return nullptr;  // the slice table is made per frame in render(), from the frame's views
    }
    void apply_update_light(const Scene& scene, const SceneChange&,
                            std::unique_ptr<frame::FrameWork>) override {
        make_march_program(scene);
    }

    void render(const frame::VolumeInputs& inputs) override {
        GLint target = 0;
        GL.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
        const Counters zero;
        GL.NamedBufferSubData(counters_.id(), 0, sizeof(zero), &zero);
        const bool direct = !*interpolation_;
        int map_size = 0;
        GL.GetTextureLevelParameteriv(inputs.shadow_map, 0, GL_TEXTURE_WIDTH, &map_size);
        const int texels = map_texels(map_size);
        const int levels = *minmax_ ? int(std::round(std::log2(double(texels)))) : 0;
        validate();  // the viewer may hold a combination that failed it
        const glm::ivec2 grid(*samples_per_slice_, *slices_);
        const Views views{
            .view_projection = glm::dmat4(inputs.uniforms.view_projection),
            .light_view_projection = glm::dmat4(inputs.uniforms.light_view_projection),
            .camera = glm::dvec3(inputs.uniforms.camera_position),
            .light = light_point(inputs.uniforms),
            .width = inputs.width,
            .height = inputs.height};
        set_uniforms(views, grid, texels, levels, direct);
        GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_EPIPOLAR_COUNTERS_BINDING, counters_.id());
        valid_slices_ = 0;
        if (!direct) {
            place_samples(inputs, views, grid, texels);
            march_samples(inputs, grid, texels, levels);
        }
        apply(inputs, direct);
        frame_pixels_ = double(inputs.width) * inputs.height;
        drawn_grid_ = direct ? glm::ivec2(0) : grid;
        if (overlay_wanted_ && !direct) {
            draw_overlay(inputs);
            GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
            GL.Viewport(0, 0, inputs.width, inputs.height);
        }
    }

    // What every pass shares: the grid, the light on screen and its exit arc, the map and the
    // march's settings.
    void set_uniforms(const Views& views, glm::ivec2 grid, int texels, int levels, bool direct) {
        const glm::dvec2 screen = light_screen_position(views);
        const ExitArc arc = exit_arc(screen, views.width, views.height);
        light_on_screen_ = inside_image(screen, views.width, views.height);
        for (const gl::Program* program : {&coordinates_program_, &refine_program_,
                                           &rectify_program_, &march_program_, &apply_program_}) {
            const GLuint id = program->id();
            GL.ProgramUniform2i(id, SL_EPIPOLAR_GRID, grid.x, grid.y);
            GL.ProgramUniform2f(id, SL_EPIPOLAR_LIGHT_SCREEN, float(screen.x), float(screen.y));
            GL.ProgramUniform3f(id, SL_EPIPOLAR_ARC, float(arc.start), float(arc.length),
                                arc.periodic ? 1.0f : 0.0f);
            GL.ProgramUniform1i(id, SL_EPIPOLAR_MAP_TEXELS, texels);
            GL.ProgramUniform1f(id, SL_EPIPOLAR_DEPTH_THRESHOLD, float(*depth_threshold_));
            GL.ProgramUniform1i(id, SL_EPIPOLAR_MAX_STEP, *max_step_);
            GL.ProgramUniform1i(id, SL_EPIPOLAR_SAMPLES, *samples_);
            GL.ProgramUniform1i(id, SL_EPIPOLAR_MINMAX_LEVELS, levels);
            GL.ProgramUniform1i(id, SL_EPIPOLAR_DIRECT, direct ? 1 : 0);
        }
    }

    // The epipolar slices, their samples' screen coordinates and depths, and the samples that
    // must be marched (depth breaks, every max_step-th).
    void place_samples(const frame::VolumeInputs& inputs, const Views& views, glm::ivec2 grid,
                       int texels) {
        inputs.timeline.section("slices");
        GL.BindTextureUnit(SL_EPIPOLAR_LIGHT_DEPTH_UNIT, inputs.shadow_map);
        GL.BindSampler(SL_EPIPOLAR_LIGHT_DEPTH_UNIT,
                       plain_sampler_.id());  // depths, not comparisons
        upload_slices(make_slices(views, grid.y, texels));
        allocate(grid, texels);
        GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_EPIPOLAR_MARCHED_LIST_BINDING,
                          marched_list_.id());
        GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_EPIPOLAR_SLICES_BINDING,
                          slices_buffer_.id());

        inputs.timeline.section("coordinates");
        GL.UseProgram(coordinates_program_.id());
        GL.BindTextureUnit(SL_EPIPOLAR_SURFACE_DEPTH_UNIT, inputs.surface_depth);
        GL.BindImageTexture(SL_EPIPOLAR_COORDINATES_IMAGE, coordinates_.id(), 0, GL_FALSE, 0,
                            GL_WRITE_ONLY, GL_RGBA32F);
        gl::dispatch_compute({grid.x, grid.y, 1}, {64, 1, 1});

        inputs.timeline.section("refine");
        GL.UseProgram(refine_program_.id());
        GL.BindTextureUnit(SL_EPIPOLAR_COORDINATES_UNIT, coordinates_.id());
        GL.BindImageTexture(SL_EPIPOLAR_MARKS_IMAGE, marks_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                            GL_R32I);
        gl::dispatch_compute({grid.x, grid.y, 1}, {64, 1, 1});
    }

    // The min-max trees of the rectified shadow map, the marched samples, and the rest
    // interpolated between them.
    void march_samples(const frame::VolumeInputs& inputs, glm::ivec2 grid, int texels, int levels) {
        inputs.timeline.section("min-max trees");
        GL.UseProgram(rectify_program_.id());
        GL.BindImageTexture(SL_EPIPOLAR_TREE_IMAGE, tree_.id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                            GL_RG32F);
        gl::dispatch_compute({texels / 64, grid.y, 1}, {64, 1, 1});
        if (levels > 6) {  // 1 to 6 by rectify.comp
            GL.UseProgram(minmax_program_.id());
            GL.ProgramUniform3i(minmax_program_.id(), SL_EPIPOLAR_TREE_LEVELS, levels, texels,
                                grid.y);
            gl::dispatch_compute({grid.y, 1, 1}, {64, 1, 1});
        }

        inputs.timeline.section("march");
        GL.UseProgram(march_program_.id());
        GL.BindTextureUnit(SL_EPIPOLAR_TREE_UNIT, tree_.id());
        GL.BindTextureUnit(SL_MEDIUM_TABLE_UNIT, closed_form_.medium_table());
        GL.BindImageTexture(SL_EPIPOLAR_SCATTERING_IMAGE, scattering_.id(), 0, GL_FALSE, 0,
                            GL_WRITE_ONLY, GL_RGBA32F);
        GL.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, counters_.id());
        GL.DispatchComputeIndirect(0);  // refine.comp's count of marched samples
        GL.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        GL.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                         GL_SHADER_STORAGE_BARRIER_BIT);

        inputs.timeline.section("interpolate");
        GL.UseProgram(interpolate_program_.id());
        GL.BindTextureUnit(SL_EPIPOLAR_MARKS_UNIT, marks_.id());
        GL.ProgramUniform2i(interpolate_program_.id(), SL_EPIPOLAR_GRID, grid.x, grid.y);
        GL.BindImageTexture(SL_EPIPOLAR_SCATTERING_IMAGE, scattering_.id(), 0, GL_FALSE, 0,
                            GL_READ_WRITE, GL_RGBA32F);
        gl::dispatch_compute({grid.x, grid.y, 1}, {64, 1, 1});
    }

    // Each pixel's I_s from its slice's samples (or marched directly), added to the frame's.
    void apply(const frame::VolumeInputs& inputs, bool direct) {
        inputs.timeline.section("apply");
        GL.UseProgram(apply_program_.id());
        GL.BindTextureUnit(SL_EPIPOLAR_SURFACE_DEPTH_UNIT, inputs.surface_depth);
        if (!direct) {
            GL.BindTextureUnit(SL_EPIPOLAR_COORDINATES_UNIT, coordinates_.id());
            GL.BindTextureUnit(SL_EPIPOLAR_SCATTERING_UNIT, scattering_.id());
        }
        GL.BindVertexArray(empty_vertex_array_.id());
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
        GL.Disable(GL_BLEND);
        GL.BindSampler(SL_EPIPOLAR_LIGHT_DEPTH_UNIT, 0);
        GL.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    }

    frame::MethodStatistics statistics() const override {
        Counters counters;
        GL.GetNamedBufferSubData(counters_.id(), 0, sizeof(counters), &counters);
        return {{"slices", double(drawn_grid_.y)},
                {"valid_slices", double(valid_slices_)},
                {"samples_per_slice", double(drawn_grid_.x)},
                {"marched_samples", double(counters.marched_samples)},
                {"tree_lookups", double(counters.tree_lookups)},
                {"fixup_pixels", double(counters.fixup_pixels)},
                {"fixup_share", frame_pixels_ > 0 ? counters.fixup_pixels / frame_pixels_ : 0.0},
                {"samples_evaluated", double(counters.lit_samples) + counters.fixup_samples},
                {"light_on_screen", light_on_screen_ ? 1.0 : 0.0}};
    }

    // The overlay is drawn by the frame after the one that asked for it (the previewer asks every
    // frame it shows it), so frames nobody looks at do not pay for it.
    gl::TextureViews textures() const override {
        overlay_wanted_ = true;
        gl::TextureViews views;
        if (overlay_) {
            views.push_back(
                {name() + "/samples (orange marched, blue interpolated)", overlay_.texture()});
        }
        if (coordinates_) {
            views.push_back(
                {name() + "/samples' in-scattering (x sample, y slice)", scattering_.id()});
            views.push_back({name() + "/min-max trees (x level by level, y slice)", tree_.id()});
        }
        return views;
    }

private:
    frame::Param<int> slices_;
    frame::Param<int> samples_per_slice_;
    frame::Param<int> max_step_;
    frame::Param<double> depth_threshold_;
    frame::Param<int> samples_;
    frame::Param<LitIntegral> lit_integral_;
    frame::Param<bool> minmax_;
    frame::Param<bool> interpolation_;
    void make_march_program(const Scene& scene) {
        const bool closed = *lit_integral_ == LitIntegral::closed_form;
        if (closed) {
            analytic::AnalyticRegionPass::require_closed_form(scene, name());
        }
        const bool remake = closed ? closed_form_.set_scene(scene) : false;
        if (march_program_ && !remake && march_closed_form_ == closed) {
            return;
        }
        std::vector<std::string> defines;
        if (closed) {
            defines = analytic::closed_form_defines(scene);
            defines.push_back("EPIPOLAR_CLOSED_FORM 1");
        }
        march_program_ =
            gl::create_program({{GL_COMPUTE_SHADER, "epipolar/shaders/march.comp"}}, defines);
        march_closed_form_ = closed;
    }

    void upload_slices(const std::vector<Slice>& slices) {
        std::vector<float> data;
        data.reserve(slices.size() * 8);
        for (const Slice& s : slices) {
            data.insert(data.end(), {float(s.entry.x), float(s.entry.y), float(s.exit.x),
                                     float(s.exit.y), float(s.map_origin.x), float(s.map_origin.y),
                                     float(s.map_step.x), float(s.map_step.y)});
            valid_slices_ += s.entry != s.exit ? 1 : 0;
        }
        GL.NamedBufferData(slices_buffer_.id(), GLsizeiptr(data.size() * sizeof(float)),
                           data.data(), GL_STREAM_DRAW);
    }

    void allocate(glm::ivec2 grid, int texels) {
        if (grid == grid_ && texels == texels_) {
            return;
        }
        coordinates_ = gl::create_texture_2d(GL_RGBA32F, grid.x, grid.y, GL_NEAREST);
        coordinates_.label("epipolar coordinates");
        marks_ = gl::create_texture_2d(GL_R32I, grid.x, grid.y, GL_NEAREST);
        marks_.label("epipolar marched samples");
        scattering_ = gl::create_texture_2d(GL_RGBA32F, grid.x, grid.y, GL_NEAREST);
        scattering_.label("epipolar in-scattering");
        tree_ = gl::create_texture_2d(GL_RG32F, texels, grid.y, GL_NEAREST);
        marched_list_ = gl::create_buffer(nullptr, size_t(grid.x) * size_t(grid.y) * 4);
        tree_.label("epipolar min-max trees");
        grid_ = grid;
        texels_ = texels;
    }

    void draw_overlay(const frame::VolumeInputs& inputs) {
        overlay_.bind_cleared(inputs.width, inputs.height, "epipolar samples");
        GL.UseProgram(overlay_program_.id());
        GL.ProgramUniform2i(overlay_program_.id(), SL_EPIPOLAR_GRID, grid_.x, grid_.y);
        GL.BindTextureUnit(SL_EPIPOLAR_COORDINATES_UNIT, coordinates_.id());
        GL.BindTextureUnit(SL_EPIPOLAR_MARKS_UNIT, marks_.id());
        GL.DrawArrays(GL_POINTS, 0, grid_.x * grid_.y);
    }

    gl::Program coordinates_program_, refine_program_, rectify_program_, minmax_program_,
        march_program_, interpolate_program_, apply_program_, overlay_program_;
    bool march_closed_form_ = false;  // march_program_ integrates lit runs in closed form
    analytic::ClosedFormScene closed_form_;
    gl::VertexArray empty_vertex_array_;
    gl::Sampler plain_sampler_;
    gl::Buffer slices_buffer_, counters_, marched_list_;
    gl::Texture coordinates_, marks_, scattering_, tree_;
    glm::ivec2 grid_{0}, drawn_grid_{0};
    int texels_ = 0;
    int valid_slices_ = 0;
    bool light_on_screen_ = false;
    double frame_pixels_ = 0.0;
    gl::PictureTarget overlay_;
    mutable bool overlay_wanted_ = false;
};

}  // namespace

void register_methods(frame::MethodRegistry& registry) {
    registry.add("epipolar", 60, [] { return std::make_unique<EpipolarMethod>(); });
}

}  // namespace sl::epipolar
