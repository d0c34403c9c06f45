#include "analytic/region_pass.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "analytic/gpu_tables.h"
#include "analytic/in_scattering.h"
#include "analytic/shaders/analytic_interface.h"
#include "core/error.h"
#include "gl/shaders.h"

namespace sl::analytic {

using gl::GL;

void AnalyticRegionPass::require_closed_form(const Scene& scene, const std::string& method) {
    const Medium& m = scene.medium;
    if (m.model == MediumModel::simplified && m.phase != PhaseFunction::isotropic && m.a1 == 0.0f) {
        fail(
            "method '{}' integrates the lit regions in closed form, which covers every medium but "
            "the simplified model with a1 = 0 (no 1/r² falloff) and an anisotropic phase function "
            "('{}'): use 'march', 'planes' or 'reference', or set a1 > 0 or phase = 'isotropic'",
            method, to_string(m.phase));
    }
}

std::string AnalyticRegionPass::accepts() {
    return "both medium models, all seven phase functions (HG and Schlick at any |g| < 1), "
           "absorption, a smooth cone edge (within 1% of the exact, results/analytic_media.md); "
           "spot lights (cone or pyramid), point lights and directional lights, any number; not "
           "the simplified model with a1 = 0 and an anisotropic phase function";
}

std::vector<std::string> closed_form_defines(const Scene& scene) {
    const Medium& medium = scene.medium;
    const int form = medium.model == MediumModel::physical      ? 2
                     : medium.phase != PhaseFunction::isotropic ? 1
                                                                : 0;
    std::vector<std::string> defines = {fmt::format("SL_MEDIUM_FORM {}", form)};
    if (scene.light.smooth_edge()) {
        defines.push_back("SL_SMOOTH_CONE_EDGE 1");
        defines.push_back(fmt::format("FALLOFF_PIECES {}", kFalloffPieces));
    }
    return defines;
}

void AnalyticRegionPass::upload(const Scene& scene, const std::vector<glm::vec3>& positions,
                                const std::vector<glm::uvec3>& triangles) {
    upload_mesh(positions, triangles);
    set_scene(scene);
}

double winding_number(const std::vector<glm::vec3>& positions,
                      const std::vector<glm::uvec3>& triangles, const glm::dvec3& point) {
    double sum = 0.0;
    for (const glm::uvec3& t : triangles) {
        const glm::dvec3 a = glm::dvec3(positions[t.x]) - point;
        const glm::dvec3 b = glm::dvec3(positions[t.y]) - point;
        const glm::dvec3 c = glm::dvec3(positions[t.z]) - point;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        // tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|).
        const double numerator = glm::dot(a, glm::cross(b, c));
        const double denominator =
            la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        sum += 2.0 * std::atan2(numerator, denominator);
    }
    return sum / (4.0 * glm::pi<double>());
}

namespace {

// The triangles not lying on a shared side's plane (upload_mesh): all three corners within 1e-5
// of their distance from L, beside which a float corner's rounding (6e-8 of its coordinates) and
// the planes' (1e-16) are nothing.
std::vector<glm::uvec3> off_shared_sides(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::uvec3>& triangles,
                                         const SpotLight& light,
                                         const std::array<bool, 4>& shared_sides) {
    const std::vector<bt::Plane> planes = bt::influence_planes(light);
    const glm::dvec3 apex(light.position);
    std::vector<glm::uvec3> kept;
    kept.reserve(triangles.size());
    for (const glm::uvec3& t : triangles) {
        bool on_shared = false;
        for (size_t k = 0; k < shared_sides.size() && !on_shared; ++k) {
            if (!shared_sides[k]) {
                continue;
            }
            on_shared = true;
            for (const uint32_t corner : {t.x, t.y, t.z}) {
                const glm::dvec3 p(positions[corner]);
                const double tolerance = 1e-5 * (glm::length(p - apex) + glm::length(apex));
                on_shared = on_shared && std::abs(planes[k].distance(p)) <= tolerance;
            }
        }
        if (!on_shared) {
            kept.push_back(t);
        }
    }
    return kept;
}

}  // namespace

void AnalyticRegionPass::upload_mesh(const std::vector<glm::vec3>& positions,
                                     const std::vector<glm::uvec3>& triangles,
                                     const SpotLight& light,
                                     const std::array<bool, 4>& shared_sides) {
    const bool leave_out = light.cube_face && std::find(shared_sides.begin(), shared_sides.end(),
                                                        true) != shared_sides.end();
    faces_ = leave_out ? create_region_faces(
                             positions, off_shared_sides(positions, triangles, light, shared_sides))
                       : create_region_faces(positions, triangles);
    positions_ = positions;
    triangles_ = triangles;
    windings_eye_.reset();
    if (faces_.index_count() > 0) {
        faces_.mesh.vertex_array.label("lit regions");
    }  // else no lit region (or only slivers): draw() adds nothing
}

bool ClosedFormScene::set_scene(const Scene& scene) {
    if (!medium_ || !(*medium_ == scene.medium)) {
        medium_table_ = create_medium_table(scene.medium);
        medium_ = scene.medium;
    }
    std::vector<std::string> defines = closed_form_defines(scene);
    const bool remake = defines_ != defines;
    defines_ = std::move(defines);
    return remake;
}

TextureViews ClosedFormScene::textures(const std::string& owner) const {
    if (!medium_table_) {
        return {};
    }
    return {{owner + "/G(z) table of the medium", medium_table_.id()}};
}

SignedDrawScope::SignedDrawScope(const VolumeInputs& inputs, const ClosedFormScene& closed_form) {
    GL.BindTextureUnit(SL_ANALYTIC_SURFACE_DEPTH_UNIT, inputs.surface_depth);
    GL.BindTextureUnit(SL_MEDIUM_TABLE_UNIT, closed_form.medium_table());
    GL.Enable(GL_BLEND);
    GL.BlendFunc(GL_ONE, GL_ONE);
    GL.Enable(GL_DEPTH_CLAMP);
}

SignedDrawScope::~SignedDrawScope() {
    GL.Disable(GL_DEPTH_CLAMP);
    GL.Disable(GL_BLEND);
}

void AnalyticRegionPass::set_scene(const Scene& scene) {
    const bool remade = closed_form_.set_scene(scene);
    if (remade || shell_ != scene.light.cube_face) {
        shell_ = scene.light.cube_face;
        // The faces' and the eye's G over a point light's shell (upload_mesh); the walk route
        // draws no faces, and integrates over the face's own pyramid.
        std::vector<std::string> defines = closed_form_defines(scene);
        if (shell_) {
            defines.push_back("SL_POINT_SHELL 1");
        }
        eye_program_ =
            gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                {GL_FRAGMENT_SHADER, "analytic/shaders/regions_eye.frag"}},
                               defines);
        defines.push_back("SL_FACE_CORNERS 1");  // z from faces_.corners
        program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/world_position.vert"},
                                       {GL_FRAGMENT_SHADER, "analytic/shaders/regions.frag"}},
                                      defines);
        walk_program_ =
            gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                {GL_FRAGMENT_SHADER, "analytic/shaders/regions_walk.frag"}},
                               closed_form_defines(scene));
    }
    if (!eye_vertex_array_) {
        eye_vertex_array_ = gl::create_vertex_array();
    }
    if (!fragments_) {
        fragments_ = gl::create_query(GL_FRAGMENT_SHADER_INVOCATIONS);
        rasterized_ = gl::create_query(GL_SAMPLES_PASSED);
    }
}

