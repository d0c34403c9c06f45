#include "froxel/froxel.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "frame/method_registry.h"
#include "frame/shadow_fit.h"
#include "froxel/shaders/froxel_interface.h"
#include "gl/functions.h"
#include "gl/shaders.h"

namespace sl::froxel {

namespace {

using gl::GL;

constexpr int kMaxSide = 2048;           // GL 4.5's least GL_MAX_3D_TEXTURE_SIZE
constexpr double kMaxFroxels = 1 << 26;  // 1 GiB per RGBA32F volume
constexpr int kJitterPeriod = 16;        // frames of the Halton sequence

void set_grid_uniforms(GLuint program, const FroxelGrid& grid) {
    GL.ProgramUniform3i(program, SL_FROXEL_GRID_SIZE, grid.size.x, grid.size.y, grid.size.z);
    GL.ProgramUniform2f(program, SL_FROXEL_GRID_DEPTH, grid.depth_extent, grid.linear_depth);
}

// The radical inverse of i in base 2 (Halton's first dimension).
float halton2(int i) {
    float result = 0.0f, f = 0.5f;
    for (; i > 0; i /= 2, f *= 0.5f) {
        result += f * float(i % 2);
    }
    return result;
}

gl::Texture create_volume(const FroxelGrid& grid, const char* label) {
    gl::Texture texture =
        gl::create_texture_3d(GL_RGBA32F, grid.size.x, grid.size.y, grid.size.z, GL_LINEAR);
    texture.label(label);
    return texture;
}

}  // namespace

double slice_depth(const FroxelGrid& grid, double s) {
    const double E = grid.depth_extent, c = grid.linear_depth;
    return c * std::exp(s / grid.size.z * std::log1p(E / c)) - c;
}

double influence_depth(const Scene& scene, double aspect) {
    const Camera& camera = scene.camera;
    const glm::dvec3 eye(camera.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
    const glm::dmat4 inverse =
        glm::inverse(glm::dmat4(frame::shadow_view_projection(scene.light, camera, float(aspect))));
    double farthest = -HUGE_VAL;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec4 p = inverse * glm::dvec4(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1,
                                                  corner & 4 ? 1 : -1, 1.0);
        farthest = std::max(farthest, glm::dot(glm::dvec3(p) / p.w - eye, forward));
    }
    return std::clamp(farthest, double(camera.near), double(camera.far));
}

FroxelGrid make_grid(const Scene& scene, int width, int height, double grid_scale, int slices,
                     double depth_extent, double linear_depth) {
    FroxelGrid grid;
    const auto side = [&](double base, double image, double reference) {
        return std::max(1, int(std::lround(base * grid_scale * image / reference)));
    };
    grid.size = {side(160.0, width, 1280.0), side(90.0, height, 720.0),
                 std::max(1, int(std::lround(slices * grid_scale)))};
    const double froxels = double(grid.size.x) * grid.size.y * grid.size.z;
    if (std::max({grid.size.x, grid.size.y, grid.size.z}) > kMaxSide || froxels > kMaxFroxels) {
        fail(
            "froxel grid {} x {} x {} is too large (at most {} per side and 2^26 froxels): "
            "lower grid_scale or slices",
            grid.size.x, grid.size.y, grid.size.z, kMaxSide);
    }
    grid.depth_extent = float(
        depth_extent > 0.0 ? depth_extent : influence_depth(scene, double(width) / double(height)));
    grid.linear_depth = float(linear_depth > 0.0 ? linear_depth : grid.depth_extent / 8.0);
    return grid;
}

void FroxelIntegrator::integrate(const FroxelGrid& grid, GLuint densities,
                                 GLuint integrated) const {
    if (!program_) {
        program_ = gl::create_program({{GL_COMPUTE_SHADER, "froxel/shaders/integrate.comp"}});
    }
    set_grid_uniforms(program_.id(), grid);
    GL.UseProgram(program_.id());
    GL.BindTextureUnit(SL_FROXEL_INTEGRATE_DENSITIES_UNIT, densities);
    GL.BindImageTexture(SL_FROXEL_INTEGRATE_IMAGE, integrated, 0, GL_TRUE, 0, GL_WRITE_ONLY,
                        GL_RGBA32F);
    gl::dispatch_compute({grid.size.x, grid.size.y, 1}, {8, 8, 1});
}

namespace {

class FroxelMethod final : public frame::VolumeMethod {
public:
    FroxelMethod() : VolumeMethod("froxel") {
        grid_scale_ = declare_real("grid_scale", 1.0, 0.05, 16.0,
                                   "the grid relative to 160 x 90 columns at 1280 x 720 (scaled "
                                   "with the image) and `slices` slices, on every axis");
        slices_ = declare_integer("slices", 64, 1, 2048, "depth slices at grid_scale 1");
        depth_extent_ = declare_real("depth_extent", 0.0, 0.0, 1e6,
                                     "metres of view depth the grid covers (0: the farthest "
                                     "point of the light's influence volume, within the camera's "
                                     "far plane)");
        linear_depth_ = declare_real("linear_depth", 0.0, 0.0, 1e6,
                                     "metres: slices are linear in depth well within it and "
                                     "exponential beyond (0: an eighth of depth_extent)");
        samples_ = declare_integer("samples", 1, 1, 64,
                                   "points per froxel, stratified along its depth span");
        jitter_ = declare_flag("jitter", false,
                               "on: the points move within their strata every frame (per-froxel "
                               "noise plus a Halton step), for the temporal filter");
        temporal_ = declare_flag("temporal", false,
                                 "on: reprojection into the last frame's grid with an exponential "
                                 "history, clamped to the current neighbourhood");
        history_weight_ = declare_real("history", 0.9, 0.0, 0.99,
                                       "the history's weight in each frame's blend (temporal = 1)");
        declare_shadow_parameters();
    }

