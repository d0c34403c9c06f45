#pragma once
// Volume-based integration over closed region meshes (Nilsson §3.2.2): every face of the lit
// regions drawn once, back faces adding G(z) and front faces subtracting it, with signed
// additive blending into the float target (analytic/shaders/regions.frag). Used by `beamtree`,
// `hybrid2` and `hybrid3`.

#include <array>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "analytic/gpu_tree.h"
#include "analytic/region_faces.h"
#include "beamtree/frame_regions.h"

#include "frame/volume_method.h"
#include "gl/objects.h"
#include "scenes/scene.h"

namespace sl::analytic {

using frame::VolumeInputs;
using gl::Program;
using gl::Query;
using gl::Texture;
using gl::TextureViews;

// The defines of a program that includes analytic/shaders/in_scattering.glsl for this scene:
// SL_MEDIUM_FORM, the one closed form its medium needs (0 Nilsson eq. 2.17, 1 the simplified
// model's table, 2 the physical model), and SL_SMOOTH_CONE_EDGE and FALLOFF_PIECES
// (= kFalloffPieces) where the light has a smooth edge.
std::vector<std::string> closed_form_defines(const Scene& scene);

// The generalized winding number of a closed, outward-wound triangle mesh about `point`: the sum
// of the triangles' signed solid angles over 4π (van Oosterom & Strackee 1983), 1 inside a closed
// region, 0 outside, n inside n overlapping ones (every cell's faces: each lit cell counts).
double winding_number(const std::vector<glm::vec3>& positions,
                      const std::vector<glm::uvec3>& triangles, const glm::dvec3& point);

// What a pass that draws faces with analytic/shaders/regions.frag keeps of the scene: the
// medium's table, made again only when the medium changes, and the closed form and kind of cone
// edge its programs were made for (closed_form_defines).
class ClosedFormScene {
public:
    // Updates the table; true when the programs must be made (again): on the first call, and
    // when the medium's closed form or the light's edge (hard or smooth) changes.
    bool set_scene(const Scene& scene);
    GLuint medium_table() const { return medium_table_.id(); }
    // The table, named "<owner>/..." (none before the first set_scene).
    TextureViews textures(const std::string& owner) const;

private:
    Texture medium_table_;
    std::optional<Medium> medium_;                     // what medium_table_ was made for
    std::optional<std::vector<std::string>> defines_;  // what the programs were made for
};

// The GL state of a signed draw of region faces, for its scope: the surface depth at unit 0 and
// the medium table at SL_MEDIUM_TABLE_UNIT bound, additive blending (signed sums in the float
// target), depth clamp (faces in front of the near plane still count).
class SignedDrawScope {
public:
    SignedDrawScope(const VolumeInputs& inputs, const ClosedFormScene& closed_form);
    ~SignedDrawScope();
    SignedDrawScope(const SignedDrawScope&) = delete;
    SignedDrawScope& operator=(const SignedDrawScope&) = delete;
};

class AnalyticRegionPass {
public:
    // Throws sl::Error when the closed forms do not cover the scene's light model: only the
    // simplified model with a1 = 0 and an anisotropic phase function (every other medium, and a
    // smooth cone edge, is integrated: analytic/shaders/in_scattering.glsl).
    static void require_closed_form(const Scene& scene, const std::string& method);
    // What the methods built on this pass accept (VolumeMethod::accepts).
    static std::string accepts();

