#pragma once
// The GPU frame (DESIGN.md §2): shadow map from the spot light -> surfaces (I_obj·T(Z)) ->
// volumetric method (I_s) -> composite and tone map. Owns the scene's GPU meshes and the frame's
// render targets; one renderer per scene and size.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/image.h"
#include "gl/objects.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/volume_method.h"
#include "scenes/scene.h"

namespace sl::gl {

enum class ShadowFilter { hard, pcf };

struct RenderOptions {
    int width = 640;
    int height = 360;
    int shadow_map_size = 2048;
    ShadowFilter shadow_filter = ShadowFilter::pcf;
    int pcf_radius = 1;  // (2r+1)² taps
};

// GPU time per pass (GL_TIME_ELAPSED), milliseconds.
struct PassTimings {
    double shadow_ms = 0;
    double surface_ms = 0;
    double volume_ms = 0;
    double composite_ms = 0;
    double total_ms() const { return shadow_ms + surface_ms + volume_ms + composite_ms; }
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

    // Draws one frame with `method`, waits for it, and returns its timings: what a measured
    // frame costs, with nothing read back.
    FrameTimings draw(VolumeMethod& method);
    // Every buffer of the last frame drawn, read back (timings left empty).
    Frame read_back() const;
    // draw() then read_back().
    Frame render(VolumeMethod& method);

    const RenderOptions& options() const { return options_; }
    const shared::FrameUniforms& uniforms() const { return uniforms_; }

private:
    struct GpuMesh {
        Buffer vertices;
        Buffer indices;
        VertexArray vertex_array;
        GLsizei index_count = 0;
    };
    class PassTimer;

    void draw_objects(bool with_normals);
    Image read_rgb(GLuint texture) const;

    const Scene& scene_;
    RenderOptions options_;
    shared::FrameUniforms uniforms_{};
    Buffer uniform_buffer_;
    std::map<const Mesh*, GpuMesh> meshes_;

    Program shadow_program_;
    Program surface_program_;
    Program composite_program_;
    VertexArray empty_vertex_array_;

    Texture shadow_map_;
    Framebuffer shadow_framebuffer_;
    Texture surface_color_;
    Texture surface_depth_;
    Framebuffer surface_framebuffer_;
    Texture in_scattering_;
    Framebuffer volume_framebuffer_;
    Texture hdr_;
    Texture display_;
    Framebuffer composite_framebuffer_;
    Query timers_[4];
};

// The uniform block for `scene` seen at the given size (exposed for tests and CPU oracles).
shared::FrameUniforms make_frame_uniforms(const Scene& scene, const RenderOptions& options);

}  // namespace sl::gl
