// Sampling planes and Nilsson's Methods 1 and 2 (sampling/): the GLSL integrand against the C++
// one, the slicer and the partition on the CPU, and the methods' images against independent
// oracles (the closed-form integral, a CPU sum over the same samples with exact visibility, and
// the reference).

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "analytic/in_scattering.h"
#include "beamtree/beam_tree.h"
#include "core/error.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "reference/reference.h"
#include "sampling/slices.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using Sampling = GlTest;

frame::Frame render(const Scene& scene, const std::string& method, int size,
                    const std::vector<std::pair<std::string, std::string>>& settings = {}) {
    return render_method(scene, method, size, size, settings);
}

// The eye ray through pixel (x, y) (row 0 at the top), as the GPU makes it.
// scattering.glsl's e(t) equals analytic::scattering_density for every phase function and both
// models, to 1e-4 of the larger of the value and the image's peak (3e-3 with a smooth edge).
TEST_F(Sampling, GlslIntegrandMatchesCppForEveryPhaseFunction) {
    const int width = 64, height = 36;
    for (int phase = 0; phase <= int(PhaseFunction::nishita_hazy); ++phase) {
        for (const MediumModel model : {MediumModel::simplified, MediumModel::physical}) {
            Scene scene = boxes_scene(model);
            scene.medium.phase = PhaseFunction(phase);
            scene.medium.g = 0.7f;
            scene.light.falloff_degrees = phase % 2 ? 4.0f : 0.0f;  // both cone edges
            // The smooth edge's slope (about 21 per radian over 4°) amplifies the float32 ray
            // directions of the GPU side: a looser bound there.
            const double tolerance = scene.light.falloff_degrees > 0.0f ? 3e-3 : 1e-4;
            const gl::shared::FrameUniforms uniforms =
                frame::make_frame_uniforms(scene, {.width = width, .height = height});
            const std::vector<float> rgba =
                render_test_pattern(uniforms, "tests/shaders/scattering.frag", width, height);
            const double peak = red_peak(rgba);
            ASSERT_GT(peak, 0.0);
            for_each_pattern_pixel(
                uniforms, width, height,
                [&](int x, int y, const analytic::EyeRay& ray, double t, size_t index) {
                    const glm::dvec3 cpu =
                        analytic::scattering_density(ray, t, scene.light, scene.medium);
                    for (int c = 0; c < 3; ++c) {
                        const double gpu = rgba[index + size_t(c)];
                        ASSERT_NEAR(gpu, cpu[c], tolerance * std::max(std::abs(cpu[c]), peak))
                            << to_string(scene.medium.phase) << " " << to_string(model) << " pixel "
                            << x << ", " << y;
                    }
                });
        }
    }
}

// Slices are planes of constant eye depth, (k + ½) dz, inside the influence pyramid: every
// vertex lies on its plane and inside the pyramid.
TEST(Slices, LieOnTheirPlanesInsideThePyramid) {
    const Scene scene = load_canonical("parallel");
    const double dz = 0.25;
    const std::vector<sampling::Slice> slices =
        sampling::influence_slices(scene.camera, scene.light, dz);
    ASSERT_GT(slices.size(), 10u);
    const glm::dvec3 eye(scene.camera.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(scene.camera.target) - eye);
    const std::vector<bt::Plane> pyramid = bt::influence_planes(scene.light);
    for (const sampling::Slice& slice : slices) {
        EXPECT_NEAR(std::fmod(slice.depth / dz, 1.0), 0.5, 1e-9);
        for (const glm::dvec3& v : slice.polygon.vertices) {
            EXPECT_NEAR(glm::dot(v - eye, forward), slice.depth, 1e-9 * scene.light.far);
            for (const bt::Plane& plane : pyramid)
                EXPECT_LE(plane.distance(v), 1e-6 * scene.light.far);
        }
    }
    EXPECT_THROW(sampling::influence_slices(scene.camera, scene.light, 0.0), Error);
    EXPECT_THROW(sampling::influence_slices(scene.camera, scene.light, 1e-6), Error);
}

