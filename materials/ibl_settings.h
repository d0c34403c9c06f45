#pragma once
// The IBL choices a scene file makes: which lobe, which prefilter, which shading path. Plain data
// the scene format names, so it lies below scenes/; ibl/ computes with it. The types keep their
// concept's namespace.

#include <cstdint>
#include <string>

namespace sl::ibl {

// The microfacet distribution: Beckmann (Moschos eq. 2.10) or GGX (Trowbridge-Reitz).
enum class Distribution { beckmann, ggx };
const char* to_string(Distribution distribution);
Distribution parse_distribution(const std::string& name);  // fails on an unknown name

enum class PrefilterMethod { cone, importance };
const char* to_string(PrefilterMethod method);
PrefilterMethod parse_prefilter_method(const std::string& name);

// Moschos algorithms 7–8 (Beckmann D, Schlick F, Beckmann G, Lambert, level from the roughness
// table) or the split-sum path (prefiltered radiance × DFG, SH9 irradiance for the diffuse part).
enum class Shading { moschos, split_sum };
const char* to_string(Shading shading);
Shading parse_shading(const std::string& name);

struct PrefilterSettings {
    PrefilterMethod method = PrefilterMethod::importance;
    Distribution distribution = Distribution::ggx;  // importance sampling only
    int samples = 256;                              // per texel
    int min_face_size = 8;                          // importance: the chain stops there
    bool filtered = true;                           // importance: filtered importance sampling
    int threads = 0;                                // 0: every hardware thread
    uint64_t seed = 1;                              // cone: the random sequence

    // A one-line description: the cache key's settings part and what the CLI prints.
    std::string describe() const;
};

}  // namespace sl::ibl
