#pragma once
// The GPU side of image-based lighting: the prefiltered chain as one mipmapped cube map (level l
// of the chain = mip l), the split-sum DFG table, the uniforms ibl/shaders/ibl.glsl reads (SH9,
// the roughness-to-level mapping) and the skybox. Built from what ibl/ computed on the CPU; the
// frame renderer (frame/renderer.h) binds it for its surface pass.

#include <memory>

#include "gl/objects.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/texture_view.h"
#include "ibl/environment.h"
#include "scenes/scene.h"

namespace sl::ibl {

class EnvironmentTextures {
public:
    // Loads (and prefilters, or reads from the cache) the scene's environment; with none, 1x1
    // stand-in textures so that the samplers stay complete.
    explicit EnvironmentTextures(const Scene& scene);

    // Fills the frame's environment members; intensity and skybox come from `current` (the scene's
    // environment now: those two change without a new bake), the rest from what was loaded.
    void set_uniforms(gl::shared::FrameUniforms& uniforms, const Environment& current) const;
    // Binds the cube map and the DFG table to their units (SL_ENVIRONMENT_UNIT, SL_DFG_UNIT).
    void bind() const;
    bool enabled() const { return loaded_ != nullptr; }
    // The environment where no surface was drawn (depth 1), into the bound framebuffer with its
    // depth test; the depth buffer is left as it was. The frame uniforms must be bound.
    void draw_skybox() const;
    // What was loaded (nullptr without an environment).
    const LoadedEnvironment* loaded() const { return loaded_.get(); }
    gl::TextureViews textures() const;
    // What the textures were made from (file, size, prefilter): a change needs new textures.
    const Environment& source() const { return environment_; }

private:
    Environment environment_;
    std::unique_ptr<LoadedEnvironment> loaded_;
    gl::Texture cube_;
    gl::Texture dfg_;
    gl::Program skybox_program_;
    gl::VertexArray empty_vertex_array_;
};

}  // namespace sl::ibl
