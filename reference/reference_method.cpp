#include "reference/reference_method.h"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/image.h"
#include "frame/method_registry.h"
#include "gl/objects.h"
#include "gl/shaders.h"
#include "reference/cache.h"

namespace sl::reference {

namespace {

using gl::GL;

class ReferenceMethod final : public frame::VolumeMethod {
public:
    ReferenceMethod() : VolumeMethod("reference") {
        shadow_samples_ = declare_integer("shadow_samples", 256, 2, 65536,
                                          "visibility samples along each ray's lit interval");
        transition_tolerance_ = declare_real("transition_tolerance", 1e-6, 1e-9, 1e-2,
                                             "metres: bisection of each light/shadow transition");
    }
    std::string accepts() const override {
        return "every medium and light, any number (closed forms per visible interval, a point "
               "light whole, quadrature for a smooth cone edge)";
    }
    // The reference sums over the lights as declared (a point light whole, not as six faces).
    bool takes_every_light() const override { return true; }
    void prepare_light(const Scene&) override {}
    // Nothing per frame: render() recomputes (or loads) the reference when its key changes.
    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene&,
                                                       const SceneChange&) const override {
        return nullptr;
    }
    void apply_update_light(const Scene&, const SceneChange&,
                            std::unique_ptr<frame::FrameWork>) override {}
    void render(const frame::VolumeInputs& inputs) override {
        // Recomputed (or loaded from the cache) whenever anything it depends on changes: the
        // viewer moves the camera and the light between frames.
        const uint64_t key = reference_key(inputs.scene, inputs.width, inputs.height, options());
        if (!texture_ || key != computed_key_) {
            upload(compute(inputs.scene, inputs.width, inputs.height));
            computed_key_ = key;
        }
        GL.UseProgram(program_.id());
        GL.BindTextureUnit(0, texture_.id());
        GL.BindVertexArray(vertex_array_.id());
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    const Image& in_scattering() const { return image_; }
    gl::TextureViews textures() const override {
        return texture_ ? gl::TextureViews{{"reference/I_s", texture_.id()}} : gl::TextureViews{};
    }

private:
    frame::Param<int> shadow_samples_;
    frame::Param<double> transition_tolerance_;

    ReferenceOptions options() const {
        return {.shadow_samples = *shadow_samples_, .transition_tolerance = *transition_tolerance_};
    }

    Image compute(const Scene& scene, int width, int height) const {
        const bool show = isatty(STDERR_FILENO);
        std::atomic<int> shown = -1;
        Image image = cached_reference(scene, width, height, options(), [&](double done) {
            const int percent = int(100.0 * done);
            if (show && percent / 2 > shown.exchange(percent / 2)) {
                std::fprintf(stderr, "\rreference %dx%d [%-50s] %3d%%", width, height,
                             std::string(size_t(percent / 2), '#').c_str(), percent);
            }
        });
        if (show && shown >= 0) {
            std::fputs("\n", stderr);
        }
        return image;
    }

    void upload(Image image) {
        image_ = std::move(image);
        width_ = image_.width;
        height_ = image_.height;
        std::vector<float> rgb(image_.rgb.size());
        for (int y = 0; y < height_; ++y) {  // GL rows run bottom to top
            std::copy_n(&image_.rgb[size_t(height_ - 1 - y) * width_ * 3], size_t(width_) * 3,
                        &rgb[size_t(y) * width_ * 3]);
        }
        texture_ = gl::create_texture_2d(GL_RGBA32F, width_, height_, GL_NEAREST);
        GL.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        GL.TextureSubImage2D(texture_.id(), 0, 0, 0, width_, height_, GL_RGB, GL_FLOAT, rgb.data());
        if (!program_) {
            program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                           {GL_FRAGMENT_SHADER, "gl/shaders/copy.frag"}});
            vertex_array_ = gl::create_vertex_array();
        }
    }

    Image image_;
    int width_ = 0, height_ = 0;
    uint64_t computed_key_ = 0;
    gl::Texture texture_;
    gl::Program program_;
    gl::VertexArray vertex_array_;
};

}  // namespace

void register_methods(frame::MethodRegistry& registry) {
    registry.add("reference", 90, [] { return std::make_unique<ReferenceMethod>(); });
}

}  // namespace sl::reference
