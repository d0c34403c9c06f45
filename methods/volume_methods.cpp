// The registry of volumetric methods, and the methods that live outside a folder of their own.

#include "gl/volume_method.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "gl/analytic_pass.h"
#include "gl/objects.h"
#include "gl/shaders.h"
#include "reference/cache.h"
#include "sampling/march.h"
#include "sampling/planes.h"

namespace sl::methods {

using gl::GL;
using gl::Parameter;
using gl::VolumeInputs;
using gl::VolumeMethod;

namespace {

// `none`: no participating medium is rendered, I_s = 0; the frame is the surfaces alone
// (I_obj·T(Z)). The baseline every method's cost is measured against.
class NoVolume final : public VolumeMethod {
public:
    std::string name() const override { return "none"; }
    void prepare(const Scene&) override {}
    void render(const VolumeInputs&) override {}
};

// `reference`: the exact CPU reference (reference/), computed once per scene and size, cached on
// disk under $SHAFTLAB_CACHE (default ~/.cache/shaftlab) by a hash of everything it depends on,
// and copied into the frame's in-scattering target.
class ReferenceMethod final : public VolumeMethod {
public:
    ReferenceMethod() {
        declare({.name = "shadow_samples",
                 .type = Parameter::Type::integer,
                 .default_value = 256,
                 .min = 2,
                 .max = 65536,
                 .description = "visibility samples along each ray's lit interval"});
        declare({.name = "transition_tolerance",
                 .default_value = 1e-6,
                 .min = 1e-9,
                 .max = 1e-2,
                 .description = "metres: bisection of each light/shadow transition"});
    }
    std::string name() const override { return "reference"; }
    void prepare(const Scene&) override {}
    void render(const VolumeInputs& inputs) override {
        // Recomputed (or loaded from the cache) whenever anything it depends on changes: the
        // viewer moves the camera and the light between frames.
        const uint64_t key =
            reference::reference_key(inputs.scene, inputs.width, inputs.height, options());
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
    reference::ReferenceOptions options() const {
        return {.shadow_samples = int(parameter("shadow_samples")),
                .transition_tolerance = parameter("transition_tolerance")};
    }

    Image compute(const Scene& scene, int width, int height) const {
        const bool show = isatty(STDERR_FILENO);
        std::atomic<int> shown = -1;
        Image image =
            reference::cached_reference(scene, width, height, options(), [&](double done) {
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

// `beamtree`: volume integration over the beam tree's lit regions alone (Nilsson's "Beam Tree"
// column, DESIGN.md §3): every lit-region face in one draw, signed additive blending into the
// float target, G(z) in closed form. Exact where the objects are their own bounding volumes,
// B̂ ⊆ B otherwise (the uncertain regions are left to the hybrids).
class BeamTreeMethod final : public VolumeMethod {
public:
    std::string name() const override { return "beamtree"; }
    void prepare(const Scene& scene) override {
        gl::AnalyticRegionPass::require_closed_form(scene, name());
        const auto start = std::chrono::steady_clock::now();
        const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
        const bt::RegionMesh lit = bt::extract_regions(tree).mesh(bt::Region::lit);
        build_ms_ =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        pass_.upload(scene, lit.positions, lit.triangles);
    }
    void render(const VolumeInputs& inputs) override { pass_.draw(inputs); }
    gl::TextureViews textures() const override { return pass_.textures(name()); }
    gl::MethodStatistics statistics() const override {
        return {{"cpu_ms_beamtree", build_ms_}, {"region_faces", double(pass_.triangle_count())}};
    }

private:
    gl::AnalyticRegionPass pass_;
    double build_ms_ = 0.0;
};

using Factory = std::function<std::unique_ptr<VolumeMethod>()>;

const std::vector<std::pair<std::string, Factory>>& registry() {
    static const std::vector<std::pair<std::string, Factory>> methods = {
        {"none", [] { return std::make_unique<NoVolume>(); }},
        {"beamtree", [] { return std::make_unique<BeamTreeMethod>(); }},
        {"planes", [] { return sampling::create_planes_method(sampling::PlanesVariant::planes); }},
        {"hybrid1",
         [] { return sampling::create_planes_method(sampling::PlanesVariant::hybrid1); }},
        {"hybrid2",
         [] { return sampling::create_planes_method(sampling::PlanesVariant::hybrid2); }},
        {"march", [] { return sampling::create_march_method(sampling::MarchVariant::march); }},
        {"hybrid3", [] { return sampling::create_march_method(sampling::MarchVariant::hybrid3); }},
        {"reference", [] { return std::make_unique<ReferenceMethod>(); }},
    };
    return methods;
}

}  // namespace

std::vector<std::string> volume_method_names() {
    std::vector<std::string> names;
    for (const auto& [name, factory] : registry()) {
        names.push_back(name);
    }
    return names;
}

std::unique_ptr<VolumeMethod> create_volume_method(const std::string& name) {
    for (const auto& [known, factory] : registry()) {
        if (known == name) {
            return factory();
        }
    }
    fail("unknown method '{}' (known: {})", name, fmt::join(volume_method_names(), ", "));
}

}  // namespace sl::methods
