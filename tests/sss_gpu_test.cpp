// The splatting pipeline on the GPU against a CPU evaluation of Rohat eq. 4.6 with the same
// samples: a thin translucent slab seen from above under a spot light.

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "methods/registry.h"
#include "scenes/scene_file.h"
#include "sss/diffusion.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using SssRender = GlTest;

constexpr float kHalfThickness = 0.05f;  // slab: 2 x 0.1 x 2 units, top face at y = 0.05

// Every slab scene's camera: above the slab, looking down.
const char* const kSlabCamera = R"([camera]
position = [0.0, 2.6, 0.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov = 40.0)";
// The slab's spot light: above it, to one side.
const char* const kSlabSpotKeys = R"(
position = [0.35, 1.6, 0.2]
target = [0.0, 0.0, 0.0]
cone_angle = 40.0
near = 0.2
far = 5.0
intensity = [2.0, 1.6, 1.2])";

Scene slab_scene(const std::string& model, const std::string& weighting, bool footprint = false,
                 int grid = 48) {
    const std::string text = fmt::format(R"({}
[light]{}
[medium]
model = "physical"
[sss]
mm_per_unit = 20.0
grid = [{}, {}]
footprint = {}
jitter = false
map_size = 256
profile_texels = 512
environment_samples = 0
weighting = "{}"
[materials.marble]
translucent = "marble"
model = "{}"
[[objects]]
shape = "box"
size = [2.0, {}, 2.0]
material = "marble"
)",
                                         kSlabCamera, kSlabSpotKeys, grid, grid * 5 / 6, footprint,
                                         weighting, model, 2.0f * kHalfThickness);
    return parse_scene(text, "sss-slab", {}, SceneSearchPaths::defaults());
}

// A point on the slab's top face along a ray, if within its extent.
std::optional<glm::dvec3> on_top(const glm::dvec3& o, const glm::dvec3& d) {
    if (std::abs(d.y) < 1e-12) {
        return std::nullopt;
    }
    const glm::dvec3 p = o + (kHalfThickness - o.y) / d.y * d;
    if (std::abs(p.x) > 1.0 || std::abs(p.z) > 1.0) {
        return std::nullopt;
    }
    return p;
}

float fresnel_transmittance(double eta, double cos_theta) {
    const double f0 = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
    const double c = std::clamp(1.0 - cos_theta, 0.0, 1.0);
    return float(1.0 - (f0 + (1.0 - f0) * std::pow(c, 5.0)));
}

struct Sample {
    glm::dvec3 position;
    glm::vec3 weight;
    double thickness_mm;  // along the light's ray to the bottom face (Rohat §5.1.2)
};

// The samples the GPU takes (splat_light.vert), computed on the CPU: the grid over the region of
// interest, each cell's centre looked up at its light-map texel, whose centre ray meets the slab.
std::vector<Sample> cpu_samples(const Scene& scene, const glm::vec4& roi, double r_max_units) {
    const Subsurface& s = scene.subsurface;
    const SpotLight& light = scene.light;
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(light.projection() * light.view()));
    const double tan_half = std::tan(glm::radians(double(light.cone_half_angle_degrees)));
    const double eta = scene.materials.back().translucency->medium.eta;
    (void)r_max_units;
    std::vector<Sample> samples;
    double area_sum = 0.0;
    for (int j = 0; j < s.grid_y; ++j)
        for (int i = 0; i < s.grid_x; ++i) {
            const glm::dvec2 uv = glm::dvec2(roi.x, roi.y) + (glm::dvec2(i, j) + 0.5) /
                                                                 glm::dvec2(s.grid_x, s.grid_y) *
                                                                 glm::dvec2(roi.z, roi.w);
            const glm::ivec2 texel =
                glm::clamp(glm::ivec2(uv * double(s.map_size)), 0, s.map_size - 1);
            const glm::dvec2 ndc = (glm::dvec2(texel) + 0.5) / double(s.map_size) * 2.0 - 1.0;
            const glm::dvec4 a = inverse * glm::dvec4(ndc, -1.0, 1.0);
            const glm::dvec4 b = inverse * glm::dvec4(ndc, 1.0, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w;
            const std::optional<glm::dvec3> p = on_top(o, glm::dvec3(b) / b.w - o);
            if (!p) {
                continue;
            }
            const glm::dvec3 from_light = *p - glm::dvec3(light.position);
            const double r = glm::length(from_light);
            const double cos_i = -from_light.y / r;
            const double axial = glm::dot(from_light, glm::dvec3(light.direction()));
            const double cone = light.cone_factor(glm::vec3(*p));
            const double cos_phi = axial / r;
            const double cell = double(roi.z) * roi.w / double(s.grid_x * s.grid_y);
            const double omega = 4.0 * tan_half * tan_half * cell * std::pow(cos_phi, 3.0);
            const double area = omega * r * r / cos_i;
            const glm::vec3 irradiance =
                light.intensity * float(cone * cos_i) * scene.medium.light_falloff(float(r));
            area_sum += area;
            samples.push_back({*p,
                               irradiance * float(area * s.mm_per_unit * s.mm_per_unit) *
                                   fresnel_transmittance(eta, cos_i),
                               2.0 * kHalfThickness / cos_i * s.mm_per_unit});
        }
    if (s.weighting == SplatWeighting::seed) {
        // A_vis / N_s in place of each ΔA: rescale each weight by (A_vis/N_s) / ΔA_s.
        const double mean_area = area_sum / double(samples.size());
        for (Sample& sample : samples) {
            const glm::dvec3 from_light = sample.position - glm::dvec3(light.position);
            const double r = glm::length(from_light), cos_i = -from_light.y / r;
            const double cos_phi = glm::dot(from_light, glm::dvec3(light.direction())) / r;
            const double cell = double(roi.z) * roi.w / double(s.grid_x * s.grid_y);
            const double area =
                4.0 * tan_half * tan_half * cell * std::pow(cos_phi, 3.0) * r * r / cos_i;
            sample.weight *= float(mean_area / area);
        }
    }
    return samples;
}

