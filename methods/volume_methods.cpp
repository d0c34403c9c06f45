// The registry of volumetric methods, and the methods that live outside a folder of their own.

#include "gl/volume_method.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <functional>
#include <map>

#include <unistd.h>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <cmath>
#include <numbers>

#include "analytic/phase_functions.h"
#include "analytic/quadrature.h"
#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "gl/objects.h"
#include "gl/shaders.h"
#include "reference/reference.h"

namespace sl::methods {

using gl::GL;
using gl::Parameter;
using gl::VolumeInputs;
using gl::VolumeMethod;

gl::Texture create_sun_table() {
    // 1024² keeps bilinear interpolation within 1e-4 of the closed form (tested); the data is
    // computed once per process.
    constexpr int kSize = 1024;
    constexpr double kUMax = 32.0;  // SUN_TABLE_U_MAX in in_scattering.glsl
    static const std::vector<float> table = [] {
        std::vector<float> values(size_t(kSize) * kSize);
        for (int iu = 0; iu < kSize; ++iu) {
            const double u = kUMax * iu / (kSize - 1);
            double previous_v = 0.0, sum = 0.0;
            for (int iv = 0; iv < kSize; ++iv) {
                const double v = 0.5 * std::numbers::pi * iv / (kSize - 1);
                sum += analytic::integrate([&](double z) { return std::exp(-u * std::tan(z)); },
                                           previous_v, std::min(v, 0.5 * std::numbers::pi - 1e-12));
                previous_v = v;
                values[size_t(iv) * kSize + iu] = float(sum);
            }
        }
        return values;
    }();
    gl::Texture texture = gl::create_texture_2d(GL_R32F, kSize, kSize, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, kSize, kSize, GL_RED, GL_FLOAT, table.data());
    return texture;
}

gl::Texture create_phase_table(const Medium& medium) {
    constexpr int kSize = 1024;  // PHASE_TABLE_SIZE in in_scattering.glsl
    std::vector<float> table(kSize);
    double sum = 0.0, previous = -0.5 * std::numbers::pi;
    for (int i = 0; i < kSize; ++i) {
        const double theta = std::numbers::pi * (double(i) / (kSize - 1) - 0.5);
        sum += analytic::integrate(
            [&](double t) { return analytic::phase(medium.phase, medium.g, -std::sin(t)); },
            previous, theta);
        previous = theta;
        table[size_t(i)] = float(sum);
    }
    gl::Texture texture = gl::create_texture_2d(GL_R32F, kSize, 1, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, kSize, 1, GL_RED, GL_FLOAT, table.data());
    return texture;
}

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
        if (!texture_ || width_ != inputs.width || height_ != inputs.height ||
            computed_with_ != parameters_key()) {
            upload(compute(inputs.scene, inputs.width, inputs.height));
        }
        GL.UseProgram(program_.id());
        GL.BindTextureUnit(0, texture_.id());
        GL.BindVertexArray(vertex_array_.id());
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    const Image& in_scattering() const { return image_; }

private:
    static std::filesystem::path cache_directory() {
        if (const char* dir = std::getenv("SHAFTLAB_CACHE"); dir && *dir)
            return dir;
        if (const char* home = std::getenv("HOME"); home && *home) {
            return std::filesystem::path(home) / ".cache" / "shaftlab";
        }
        return std::filesystem::temp_directory_path() / "shaftlab-cache";
    }

