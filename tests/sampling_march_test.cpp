// Ray marching (sampling/march.cpp): Moschos' clipping cases on the CPU, convergence to the
// closed form, depth-aware blur and upsampling at a depth edge, and hybrid3 against march and the
// reference.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "analytic/in_scattering.h"
#include "beamtree/beam_tree.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "reference/reference.h"
#include "sampling/ray_clip.h"
#include "scenes/mesh.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using March = GlTest;
using glm::dvec3;
using sampling::ClipCase;

frame::Frame render(const Scene& scene, const std::string& method, int width, int height,
                    const std::vector<std::pair<std::string, std::string>>& settings = {}) {
    return render_method(scene, method, width, height, settings);
}

// A light at the origin pointing down -z, 30° cone, range [1, 10].
SpotLight test_light() {
    SpotLight light;
    light.position = glm::vec3(0.0f);
    light.target = glm::vec3(0.0f, 0.0f, -1.0f);
    light.cone_half_angle_degrees = 30.0f;
    light.near = 1.0f;
    light.far = 10.0f;
    return light;
}

struct ClipCaseTest {
    ClipCase expected;
    dvec3 origin, direction;
    double trace_end;
    double start, end;  // expected when it samples
};

// Moschos figure 3.18, one ray per case, against a pyramid whose faces are easy to intersect:
// rays along -z through the axis enter at z = -1 (near range) and leave at z = -10 (backplate).
TEST(RayClip, EveryCaseOfAlgorithm4) {
    const std::vector<bt::Plane> pyramid = bt::influence_planes(test_light());
    const dvec3 down(0, 0, -1);
    const ClipCaseTest cases[] = {
        {ClipCase::A, {20, 0, 0}, down, 100.0, 0, 0},      // beside the pyramid: misses it
        {ClipCase::B, {0, 0, -5}, down, 100.0, 0.0, 5.0},  // inside, leaves before the end
        {ClipCase::C, {0, 0, -5}, down, 2.0, 0.0, 2.0},    // inside, still inside at the end
        {ClipCase::D, {0, 0, 1}, down, 100.0, 2.0, 11.0},  // enters and leaves before the end
        {ClipCase::E, {0, 0, 1}, down, 6.0, 2.0, 6.0},     // enters, the surface is inside
        {ClipCase::F, {0, 0, 1}, down, 1.5, 0, 0},         // the surface is before the entry
    };
    for (const ClipCaseTest& c : cases) {
        const sampling::ClippedTrace clipped =
            sampling::clip_trace(c.origin, c.direction, c.trace_end, pyramid);
        EXPECT_EQ(clipped.clip_case, c.expected) << "expected case " << to_string(c.expected)
                                                 << ", got " << to_string(clipped.clip_case);
        EXPECT_EQ(clipped.sample(), c.expected != ClipCase::A && c.expected != ClipCase::F);
        if (clipped.sample()) {
            EXPECT_NEAR(clipped.start, c.start, 1e-9) << to_string(c.expected);
            EXPECT_NEAR(clipped.end, c.end, 1e-9) << to_string(c.expected);
        }
    }
}

// A ray that starts inside the cone and leaves it sideways: the exact cone interval starts at 0
// and ends where the angle to the axis reaches the half-angle; the pyramid (which circumscribes
// the cone) lets it go further.
TEST(RayClip, RayStartingInsideTheConeEndsOnItsSurface) {
    const SpotLight light = test_light();
    const analytic::EyeRay ray{{0.0, 0.0, -5.0}, glm::normalize(dvec3(1.0, 0.3, 0.0))};
    const analytic::Interval cone = analytic::light_interval(ray, light, 100.0);
    EXPECT_DOUBLE_EQ(cone.begin, 0.0);
    const dvec3 exit = ray.origin + cone.end * ray.direction;
    const double angle = std::acos(glm::dot(glm::normalize(exit), dvec3(0, 0, -1)));
    EXPECT_NEAR(glm::degrees(angle), 30.0, 1e-9);
    const sampling::ClippedTrace pyramid =
        sampling::clip_trace(ray.origin, ray.direction, 100.0, bt::influence_planes(light));
    EXPECT_EQ(pyramid.clip_case, ClipCase::B);
    EXPECT_GT(pyramid.end, cone.end);
}