// GPU splats of a flat slab under a spot light match the CPU sum of eq. 4.6 (same samples, same
// tabulated profile) within 2% relative RMSE, for the dipole, the multipole (thickness from the
// back-face pass) and the seed's A_vis/N_s weighting.
TEST_F(SssRender, SlabSplatsMatchTheCpuSumOfEquation46) {
    const int w = 96, h = 96;
    for (const auto& [model, weighting] :
         {std::pair{"dipole", "jacobian"}, std::pair{"multipole", "jacobian"},
          std::pair{"dipole", "seed"}}) {
        const Scene scene = slab_scene(model, weighting);
        frame::SceneRenderer renderer(scene, {.width = w, .height = h});
        const auto method = methods::create_volume_method("none");
        method->prepare(scene);
        renderer.render(*method);
        const sss::SubsurfacePass& pass = *renderer.subsurface();
        const Image scatter = renderer.read_rgb(pass.scatter());
        const sss::SubsurfaceMaterial& m = pass.materials().front();
        const double mm = scene.subsurface.mm_per_unit;
        const glm::vec4 roi = pass.region_of_interest(0, scene.light);
        const std::vector<Sample> samples = cpu_samples(scene, roi, m.r_max_mm / mm);
        ASSERT_GT(samples.size(), 1000u);
        const sss::RgbDiffusion d =
            sss::RgbDiffusion::of(scene.materials.back().translucency->medium);
        const sss::RadialProfile dipole = sss::tabulate_dipole(d, m.r_max_mm, 512);
        const sss::SlabProfiles multipole =
            sss::tabulate_multipole(d, m.r_max_mm, m.d_min_mm, m.d_max_mm, 512, 64);
        const PixelUnprojector unproject(scene.camera, w, h);
        const double eta = scene.materials.back().translucency->medium.eta;
        double error = 0, norm = 0;
        int pixels = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::dvec3 o = unproject.point(x, y, -1.0);
                const std::optional<glm::dvec3> p = on_top(o, unproject.point(x, y, 1.0) - o);
                if (!p || std::abs(p->x) > 0.95 || std::abs(p->z) > 0.95) {
                    continue;
                }
                const double cos_o = glm::normalize(glm::dvec3(scene.camera.position) - *p).y;
                glm::dvec3 expected(0.0);
                for (const Sample& s : samples) {
                    const double r = glm::distance(s.position, *p) * mm;
                    const glm::vec3 profile = std::string(model) == "dipole"
                                                  ? dipole.lookup(r)
                                                  : multipole.lookup_R(r, s.thickness_mm);
                    expected += glm::dvec3(profile * s.weight);
                }
                expected *= fresnel_transmittance(eta, cos_o) / M_PI;
                // Image rows run top to bottom.
                const glm::dvec3 got(scatter.at(x, y));
                error += glm::dot(got - expected, got - expected);
                norm += glm::dot(expected, expected);
                ++pixels;
            }
        ASSERT_GT(pixels, 4000);
        const double rel_rmse = std::sqrt(error / norm);
        EXPECT_LT(rel_rmse, 0.02) << model << " / " << weighting;
        RecordProperty(fmt::format("{}_{}_rel_rmse", model, weighting), std::to_string(rel_rmse));
    }
}

