#pragma once
// Roughness-prefiltered cube map chains, two ways (kept side by side and compared in
// results/ibl.md):
//
// - `cone` — Moschos algorithm 6 (§3.3.3): level l has face size size/2^l and the roughness of row
//   l of figure 3.24; each texel averages `samples` random directions drawn uniformly on the disk
//   of radius tan θ_l one unit along the texel direction (the sampling cone of figure 3.25),
//   weighted by their cosine to that direction, read from level 0 by bilinear lookup.
// - `importance` — today's practice (Karis 2013; Colbert & Křivánek 2007 for the filtering):
//   n = v = r, half vectors importance sampled from D (GGX or Beckmann) with Hammersley points,
//   weights n·l, each sample read from the source's box-filtered mip at
//   lod = ½ log2(Ω_s / Ω_p) + 1 (Ω_s = 1/(N pdf(l)), Ω_p the level-0 texel's solid angle),
//   roughness spaced evenly in √α: α_l = (l / (L − 1))².
//
// Both estimators are self-normalised (divided by their weight sum), so a constant environment
// stays constant at every level. Algorithm 6's inv_pdf = π tan² θ factor is applied by the seed's
// shading instead (Moschos algorithm 7; see ibl/shaders/ibl.glsl).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ibl/cube_map.h"
#include "ibl/microfacet.h"

namespace sl::ibl {

// Moschos figure 3.24: per level, the roughness and the sampling cone's half-angle θ (degrees);
// the lobe-aperture column is tan θ.
struct ConeLevel {
    float roughness;
    float cone_degrees;
};
const std::vector<ConeLevel>& moschos_cone_levels();
// What the seed's shading (Moschos algorithms 7-8) multiplies by at figure 3.24 row `level`
// (clamped to the table): the cone's measure over π, tan² θ, and Beckmann's D(n) = 1/(π α²)
// times the measure π tan² θ, i.e. tan² θ / α² (0 on row 0, which has no cone).
glm::vec2 moschos_cone_measure(size_t level);

struct PrefilteredChain {
    PrefilterSettings settings;
    CubeMipChain levels;           // levels[0] is the source
    std::vector<float> roughness;  // α of each level
    double seconds = 0;            // wall time of the bake (0 when read from the cache)
    std::vector<double> level_seconds;
};

// Roughness ↔ level, shared by the bake and the shaders. Importance: lod = √α (L − 1). Cone
// (Moschos algorithm 7, "interpolate between the roughness hard-coded values"): piecewise linear
// in the table's roughness column.
float importance_roughness(int level, int levels);
float roughness_to_lod(const PrefilteredChain& chain, float alpha);

int chain_length(PrefilterMethod method, int face_size, int min_face_size);
// Bakes every level. `progress` receives the fraction done.
PrefilteredChain prefilter(const CubeMap& source, const PrefilterSettings& settings,
                           const std::function<void(double)>& progress = {});

// What a prefiltered texel estimates, integrated by brute force: for direction r (= n = v) and the
// importance path's lobe, ∫ L(l) D(h)(n·l) dl / ∫ D(h)(n·l) dl (Beckmann or GGX at α) over a
// dense grid of `grid`² directions per cube face, L by bilinear lookup of `source`.
glm::vec3 brute_force_lobe(const CubeMap& source, glm::vec3 r, Distribution distribution,
                           float alpha, int grid);
// Whether a grid of `grid`² directions per face resolves a lobe of roughness `alpha`: the lobe must
// span a few grid cells (α ≥ 4 cells of 2/grid), or the brute force itself is the larger error.
bool brute_force_resolves(float alpha, int grid);
// The same for one whole level (every texel), multithreaded.
CubeMap brute_force_level(const CubeMap& source, int face_size, Distribution distribution,
                          float alpha, int grid);

// Relative RMSE of `estimate` against `truth` over every texel and channel,
// sqrt(Σ (e − t)²) / sqrt(Σ t²).
double relative_rmse(const CubeMap& estimate, const CubeMap& truth);

// The chain for `source` read from the disk cache (keyed by `source_key`, e.g. the environment
// file's contents and the conversion settings, and the prefilter settings), or baked and stored.
PrefilteredChain cached_prefilter(const CubeMap& source, const std::string& source_key,
                                  const PrefilterSettings& settings);
std::filesystem::path prefilter_cache_file(const std::string& source_key,
                                           const PrefilterSettings& settings);

}  // namespace sl::ibl
