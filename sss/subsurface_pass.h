#pragma once
// Translucent objects by splatting (Rohat §5.1, §5.3): per light, a light-view pass writes world
// positions and normals (with the object's id as the validity flag) and, for the multipole, a
// back-face pass the far side; an N x M grid over each object's region of interest in that map
// becomes point samples that a geometry shader expands into screen-aligned quads of radius r_max;
// their fragments add F_t/π R_d(|x_s − x_o|) × (what the sample carries) to a float target with
// additive blending and no depth test, for the eye G-buffer's pixels of the same object. With an
// environment, uniform surface samples lit by SH9 irradiance are splatted the same way. The sum is
// finally added to the surface pass's colour (the deferred composite of listing 5.6; the
// specular term is drawn by the surface pass itself). The lights are the scene's spot lights
// (its `[light]`, or every spot light and point-light face of its `[[lights]]`; a directional
// light is refused by the constructor) and then [sss]'s own; the frame draws the pass once, after
// the first light's surfaces, and it splats them all.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gl/objects.h"
#include "scenes/scene.h"

namespace sl::sss {

// One translucent material as uploaded: its profiles' layer and extents.
struct SubsurfaceMaterial {
    int material = 0;       // index into Scene::materials
    int layer = 0;          // in the profile texture arrays
    double r_max_mm = 0.0;  // splat radius (eq. 4.3)
    double d_min_mm = 0.0;  // multipole thickness range: 4 and 64 mean free paths (§5.1.2)
    double d_max_mm = 0.0;
    bool multipole = false;
    glm::vec3 total_reflectance{0.0f};  // ∫ R dA of the profile, the albedo under ambient light
};

struct SubsurfaceStats {
    size_t lights = 0;
    size_t splat_draws = 0;              // (light, object) pairs drawn
    size_t grid_samples = 0;             // N·M per draw, summed
    size_t environment_samples = 0;      // uniform surface samples, all objects
    double sample_elimination_ms = 0.0;  // building them (once)
};

// Draws object `index` of the scene with `program`, its model and normal matrices set.
using DrawObject = std::function<void(size_t index, GLuint program)>;

class SubsurfacePass {
public:
    // Tabulates the profiles and builds the environment samples; needs a current GL context.
    // Throws sl::Error for a scene with a directional light (the splats model lights at a point).
    SubsurfacePass(const Scene& scene, int width, int height);
    ~SubsurfacePass();

    // The whole pass for one frame: eye G-buffer (depth-tested against `surface_depth`), light
    // maps and splats per light, environment splats, then the scattered radiance added to colour
    // attachment 0 of `surface_framebuffer`. The frame uniforms must be bound; `frame` seeds
    // the jitter.
    void render(const DrawObject& draw, const glm::mat4& view_projection, GLuint surface_depth,
                GLuint surface_framebuffer, uint32_t frame);

    GLuint scatter() const { return scatter_.id(); }              // Σ splats, before T(Z)
    GLuint eye_positions() const { return eye_positions_.id(); }  // xyz, object id + 1
    GLuint light_positions() const { return light_positions_.id(); }
    const std::vector<SubsurfaceMaterial>& materials() const { return materials_; }
    const SubsurfaceMaterial* material_of(int scene_material) const;
    const SubsurfaceStats& stats() const { return stats_; }
    // The region of interest of object `index` in light `light`'s map: uv min and size (§5.1).
    glm::vec4 region_of_interest(size_t index, const SpotLight& light) const;

private:
    struct EnvironmentSamples {
        size_t object = 0;
        gl::Buffer vertices;
        gl::VertexArray vertex_array;
        GLsizei count = 0;
        float area_per_sample = 0.0f;
    };
    // Set-up, in the constructor's order.
    void upload_profiles();
    void build_environment_samples();
    void create_programs();
    void create_targets();
    // The frame's passes, in render()'s order.
    std::vector<size_t> translucent_objects() const;
    void draw_eye_gbuffer(const DrawObject& draw, const glm::mat4& view_projection,
                          GLuint surface_depth, const std::vector<size_t>& translucent);
    void draw_light_maps(const DrawObject& draw, const SpotLight& light,
                         const std::vector<size_t>& translucent);
    void splat_light(const SpotLight& light, const std::vector<size_t>& translucent,
                     uint32_t frame);
    void splat_environment();
    void composite(GLuint surface_framebuffer);
    void set_light(GLuint program, const SpotLight& light) const;
    void set_material(GLuint program, size_t object) const;

    const Scene& scene_;
    int width_, height_;
    std::vector<SubsurfaceMaterial> materials_;
    std::vector<EnvironmentSamples> environment_;
    SubsurfaceStats stats_;
    bool any_multipole_ = false;

    gl::Program gbuffer_program_;
    gl::Program splat_program_;
    gl::Program points_program_;
    gl::Program area_program_;
    gl::Program combine_program_;
    gl::VertexArray empty_vertex_array_;

    gl::Texture profile_R_, profile_T_;
    gl::Texture eye_positions_, eye_normals_;
    gl::Framebuffer eye_framebuffer_;
    gl::Texture light_positions_, light_normals_, light_depth_;
    gl::Framebuffer light_framebuffer_;
    gl::Texture back_positions_, back_scratch_, back_depth_;
    gl::Framebuffer back_framebuffer_;
    gl::Texture area_sums_;
    gl::Framebuffer area_framebuffer_;
    gl::Texture scatter_;
    gl::Framebuffer scatter_framebuffer_;
};

}  // namespace sl::sss
