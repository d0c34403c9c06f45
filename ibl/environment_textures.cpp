#include "ibl/environment_textures.h"

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/shaders.h"

namespace sl::ibl {

using gl::GL;
using gl::Texture;

namespace {

Texture create_cube(int size, int levels) {
    GLuint id = 0;
    GL.CreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    GL.TextureStorage2D(id, levels, GL_RGBA32F, size, size);
    GL.TextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    GL.TextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    GL.TextureParameteri(id, GL_TEXTURE_MAX_LEVEL, levels - 1);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
        GL.TextureParameteri(id, wrap, GL_CLAMP_TO_EDGE);
    }
    return Texture(id);
}

}  // namespace

EnvironmentTextures::EnvironmentTextures(const Scene& scene) : environment_(scene.environment) {
    if (!environment_.enabled()) {
        cube_ = create_cube(1, 1);
        const float black[3] = {0, 0, 0};
        for (int face = 0; face < 6; ++face) {
            GL.TextureSubImage3D(cube_.id(), 0, 0, 0, face, 1, 1, 1, GL_RGB, GL_FLOAT, black);
        }
        dfg_ = gl::create_texture_2d(GL_RG32F, 1, 1, GL_NEAREST);
        return;
    }
    loaded_ = std::make_unique<LoadedEnvironment>(load_environment(environment_));
    const PrefilteredChain& chain = loaded_->chain;
    if (chain.levels.size() > SL_MAX_ENVIRONMENT_LEVELS) {
        fail("environment: {} prefiltered levels, at most {} (face_size too large)",
             chain.levels.size(), SL_MAX_ENVIRONMENT_LEVELS);
    }
    cube_ = create_cube(chain.levels[0].size, int(chain.levels.size()));
    cube_.label("environment (prefiltered)");
    for (size_t l = 0; l < chain.levels.size(); ++l) {
        const CubeMap& level = chain.levels[l];
        for (int face = 0; face < 6; ++face) {
            GL.TextureSubImage3D(cube_.id(), GLint(l), 0, 0, face, level.size, level.size, 1,
                                 GL_RGB, GL_FLOAT, level.faces[size_t(face)].rgb.data());
        }
    }
    const DfgTable& dfg = loaded_->dfg;
    dfg_ = gl::create_texture_2d(GL_RG32F, dfg.size, dfg.size, GL_LINEAR);
    GL.TextureSubImage2D(dfg_.id(), 0, 0, 0, dfg.size, dfg.size, GL_RG, GL_FLOAT, dfg.ab.data());
    dfg_.label("environment DFG table");
    skybox_program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                          {GL_FRAGMENT_SHADER, "ibl/shaders/skybox.frag"}});
    empty_vertex_array_ = gl::create_vertex_array();
    gl::check_errors("uploading the environment");
}

void EnvironmentTextures::draw_skybox() const {
    GL.DepthFunc(GL_LEQUAL);
    GL.DepthMask(GL_FALSE);
    GL.UseProgram(skybox_program_.id());
    GL.BindVertexArray(empty_vertex_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    GL.DepthMask(GL_TRUE);
    GL.DepthFunc(GL_LESS);
}

void EnvironmentTextures::set_uniforms(gl::shared::FrameUniforms& u,
                                       const Environment& current) const {
    u.environment = glm::vec4(0.0f);
    u.environment_options = glm::vec4(0.0f);
    if (!loaded_) {
        return;
    }
    const PrefilteredChain& chain = loaded_->chain;
    const bool cone = chain.settings.method == PrefilterMethod::cone;
    u.environment = glm::vec4(1.0f, current.shading == Shading::moschos ? 0.0f : 1.0f,
                              float(chain.levels.size()), cone ? 1.0f : 0.0f);
    u.environment_options = glm::vec4(
        current.skybox ? 1.0f : 0.0f,
        chain.settings.distribution == Distribution::ggx ? 1.0f : 0.0f, current.intensity, 0.0f);
    for (size_t i = 0; i < 9; ++i) {
        u.environment_sh9[i] = glm::vec4(loaded_->sh.coefficients[i], 0.0f);
    }
    // Figure 3.24 per level, for the seed's shading: roughness, tan² θ, tan² θ / α².
    const auto& table = moschos_cone_levels();
    for (size_t l = 0; l < SL_MAX_ENVIRONMENT_LEVELS; ++l) {
        const float roughness = l < chain.roughness.size()
                                    ? chain.roughness[l]
                                    : table[std::min(l, table.size() - 1)].roughness;
        u.environment_levels[l] = glm::vec4(roughness, moschos_cone_measure(l), 0.0f);
    }
}

void EnvironmentTextures::bind() const {
    GL.BindTextureUnit(SL_ENVIRONMENT_UNIT, cube_.id());
    GL.BindTextureUnit(SL_DFG_UNIT, dfg_.id());
}

gl::TextureViews EnvironmentTextures::textures() const {
    if (!loaded_) {
        return {};
    }
    return {{"environment/DFG table (A, B)", dfg_.id()}};
}

}  // namespace sl::ibl
