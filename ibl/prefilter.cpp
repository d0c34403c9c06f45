#include "ibl/prefilter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "core/cache.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/metrics.h"

namespace sl::ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

uint64_t splitmix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// A small counter-based generator: one independent stream per texel, so a bake's result does
// not depend on how its rows were split between threads.
class TexelRandom {
public:
    explicit TexelRandom(uint64_t key) : state_(splitmix64(key)) {}
    float next() {
        state_ = splitmix64(state_);
        return float(state_ >> 40) * (1.0f / 16777216.0f);
    }

private:
    uint64_t state_;
};

// Runs body(face, y) for every row of every face of a level of `size`, on `threads` threads.
// The chain's rows done so far, for the progress callback.
struct RowProgress {
    int threads = 0;
    int64_t total = 0;
    const std::function<void(double)>& report;
    std::atomic<int64_t> done{0};
};

// Calls body(face, row) for each of the 6 x size rows of a level, in parallel.
void for_each_row(int size, RowProgress& rows, const std::function<void(int, int)>& body) {
    tbb::task_arena arena(rows.threads > 0 ? rows.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, 6 * size),
                          [&](const tbb::blocked_range<int>& r) {
                              for (int row = r.begin(); row != r.end(); ++row) {
                                  body(row / size, row % size);
                              }
                              const int64_t done = rows.done += r.size();
                              if (rows.report) {
                                  rows.report(double(done) / double(rows.total));
                              }
                          });
    });
}

// A texel's direction n and a tangent frame (t, b) about it.
struct TexelFrame {
    glm::vec3 n, t, b;
};

// Sets every texel of `level` to shade(face, x, y, frame), rows in parallel.
void for_each_texel(CubeMap& level, RowProgress& rows,
                    const std::function<glm::vec3(int, int, int, const TexelFrame&)>& shade) {
    for_each_row(level.size, rows, [&](int f, int y) {
        for (int x = 0; x < level.size; ++x) {
            TexelFrame frame;
            frame.n = level.direction(f, x, y);
            orthonormal_basis(frame.n, frame.t, frame.b);
            level.set(f, x, y, shade(f, x, y, frame));
        }
    });
}

// One importance-sampled direction of the level's lobe in the local frame (n = v = +z), with
// its cosine weight and the source lod it is read at: the same for every texel of the level.
struct LobeSample {
    glm::vec3 l;
    float weight;
    float lod;
};

std::vector<LobeSample> lobe_samples(const PrefilterSettings& s, float alpha, int source_size) {
    const float texel_solid_angle_0 = 4.0f * kPi / (6.0f * float(source_size * source_size));
    std::vector<LobeSample> samples;
    samples.reserve(size_t(s.samples));
    for (int i = 0; i < s.samples; ++i) {
        const glm::vec3 h =
            sample_half_vector(s.distribution, alpha, hammersley(uint32_t(i), uint32_t(s.samples)));
        const glm::vec3 l = 2.0f * h.z * h - glm::vec3(0, 0, 1);
        if (l.z <= 0.0f) {
            continue;
        }
        float lod = 0.0f;
        if (s.filtered) {
            // pdf(l) = D(h)(n·h) / (4 v·h) = D(h) / 4 with n = v.
            const float pdf = distribution(s.distribution, alpha, h.z) / 4.0f;
            const float sample_solid_angle = 1.0f / (float(s.samples) * std::max(pdf, 1e-8f));
            lod = std::max(0.0f, 0.5f * std::log2(sample_solid_angle / texel_solid_angle_0) + 1.0f);
        }
        samples.push_back({l, l.z, lod});
    }
    return samples;
}