    void prepare_light(const Scene& scene) override {
        if (!inject_program_) {
            inject_program_ =
                gl::create_program({{GL_COMPUTE_SHADER, "froxel/shaders/inject.comp"}});
            temporal_program_ =
                gl::create_program({{GL_COMPUTE_SHADER, "froxel/shaders/temporal.comp"}});
            apply_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                    {GL_FRAGMENT_SHADER, "froxel/shaders/apply.frag"}});
            atlas_program_ = gl::create_program({{GL_COMPUTE_SHADER, "froxel/shaders/atlas.comp"}});
            empty_vertex_array_ = gl::create_vertex_array();
        }
        previous_.reset();
        frame_index_ = 0;
        update_light(scene, SceneChange::everything(scene));
    }
    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene&,
                                                       const SceneChange&) const override {
        return nullptr;  // the grid is made on the GPU every frame
    }
    void apply_update_light(const Scene&, const SceneChange&,
                            std::unique_ptr<frame::FrameWork>) override {}

    void render(const frame::VolumeInputs& inputs) override {
        const FroxelGrid grid = make_grid(inputs.scene, inputs.width, inputs.height, *grid_scale_,
                                          *slices_, *depth_extent_, *linear_depth_);
        allocate(grid);
        const bool temporal = *temporal_;
        if (!temporal) {
            previous_.reset();  // a history resumes from scratch, not from a stale frame
        }

        inputs.timeline.section("inject");
        GLuint program = inject_program_.id();
        set_grid_uniforms(program, grid);
        GL.ProgramUniform1i(program, SL_FROXEL_INJECT_SAMPLES, *samples_);
        GL.ProgramUniform1i(program, SL_FROXEL_INJECT_JITTER, int(*jitter_));
        GL.ProgramUniform1f(program, SL_FROXEL_INJECT_FRAME_OFFSET,
                            halton2(frame_index_ % kJitterPeriod + 1));
        GL.UseProgram(program);
        GL.BindImageTexture(SL_FROXEL_INJECT_IMAGE, injected_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY,
                            GL_RGBA32F);
        gl::dispatch_compute(grid.size, {4, 4, 4});

        GLuint densities = injected_.id();
        if (temporal) {
            inputs.timeline.section("temporal");
            const int current = frame_index_ % 2;
            const gl::Texture& result = history_[current];
            program = temporal_program_.id();
            set_grid_uniforms(program, grid);
            // Without a previous frame of this grid, the history's weight is 0.
            GL.ProgramUniform1f(program, SL_FROXEL_TEMPORAL_HISTORY,
                                previous_ ? float(*history_weight_) : 0.0f);
            const Previous p = previous_.value_or(Previous{});
            GL.ProgramUniformMatrix4fv(program, SL_FROXEL_TEMPORAL_PREVIOUS_VIEW_PROJECTION, 1,
                                       GL_FALSE, &p.view_projection[0][0]);
            GL.ProgramUniform4fv(program, SL_FROXEL_TEMPORAL_PREVIOUS_CAMERA, 1, &p.camera[0]);
            GL.ProgramUniform4fv(program, SL_FROXEL_TEMPORAL_PREVIOUS_FORWARD, 1, &p.forward[0]);
            GL.ProgramUniform2f(program, SL_FROXEL_TEMPORAL_PREVIOUS_DEPTH, p.depth.x, p.depth.y);
            GL.UseProgram(program);
            GL.BindTextureUnit(SL_FROXEL_TEMPORAL_CURRENT_UNIT, injected_.id());
            GL.BindTextureUnit(SL_FROXEL_TEMPORAL_PREVIOUS_UNIT, history_[1 - current].id());
            GL.BindImageTexture(SL_FROXEL_TEMPORAL_IMAGE, result.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY,
                                GL_RGBA32F);
            gl::dispatch_compute(grid.size, {4, 4, 4});
            densities = result.id();
            previous_ = Previous{.view_projection = inputs.uniforms.view_projection,
                                 .camera = inputs.uniforms.camera_position,
                                 .forward = inputs.uniforms.camera_forward,
                                 .depth = {grid.depth_extent, grid.linear_depth}};
        }
        inputs.timeline.section("integrate");
        integrator_.integrate(grid, densities, integrated_.id());

        inputs.timeline.section("apply");
        program = apply_program_.id();
        set_grid_uniforms(program, grid);
        GL.UseProgram(program);
        GL.BindTextureUnit(SL_FROXEL_APPLY_SURFACE_DEPTH_UNIT, inputs.surface_depth);
        GL.BindTextureUnit(SL_FROXEL_APPLY_INTEGRATED_UNIT, integrated_.id());
        GL.BindVertexArray(empty_vertex_array_.id());
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
        GL.Disable(GL_BLEND);
        ++frame_index_;
        if (atlases_wanted_) {
            draw_atlas(density_atlas_, densities, "froxel densities by slice");
            draw_atlas(integral_atlas_, integrated_.id(), "froxel integral by slice");
        }
    }

    frame::MethodStatistics statistics() const override {
        return {{"froxels", double(grid_.size.x) * grid_.size.y * grid_.size.z},
                {"grid_x", double(grid_.size.x)},
                {"grid_y", double(grid_.size.y)},
                {"grid_slices", double(grid_.size.z)},
                {"depth_extent", double(grid_.depth_extent)}};
    }

    // The slice atlases are made by the frame after the one that asked for them (the previewer
    // asks every frame it shows them), so frames nobody looks at do not pay for them.
    gl::TextureViews textures() const override {
        atlases_wanted_ = true;
        gl::TextureViews views;
        if (density_atlas_) {
            views.push_back(
                {name() + "/densities S by slice (nearest bottom left)", density_atlas_.id()});
            views.push_back({name() + "/integral I_s to each slice (nearest bottom left)",
                             integral_atlas_.id()});
        }
        return views;
    }

