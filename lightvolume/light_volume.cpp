#include "lightvolume/light_volume.h"

#include <algorithm>
#include <cmath>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "analytic/region_pass.h"
#include "analytic/shaders/analytic_interface.h"
#include "core/error.h"
#include "frame/method_registry.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/shaders.h"
#include "lightvolume/shaders/lightvolume_interface.h"

namespace sl::lightvolume {

namespace {

using gl::GL;

// The k-th border vertex of the grid (grid.glsl's border_vertex), as (i, j).
glm::ivec2 border_vertex(int k, int resolution) {
    const int n = resolution - 1;
    if (k < n)
        return {k, 0};
    if (k < 2 * n)
        return {n, k - n};
    if (k < 3 * n)
        return {n - (k - 2 * n), n};
    return {0, n - (k - 3 * n)};
}

// Vertices of the closed grid: N² displaced, 4(N - 1) on the near plane's border, its centre.
int light_volume_vertex_count(int resolution) {
    return resolution * resolution + 4 * (resolution - 1) + 1;
}

}  // namespace

std::vector<glm::uvec3> light_volume_triangles(int resolution) {
    if (resolution < 2) {
        fail("a light volume needs at least 2 grid vertices per side, not {}", resolution);
    }
    const int n = resolution;
    const auto grid = [n](int i, int j) { return uint32_t(i + n * j); };
    const int border = 4 * (n - 1);
    const auto near_border = [n](int k) { return uint32_t(n * n + k); };
    const uint32_t centre = uint32_t(n * n + border);
    std::vector<glm::uvec3> triangles;
    triangles.reserve(size_t(2 * (n - 1) * (n - 1) + 3 * border));
    // The map's projection reverses orientation (its depth grows away from the light), so the
    // faces are wound clockwise in the map to face outwards in the world.
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            triangles.push_back({grid(i, j), grid(i + 1, j + 1), grid(i + 1, j)});
            triangles.push_back({grid(i, j), grid(i, j + 1), grid(i + 1, j + 1)});
        }
    }
    for (int k = 0; k < border; ++k) {
        const int next = (k + 1) % border;
        const glm::ivec2 a = border_vertex(k, n), b = border_vertex(next, n);
        triangles.push_back({grid(a.x, a.y), grid(b.x, b.y), near_border(next)});
        triangles.push_back({grid(a.x, a.y), near_border(next), near_border(k)});
        triangles.push_back({centre, near_border(k), near_border(next)});
    }
    return triangles;
}