void check(const PrefilterSettings& s, const CubeMap& source) {
    if (s.samples < 1 || s.samples > 1 << 20) {
        fail("prefilter: samples {} must be in 1..{}", s.samples, 1 << 20);
    }
    if (s.min_face_size < 1) {
        fail("prefilter: min_face_size {} must be at least 1", s.min_face_size);
    }
    if (s.threads < 0) {
        fail("prefilter: threads {} must be 0 (all) or more", s.threads);
    }
    if (source.size < 1 || (source.size & (source.size - 1))) {
        fail("prefilter: the source's face size {} must be a power of two", source.size);
    }
}

}  // namespace

const std::vector<ConeLevel>& moschos_cone_levels() {
    // Moschos figure 3.24: roughness, sampling-cone half-angle (the lobe aperture column is tan θ).
    static const std::vector<ConeLevel> levels = {
        {0.0f, 0.0f},  {0.01f, 1.0f}, {0.05f, 6.0f}, {0.1f, 12.0f}, {0.2f, 23.0f}, {0.3f, 32.0f},
        {0.4f, 40.0f}, {0.5f, 47.0f}, {0.6f, 52.0f}, {0.7f, 56.0f}, {1.0f, 65.0f}};
    return levels;
}

glm::vec2 moschos_cone_measure(size_t level) {
    const auto& table = moschos_cone_levels();
    const ConeLevel row = table[std::min(level, table.size() - 1)];
    const float t = std::tan(row.cone_degrees * kPi / 180.0f);
    return {t * t, row.roughness > 0.0f ? t * t / (row.roughness * row.roughness) : 0.0f};
}

float importance_roughness(int level, int levels) {
    if (levels <= 1) {
        return 0.0f;
    }
    const float t = float(level) / float(levels - 1);
    return t * t;
}

float roughness_to_lod(const PrefilteredChain& chain, float alpha) {
    const int levels = int(chain.levels.size());
    alpha = std::max(alpha, 0.0f);
    if (chain.settings.method == PrefilterMethod::importance) {
        return std::min(std::sqrt(alpha), 1.0f) * float(levels - 1);
    }
    for (int l = 0; l + 1 < levels; ++l) {
        const float a0 = chain.roughness[size_t(l)], a1 = chain.roughness[size_t(l) + 1];
        if (alpha <= a1) {
            return float(l) + std::clamp((alpha - a0) / (a1 - a0), 0.0f, 1.0f);
        }
    }
    return float(levels - 1);
}

int chain_length(PrefilterMethod method, int face_size, int min_face_size) {
    int levels = 1;
    if (method == PrefilterMethod::cone) {
        const int table = int(moschos_cone_levels().size());
        while (levels < table && (face_size >> levels) >= 1)
            ++levels;
    } else {
        while ((face_size >> levels) >= std::max(min_face_size, 1))
            ++levels;
    }
    return levels;
}

namespace {

// Level l by Moschos algorithm 6: random points on the cone's base disk (radius tan θ at unit
// distance), cosine weighted; self-normalised (see the header). Returns its roughness.
float cone_level(const CubeMap& source, const PrefilterSettings& s, int l, CubeMap& level,
                 RowProgress& rows) {
    const ConeLevel cone = moschos_cone_levels()[size_t(l)];
    const float radius = std::tan(cone.cone_degrees * kPi / 180.0f);
    for_each_texel(level, rows, [&](int f, int x, int y, const TexelFrame& frame) {
        const auto& [n, t, b] = frame;
        TexelRandom random(s.seed * 0x100000001B3ull ^ (uint64_t(l) << 56 | uint64_t(f) << 48 |
                                                        uint64_t(y) << 24 | uint64_t(x)));
        glm::vec3 sum(0.0f);
        float weights = 0.0f;
        for (int i = 0; i < s.samples; ++i) {
            const float r = radius * std::sqrt(random.next());
            const float phi = 2.0f * kPi * random.next();
            const glm::vec3 d = glm::normalize(n + r * std::cos(phi) * t + r * std::sin(phi) * b);
            const float w = glm::dot(n, d);
            sum += w * source.sample(d);
            weights += w;
        }
        return sum / weights;
    });
    return cone.roughness;
}

// Level l of `levels` by importance sampling the GGX or Beckmann lobe, the same directions for
// every texel, read from the source's mip chain where filtered. Returns its roughness.
float importance_level(const CubeMap& source, const CubeMipChain& source_mips,
                       const PrefilterSettings& s, int l, int levels, CubeMap& level,
                       RowProgress& rows) {
    const float alpha = importance_roughness(l, levels);
    const std::vector<LobeSample> samples = lobe_samples(s, alpha, source.size);
    float weights = 0.0f;
    for (const LobeSample& sample : samples)
        weights += sample.weight;
    for_each_texel(level, rows, [&](int, int, int, const TexelFrame& frame) {
        const auto& [n, t, b] = frame;
        glm::vec3 sum(0.0f);
        for (const LobeSample& sample : samples) {
            const glm::vec3 d = sample.l.x * t + sample.l.y * b + sample.l.z * n;
            sum += sample.weight *
                   (s.filtered ? sample_lod(source_mips, d, sample.lod) : source.sample(d));
        }
        return weights > 0.0f ? sum / weights : source.sample(n);
    });
    return alpha;
}

}  // namespace

