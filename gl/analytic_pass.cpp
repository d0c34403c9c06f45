#include "gl/analytic_pass.h"

#include <cmath>
#include <numbers>

#include "analytic/phase_functions.h"
#include "analytic/quadrature.h"
#include "core/error.h"
#include "gl/shaders.h"

namespace sl::gl {

Texture create_sun_table() {
    // 1024² keeps bilinear interpolation within 1e-4 of the closed form (tested); the data is
    // computed once per process.
    constexpr int kSize = 1024;
    constexpr double kUMax = 32.0;  // SUN_TABLE_U_MAX in in_scattering.glsl
    static const std::vector<float> table = [] {
        std::vector<float> values(size_t(kSize) * kSize);
        for (int iu = 0; iu < kSize; ++iu) {
            const double u = kUMax * iu / (kSize - 1);
            double previous_v = 0.0, sum = 0.0;
            for (int iv = 0; iv < kSize; ++iv) {
                const double v = 0.5 * std::numbers::pi * iv / (kSize - 1);
                sum += analytic::integrate([&](double z) { return std::exp(-u * std::tan(z)); },
                                           previous_v, std::min(v, 0.5 * std::numbers::pi - 1e-12));
                previous_v = v;
                values[size_t(iv) * kSize + iu] = float(sum);
            }
        }
        return values;
    }();
    Texture texture = create_texture_2d(GL_R32F, kSize, kSize, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, kSize, kSize, GL_RED, GL_FLOAT, table.data());
    return texture;
}

Texture create_phase_table(const Medium& medium) {
    constexpr int kSize = 1024;  // PHASE_TABLE_SIZE in in_scattering.glsl
    std::vector<float> table(kSize);
    double sum = 0.0, previous = -0.5 * std::numbers::pi;
    for (int i = 0; i < kSize; ++i) {
        const double theta = std::numbers::pi * (double(i) / (kSize - 1) - 0.5);
        sum += analytic::integrate(
            [&](double t) { return analytic::phase(medium.phase, medium.g, -std::sin(t)); },
            previous, theta);
        previous = theta;
        table[size_t(i)] = float(sum);
    }
    Texture texture = create_texture_2d(GL_R32F, kSize, 1, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, kSize, 1, GL_RED, GL_FLOAT, table.data());
    return texture;
}

void AnalyticRegionPass::require_closed_form(const Scene& scene, const std::string& method) {
    const bool anisotropic = scene.medium.phase != PhaseFunction::isotropic;
    const bool physical = scene.medium.model == MediumModel::physical;
    const bool pure_inverse_square = scene.medium.a0 == 0.0f;
    if ((anisotropic && (physical || !pure_inverse_square)) || scene.light.falloff_degrees > 0.0f) {
        fail(
            "method '{}' integrates the lit regions in closed form, which needs a hard cone edge "
            "and either the isotropic phase function or the simplified model with a0 = 0; the "
            "scene has phase '{}', model '{}', a0 {} and falloff {}",
            method, to_string(scene.medium.phase), physical ? "physical" : "simplified",
            scene.medium.a0, scene.light.falloff_degrees);
    }
}

void AnalyticRegionPass::upload(const Scene& scene, const std::vector<glm::vec3>& positions,
                                const std::vector<glm::uvec3>& triangles) {
    index_count_ = GLsizei(triangles.size() * 3);
    if (index_count_ == 0) {
        return;  // no lit region (or only slivers): draw() adds nothing
    }
    vertices_ = create_buffer(positions.data(), positions.size() * sizeof(glm::vec3));
    indices_ = create_buffer(triangles.data(), triangles.size() * sizeof(glm::uvec3));
    vertex_array_ = create_vertex_array();
    GL.VertexArrayVertexBuffer(vertex_array_.id(), 0, vertices_.id(), 0, sizeof(glm::vec3));
    GL.VertexArrayElementBuffer(vertex_array_.id(), indices_.id());
    GL.EnableVertexArrayAttrib(vertex_array_.id(), 0);
    GL.VertexArrayAttribFormat(vertex_array_.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    GL.VertexArrayAttribBinding(vertex_array_.id(), 0, 0);
    vertex_array_.label("lit regions");
    if (!program_) {
        program_ = create_program({{GL_VERTEX_SHADER, "gl/shaders/beamtree.vert"},
                                   {GL_FRAGMENT_SHADER, "gl/shaders/beamtree.frag"}});
        sun_table_ = create_sun_table();
        fragments_ = create_query(GL_FRAGMENT_SHADER_INVOCATIONS);
    }
    phase_table_ = create_phase_table(scene.medium);
}

void AnalyticRegionPass::draw(const VolumeInputs& inputs, bool exclude_interval) const {
    if (index_count_ == 0)
        return;
    GL.UseProgram(program_.id());
    GL.ProgramUniform1i(program_.id(), 0, exclude_interval ? 1 : 0);
    GL.BindTextureUnit(0, inputs.surface_depth);
    GL.BindTextureUnit(kSunTableUnit, sun_table_.id());
    GL.BindTextureUnit(kPhaseTableUnit, phase_table_.id());
    GL.Enable(GL_BLEND);
    GL.BlendFunc(GL_ONE, GL_ONE);  // signed sums in the float target
    GL.Enable(GL_DEPTH_CLAMP);     // faces in front of the near plane still count
    GL.BindVertexArray(vertex_array_.id());
    GL.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, fragments_.id());
    GL.DrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
    GL.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
    GL.Disable(GL_DEPTH_CLAMP);
    GL.Disable(GL_BLEND);
}

double AnalyticRegionPass::fragments() const {
    if (index_count_ == 0)
        return 0.0;
    GLuint64 count = 0;
    GL.GetQueryObjectui64v(fragments_.id(), GL_QUERY_RESULT, &count);
    return double(count);
}

TextureViews AnalyticRegionPass::textures(const std::string& owner) const {
    if (!sun_table_) {
        return {};
    }
    return {{owner + "/G(z) table (Sun et al.)", sun_table_.id()},
            {owner + "/phase CDF table", phase_table_.id()}};
}

}  // namespace sl::gl
