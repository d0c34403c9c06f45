#include "viewer/texture_preview.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "gl/debug.h"
#include "gl/shaders.h"

namespace sl::viewer {

using gl::GL;

TextureInfo texture_info(GLuint texture) {
    TextureInfo info;
    GL.GetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &info.width);
    GL.GetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &info.height);
    GL.GetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &info.internal_format);
    info.depth = info.internal_format == GL_DEPTH_COMPONENT32F ||
                 info.internal_format == GL_DEPTH_COMPONENT24 ||
                 info.internal_format == GL_DEPTH_COMPONENT16 ||
                 info.internal_format == GL_DEPTH_COMPONENT32;
    return info;
}

std::pair<float, float> value_range(GLuint texture, int channel, bool logarithmic) {
    const TextureInfo info = texture_info(texture);
    const size_t texels = size_t(info.width) * size_t(info.height);
    std::vector<float> values(texels * (info.depth ? 1 : 4));
    GL.PixelStorei(GL_PACK_ALIGNMENT, 1);
    GL.GetTextureImage(texture, 0, info.depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT,
                       GLsizei(values.size() * sizeof(float)), values.data());
    gl::check_errors("reading a texture for its value range");
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (size_t t = 0; t < texels; ++t) {
        for (int c = 0; c < (info.depth ? 1 : 4); ++c) {
            const bool wanted = info.depth || (channel == 0 ? c < 3 : c == channel - 1);
            float v = values[t * (info.depth ? 1 : 4) + size_t(c)];
            // Values beyond ±1e20 are "no value" sentinels (an empty interval's 1e30).
            if (!wanted || !std::isfinite(v) || std::abs(v) > 1e20f || (logarithmic && v <= 0.0f)) {
                continue;
            }
            if (logarithmic) {
                v = std::log10(v);
            }
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    if (!(lo <= hi)) {
        return {0.0f, 1.0f};
    }
    return {lo, hi > lo ? hi : lo + 1.0f};
}

void TexturePreview::draw(GLuint texture, const PreviewSettings& settings, int max_size) {
    if (!program_) {
        program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                       {GL_FRAGMENT_SHADER, "viewer/shaders/preview.frag"}});
        sampler_ = gl::create_plain_sampler(GL_NEAREST);
        empty_array_ = gl::create_vertex_array();
    }
    const TextureInfo info = texture_info(texture);
    const float scale =
        std::min(1.0f, float(max_size) / float(std::max({info.width, info.height, 1})));
    const int w = std::max(1, int(std::lround(info.width * scale)));
    const int h = std::max(1, int(std::lround(info.height * scale)));
    if (w != width_ || h != height_) {
        color_ = gl::create_texture_2d(GL_RGBA8, w, h, GL_LINEAR);
        color_.label("buffer preview");
        framebuffer_ = gl::create_framebuffer();
        GL.NamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
        width_ = w;
        height_ = h;
    }
    GL.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    GL.Viewport(0, 0, w, h);
    GL.Disable(GL_BLEND);
    GL.Disable(GL_DEPTH_TEST);
    const GLuint program = program_.id();
    GL.ProgramUniform1i(program, 0, info.depth ? 1 : settings.channel);
    GL.ProgramUniform2f(program, 1, settings.lo, settings.hi);
    GL.ProgramUniform1i(program, 2, settings.logarithmic ? 1 : 0);
    GL.UseProgram(program);
    GL.BindTextureUnit(0, texture);
    GL.BindSampler(0, sampler_.id());
    GL.BindVertexArray(empty_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    GL.BindSampler(0, 0);
    gl::check_errors("drawing the buffer preview");
}

}  // namespace sl::viewer
