#pragma once
// Linear float RGB images, their EXR and PNG encodings, and the tone mapping used for previews.

#include <cstddef>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

namespace sl {

// Row-major RGB image, row 0 at the top, linear radiance (no tone mapping, no gamma).
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // width * height * 3

    Image() = default;
    Image(int w, int h);

    glm::vec3 at(int x, int y) const;
    void set(int x, int y, glm::vec3 value);
};

struct ToneMap {
    float exposure = 1.0f;  // linear scale applied before the curve
};

// Reinhard (x / (1 + x)) per channel after exposure, then the sRGB transfer curve, 8 bits.
std::vector<unsigned char> tone_map_srgb8(const Image& image, const ToneMap& tone_map);

// Write 32-bit float R, G, B channels (lossless ZIP compression).
void write_exr(const Image& image, const std::filesystem::path& path);
Image read_exr(const std::filesystem::path& path);
void write_png(const Image& image, const ToneMap& tone_map, const std::filesystem::path& path);
// 8-bit RGB rows, top to bottom, already display-encoded.
void write_png(const std::vector<unsigned char>& rgb8, int width, int height,
               const std::filesystem::path& path);

}  // namespace sl
