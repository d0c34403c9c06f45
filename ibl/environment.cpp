#include "ibl/environment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "core/error.h"

namespace sl::ibl {

Image load_equirect(const std::filesystem::path& path) {
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
    uint64_t hash = 0xCBF29CE484222325ull;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) {
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            hash = (hash ^ uint8_t(buffer[i])) * 0x100000001B3ull;
        }
    }
    return hash;
}

LoadedEnvironment load_environment(const Environment& environment) {
    const auto start = std::chrono::steady_clock::now();
    LoadedEnvironment loaded;
    const Image equirect = load_equirect(environment.file);
    loaded.cube = cube_from_equirect(equirect, environment.face_size, environment.rotation_degrees);
    loaded.intensity = environment.intensity;
    loaded.key = fmt::format("{:016x} face={} rotation={}", file_hash(environment.file),
                             environment.face_size, environment.rotation_degrees);
    loaded.sh = project_sh9(loaded.cube);
    loaded.load_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    loaded.chain = cached_prefilter(loaded.cube, loaded.key, environment.prefilter);
    loaded.dfg = compute_dfg_table(environment.prefilter.distribution);
    return loaded;
}

}  // namespace sl::ibl
