#pragma once
// The GPU frame (docs/design.md §2): shadow map from the spot light -> surfaces (I_obj·T(Z), with
// the environment's light and skybox when the scene has one, ibl/environment_textures.h, and the
// translucent objects' subsurface pass, sss/subsurface_pass.h) ->
// volumetric method (I_s) -> composite and tone map. Owns the scene's GPU meshes and the frame's
// render targets; one renderer per scene and size.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "frame/volume_method.h"
#include "gl/objects.h"
#include "gl/shaders/frame_uniforms.h"
#include "ibl/environment_textures.h"
#include "scenes/scene.h"
#include "sss/subsurface_pass.h"

namespace sl::frame {

struct RenderOptions {
    int width = 640;
    int height = 360;
    ShadowSettings shadow{};  // methods that declare `shadow` parameters choose their own
    float aspect() const { return float(width) / float(height); }
};

// GPU time per pass (GL_TIME_ELAPSED), milliseconds.
struct PassTimings {
    double shadow_ms = 0;
    double surface_ms = 0;
    double volume_ms = 0;
    double composite_ms = 0;
    // The volume pass split by the method's timeline sections (they sum to volume_ms).
    std::vector<std::pair<std::string, double>> volume_sections;
    double subsurface_ms = 0;  // translucent objects (sss/subsurface_pass.h), 0 without any
    double total_ms() const {
        return shadow_ms + surface_ms + subsurface_ms + volume_ms + composite_ms;
    }
};

struct FrameTimings {
    PassTimings gpu;
    double cpu_ms = 0;  // wall time of draw(): submitting the passes and waiting for them
};

struct Frame {
    Image radiance;                      // I_eye, linear (before tone mapping)
    Image in_scattering;                 // I_s alone, linear
    Image surface;                       // I_obj·T(Z) alone, linear
    std::vector<uint8_t> display_srgb8;  // the GPU tone map, RGB rows top to bottom
    std::vector<float> depth;            // window-space depth in [0, 1], rows top to bottom
    PassTimings gpu;
    double cpu_ms = 0;  // wall time of the drawing (read-back excluded)
};

class SceneRenderer {
public:
    // Uploads the scene's meshes and allocates the targets; needs a current GL 4.5 context.
    SceneRenderer(const Scene& scene, const RenderOptions& options);
    ~SceneRenderer();

    // Draws one frame with `method`, waits for it, and returns its timings: what a measured
    // frame costs, with nothing read back. The frame uniforms are made from the scene at each
    // draw, so a caller may move the camera or the light of the scene between frames (a light
    // or medium change also needs the method's prepare() again).
    FrameTimings draw(VolumeMethod& method);
    // Every buffer of the last frame drawn, read back (timings left empty).
    Frame read_back() const;
    // I_s of the last frame drawn, read back alone (the error view's per-frame need).
    Image read_in_scattering() const { return read_rgb(in_scattering_.id()); }
    // Any RGBA float texture of the frame's size, rows top to bottom.
    Image read_rgb(GLuint texture) const;
    // draw() then read_back().
    Frame render(VolumeMethod& method);

    // The frame's buffers: shadow map (and VSM moments), surface colour and depth, I_s, the
    // composited HDR radiance and the tone-mapped display image.
    gl::TextureViews textures() const;

    const RenderOptions& options() const { return options_; }
    // The shadow map settings of the last frame drawn (the method's, or the options').
    const ShadowSettings& shadow() const { return shadow_; }
    const gl::shared::FrameUniforms& uniforms() const { return uniforms_; }
    // The scene's image-based lighting (1x1 stand-ins when it has no environment).
    const ibl::EnvironmentTextures& environment() const { return *environment_; }
    // The translucent objects' pass; null when the scene has none.
    const sss::SubsurfacePass* subsurface() const { return subsurface_.get(); }

private:
    struct GpuMesh {
        gl::Buffer vertices;
        gl::Buffer indices;
        gl::VertexArray vertex_array;
        GLsizei index_count = 0;
    };
    class PassTimer;
    class Timeline;
    class GroupTimer;

    // Set-up, in the constructor's order.
    void upload_meshes();
    void create_programs();
    void create_targets();
    void create_timers();
    // The frame's passes, in draw()'s order.
    void draw_shadow_map();
    void blur_shadow_moments();
    // `add_light`: a further light's term, added to the first's (several lights).
    void draw_surfaces(bool add_light);
    void draw_volume(VolumeMethod& method, const Scene& scene, bool add_light);
    void draw_composite();
    FrameTimings read_timings() const;

    void draw_objects(GLuint program, bool with_normals);
    void draw_object(size_t index, GLuint program, bool with_normals);
    void allocate_shadow(const ShadowSettings& settings);

    const Scene& scene_;
    RenderOptions options_;
    gl::shared::FrameUniforms uniforms_{};
    gl::Buffer uniform_buffer_;
    std::map<const Mesh*, GpuMesh> meshes_;

    gl::Program shadow_program_;
    gl::Program shadow_moments_program_;
    gl::Program shadow_blur_program_;
    gl::Program surface_program_;
    gl::Program composite_program_;
    std::unique_ptr<ibl::EnvironmentTextures> environment_;
    gl::VertexArray empty_vertex_array_;

    ShadowSettings shadow_;
    gl::Texture shadow_map_;
    gl::Texture shadow_moments_;  // VSM: RG32F; 1x1 when unused (its sampler still needs one)
    gl::Texture shadow_scratch_;  // VSM blur
    gl::Framebuffer shadow_framebuffer_;
    gl::Framebuffer shadow_blur_framebuffer_[2];
    gl::Texture surface_color_;
    gl::Texture surface_depth_;
    gl::Framebuffer surface_framebuffer_;
    gl::Texture in_scattering_;
    gl::Framebuffer volume_framebuffer_;
    gl::Texture hdr_;
    gl::Texture display_;
    gl::Framebuffer composite_framebuffer_;
    std::unique_ptr<sss::SubsurfacePass> subsurface_;
    uint32_t frame_index_ = 0;
    gl::Query composite_timer_;
    gl::Query subsurface_timer_;
    std::unique_ptr<Timeline> timeline_;         // the volume pass, by the method's sections
    std::unique_ptr<Timeline> shadow_timeline_;  // the shadow maps, one section per light
    std::unique_ptr<Timeline> surface_timeline_;
};

// The uniform block for `scene` seen at the given size (exposed for tests and CPU oracles).
gl::shared::FrameUniforms make_frame_uniforms(const Scene& scene, const RenderOptions& options);
// Its `shadow` member for the given shadow map.
glm::vec4 shadow_uniform(const ShadowSettings& settings);

}  // namespace sl::frame