// Partitioning a slice conserves its area across lit + uncertain + unlit pieces, and so does
// making the pieces conforming (T-junction vertices are collinear).
TEST(Slices, PartitionConservesArea) {
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        const Scene scene = load_canonical(name);
        const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
        size_t pieces = 0;
        for (const sampling::Slice& slice :
             sampling::influence_slices(scene.camera, scene.light, 0.5)) {
            bt::BeamTree::Partition parts = tree.partition(slice.polygon);
            std::vector<bt::Polygon*> all;
            double sum = 0.0;
            for (auto* kind : {&parts.lit, &parts.uncertain, &parts.unlit}) {
                for (bt::Polygon& piece : *kind) {
                    sum += bt::area(piece);
                    all.push_back(&piece);
                }
            }
            const double whole = bt::area(slice.polygon);
            EXPECT_NEAR(sum, whole, 1e-9 * whole + 1e-12) << name << " depth " << slice.depth;
            sampling::remove_t_junctions(all, 1e-7 * scene.light.far);
            double conforming = 0.0;
            for (const bt::Polygon* piece : all)
                conforming += bt::area(*piece);
            EXPECT_NEAR(conforming, whole, 1e-9 * whole + 1e-12) << name;
            pieces += all.size();
        }
        EXPECT_GT(pieces, 50u) << name;
    }
}

// With no occluders, `planes` converges to the closed-form integral as dz -> 0, its relative
// RMSE shrinking at least linearly: the least-squares slope of log error over log dz, over four
// dz, is >= 1.
TEST_F(Sampling, PlanesConvergeAtLeastLinearlyWithoutOccluders) {
    Scene scene = boxes_scene(MediumModel::physical);
    scene.objects.clear();
    const int size = 64;
    const Image exact = unoccluded_in_scattering(scene, size, size);
    std::vector<double> dzs, errors;
    for (const double dz : {0.4, 0.2, 0.1, 0.05}) {
        const frame::Frame frame = render(scene, "planes", size, {{"dz", std::to_string(dz)}});
        dzs.push_back(dz);
        errors.push_back(compare_images(frame.in_scattering, exact).rel_rmse);
    }
    const double slope = log_log_slope(dzs, errors);
    EXPECT_GE(slope, 1.0) << "errors " << errors.front() << " ... " << errors.back();
    EXPECT_LT(errors.back(), 0.02);
}

