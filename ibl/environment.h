#pragma once
// An HDR environment ready for shading: the equirectangular EXR read and checked, resampled to a
// cube map, its SH9 irradiance, its prefiltered chain (from the disk cache when it was baked
// before) and the split-sum DFG table. Everything the GPU needs, computed on the CPU once.

#include <filesystem>
#include <string>

#include "core/image.h"
#include "ibl/cube_map.h"
#include "ibl/microfacet.h"
#include "ibl/prefilter.h"
#include "ibl/sh9.h"
#include "scenes/scene.h"

namespace sl::ibl {

// The largest radiance an environment may have once its intensity is applied: far above any sky
// (the sun's disk is ~1e9 in these units) and far below where sums over 2^27 texels overflow.
constexpr double kMaxEnvironmentRadiance = 1e18;

// Reads an equirectangular EXR (2:1) and rejects what would poison every prefiltered texel: a
// NaN, an infinity, a negative radiance or one above kMaxEnvironmentRadiance / `intensity`,
// named with its pixel.
Image load_equirect(const std::filesystem::path& path, double intensity = 1.0);

struct LoadedEnvironment {
    CubeMap cube;  // level 0, as in the file (the intensity is applied when shading)
    Sh9 sh;
    PrefilteredChain chain;
    DfgTable dfg;
    float intensity = 1.0f;   // radiance scale, applied when shading: one cached bake for all
    float max_radiance = 0;   // of the source, before the intensity
    std::string key;          // the cache key of the source (file contents and conversion)
    double load_seconds = 0;  // reading and converting (the prefilter's time is in chain)
};

// Content hash of a file (FNV-1a 64), the part of a cache key that follows the file's bytes.
uint64_t file_hash(const std::filesystem::path& path);
// Whether two settings bake the same cube, SH9 and chain (file, face size, rotation, prefilter):
// intensity, skybox and shading are applied when shading.
bool same_bake(const Environment& a, const Environment& b);
// The environment loaded and baked (the chain from the disk cache when it is there). The last
// bake is kept in memory, so renderers of the same environment one after another (the harness's
// cells, the viewer's resizes) read and convert the file once.
LoadedEnvironment load_environment(const Environment& environment);

}  // namespace sl::ibl