// ray_clip.glsl clips like ray_clip.cpp: on every pixel's ray of a scene whose camera sees the
// light's pyramid from outside, the GPU picks the same case (but for rays within float round-off
// of a case boundary) and the same interval to 1e-4 relative.
TEST_F(March, GlslClipMatchesCpp) {
    const Scene scene = load_canonical("parallel");
    const int width = 96, height = 54;
    const gl::shared::FrameUniforms uniforms =
        frame::make_frame_uniforms(scene, {.width = width, .height = height});
    const std::vector<float> rgba =
        render_test_pattern(uniforms, "tests/shaders/ray_clip.frag", width, height);
    const std::vector<bt::Plane> pyramid = bt::influence_planes(scene.light);
    int same = 0, sampled = 0;
    std::array<int, 6> seen{};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const TestRay ray = test_pattern_ray(uniforms, x, y, width, height);
            const double trace_end = 1.0 + 24.0 * (x + 0.5) / width;
            const sampling::ClippedTrace cpu =
                sampling::clip_trace(ray.origin, ray.direction, trace_end, pyramid);
            const float* gpu = &rgba[(size_t(y) * width + x) * 4];
            ++seen[size_t(cpu.clip_case)];
            if (int(gpu[2]) != int(cpu.clip_case))
                continue;
            ++same;
            if (cpu.sample()) {
                ++sampled;
                EXPECT_NEAR(gpu[0], cpu.start, 1e-4 * (1.0 + cpu.start)) << x << ", " << y;
                EXPECT_NEAR(gpu[1], cpu.end, 1e-4 * (1.0 + cpu.end)) << x << ", " << y;
            }
        }
    }
    EXPECT_GE(same, width * height * 99 / 100);
    EXPECT_GT(sampled, width * height / 10);
    EXPECT_GT(seen[size_t(ClipCase::A)] + seen[size_t(ClipCase::F)], 0);
    EXPECT_GT(seen[size_t(ClipCase::D)] + seen[size_t(ClipCase::E)], 0);
}

// With no occluders, `march` (exact cone clipping, samples at the middle of their steps)
// converges to the closed-form integral as N grows, its relative RMSE shrinking at least like
// 1/N: the least-squares slope of log error over log N is <= -1.
TEST_F(March, ConvergesAtLeastLikeOneOverNWithoutOccluders) {
    Scene scene = boxes_scene(MediumModel::physical);
    scene.objects.clear();
    const int size = 64;
    const Image exact = unoccluded_in_scattering(scene, size, size);
    std::vector<double> ns, errors;
    for (const int n : {2, 4, 8, 16}) {
        const frame::Frame frame =
            render(scene, "march", size, size, {{"samples", std::to_string(n)}});
        ns.push_back(double(n));
        errors.push_back(compare_images(frame.in_scattering, exact).rel_rmse);
    }
    const double slope = log_log_slope(ns, errors);
    EXPECT_LE(slope, -1.0) << "errors " << errors.front() << " ... " << errors.back();
}