// Averaging each sample's profile over its own patch keeps the light it spreads (the image's sum)
// and removes the dots of a coarse grid (the mean difference between neighbouring pixels).
TEST_F(SssRender, FootprintFilterKeepsTheEnergyAndRemovesTheDots) {
    const int w = 96, h = 96;
    auto render = [&](bool footprint) {
        const Scene scene = slab_scene("dipole", "jacobian", footprint, 24);
        frame::SceneRenderer renderer(scene, {.width = w, .height = h});
        const auto method = methods::create_volume_method("none");
        method->prepare(scene);
        renderer.render(*method);
        return renderer.read_rgb(renderer.subsurface()->scatter());
    };
    const Image points = render(false), patches = render(true);
    auto sum_and_roughness = [&](const Image& image) {
        double sum = 0, roughness = 0;
        for (int y = 10; y < h - 10; ++y)
            for (int x = 10; x < w - 10; ++x) {
                sum += image.at(x, y).g;
                roughness += std::abs(image.at(x + 1, y).g - image.at(x, y).g);
            }
        return std::pair{sum, roughness / sum};
    };
    const auto [sum_points, rough_points] = sum_and_roughness(points);
    const auto [sum_patches, rough_patches] = sum_and_roughness(patches);
    EXPECT_NEAR(sum_patches, sum_points, 0.02 * sum_points);
    EXPECT_LT(rough_patches, 0.5 * rough_points);
    RecordProperty("roughness_points", std::to_string(rough_points));
    RecordProperty("roughness_patches", std::to_string(rough_patches));
}

// The subsurface pass binds maps of its own to texture units the volume methods share; the methods
// after it still see the shadow map: a scene's in-scattering is the same whether its objects are
// translucent or opaque (on NVIDIA a colour map left at the shadow unit is a GL error).
TEST_F(SssRender, VolumeMethodsAfterTheSubsurfacePassStillSeeTheShadowMap) {
    const Scene translucent = load_canonical("sss-shaft");
    Scene opaque = translucent;
    for (Material& material : opaque.materials) {
        material.translucency.reset();
    }
    ASSERT_TRUE(translucent.has_translucent_objects());
    ASSERT_FALSE(opaque.has_translucent_objects());
    const int w = 64, h = 36;
    // Methods that render the same frame twice to the bit (hybrid3's beam-tree intervals vary by
    // ~0.1% between runs on llvmpipe, too much for this check).
    for (const char* name : {"march", "planes"}) {
        auto in_scattering = [&](const Scene& scene) {
            frame::SceneRenderer renderer(scene, {.width = w, .height = h});
            const auto method = methods::create_volume_method(name);
            method->prepare(scene);
            return renderer.render(*method).in_scattering;
        };
        const Image a = in_scattering(translucent), b = in_scattering(opaque);
        EXPECT_LT(compare_images(a, b).rel_rmse, 1e-6) << name;
    }
}

// The slab under `lights` ([[lights]] entries in TOML), no ambient light: what the surfaces get
// is each light's specular term and its splats.
Scene slab_under(const std::string& lights) {
    const std::string text = std::string(R"(
[scene]
ambient = [0.0, 0.0, 0.0]
)") + kSlabCamera + R"(
[medium]
model = "physical"
[sss]
mm_per_unit = 20.0
grid = [48, 40]
jitter = false
map_size = 256
profile_texels = 512
environment_samples = 0
[materials.marble]
translucent = "marble"
[[objects]]
shape = "box"
size = [2.0, 0.1, 2.0]
material = "marble"
)" + lights;
    return parse_scene(text, "sss-slab-lights", {}, SceneSearchPaths::defaults());
}

const std::string kSpotLight = std::string("\n[[lights]]\ntype = \"spot\"") + kSlabSpotKeys + "\n";
const char* const kPointLight = R"(
[[lights]]
type = "point"
position = [-0.5, 0.9, -0.3]
near = 0.1
far = 5.0
intensity = [0.6, 0.8, 1.2]
)";

// Translucent objects take every spot and point light of [[lights]] (a point light as its six
// faces): under a spot and a point light together the slab's surfaces, splats and all, are the
// sum of what each light gives alone (the pass runs once and splats every light; were it drawn
// once per light, the sum would count each light twice), and each light adds some.
TEST_F(SssRender, TranslucentObjectsTakeEveryLightAndTheirSplatsAddUp) {
    const Scene both = slab_under(kSpotLight + kPointLight);
    ASSERT_EQ(both.spot_lights().size(), 7u);
    const int w = 96, h = 96;
    const Image together = render_method(both, "none", w, h).surface;
    const Image spot = render_method(slab_under(kSpotLight), "none", w, h).surface;
    const Image point = render_method(slab_under(kPointLight), "none", w, h).surface;
    EXPECT_GT(image_peak(spot), 0.0);
    EXPECT_GT(image_peak(point), 0.0);
    Image added = spot;
    for (size_t i = 0; i < added.rgb.size(); ++i) {
        added.rgb[i] += point.rgb[i];
    }
    EXPECT_LE(max_abs_difference(together, added), 1e-4 * image_peak(added));
}

// A directional light with translucent objects is refused by name (the splats model a light at a
// point).
TEST_F(SssRender, ASunWithTranslucentObjectsIsRefused) {
    const Scene scene = slab_under(R"(
[[lights]]
type = "directional"
direction = [0.2, -1.0, 0.1]
)");
    try {
        frame::SceneRenderer renderer(scene, {.width = 32, .height = 32});
        ADD_FAILURE() << "a sun with translucent objects was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("directional light"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sl::test