PrefilteredChain prefilter(const CubeMap& source, const PrefilterSettings& s,
                           const std::function<void(double)>& progress) {
    check(s, source);
    const auto start = std::chrono::steady_clock::now();
    PrefilteredChain chain;
    chain.settings = s;
    const int levels = chain_length(s.method, source.size, s.min_face_size);
    RowProgress rows{s.threads, 0, progress};
    for (int l = 1; l < levels; ++l)
        rows.total += 6 * (source.size >> l);

    CubeMipChain source_mips;
    if (s.method == PrefilterMethod::importance && s.filtered) {
        source_mips = build_mip_chain(source);
    }
    chain.levels.push_back(source);
    chain.roughness.push_back(0.0f);
    chain.level_seconds.push_back(0.0);
    for (int l = 1; l < levels; ++l) {
        const auto level_start = std::chrono::steady_clock::now();
        CubeMap level(source.size >> l);
        chain.roughness.push_back(
            s.method == PrefilterMethod::cone
                ? cone_level(source, s, l, level, rows)
                : importance_level(source, source_mips, s, l, levels, level, rows));
        for (int f = 0; f < 6; ++f) {
            require_finite(level.faces[size_t(f)],
                           fmt::format("prefiltered level {} face {}", l, f));
        }
        chain.levels.push_back(std::move(level));
        chain.level_seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - level_start).count());
    }
    chain.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return chain;
}

glm::vec3 brute_force_lobe(const CubeMap& source, glm::vec3 r, Distribution dist, float alpha,
                           int grid) {
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < grid; ++y)
            for (int x = 0; x < grid; ++x) {
                const glm::vec3 l = cube_direction(
                    f, {(float(x) + 0.5f) / float(grid), (float(y) + 0.5f) / float(grid)});
                const float n_dot_l = glm::dot(r, l);
                if (n_dot_l <= 0.0f) {
                    continue;
                }
                const glm::vec3 h = glm::normalize(l + r);
                const double w = double(distribution(dist, alpha, glm::dot(r, h))) * n_dot_l *
                                 texel_solid_angle(grid, x, y);
                if (w <= 0.0) {
                    continue;
                }
                sum += w * glm::dvec3(source.sample(l));
                weights += w;
            }
    return weights > 0.0 ? glm::vec3(sum / weights) : source.sample(r);
}

bool brute_force_resolves(float alpha, int grid) {
    return grid > 0 && alpha >= 4.0f * (2.0f / float(grid));
}

