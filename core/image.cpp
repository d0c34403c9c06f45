#include "core/image.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/check.h"
#include "core/error.h"

namespace sl {

namespace {

int checked_side(int w, int h) {
    if (w <= 0 || h <= 0) {
        fail("image size {}x{} is not positive", w, h);
    }
    if (w > kMaxImageSide || h > kMaxImageSide || static_cast<long long>(w) * h > kMaxImagePixels) {
        fail("image size {}x{} is larger than {} a side or {} pixels", w, h, kMaxImageSide,
             kMaxImagePixels);
    }
    return w;
}

}  // namespace

Image::Image(int w, int h)
    : width(checked_side(w, h)), height(h), rgb(static_cast<size_t>(w) * h * 3, 0.0f) {}

void require_finite(std::span<const float> values, int width, int channels,
                    std::string_view buffer) {
    for (size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            const size_t pixel = i / size_t(channels);
            fail("{}: pixel ({}, {}) channel {} is {}: outputs must be finite", buffer,
                 pixel % size_t(width), pixel / size_t(width), i % size_t(channels), values[i]);
        }
    }
}

void require_finite(const Image& image, std::string_view buffer) {
    require_finite(image.rgb, image.width, 3, buffer);
}

glm::vec3 Image::at(int x, int y) const {
    SL_DCHECK_INDEX(x, width);
    SL_DCHECK_INDEX(y, height);
    const size_t i = (static_cast<size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void Image::set(int x, int y, glm::vec3 value) {
    SL_DCHECK_INDEX(x, width);
    SL_DCHECK_INDEX(y, height);
    const size_t i = (static_cast<size_t>(y) * width + x) * 3;
    rgb[i] = value.r;
    rgb[i + 1] = value.g;
    rgb[i + 2] = value.b;
}

namespace {

unsigned char encode_srgb8(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<unsigned char>(std::lround(s * 255.0f));
}

}  // namespace

std::vector<unsigned char> tone_map_srgb8(const Image& image, const ToneMap& tone_map) {
    std::vector<unsigned char> out(image.rgb.size());
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        const float x = std::max(0.0f, image.rgb[i] * tone_map.exposure);
        out[i] = encode_srgb8(x / (1.0f + x));
    }
    return out;
}

void write_exr(const Image& image, const std::filesystem::path& path) {
    require_finite(image, path.string());
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* names[] = {"R", "G", "B"};
        Imf::FrameBuffer frame;
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            // OpenEXR takes a mutable pointer but only reads from it when writing.
            char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data() + c));
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float) * 3,
                                              sizeof(float) * 3 * image.width));
        }
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        fail("{}: cannot write EXR: {}", path.string(), e.what());
    }
}

Image read_exr(const std::filesystem::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const long long w = static_cast<long long>(window.max.x) - window.min.x + 1;
        const long long h = static_cast<long long>(window.max.y) - window.min.y + 1;
        if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide || w * h > kMaxImagePixels) {
            fail("{}: EXR of {}x{} pixels (at most {} a side and {} pixels)", path.string(), w, h,
                 kMaxImageSide, kMaxImagePixels);
        }
        Image image(static_cast<int>(w), static_cast<int>(h));
        const char* names[] = {"R", "G", "B"};
        Imf::FrameBuffer frame;
        for (int c = 0; c < 3; ++c) {
            const ptrdiff_t origin = -(window.min.y * ptrdiff_t(image.width) + window.min.x) * 3;
            char* base = reinterpret_cast<char*>(image.rgb.data() + origin + c);
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float) * 3,
                                              sizeof(float) * 3 * image.width));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail("{}: cannot read EXR: {}", path.string(), e.what());
    }
}

void write_png(const std::vector<unsigned char>& rgb8, int width, int height,
               const std::filesystem::path& path) {
    if (rgb8.size() != size_t(width) * size_t(height) * 3) {
        fail("{}: PNG pixel data does not match {}x{}", path.string(), width, height);
    }
    if (!stbi_write_png(path.c_str(), width, height, 3, rgb8.data(), width * 3)) {
        fail("{}: cannot write PNG", path.string());
    }
}

void write_png(const Image& image, const ToneMap& tone_map, const std::filesystem::path& path) {
    write_png(tone_map_srgb8(image, tone_map), image.width, image.height, path);
}

}  // namespace sl