private:
    frame::Param<double> grid_scale_;
    frame::Param<int> slices_;
    frame::Param<double> depth_extent_;
    frame::Param<double> linear_depth_;
    frame::Param<int> samples_;
    frame::Param<bool> jitter_;
    frame::Param<bool> temporal_;
    frame::Param<double> history_weight_;
    struct Previous {
        glm::mat4 view_projection{1.0f};
        glm::vec4 camera{0.0f}, forward{0.0f, 0.0f, -1.0f, 0.0f};
        glm::vec2 depth{1.0f, 1.0f};
    };

    void allocate(const FroxelGrid& grid) {
        if (grid.size == grid_.size && injected_) {
            grid_ = grid;
            return;
        }
        grid_ = grid;
        injected_ = create_volume(grid, "froxel densities");
        history_[0] = create_volume(grid, "froxel history 0");
        history_[1] = create_volume(grid, "froxel history 1");
        integrated_ = create_volume(grid, "froxel integral");
        previous_.reset();
        density_atlas_.reset();
        integral_atlas_.reset();
    }

    void draw_atlas(gl::Texture& atlas, GLuint volume, const char* label) {
        const int columns = int(std::ceil(std::sqrt(double(grid_.size.z))));
        const int rows = (grid_.size.z + columns - 1) / columns;
        const int w = columns * grid_.size.x, h = rows * grid_.size.y;
        if (!atlas) {
            atlas = gl::create_texture_2d(GL_RGBA32F, w, h, GL_NEAREST);
            atlas.label(label);
        }
        GL.UseProgram(atlas_program_.id());
        GL.ProgramUniform1i(atlas_program_.id(), SL_FROXEL_ATLAS_COLUMNS, columns);
        GL.BindTextureUnit(SL_FROXEL_ATLAS_VOLUME_UNIT, volume);
        GL.BindImageTexture(SL_FROXEL_ATLAS_IMAGE, atlas.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                            GL_RGBA32F);
        gl::dispatch_compute({w, h, 1}, {8, 8, 1});
    }

    gl::Program inject_program_, temporal_program_, apply_program_, atlas_program_;
    FroxelIntegrator integrator_;
    gl::VertexArray empty_vertex_array_;
    gl::Texture injected_, history_[2], integrated_;
    gl::Texture density_atlas_, integral_atlas_;
    FroxelGrid grid_;
    std::optional<Previous> previous_;
    int frame_index_ = 0;
    mutable bool atlases_wanted_ = false;
};

}  // namespace

void register_methods(frame::MethodRegistry& registry) {
    registry.add("froxel", 40, [] { return std::make_unique<FroxelMethod>(); });
}

}  // namespace sl::froxel