frame::MethodStatistics region_statistics(const bt::RegionStageTimes& ms, bool walk) {
    frame::MethodStatistics stats = {{"cpu_ms_beamtree", ms.total()}};
    for (const auto& [stage, value] : ms.named()) {
        stats.push_back({"cpu_ms_region_" + stage, value});
    }
    stats.push_back({"region_walk", walk ? 1.0 : 0.0});
    return stats;
}

std::unique_ptr<frame::FrameWork> region_frame_work(const Scene& scene, const SceneChange& change,
                                                    const bt::RegionRequest& request, bool built,
                                                    bool walk) {
    if (built && !change.regions() && !(change.camera && request.view_dependent(scene))) {
        return nullptr;
    }
    auto work = std::make_unique<RegionFrameWork>();
    work->regions = bt::build_frame_regions(scene, request);
    work->walk = walk;
    return work;
}

void AnalyticRegionPass::draw(const VolumeInputs& inputs) const {
    walked_ = false;
    if (faces_.index_count() == 0)
        return;
    const SignedDrawScope scope(inputs, closed_form_);
    GL.UseProgram(program_.id());
    faces_.bind();
    GL.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, fragments_.id());
    GL.BeginQuery(GL_SAMPLES_PASSED, rasterized_.id());
    GL.DrawElements(GL_TRIANGLES, faces_.index_count(), GL_UNSIGNED_INT, nullptr);
    // The eye inside the regions: every ray's missing front face at z = 0.
    const glm::vec3 eye = inputs.scene.camera.position;
    if (windings_eye_ != eye) {
        eye_windings_ = int(std::lround(winding_number(positions_, triangles_, glm::dvec3(eye))));
        windings_eye_ = eye;
    }
    if (eye_windings_ != 0) {
        GL.UseProgram(eye_program_.id());
        GL.ProgramUniform1f(eye_program_.id(), SL_REGIONS_EYE_WINDINGS, float(eye_windings_));
        GL.BindVertexArray(eye_vertex_array_.id());
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    GL.EndQuery(GL_SAMPLES_PASSED);
    GL.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
}

void AnalyticRegionPass::draw_walk(const VolumeInputs& inputs, const GpuTreeBuffers& tree) const {
    walked_ = true;
    const SignedDrawScope scope(inputs, closed_form_);
    tree.bind();
    GL.UseProgram(walk_program_.id());
    GL.BindVertexArray(eye_vertex_array_.id());
    GL.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, fragments_.id());
    GL.BeginQuery(GL_SAMPLES_PASSED, rasterized_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    GL.EndQuery(GL_SAMPLES_PASSED);
    GL.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
}

double AnalyticRegionPass::count(const Query& query) const {
    if (faces_.index_count() == 0 && !walked_)
        return 0.0;
    GLuint64 value = 0;
    GL.GetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &value);
    return double(value);
}

TextureViews AnalyticRegionPass::textures(const std::string& owner) const {
    return closed_form_.textures(owner);
}

}  // namespace sl::analytic
