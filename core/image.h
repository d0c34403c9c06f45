#pragma once
// Linear float RGB images, their EXR and PNG encodings, and the tone mapping used for previews.

#include <cstddef>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace sl {

// The largest image made or read: 16384 texels a side and 2^27 pixels (1.5 GiB of RGB floats).
constexpr int kMaxImageSide = 16384;
constexpr long long kMaxImagePixels = 1LL << 27;

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

// No output holds a NaN or an infinity: throws sl::Error naming `buffer` and its first pixel
// (x, y, row 0 at the top) with a non-finite channel. `values` is `width` pixels of `channels`
// floats a row.
void require_finite(const Image& image, std::string_view buffer);
void require_finite(std::span<const float> values, int width, int channels,
                    std::string_view buffer);

struct ToneMap {
    float exposure = 1.0f;  // linear scale applied before the curve
};

// Reinhard (x / (1 + x)) per channel after exposure, then the sRGB transfer curve, 8 bits.
std::vector<unsigned char> tone_map_srgb8(const Image& image, const ToneMap& tone_map);

// Write 32-bit float R, G, B channels (lossless ZIP compression); a non-finite pixel is an error
// (require_finite, naming the file) before anything is written.
void write_exr(const Image& image, const std::filesystem::path& path);
// Read one; larger than kMaxImageSide or kMaxImagePixels is an error before anything is
// allocated.
Image read_exr(const std::filesystem::path& path);
void write_png(const Image& image, const ToneMap& tone_map, const std::filesystem::path& path);
// 8-bit RGB rows, top to bottom, already display-encoded.
void write_png(const std::vector<unsigned char>& rgb8, int width, int height,
               const std::filesystem::path& path);

}  // namespace sl