// A wall in front of a shaft: the shaft is behind the wall, so the wall's pixels carry no I_s.
// Depth-aware upsampling and the depth-aware blur keep them dark at every buffer size; the
// depth-blind Gaussian of Moschos' algorithm 3 bleeds the shaft onto the wall's top rows (which
// shows the check can fail).
TEST_F(March, DepthAwareFilteringDoesNotBleedAcrossADepthEdge) {
    Scene scene;
    scene.name = "wall";
    scene.camera.position = glm::vec3(0.0f, 1.0f, 8.0f);
    scene.camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.light.position = glm::vec3(0.0f, 6.0f, -3.0f);
    scene.light.target = glm::vec3(0.0f, 0.0f, -3.0f);
    scene.light.cone_half_angle_degrees = 25.0f;
    scene.light.near = 0.2f;
    scene.light.far = 8.0f;
    scene.light.intensity = glm::vec3(80.0f);
    scene.medium.sigma_s = glm::vec3(0.1f);
    scene.medium.sigma_a = glm::vec3(0.0f);
    scene.materials.push_back(Material{.name = "default"});
    Object wall;
    wall.name = "wall";
    wall.mesh = std::make_shared<const Mesh>(make_box(glm::vec3(8.0f, 2.0f, 0.2f)));
    wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.0f));  // y in [-1, 1]
    scene.objects.push_back(std::move(wall));

    const int width = 96, height = 64;
    const frame::Frame sharp = render(scene, "march", width, height, {{"samples", "64"}});
    double peak = 0.0;
    for (const float v : sharp.in_scattering.rgb)
        peak = std::max(peak, double(v));
    ASSERT_GT(peak, 0.0);
    // The wall's pixels: nearer than 6.5 m (the shaft is at 11 m).
    std::vector<size_t> wall_pixels;
    for (size_t i = 0; i < sharp.depth.size(); ++i) {
        if (sharp.depth[i] < 1.0f && sharp.in_scattering.rgb[i * 3] <= 1e-6 * peak) {
            const int x = int(i % width), y = int(i / width);
            const PixelUnprojector unproject(scene.camera, width, height);
            const double distance = glm::length(unproject.point(x, y, 2.0 * sharp.depth[i] - 1.0) -
                                                glm::dvec3(scene.camera.position));
            if (distance < 6.5)
                wall_pixels.push_back(i);
        }
    }
    ASSERT_GT(wall_pixels.size(), size_t(width * 4));
    auto wall_peak = [&](const frame::Frame& frame) {
        double largest = 0.0;
        for (const size_t i : wall_pixels)
            largest = std::max(largest, double(frame.in_scattering.rgb[i * 3]));
        return largest / peak;
    };
    for (const char* scale : {"1", "0.5", "0.25"}) {
        for (const char* blur : {"none", "depth_aware"}) {
            const frame::Frame frame = render(
                scene, "march", width, height,
                {{"samples", "64"}, {"resolution_scale", scale}, {"blur", blur}, {"jitter", "1"}});
            EXPECT_LT(wall_peak(frame), 1e-3) << "scale " << scale << ", blur " << blur;
        }
    }
    const frame::Frame bleeding =
        render(scene, "march", width, height, {{"samples", "64"}, {"blur", "gauss5"}});
    EXPECT_GT(wall_peak(bleeding), 1e-2);
}

// On toplight at 256², hybrid3 beats march at the same N (16 and 64): its samples go to the
// uncertain intervals only and the lit rest is exact. It counts nothing twice: with many
// samples it matches the reference to 0.1% (the lit parts inside the marched intervals counted
// twice would add percents), and on boxes (their own outer volumes) to 0.2%.
TEST_F(March, Hybrid3BeatsMarchAndCountsNothingTwice) {
    const Scene scene = load_canonical("toplight");
    const int size = 256;
    const reference::ReferenceRenderer reference(scene);
    const Image exact = reference.render(size, size, {});
    for (const char* n : {"16", "64"}) {
        const double march_error =
            compare_images(render(scene, "march", size, size, {{"samples", n}}).in_scattering,
                           exact)
                .rel_rmse;
        const double hybrid3_error =
            compare_images(render(scene, "hybrid3", size, size, {{"samples", n}}).in_scattering,
                           exact)
                .rel_rmse;
        EXPECT_LT(hybrid3_error, march_error) << "N = " << n;
    }
    const double converged =
        compare_images(render(scene, "hybrid3", size, size, {{"samples", "256"}}).in_scattering,
                       exact)
            .rel_rmse;
    EXPECT_LT(converged, 1e-3);

    // Boxes are their own outer volumes: the uncertain regions are thin shells inside them.
    const Scene boxes = boxes_scene(MediumModel::simplified);
    const Image boxes_exact = reference::ReferenceRenderer(boxes).render(128, 128, {});
    const double hybrid3_error =
        compare_images(render(boxes, "hybrid3", 128, 128, {{"samples", "64"}}).in_scattering,
                       boxes_exact)
            .rel_rmse;
    EXPECT_LT(hybrid3_error, 2e-3);
}

