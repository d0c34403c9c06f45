#pragma once
// The lookup table of the light model's GLSL twin (analytic/shaders/in_scattering.glsl), made on
// the CPU from the same integrands as the closed forms of analytic/in_scattering.cpp. One 2D table
// per medium, RG32F, bound at SL_MEDIUM_TABLE_UNIT (analytic/shaders/analytic_interface.h); the
// second channel anchors G at the ray's far end (analytic/in_scattering.h, "Conditioning"):
//   physical:   R: H(s, v) = (1 + u) F_p(u, v), F_p(u, v) = ∫_0^v exp(-u tan ζ) p(cos 2ζ) dζ, on
//               s = u / (1 + u) in [0, 1] (x; s = 1 is u = ∞, where H = p(1) for v > 0) and
//               v in [0, π/2] (y). The scale (1 + u) keeps H bounded (F_p <= p_max / u) so that
//               every σt h, however dense the medium, has a texel.
//               G: the tail T(a, b) = s (1 + s) e^s K(a s, s) on sqrt(a), a = h / q in [0, 1]
//               (x), and b = sqrt(s / (1 + s)) in [0, 1] (y).
//   simplified: R: R(κ, β) = ∫_{-π/2}^β p(cos α(κ, b)) db, cos α = -sin b / sqrt(κ² cos² b +
//               sin² b), on κ in [0, 1] (x) and β in [-π/2, π/2] (y); κ = 1 is a0 = 0.
//               G: its complement ∫_β^{π/2}, on κ (x) and π/2 - β in [0, π] (y).
//               Not read for the isotropic phase function (Nilsson eq. 2.17 is exact), built all
//               the same.
// Tables are built once per process for each (model, phase function, g, size) and shared.

#include <memory>
#include <vector>

#include "gl/objects.h"
#include "scenes/scene.h"

namespace sl::analytic {

// Samples per axis; results/analytic_media.md measures the GPU integral's error against C++ per
// resolution: 512² is as accurate as 1024² (both at float32's floor) and builds in under 0.2 s.
constexpr int kMediumTableSize = 512;

struct MediumTable {
    int size = 0;               // size x size samples of two channels (above)
    std::vector<float> values;  // row-major, 2 (y * size + x) + channel
    double build_ms = 0.0;      // CPU time of the first build (later calls reuse it)
};

// The table for `medium` (cached).
std::shared_ptr<const MediumTable> medium_table(const Medium& medium, int size = kMediumTableSize);
gl::Texture create_medium_table(const Medium& medium, int size = kMediumTableSize);

}  // namespace sl::analytic
