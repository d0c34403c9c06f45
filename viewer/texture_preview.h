#pragma once
// The buffer previewer (Moschos §3.2.1, XEngine's): any 2D texture a pass declares — float
// colour or depth — drawn into an 8-bit preview with a channel, a value range and an optional
// log scale; not-a-number texels show magenta.

#include <utility>

#include "gl/objects.h"

namespace sl::viewer {

struct PreviewSettings {
    int channel = 0;  // 0 rgb, 1 r, 2 g, 3 b, 4 a
    float lo = 0.0f;
    float hi = 1.0f;
    bool logarithmic = false;  // lo and hi are then log10 of the values
};

struct TextureInfo {
    int width = 0;
    int height = 0;
    GLint internal_format = 0;
    bool depth = false;
};
TextureInfo texture_info(GLuint texture);

// The smallest and largest finite value of the channel (log10 of the positive ones when
// `logarithmic`), ignoring sentinels beyond ±1e20; reads the texture back. {0, 1} when there
// are none.
std::pair<float, float> value_range(GLuint texture, int channel, bool logarithmic);

class TexturePreview {
public:
    // Renders `texture` into preview(), keeping its aspect within max_size x max_size.
    void draw(GLuint texture, const PreviewSettings& settings, int max_size);
    GLuint preview() const { return color_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    gl::Program program_;
    gl::Sampler sampler_;
    gl::VertexArray empty_array_;
    gl::Texture color_;
    gl::Framebuffer framebuffer_;
    int width_ = 0, height_ = 0;
};

}  // namespace sl::viewer