// hybrid3's marched part, sample for sample on the CPU: per pixel the uncertain intervals of the
// eye ray from the tree's own walk (trace(), up to the surface and inside the cone), N =
// clamp(ceil(density x length), min_samples, samples) samples at the middles of N equal steps
// along the intervals laid end to end, each e(t) times the exact visibility (a ray cast).
Image hybrid3_marched_oracle(const Scene& scene, const frame::Frame& frame, int size,
                             double density, int min_samples, int max_samples) {
    const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
    const CpuRayCaster caster(scene);
    const PixelUnprojector unproject(scene.camera, size, size);
    Image oracle(size, size);
    std::vector<bt::RegionInterval> along;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const auto [ray, surface, hit] = pixel_ray(scene, unproject, frame, x, y);
            const analytic::Interval cone = analytic::light_interval(ray, scene.light, surface);
            if (cone.empty()) {
                continue;
            }
            tree.trace(ray.origin, ray.direction, cone.begin, cone.end, along);
            std::vector<std::pair<double, double>> uncertain;
            double length = 0.0;
            for (const bt::RegionInterval& interval : along) {
                if (interval.region == bt::Region::uncertain) {
                    uncertain.emplace_back(interval.begin, interval.end);
                    length += interval.end - interval.begin;
                }
            }
            if (!(length > 0.0)) {
                continue;
            }
            const int n = int(
                std::clamp(std::ceil(density * length), double(min_samples), double(max_samples)));
            const double step = length / n;
            glm::dvec3 sum(0.0);
            size_t k = 0;
            double covered = 0.0;
            for (int i = 0; i < n; ++i) {
                const double s = (i + 0.5) * step;
                while (k + 1 < uncertain.size() &&
                       s > covered + (uncertain[k].second - uncertain[k].first)) {
                    covered += uncertain[k].second - uncertain[k].first;
                    ++k;
                }
                const double t = uncertain[k].first + (s - covered);
                const glm::dvec3 p = ray.origin + t * ray.direction;
                if (!caster.blocked(glm::vec3(p), scene.light.position)) {
                    sum += analytic::scattering_density(ray, t, scene.light, scene.medium) * step;
                }
            }
            oracle.set(x, y, glm::vec3(sum));
        }
    }
    return oracle;
}

Image difference(const Image& a, const Image& b) {
    Image d = a;
    for (size_t i = 0; i < d.rgb.size(); ++i) {
        d.rgb[i] -= b.rgb[i];
    }
    return d;
}

// Adaptive hybrid3 marches only inside its uncertain intervals: what it adds to the analytic lit
// part (hybrid3 minus `beamtree`) equals the same-sample CPU sum over the tree's uncertain
// intervals, on toplight and multiple (whose rays cross several uncertain intervals with lit and
// unlit gaps between them). Marching a gap too would add the lit gap's in-scattering a second time
// (or, for an unlit gap, spend the samples there and sample the intervals more coarsely).
// The residual is the shadow map's against exact visibility at the shadow edges.
TEST_F(March, Hybrid3MarchesOnlyItsUncertainIntervals) {
    const int size = 64;
    for (const char* name : {"toplight", "multiple"}) {
        const Scene scene = load_canonical(name);
        const frame::Frame lit = render(scene, "beamtree", size, size);
        const frame::Frame hybrid3 = render(
            scene, "hybrid3", size, size,
            {{"density", "64"}, {"min_samples", "2"}, {"samples", "256"}, {"shadow", "hard"}});
        const Image marched = difference(hybrid3.in_scattering, lit.in_scattering);
        const Image oracle = hybrid3_marched_oracle(scene, hybrid3, size, 64.0, 2, 256);
        const ErrorMetrics error = compare_images(marched, oracle);
        std::printf("%s: hybrid3 marched part vs same-sample oracle rel_rmse %.4f\n", name,
                    error.rel_rmse);
        EXPECT_LT(error.rel_rmse, 0.05) << name;
    }
}

// Adaptive hybrid3 converges to the reference as its budget (samples per metre) grows: over
// 2 ... 32 samples per metre (1 to ~16 per pixel here) the least-squares slope of log error over
// log density is at most -0.75 (midpoint samples of a function with visibility steps converge
// like 1/N), down to the shadow map's floor (1.3e-4 on toplight from 128 per metre on).
TEST_F(March, Hybrid3ConvergesAsItsDensityGrows) {
    const Scene scene = load_canonical("toplight");
    const int size = 96;
    const Image exact = reference::ReferenceRenderer(scene).render(size, size, {});
    std::vector<double> densities, errors;
    for (const double density : {2.0, 4.0, 8.0, 16.0, 32.0}) {
        const frame::Frame frame = render(
            scene, "hybrid3", size, size,
            {{"density", std::to_string(density)}, {"min_samples", "1"}, {"samples", "4096"}});
        densities.push_back(density);
        errors.push_back(compare_images(frame.in_scattering, exact).rel_rmse);
    }
    const double slope = log_log_slope(densities, errors);
    std::printf("hybrid3 error at density 2..32: %.5f %.5f %.5f %.5f %.5f, slope %.2f\n", errors[0],
                errors[1], errors[2], errors[3], errors[4], slope);
    EXPECT_LE(slope, -0.75);
    EXPECT_LT(errors.back(), 5e-4);
}

}  // namespace
}  // namespace sl::test