    // Uploads the region faces (closed, outward-wound) and the scene's tables.
    void upload(const Scene& scene, const std::vector<glm::vec3>& positions,
                const std::vector<glm::uvec3>& triangles);
    // The per-frame halves of upload(): new faces (fresh buffers, so the previous frame's stay
    // alive until the GPU is done with them), and the scene's medium table and edge program,
    // remade only when the medium, the kind of cone edge or the light's kind differs from the last
    // call's. For a face of a point light (SpotLight::cube_face), `light` and its
    // `shared_sides` (bt::shared_sides) leave out the faces that lie on a shared side's plane:
    // its neighbour leaves out the same, and the pairs they make would cancel, since the faces
    // of a point light integrate over its whole shell (SL_POINT_SHELL in in_scattering.glsl)
    // where a spot's integrate over its pyramid. The eye's winding number counts every face.
    void upload_mesh(const std::vector<glm::vec3>& positions,
                     const std::vector<glm::uvec3>& triangles, const SpotLight& light = {},
                     const std::array<bool, 4>& shared_sides = {});
    void set_scene(const Scene& scene);
    // Adds ∫ e over the regions' part of every eye ray, up to the first surface. A ray that
    // starts inside a region has no front face to subtract G at its start (it lies behind the
    // eye): when the eye is inside the regions, a full-screen pass subtracts G(0) once per
    // region about it (the winding number, on the CPU) — the closed form's antiderivative is
    // not 0 at the eye.
    void draw(const VolumeInputs& inputs) const;
    // The same integral by the walk route: a full-screen pass that adds G(z1) - G(z0) over each
    // lit interval of the region lists the walk wrote this frame (RegionLists::walk, bound), and
    // walks `tree` itself where a list overflowed (analytic/shaders/regions_walk.frag). Needs no
    // mesh. (Walking and integrating in one pass costs more on a software rasterizer: every lane
    // of a SIMD group pays for each G evaluation inside the walk's loop.)
    void draw_walk(const VolumeInputs& inputs, const GpuTreeBuffers& tree) const;
    size_t triangle_count() const { return size_t(faces_.index_count()) / 3; }
    // Its lookup tables, named "<owner>/...".
    TextureViews textures(const std::string& owner) const;
    // Fragment-shader invocations of the last draw (waits for it): what the rasterizer shaded,
    // helper and block granularity included (llvmpipe counts whole 4×4 blocks).
    double fragments() const { return count(fragments_); }
    // The fragments the last draw rasterized (GL_SAMPLES_PASSED, one sample per pixel, no depth
    // test): (pixel, triangle) pairs, which an eye ray's crossings of the regions bound from below.
    double rasterized() const { return count(rasterized_); }

private:
    double count(const Query& query) const;  // the last draw's result (0 without a mesh)

    RegionFaces faces_;                 // those drawn
    std::vector<glm::vec3> positions_;  // the whole mesh, for the eye's winding number
    std::vector<glm::uvec3> triangles_;
    // The regions about the eye (the winding number rounded), for the eye it was taken at: taken
    // again only when the eye moves or the mesh is replaced.
    mutable std::optional<glm::vec3> windings_eye_;
    mutable int eye_windings_ = 0;
    Program program_;
    Program eye_program_;          // the full-screen -G(0) of rays that start inside a region
    Program walk_program_;         // the walk route's full-screen pass
    mutable bool walked_ = false;  // the last draw was draw_walk (the queries count it)
    gl::VertexArray eye_vertex_array_;
    ClosedFormScene closed_form_;
    bool shell_ = false;  // the programs integrate over a point light's shell (cube_face)
    Query fragments_;
    Query rasterized_;
};

// The CPU half of a region method's per-frame update (VolumeMethod::cpu_update): the frame's
// tree and meshes (beamtree/frame_regions.h).
struct RegionFrameWork final : frame::FrameWork {
    bt::FrameRegions regions;
    bool walk = false;  // built for the walk route: the tree alone (analytic/gpu_tree.h)
};
// The statistics of the last region build: cpu_ms_beamtree (the whole CPU update),
// cpu_ms_region_<stage> for each stage of bt::RegionStageTimes, and region_walk (1 when it was
// built for the walk route, 0 for the mesh route).
frame::MethodStatistics region_statistics(const bt::RegionStageTimes& ms, bool walk);
// The frame's regions as `request` asks, or null when `change` leaves them as they are (and
// `built` says there are some). `walk`: for the walk route (the request asks for the GPU tree).
std::unique_ptr<frame::FrameWork> region_frame_work(const Scene& scene, const SceneChange& change,
                                                    const bt::RegionRequest& request, bool built,
                                                    bool walk = false);

}  // namespace sl::analytic