std::vector<glm::dvec3> light_volume_positions(const std::vector<float>& depths, int size,
                                               const glm::mat4& light_clip_to_world,
                                               int resolution) {
    if (size < 1 || depths.size() != size_t(size) * size_t(size)) {
        fail("the light volume needs the shadow map's {} x {} depths, not {}", size, size,
             depths.size());
    }
    const glm::dmat4 inverse(light_clip_to_world);
    const double last = double(resolution - 1);
    const auto unproject = [&](glm::dvec2 uv, double depth) {
        const glm::dvec4 p = inverse * glm::dvec4(2.0 * uv - 1.0, 2.0 * depth - 1.0, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const auto point = [&](glm::ivec2 ij, bool near_plane) {
        double depth = 0.0;
        if (!near_plane) {
            const auto texel = [&](int index) {
                return int(std::round(double(index) * double(size - 1) / last));
            };
            depth = depths[size_t(texel(ij.y)) * size_t(size) + size_t(texel(ij.x))];
        }
        return unproject(glm::dvec2(ij) / last, depth);
    };
    std::vector<glm::dvec3> positions;
    positions.reserve(size_t(light_volume_vertex_count(resolution)));
    for (int j = 0; j < resolution; ++j) {
        for (int i = 0; i < resolution; ++i) {
            positions.push_back(point({i, j}, false));
        }
    }
    for (int k = 0; k < 4 * (resolution - 1); ++k) {
        positions.push_back(point(border_vertex(k, resolution), true));
    }
    positions.push_back(unproject({0.5, 0.5}, 0.0));
    return positions;
}

glm::mat4 light_clip_to_world(const glm::mat4& light_view_projection) {
    return glm::mat4(glm::inverse(glm::dmat4(light_view_projection)));
}

namespace {

class LightVolumeMethod final : public frame::VolumeMethod {
public:
    LightVolumeMethod() : VolumeMethod("lightvolume") {
        resolution_parameter_ =
            declare_integer("resolution", 256, 0, 4096,
                            "grid vertices per side over the shadow map, at least 2 (0: one per "
                            "texel, the map's size)");
        declare_shadow_size(
            "shadow map resolution (texels per side): the lit volume's (the frame's default, so "
            "that frame times compare)");
    }
    void validate() const override {
        if (*resolution_parameter_ == 1) {
            fail(
                "lightvolume: resolution 1 makes no grid: give at least 2 vertices per side, or "
                "0 for one per shadow-map texel");
        }
    }
    std::string accepts() const override { return analytic::AnalyticRegionPass::accepts(); }

    void prepare_light(const Scene& scene) override {
        analytic::AnalyticRegionPass::require_closed_form(scene, name());
        if (!empty_vertex_array_) {
            empty_vertex_array_ = gl::create_vertex_array();
            plain_sampler_ = gl::create_plain_sampler(GL_NEAREST);
            fragments_ = gl::create_query(GL_FRAGMENT_SHADER_INVOCATIONS);
            wireframe_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "lightvolume/shaders/light_volume.vert"},
                                    {GL_FRAGMENT_SHADER, "lightvolume/shaders/wireframe.frag"}});
        }
        update_light(scene, SceneChange::everything(scene));
    }
    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene& scene,
                                                       const SceneChange&) const override {
        analytic::AnalyticRegionPass::require_closed_form(scene, name());
        return nullptr;  // the volume is made on the GPU from the frame's shadow map
    }
    void apply_update_light(const Scene& scene, const SceneChange&,
                            std::unique_ptr<frame::FrameWork>) override {
        if (closed_form_.set_scene(scene)) {
            const std::vector<std::string> defines = analytic::closed_form_defines(scene);
            program_ =
                gl::create_program({{GL_VERTEX_SHADER, "lightvolume/shaders/light_volume.vert"},
                                    {GL_FRAGMENT_SHADER, "analytic/shaders/regions.frag"}},
                                   defines);
            eye_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "lightvolume/shaders/light_volume_eye.vert"},
                                    {GL_FRAGMENT_SHADER, "analytic/shaders/regions_eye.frag"}},
                                   defines);
            // One region about the eye when the triangle is not collapsed (regions_eye.frag).
            GL.ProgramUniform1f(eye_program_.id(), SL_REGIONS_EYE_WINDINGS, 1.0f);
        }
    }

    void render(const frame::VolumeInputs& inputs) override {
        int map_size = 0;
        GL.GetTextureLevelParameteriv(inputs.shadow_map, 0, GL_TEXTURE_WIDTH, &map_size);
        validate();  // the viewer may hold a value that failed it
        const int wanted = *resolution_parameter_;
        const int resolution = std::max(2, wanted == 0 ? map_size : wanted);
        if (resolution != resolution_) {
            const std::vector<glm::uvec3> triangles = light_volume_triangles(resolution);
            indices_ = gl::create_buffer(triangles.data(), triangles.size() * sizeof(glm::uvec3));
            indices_.label("light volume grid");
            index_count_ = GLsizei(triangles.size() * 3);
            GL.VertexArrayElementBuffer(empty_vertex_array_.id(), indices_.id());
            resolution_ = resolution;
        }
        inputs.timeline.section("light volume");
        // The shadow map's placement is the frame's (a sun's follows the camera:
        // frame/shadow_fit.h), so the grid's too.
        const glm::mat4 clip_to_world = light_clip_to_world(inputs.uniforms.light_view_projection);
        for (const gl::Program* program : {&program_, &eye_program_, &wireframe_program_}) {
            GL.ProgramUniform1i(program->id(), SL_LIGHT_VOLUME_RESOLUTION, resolution_);
            GL.ProgramUniformMatrix4fv(program->id(), SL_LIGHT_VOLUME_CLIP_TO_WORLD, 1, GL_FALSE,
                                       &clip_to_world[0][0]);
        }
        GL.BindTextureUnit(SL_LIGHT_VOLUME_LIGHT_DEPTH_UNIT, inputs.shadow_map);
        GL.BindSampler(SL_LIGHT_VOLUME_LIGHT_DEPTH_UNIT,
                       plain_sampler_.id());  // depths, not comparisons
        GL.BindVertexArray(empty_vertex_array_.id());
        {
            const analytic::SignedDrawScope scope(inputs, closed_form_);
            GL.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, fragments_.id());
            GL.UseProgram(program_.id());
            GL.DrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
            GL.UseProgram(eye_program_.id());  // collapses to nothing unless the eye is inside
            GL.DrawArrays(GL_TRIANGLES, 0, 3);
            GL.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
        }
        if (wireframe_wanted_) {
            draw_wireframe(inputs);
        }
        GL.BindSampler(SL_LIGHT_VOLUME_LIGHT_DEPTH_UNIT, 0);
    }

    frame::MethodStatistics statistics() const override {
        GLuint64 fragments = 0;
        GL.GetQueryObjectui64v(fragments_.id(), GL_QUERY_RESULT, &fragments);
        return {{"grid_resolution", double(resolution_)},
                {"region_faces", double(index_count_ / 3)},
                {"fragments_analytic", double(fragments)}};
    }

    // The wireframe is drawn by the frame after the one that asked for it (the previewer asks
    // every frame it shows it), so frames nobody looks at do not pay for it.
    gl::TextureViews textures() const override {
        wireframe_wanted_ = true;
        gl::TextureViews views;
        if (wireframe_) {
            views.push_back(
                {name() + "/wireframe (front faces green, back orange)", wireframe_.texture()});
        }
        for (gl::TextureView& view : closed_form_.textures(name())) {
            views.push_back(std::move(view));
        }
        return views;
    }

private:
    frame::Param<int> resolution_parameter_;
    void draw_wireframe(const frame::VolumeInputs& inputs) {
        GLint target = 0;
        GL.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
        wireframe_.bind_cleared(inputs.width, inputs.height, "light volume wireframe");
        GL.UseProgram(wireframe_program_.id());
        GL.PolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        GL.DrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
        GL.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    }

    gl::Program program_, eye_program_, wireframe_program_;
    gl::VertexArray empty_vertex_array_;  // no attributes: the grid's indices alone
    gl::Buffer indices_;
    gl::Sampler plain_sampler_;
    analytic::ClosedFormScene closed_form_;
    gl::Query fragments_;
    gl::PictureTarget wireframe_;
    mutable bool wireframe_wanted_ = false;
    GLsizei index_count_ = 0;
    int resolution_ = 0;
};

}  // namespace

void register_methods(frame::MethodRegistry& registry) {
    registry.add("lightvolume", 50, [] { return std::make_unique<LightVolumeMethod>(); });
}

}  // namespace sl::lightvolume
