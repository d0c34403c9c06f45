#pragma once
// Volume-based integration over closed region meshes (Nilsson §3.2.2): every face of the lit
// regions drawn once, back faces adding G(z) and front faces subtracting it, with signed
// additive blending into the float target (analytic/shaders/regions.frag). Used by `beamtree`,
// `hybrid2` and `hybrid3`.

#include <vector>

#include <glm/vec3.hpp>

#include "gl/objects.h"
#include "gl/volume_method.h"
#include "scenes/scene.h"

namespace sl::analytic {

using gl::Program;
using gl::Query;
using gl::Texture;
using gl::TextureViews;
using gl::VolumeInputs;

// The defines of a program that includes analytic/shaders/in_scattering.glsl for this light:
// SL_SMOOTH_CONE_EDGE and FALLOFF_PIECES (= kFalloffPieces) where it has a smooth edge.
std::vector<std::string> edge_defines(const SpotLight& light);

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
    // Adds ∫ e over the regions' part of every eye ray, up to the first surface.
    void draw(const VolumeInputs& inputs) const;
    size_t triangle_count() const { return size_t(mesh_.index_count) / 3; }
    // Its lookup tables, named "<owner>/...".
    TextureViews textures(const std::string& owner) const;
    // Fragment-shader invocations of the last draw (waits for it).
    double fragments() const;

private:
    gl::TriangleMesh mesh_;
    Program program_;
    Texture medium_table_;
    Query fragments_;
    bool smooth_edge_ = false;  // what program_ was made for
};

}  // namespace sl::analytic