    Image compute(const Scene& scene, int width, int height) {
        const reference::ReferenceOptions options{
            .shadow_samples = int(parameter("shadow_samples")),
            .transition_tolerance = parameter("transition_tolerance")};
        const std::filesystem::path file =
            cache_directory() /
            fmt::format("reference-{:016x}.exr",
                        reference::reference_key(scene, width, height, options));
        std::error_code ec;
        if (std::filesystem::is_regular_file(file, ec)) {
            return read_exr(file);
        }
        const reference::ReferenceRenderer renderer(scene);
        const bool show = isatty(STDERR_FILENO);
        std::atomic<int> shown = -1;
        const Image image = renderer.render(width, height, options, [&](double done) {
            const int percent = int(100.0 * done);
            if (show && percent / 2 > shown.exchange(percent / 2)) {
                std::fprintf(stderr, "\rreference %dx%d [%-50s] %3d%%", width, height,
                             std::string(size_t(percent / 2), '#').c_str(), percent);
            }
        });
        if (show) {
            std::fputs("\n", stderr);
        }
        // Cache it: a failure here only costs the next run the time again.
        std::filesystem::create_directories(file.parent_path(), ec);
        const std::filesystem::path temporary = file.string() + fmt::format(".{}.tmp", getpid());
        try {
            write_exr(image, temporary);
            std::filesystem::rename(temporary, file, ec);
        } catch (const Error&) {
            std::filesystem::remove(temporary, ec);
        }
        return image;
    }

    std::pair<double, double> parameters_key() const {
        return {parameter("shadow_samples"), parameter("transition_tolerance")};
    }

    void upload(Image image) {
        computed_with_ = parameters_key();
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
    std::pair<double, double> computed_with_;
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
        if (scene.medium.phase != PhaseFunction::isotropic || scene.light.falloff_degrees > 0.0f) {
            fail(
                "method 'beamtree' needs the isotropic phase function and a hard cone edge (its "
                "closed forms); the scene has phase '{}' and falloff {}",
                to_string(scene.medium.phase), scene.light.falloff_degrees);
        }
        bt::VolumeLibrary library({.max_outer_planes = scene.bounds.max_outer_planes,
                                   .automatic_inner = scene.bounds.automatic_inner});
        const bt::BeamTree tree(scene.light, library.build(scene, nullptr));
        const bt::RegionMesh lit = bt::extract_regions(tree).mesh(bt::Region::lit);
        index_count_ = GLsizei(lit.triangles.size() * 3);
        vertices_ =
            gl::create_buffer(lit.positions.data(), lit.positions.size() * sizeof(glm::vec3));
        indices_ =
            gl::create_buffer(lit.triangles.data(), lit.triangles.size() * sizeof(glm::uvec3));
        vertex_array_ = gl::create_vertex_array();
        GL.VertexArrayVertexBuffer(vertex_array_.id(), 0, vertices_.id(), 0, sizeof(glm::vec3));
        GL.VertexArrayElementBuffer(vertex_array_.id(), indices_.id());
        GL.EnableVertexArrayAttrib(vertex_array_.id(), 0);
        GL.VertexArrayAttribFormat(vertex_array_.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
        GL.VertexArrayAttribBinding(vertex_array_.id(), 0, 0);
        if (!program_) {
            program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/beamtree.vert"},
                                           {GL_FRAGMENT_SHADER, "gl/shaders/beamtree.frag"}});
            sun_table_ = methods::create_sun_table();
        }
    }
    void render(const VolumeInputs& inputs) override {
        GL.UseProgram(program_.id());
        GL.BindTextureUnit(0, inputs.surface_depth);
        GL.BindTextureUnit(kSunTableUnit, sun_table_.id());
        GL.BindTextureUnit(kPhaseTableUnit, phase_table_.id());
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);  // signed sums in the float target
        GL.Enable(GL_DEPTH_CLAMP);     // faces in front of the near plane still count
        GL.BindVertexArray(vertex_array_.id());
        GL.DrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
        GL.Disable(GL_DEPTH_CLAMP);
        GL.Disable(GL_BLEND);
    }

private:
    gl::Buffer vertices_, indices_;
    gl::VertexArray vertex_array_;
    gl::Program program_;
    gl::Texture sun_table_;
    gl::Texture phase_table_;
    GLsizei index_count_ = 0;
};

using Factory = std::function<std::unique_ptr<VolumeMethod>()>;

const std::vector<std::pair<std::string, Factory>>& registry() {
    static const std::vector<std::pair<std::string, Factory>> methods = {
        {"none", [] { return std::make_unique<NoVolume>(); }},
        {"beamtree", [] { return std::make_unique<BeamTreeMethod>(); }},
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
