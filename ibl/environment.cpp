#include "ibl/environment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"
#include "core/hash.h"

namespace sl::ibl {

Image load_equirect(const std::filesystem::path& path, double intensity) {
    Image image = read_exr(path);
    if (image.width != 2 * image.height) {
        fail("{}: an equirectangular environment must be 2:1, not {}x{}", path.string(),
             image.width, image.height);
    }
    double mean = 0.0;
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        const float v = image.rgb[i];
        if (!std::isfinite(v)) {
            const size_t pixel = i / 3;
            fail("{}: pixel ({}, {}) has radiance {} (must be finite)", path.string(),
                 pixel % size_t(image.width), pixel / size_t(image.width), v);
        }
        if (double(v) * intensity > kMaxEnvironmentRadiance) {
            const size_t pixel = i / 3;
            fail(
                "{}: pixel ({}, {}) has radiance {} (x intensity {}: above {}, the range the "
                "prefilter and SH9 integrate without overflow)",
                path.string(), pixel % size_t(image.width), pixel / size_t(image.width), v,
                intensity, kMaxEnvironmentRadiance);
        }
        mean += double(std::max(v, 0.0f)) / double(image.rgb.size());
    }
    // Lossy EXR compression rings slightly below zero next to dark texels (Blender's studio
    // lights do, by up to 2.5% of their mean): such values are clamped to zero; anything below
    // -5% of the mean is a real negative radiance and an error.
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        float& v = image.rgb[i];
        if (v < 0.0f && double(-v) > 0.05 * mean) {
            const size_t pixel = i / 3;
            fail("{}: pixel ({}, {}) has radiance {} (must be non-negative)", path.string(),
                 pixel % size_t(image.width), pixel / size_t(image.width), v);
        }
        v = std::max(v, 0.0f);
    }
    return image;
}

uint64_t file_hash(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        fail("{}: cannot read", path.string());
    }
    uint64_t hash = kFnv1aOffset;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) {
        hash = fnv1a(std::string_view(buffer, size_t(in.gcount())), hash);
    }
    return hash;
}

bool same_bake(const Environment& a, const Environment& b) {
    return a.file == b.file && a.face_size == b.face_size &&
           a.rotation_degrees == b.rotation_degrees &&
           a.prefilter.describe() == b.prefilter.describe();
}

LoadedEnvironment load_environment(const Environment& environment) {
    static std::mutex mutex;
    static std::optional<std::pair<Environment, LoadedEnvironment>> last;
    const std::lock_guard lock(mutex);
    auto check_range = [&](const LoadedEnvironment& loaded) {
        if (double(loaded.max_radiance) * environment.intensity > kMaxEnvironmentRadiance) {
            fail(
                "{}: radiance {} x intensity {} is above {}, the range the prefilter and SH9 "
                "integrate without overflow",
                environment.file.string(), loaded.max_radiance, environment.intensity,
                kMaxEnvironmentRadiance);
        }
    };
    if (last && same_bake(last->first, environment)) {
        check_range(last->second);
        LoadedEnvironment copy = last->second;
        copy.intensity = environment.intensity;
        copy.load_seconds = 0.0;
        copy.chain.seconds = 0.0;
        return copy;
    }
    const auto start = std::chrono::steady_clock::now();
    LoadedEnvironment loaded;
    const Image equirect = load_equirect(environment.file, environment.intensity);
    loaded.max_radiance = *std::max_element(equirect.rgb.begin(), equirect.rgb.end());
    loaded.cube = cube_from_equirect(equirect, environment.face_size, environment.rotation_degrees);
    loaded.intensity = environment.intensity;
    loaded.key = fmt::format("{:016x} face={} rotation={}", file_hash(environment.file),
                             environment.face_size, environment.rotation_degrees);
    loaded.sh = project_sh9(loaded.cube);
    loaded.load_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    loaded.chain = cached_prefilter(loaded.cube, loaded.key, environment.prefilter);
    loaded.dfg = compute_dfg_table(environment.prefilter.distribution);
    last.emplace(environment, loaded);
    return loaded;
}

}  // namespace sl::ibl