CubeMap brute_force_level(const CubeMap& source, int face_size, Distribution dist, float alpha,
                          int grid) {
    CubeMap level(face_size);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, 6 * face_size), [&](const tbb::blocked_range<int>& rows) {
            for (int row = rows.begin(); row != rows.end(); ++row) {
                const int f = row / face_size, y = row % face_size;
                for (int x = 0; x < face_size; ++x) {
                    level.set(
                        f, x, y,
                        brute_force_lobe(source, level.direction(f, x, y), dist, alpha, grid));
                }
            }
        });
    return level;
}

double relative_rmse(const CubeMap& estimate, const CubeMap& truth) {
    if (estimate.size != truth.size) {
        fail("relative_rmse: face sizes {} and {} differ", estimate.size, truth.size);
    }
    return compare_images(faces_to_strip(estimate), faces_to_strip(truth)).rel_rmse;
}

// ---- the disk cache -------------------------------------------------------------------------

namespace {

constexpr char kMagic[8] = {'S', 'L', 'I', 'B', 'L', 'C', '0', '1'};

std::optional<PrefilteredChain> read_chain(const std::filesystem::path& file,
                                           const PrefilterSettings& settings) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        return std::nullopt;
    }
    char magic[8];
    int32_t levels = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&levels), sizeof(levels));
    if (!in || std::memcmp(magic, kMagic, 8) != 0 || levels < 1 || levels > 16) {
        return std::nullopt;
    }
    PrefilteredChain chain;
    chain.settings = settings;
    for (int l = 0; l < levels; ++l) {
        int32_t size = 0;
        float roughness = 0;
        in.read(reinterpret_cast<char*>(&size), sizeof(size));
        in.read(reinterpret_cast<char*>(&roughness), sizeof(roughness));
        if (!in || size < 1 || size > 16384) {
            return std::nullopt;
        }
        CubeMap level(size);
        for (Image& face : level.faces) {
            in.read(reinterpret_cast<char*>(face.rgb.data()),
                    std::streamsize(face.rgb.size() * sizeof(float)));
        }
        if (!in) {
            return std::nullopt;
        }
        chain.levels.push_back(std::move(level));
        chain.roughness.push_back(roughness);
        chain.level_seconds.push_back(0.0);
    }
    return chain;
}

void write_chain(const PrefilteredChain& chain, const std::filesystem::path& file) {
    std::ofstream out(file, std::ios::binary);
    const int32_t levels = int32_t(chain.levels.size());
    out.write(kMagic, 8);
    out.write(reinterpret_cast<const char*>(&levels), sizeof(levels));
    for (size_t l = 0; l < chain.levels.size(); ++l) {
        const int32_t size = chain.levels[l].size;
        out.write(reinterpret_cast<const char*>(&size), sizeof(size));
        out.write(reinterpret_cast<const char*>(&chain.roughness[l]), sizeof(float));
        for (const Image& face : chain.levels[l].faces) {
            out.write(reinterpret_cast<const char*>(face.rgb.data()),
                      std::streamsize(face.rgb.size() * sizeof(float)));
        }
    }
    if (!out) {
        fail("{}: cannot write the prefilter cache", file.string());
    }
}

}  // namespace

std::filesystem::path prefilter_cache_file(const std::string& source_key,
                                           const PrefilterSettings& settings) {
    // Threads do not change the result (one random stream per texel), so they are not in the key.
    return cache_directory() /
           fmt::format("prefilter-{:016x}.bin", fnv1a(source_key + "|" + settings.describe()));
}

PrefilteredChain cached_prefilter(const CubeMap& source, const std::string& source_key,
                                  const PrefilterSettings& settings) {
    const std::filesystem::path file = prefilter_cache_file(source_key, settings);
    if (std::optional<PrefilteredChain> cached = read_chain(file, settings);
        cached && cached->levels[0].size == source.size) {
        return std::move(*cached);
    }
    PrefilteredChain chain = prefilter(source, settings);
    write_cache_file(
        file, [&](const std::filesystem::path& temporary) { write_chain(chain, temporary); });
    return chain;
}

}  // namespace sl::ibl