// `hybrid1` changes nothing but visibility: against a CPU sum over the very same samples (slices
// at (k + ½) dz, weights dz / (V·forward)) with exact visibility from a brute-force ray caster,
// its error is at most that of `planes`, whose samples go through the shadow map; and the two
// images agree to a few percent. With the regions found on the GPU (partition=gpu: each plane
// fragment descends the uploaded tree) and on the CPU (partition=cpu: Nilsson's per-frame
// partition of every plane), both are that close to the oracle, and to each other up to the
// float round-off at piece edges; so is hybrid2.
TEST_F(Sampling, Hybrid1RemovesOnlyShadowMapError) {
    const Scene scene = boxes_scene(MediumModel::simplified);
    const int size = 80;
    const double dz = 0.1;
    const frame::Frame planes = render(scene, "planes", size, {{"dz", "0.1"}, {"shadow", "hard"}});
    const frame::Frame hybrid1 =
        render(scene, "hybrid1", size, {{"dz", "0.1"}, {"shadow", "hard"}});
    const frame::Frame hybrid1_cpu =
        render(scene, "hybrid1", size, {{"dz", "0.1"}, {"shadow", "hard"}, {"partition", "cpu"}});
    const frame::Frame hybrid2 =
        render(scene, "hybrid2", size, {{"dz", "0.1"}, {"shadow", "hard"}});
    const frame::Frame hybrid2_cpu =
        render(scene, "hybrid2", size, {{"dz", "0.1"}, {"shadow", "hard"}, {"partition", "cpu"}});

    const CpuRayCaster caster(scene);
    const PixelUnprojector unproject(scene.camera, size, size);
    const glm::dvec3 eye(scene.camera.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(scene.camera.target) - eye);
    const auto [near_depth, far_depth] = sampling::influence_depth_range(scene.camera, scene.light);
    Image oracle(size, size);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const auto [ray, distance, hit] = pixel_ray(scene, unproject, planes, x, y);
            const double surface = hit ? distance : 1e30;
            const double cos_forward = glm::dot(ray.direction, forward);
            glm::dvec3 sum(0.0);
            for (double k = std::max(0.0, std::floor(near_depth / dz)); (k + 0.5) * dz <= far_depth;
                 k += 1.0) {
                const double t = (k + 0.5) * dz / cos_forward;
                if (t >= surface)
                    break;
                const glm::dvec3 e =
                    analytic::scattering_density(ray, t, scene.light, scene.medium);
                const glm::dvec3 p = ray.origin + t * ray.direction;
                if (e != glm::dvec3(0.0) && !caster.blocked(glm::vec3(p), scene.light.position))
                    sum += e * dz / cos_forward;
            }
            oracle.set(x, y, glm::vec3(sum));
        }
    }
    const double hybrid1_error = compare_images(hybrid1.in_scattering, oracle).rel_rmse;
    const double planes_error = compare_images(planes.in_scattering, oracle).rel_rmse;
    EXPECT_LE(hybrid1_error, planes_error);
    EXPECT_LT(hybrid1_error, 0.01);
    EXPECT_LT(compare_images(hybrid1.in_scattering, planes.in_scattering).rel_rmse, 0.05);
    const double hybrid1_cpu_error = compare_images(hybrid1_cpu.in_scattering, oracle).rel_rmse;
    EXPECT_LT(hybrid1_cpu_error, 0.01);
    const double gpu_vs_cpu1 =
        compare_images(hybrid1.in_scattering, hybrid1_cpu.in_scattering).rel_rmse;
    const double gpu_vs_cpu2 =
        compare_images(hybrid2.in_scattering, hybrid2_cpu.in_scattering).rel_rmse;
    std::printf(
        "against the same-sample oracle: hybrid1 gpu %.2e cpu %.2e; planes %.2e; gpu vs "
        "cpu: hybrid1 %.2e, hybrid2 %.2e\n",
        hybrid1_error, hybrid1_cpu_error, planes_error, gpu_vs_cpu1, gpu_vs_cpu2);
    EXPECT_LT(gpu_vs_cpu1, 2e-3);
    EXPECT_LT(gpu_vs_cpu2, 2e-3);
}

// On `toplight` at 256², Method 2 is at least as accurate as `planes` at the same dz (0.5 and
// 0.1): the lit part is exact. It counts nothing twice: at dz = 0.1 its error is below 1%
// (the lit part counted twice would double most of the image), and it never falls below the
// analytic lit part alone (`beamtree`) by more than the float32 round-off of its signed sums.
TEST_F(Sampling, Hybrid2BeatsPlanesOnToplight) {
    const Scene scene = load_canonical("toplight");
    const int size = 256;
    const reference::ReferenceRenderer reference(scene);
    const Image exact = reference.render(size, size, {});
    const frame::Frame lit_only = render(scene, "beamtree", size);
    for (const char* dz : {"0.5", "0.1"}) {
        const frame::Frame planes = render(scene, "planes", size, {{"dz", dz}});
        const frame::Frame hybrid2 = render(scene, "hybrid2", size, {{"dz", dz}});
        const double planes_error = compare_images(planes.in_scattering, exact).rel_rmse;
        const double hybrid2_error = compare_images(hybrid2.in_scattering, exact).rel_rmse;
        EXPECT_LE(hybrid2_error, planes_error) << "dz " << dz;
        if (std::string(dz) == "0.1") {
            EXPECT_LT(hybrid2_error, 0.01);
        }
        for (size_t i = 0; i < hybrid2.in_scattering.rgb.size(); ++i) {
            const float lit = lit_only.in_scattering.rgb[i];
            ASSERT_GE(hybrid2.in_scattering.rgb[i], lit - 2e-4f * (1e-2f + std::abs(lit)))
                << "dz " << dz << " value " << i;
        }
    }
}

}  // namespace
}  // namespace sl::test
