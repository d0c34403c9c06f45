// Regions on the GPU, pixel by pixel: the boundary meshes and the walk route against the tree's
// own lit integral on the CPU (analytic/ closed forms over trace()'s intervals), against the
// cells' meshes, and the walk against trace() along random lines.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "analytic/gpu_tree.h"
#include "analytic/in_scattering.h"
#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/bounding_volumes.h"
#include "beamtree/regions.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"
#include "tests/gl_support.h"
#include "tests/random_scenes.h"

namespace sl::test {
namespace {

struct BoundaryCase {
    std::string name;
    Scene scene;
};

// Pixels more than 5% (and 1e-3 of the peak) apart.
size_t pixels_off(const Image& image, const Image& against, double peak) {
    size_t off = 0;
    for (size_t i = 0; i < against.rgb.size(); ++i) {
        const double o = against.rgb[i], b = image.rgb[i];
        off += std::abs(b - o) > 0.05 * o + 1e-3 * peak ? 1 : 0;
    }
    return off;
}

// beamtree's image on the CPU: per pixel, the closed form of ∫e over the lit intervals of the
// tree's own walk along the eye ray (trace()), up to the frame's surface.
Image lit_integral(const Scene& scene, const frame::Frame& frame, int width, int height) {
    const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
    const PixelUnprojector unproject(scene.camera, width, height);
    Image image(width, height);
    std::vector<bt::RegionInterval> along;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const auto [ray, surface, hit] = pixel_ray(scene, unproject, frame, x, y);
            tree.trace(ray.origin, ray.direction, 0.0, surface, along);
            dvec3 sum(0.0);
            for (const bt::RegionInterval& interval : along) {
                if (interval.region == bt::Region::lit) {
                    sum += analytic::in_scattering(ray, interval.begin, interval.end, scene.light,
                                                   scene.medium);
                }
            }
            image.set(x, y, glm::vec3(sum));
        }
    }
    return image;
}

// Regions as surfaces on the GPU, pixel by pixel, against the tree's own lit integral on the CPU
// (lit_integral) and against every lit cell's faces (surfaces=cells), on the canonical scenes and
// on 20 random scenes with overlapping, flat, edge-on and face-sharing objects seen across the
// beam:
// - the boundary merged into maximal polygons (surfaces=boundary, the default) draws the image of
//   its faces fanned one by one (surfaces=fragments) to float round-off: 1e-4 of the image
//   (measured ≤ 2.1e-5);
// - on the canonical scenes it is the CPU integral to 1e-4 (measured 7.7e-6 to 6.8e-5), and the
//   cells' image on toplight and multiple. On parallel the cell mesh is 5.7e-4 off, the boundary
//   not: the cells leave out lit slivers thinner than 1e-5 of the influence volume
//   (Regions::drawn), which parallel has next to the light;
// - on the random scenes, pixels more than 5% (and 1e-3 of the peak) off the CPU integral are at
//   most 0.1% of the lit ones (measured 0 to 2 of 3,874 to 7,313). Those are rays along a sliver
//   of lit region thinner than a pixel's subpixel grid (the tree gives it a zero-length interval):
//   its front and back faces, seen almost edge-on, snap to different pixel centres, and the pixel
//   gets one of the pair's ±G(z). The cell mesh, without slivers, has as many (seeds 505, 511).
using BoundaryOnTheGpu = GlTest;

// The canonical scenes, and 20 random ones seen from the side of the beam's middle.
std::vector<BoundaryCase> gpu_boundary_cases(bt::VolumeLibrary& library) {
    std::vector<BoundaryCase> cases;
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        cases.push_back({name, load_canonical(name)});
    }
    for (int seed = 500; seed < 520; ++seed) {
        RandomScene random = random_scene(seed, library);
        Scene& scene = random.scene;
        scene.medium.sigma_s = glm::vec3(0.05f);
        scene.materials.emplace_back();  // the objects' material 0 (the tree needs none)
        // From the side of the beam's middle, as far out as the beam is long.
        const glm::vec3 middle =
            scene.light.position + 0.5f * scene.light.far * scene.light.direction();
        const glm::vec3 side =
            glm::normalize(glm::cross(scene.light.direction(), scene.light.up()));
        scene.camera.position = middle + scene.light.far * side;
        scene.camera.target = middle;
        scene.camera.up = -scene.light.direction();
        scene.camera.fov_y_degrees = 60.0f;
        cases.push_back({fmt::format("seed {} (kinds {})", seed, random.kinds), std::move(scene)});
    }
    return cases;
}

// The worst figures over the cases, printed at the end.
struct GpuBoundaryTotals {
    double worst_merged = 0.0, worst_canonical = 0.0, worst_pixels = 0.0;
    double worst_walk = 0.0, worst_walk_exact = 0.0, worst_walk_pixels = 0.0;
};

// One case's image on the mesh route, and the CPU integral it is held to.
struct CaseImages {
    const BoundaryCase& c;
    bool canonical;
    int w, h;
    frame::Frame boundary;  // beamtree, mesh route, maximal polygons
    Image oracle;           // lit_integral
    double peak = 0.0;
    size_t lit = 0;
};

const std::vector<std::pair<std::string, std::string>> kByMesh = {{"route", "mesh"}};
const std::vector<std::pair<std::string, std::string>> kByWalk = {{"route", "walk"}};

// The mesh route: maximal polygons against fanned faces, the CPU integral and the cells.
void check_mesh_route(const CaseImages& k, GpuBoundaryTotals& totals) {
    const frame::Frame fragments = render_method(k.c.scene, "beamtree", k.w, k.h,
                                                 {{"route", "mesh"}, {"surfaces", "fragments"}});
    const ErrorMetrics merged = compare_images(k.boundary.in_scattering, fragments.in_scattering);
    totals.worst_merged = std::max(totals.worst_merged, merged.rel_rmse);
    EXPECT_LT(merged.rel_rmse, 1e-4) << k.c.name << ": max_abs " << merged.max_abs;
    if (k.canonical) {
        const ErrorMetrics exact = compare_images(k.boundary.in_scattering, k.oracle);
        totals.worst_canonical = std::max(totals.worst_canonical, exact.rel_rmse);
        EXPECT_LT(exact.rel_rmse, 1e-4) << k.c.name << ": max_abs " << exact.max_abs;
        if (k.c.name != "parallel") {
            const frame::Frame cells = render_method(k.c.scene, "beamtree", k.w, k.h,
                                                     {{"route", "mesh"}, {"surfaces", "cells"}});
            EXPECT_LT(compare_images(k.boundary.in_scattering, cells.in_scattering).rel_rmse, 1e-4)
                << k.c.name;
        }
    }
    const size_t off = pixels_off(k.boundary.in_scattering, k.oracle, k.peak);
    totals.worst_pixels = std::max(totals.worst_pixels, double(off) / double(k.lit));
    EXPECT_LE(double(off), 1e-3 * double(k.lit)) << k.c.name << ": " << off << " of " << k.lit;
}

// The walk route: the tree's own integral, and the mesh route's image but for the mesh route's
// sliver pixels; the hybrids read the walk's region lists as the meshes'.
void check_walk_route(const CaseImages& k, GpuBoundaryTotals& totals) {
    const frame::Frame walk = render_method(k.c.scene, "beamtree", k.w, k.h, kByWalk);
    const size_t walk_off = pixels_off(walk.in_scattering, k.oracle, k.peak);
    EXPECT_LE(double(walk_off), 1e-3 * double(k.lit)) << k.c.name << ": walk, " << walk_off;
    totals.worst_walk_pixels = std::max(totals.worst_walk_pixels, double(walk_off) / double(k.lit));
    if (k.canonical) {
        const double exact = compare_images(walk.in_scattering, k.oracle).rel_rmse;
        totals.worst_walk_exact = std::max(totals.worst_walk_exact, exact);
        EXPECT_LT(exact, 1e-4) << k.c.name << ": walk against the CPU integral";
    }
    for (const char* method : {"beamtree", "hybrid1", "hybrid2", "hybrid3"}) {
        const bool beamtree = std::string(method) == "beamtree";
        const frame::Frame mesh_frame =
            beamtree ? frame::Frame{} : render_method(k.c.scene, method, k.w, k.h, kByMesh);
        const frame::Frame walk_frame =
            beamtree ? frame::Frame{} : render_method(k.c.scene, method, k.w, k.h, kByWalk);
        const Image& from_mesh = beamtree ? k.boundary.in_scattering : mesh_frame.in_scattering;
        const Image& from_walk = beamtree ? walk.in_scattering : walk_frame.in_scattering;
        const ErrorMetrics e = compare_images(from_walk, from_mesh);
        const size_t apart = pixels_off(from_walk, from_mesh, k.peak);
        EXPECT_LE(double(apart), 1e-3 * double(k.lit)) << k.c.name << ": " << method;
        if (k.canonical) {
            // hybrid1 and hybrid2 classify plane samples at fixed depths: one that lies between
            // a face's float crossing and the plane's own flips between the shadow map and the
            // closed form (measured 2.0e-4 on toplight; the planes' own error against the
            // reference is 100 times that).
            const bool planes = !beamtree && std::string(method) != "hybrid3";
            totals.worst_walk = std::max(totals.worst_walk, e.rel_rmse);
            EXPECT_LT(e.rel_rmse, planes ? 5e-4 : 1e-4)
                << k.c.name << ": " << method << " walk against mesh";
        }
    }
}

TEST_F(BoundaryOnTheGpu, IntegratesLikeTheTreePixelByPixel) {
    bt::VolumeLibrary library;
    GpuBoundaryTotals totals;
    size_t compared = 0;
    for (const BoundaryCase& c : gpu_boundary_cases(library)) {
        const bool canonical = !c.name.starts_with("seed");
        CaseImages k{c, canonical, canonical ? 160 : 96, canonical ? 90 : 96, {}, {}};
        k.boundary = render_method(c.scene, "beamtree", k.w, k.h, kByMesh);
        k.oracle = lit_integral(c.scene, k.boundary, k.w, k.h);
        for (const float v : k.oracle.rgb) {
            k.peak = std::max(k.peak, double(v));
            k.lit += v > 0.0f ? 1 : 0;
        }
        if (!(k.peak > 1e-5)) {
            continue;  // the beam is not in view
        }
        check_mesh_route(k, totals);
        check_walk_route(k, totals);
        ++compared;
    }
    std::printf(
        "boundary on the GPU: %zu scenes; maximal polygons against fanned faces %.2e, canonical "
        "scenes against the CPU integral %.2e, worst share of pixels off %.2e\n"
        "walk route: canonical scenes against the mesh route %.2e (all four methods), against "
        "the CPU integral %.2e; worst share of pixels off the CPU integral %.2e\n",
        compared, totals.worst_merged, totals.worst_canonical, totals.worst_pixels,
        totals.worst_walk, totals.worst_walk_exact, totals.worst_walk_pixels);
    EXPECT_GE(compared, 20u);
}

// On the real building, in the frame where the mesh route was found off (house-sweep at
// t = 0.6667 s, 640x360, walls in convex pieces): its boundary meshes hold triangles that are
// degenerate in float (three collinear corners at a T-vertex), which the rasterizer still gives
// a pixel now and then, with an interpolated position far off or infinite; 4 pixels were 0.03 to
// 0.08 off (2.3 % of the image against the walk route) while the crossings' distances came from
// the interpolated position. From the triangles' corners (analytic/region_faces.h,
// face_distance.glsl) the mesh route is the walk route but for float round-off, in beamtree's
// signed pass and in the region lists the hybrids march.
TEST_F(BoundaryOnTheGpu, OnTheHouseTheMeshRouteIsTheWalkRoute) {
    const Scene scene = scene_at(load_canonical("house-sweep"), 0.6667);
    for (const char* method : {"beamtree", "hybrid3"}) {
        const frame::Frame mesh = render_method(scene, method, 640, 360, {{"route", "mesh"}});
        const frame::Frame walk = render_method(scene, method, 640, 360, {{"route", "walk"}});
        const double peak = image_peak(walk.in_scattering);
        ASSERT_GT(peak, 0.01) << method << ": the shafts are in view";
        size_t lit = 0;
        for (const float v : walk.in_scattering.rgb) {
            lit += v > 0.0f ? 1 : 0;
        }
        const ErrorMetrics e = compare_images(mesh.in_scattering, walk.in_scattering);
        const size_t off = pixels_off(mesh.in_scattering, walk.in_scattering, peak);
        std::printf(
            "house-sweep, %s: mesh route against walk route %.2e, max_abs %.2e of the "
            "peak, %zu of %zu values off\n",
            method, e.rel_rmse, e.max_abs / peak, off, lit);
        // beamtree: 3.2e-4, max_abs 2.6% of the peak, no pixel 5% off (interpolated: 2.3e-2,
        // 147% of the peak). hybrid3 marches the uncertain intervals between crossings that
        // differ in the last float bits, so its samples move: 1.9e-3, 2.7% (interpolated:
        // 2.3e-2, 147%).
        const bool beamtree = std::string(method) == "beamtree";
        EXPECT_LT(e.rel_rmse, beamtree ? 1e-3 : 5e-3) << method;
        EXPECT_LT(e.max_abs, 0.05 * peak) << method;
        if (beamtree) {
            EXPECT_EQ(off, 0u);
        }
    }
}

// The GPU's walk (beamtree/shaders/walk.glsl, the walk route of docs/design.md §14) along random
// segments against the tree's own trace(): the lengths the walk finds lit, uncertain and unlit
// equal trace()'s to float round-off, on the canonical scenes, on 20 random scenes and on
// multiple:256 (depth > 100, so the walk's short stack overflows and restarts), there also with a
// stack of 2 entries. Its pieces tile each segment (tests/shaders/walk.frag counts a gap or an
// overlap as 1000 pieces) and no walk gives up.
struct WalkCase {
    std::string name;
    Scene scene;
    std::vector<std::string> defines;
    bt::GpuTreeLayout layout = bt::GpuTreeLayout::depth_first;
};

// Random segments between points of the influence volume and a little around it, with float
// ends so that both sides walk the same segment: per texel an origin and a direction with t1 in w.
struct WalkSegments {
    std::vector<glm::vec4> origins, directions;
    std::vector<std::pair<dvec3, dvec3>> lines;  // origin, direction in double
};

WalkSegments random_segments(std::mt19937& rng, const SpotLight& light, size_t count) {
    const double size = double(light.far);
    WalkSegments out;
    for (size_t i = 0; i < count; ++i) {
        dvec3 a, b;
        do {
            a = random_point(rng, light) + random_unit(rng) * uniform(rng, 0, 0.3 * size);
            b = random_point(rng, light) + random_unit(rng) * uniform(rng, 0, 0.3 * size);
        } while (!(glm::length(b - a) > 1e-3 * size));
        a = dvec3(glm::vec3(a));
        const dvec3 direction = dvec3(glm::normalize(glm::vec3(b - a)));
        const double t1 = double(float(glm::length(b - a) + uniform(rng, 0.0, 0.2 * size)));
        out.origins.push_back(glm::vec4(glm::vec3(a), 0.0f));
        out.directions.push_back(glm::vec4(glm::vec3(direction), float(t1)));
        out.lines.push_back({a, direction});
    }
    return out;
}

// What walk.frag finds along each segment (rgb: lit, uncertain, unlit lengths; a: pieces), with
// the tree uploaded as the methods upload it.
std::vector<float> walk_on_gpu(const WalkCase& c, const bt::BeamTree& tree,
                               const WalkSegments& segments, int width, int height) {
    analytic::GpuTreeBuffers buffers;  // what the methods upload, at classify.glsl's bindings
    buffers.upload(tree.gpu_tree(c.layout));
    buffers.bind();
    const gl::Texture origin_texture = gl::create_texture_2d(GL_RGBA32F, width, height, GL_NEAREST);
    const gl::Texture direction_texture =
        gl::create_texture_2d(GL_RGBA32F, width, height, GL_NEAREST);
    gl::GL.TextureSubImage2D(origin_texture.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT,
                             segments.origins.data());
    gl::GL.TextureSubImage2D(direction_texture.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT,
                             segments.directions.data());
    gl::GL.BindTextureUnit(0, origin_texture.id());
    gl::GL.BindTextureUnit(1, direction_texture.id());
    const gl::shared::FrameUniforms uniforms =
        frame::make_frame_uniforms(c.scene, {.width = width, .height = height});
    return render_test_pattern(uniforms, "tests/shaders/walk.frag", width, height, c.defines);
}

// The walk against trace() over many segments, summed over cases.
struct WalkTotals {
    double worst = 0.0;  // of the far range
    size_t segments = 0, beyond = 0, deepest = 0;
    std::array<double, 3> lengths{};
};

// One case: kWidth x kHeight random segments walked on the GPU and traced on the CPU; the
// lengths per region agree to 2e-4 of the far range (float round-off: a ray nearly in a plane's
// direction moves its crossing by more, far below a shaft's width), the pieces tile each segment
// and no walk gives up.
void walk_against_trace(const WalkCase& c, const bt::BeamTree& tree, std::mt19937& rng,
                        WalkTotals& totals) {
    constexpr int kWidth = 128, kHeight = 64;
    totals.deepest = std::max(totals.deepest, tree.stats().max_depth);
    const double size = double(c.scene.light.far);
    const WalkSegments lines = random_segments(rng, c.scene.light, size_t(kWidth) * kHeight);
    const std::vector<float> rgba = walk_on_gpu(c, tree, lines, kWidth, kHeight);
    std::vector<bt::RegionInterval> intervals;
    for (size_t i = 0; i < lines.lines.size(); ++i) {
        const auto& [a, direction] = lines.lines[i];
        tree.trace(a, direction, 0.0, double(lines.directions[i].w), intervals);
        std::array<double, 3> expected{};
        for (const bt::RegionInterval& interval : intervals) {
            expected[size_t(interval.region)] += interval.end - interval.begin;
        }
        const float pieces = rgba[i * 4 + 3];
        ASSERT_GT(pieces, 0.0f) << c.name << ": the walk gave up on segment " << i;
        ASSERT_LT(pieces, 1000.0f) << c.name << ": pieces do not tile segment " << i;
        for (size_t r = 0; r < 3; ++r) {
            const double error = std::abs(double(rgba[i * 4 + r]) - expected[r]) / size;
            totals.worst = std::max(totals.worst, error);
            totals.lengths[r] += expected[r];
            EXPECT_LT(error, 2e-4) << c.name << " segment " << i << " region " << r;
            totals.beyond += error > 1e-5 ? 1 : 0;
        }
        ++totals.segments;
    }
}

void print_walk(const char* what, const WalkTotals& t) {
    std::printf(
        "%s: %zu segments, deepest tree %zu; lengths lit %.0f, uncertain %.0f, unlit %.0f m; "
        "worst error %.2e of the far range, %zu lengths beyond 1e-5\n",
        what, t.segments, t.deepest, t.lengths[0], t.lengths[1], t.lengths[2], t.worst, t.beyond);
}

TEST_F(BoundaryOnTheGpu, WalkFindsTheTreesIntervalsAlongRandomLines) {
    bt::VolumeLibrary library;
    std::vector<WalkCase> cases;
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        cases.push_back({name, load_canonical(name), {}});
    }
    const Scene deep = load_scene("multiple:256", SceneSearchPaths::defaults());
    cases.push_back({"multiple:256", deep, {}});
    cases.push_back({"multiple:256, stack 2", deep, {"SL_WALK_STACK 2"}});
    cases.push_back({"multiple:256, build layout", deep, {}, bt::GpuTreeLayout::build});
    for (int seed = 600; seed < 620; ++seed) {
        cases.push_back({fmt::format("seed {}", seed), random_scene(seed, library).scene, {}});
    }
    std::mt19937 rng(23);
    WalkTotals totals;
    for (const WalkCase& c : cases) {
        bt::VolumeLibrary& volumes =
            bt::VolumeLibrary::shared({.max_outer_planes = c.scene.bounds.max_outer_planes,
                                       .automatic_inner = c.scene.bounds.automatic_inner});
        walk_against_trace(c, bt::BeamTree(c.scene.light, volumes.build(c.scene, nullptr)), rng,
                           totals);
    }
    print_walk("walk on the GPU", totals);
    EXPECT_GT(totals.deepest, 100u) << "multiple:256 should overflow the walk's stack";
    EXPECT_LT(double(totals.beyond), 1e-3 * double(totals.segments) * 3.0);
    for (double total : totals.lengths) {
        EXPECT_GT(total, 0.1 * double(totals.segments)) << "every region should be crossed";
    }
}

// Trees of half a million nodes walked exactly: multiple:4000's 4,000 objects make a tree of
// about 510,000 nodes without the grid of sub-beams at its top (TreeBuild), deep enough for the
// walk's short stack to overflow and restart, and one of about 460,000 with it (what the methods
// build); the GPU walks both to the lengths trace() finds.
TEST_F(BoundaryOnTheGpu, WalkIsExactOnTreesOfHalfAMillionNodes) {
    WalkCase c{"multiple:4000", load_canonical("multiple:4000"), {}};
    bt::VolumeLibrary& library = bt::VolumeLibrary::shared(c.scene.bounds);
    const std::vector<bt::ObjectVolumes> volumes = library.build(c.scene, nullptr);
    const bt::BeamTree deep(c.scene.light, volumes,
                            {.grid_from = std::numeric_limits<size_t>::max()});
    const bt::BeamTree gridded(c.scene.light, volumes);
    EXPECT_GT(deep.stats().max_depth, 100u) << "the walk's stack should overflow";
    for (const bt::BeamTree* tree : {&deep, &gridded}) {
        ASSERT_GT(tree->stats().nodes, 400000u);
        std::mt19937 rng(29);
        WalkTotals totals;
        walk_against_trace(c, *tree, rng, totals);
        print_walk("walk on a tree of half a million nodes", totals);
        std::printf("  %zu nodes, depth %zu\n", tree->stats().nodes, tree->stats().max_depth);
        EXPECT_LT(double(totals.beyond), 1e-3 * double(totals.segments) * 3.0);
        EXPECT_GT(totals.lengths[0], 0.1 * double(totals.segments)) << "lit crossed";
        EXPECT_GT(totals.lengths[2], 0.1 * double(totals.segments)) << "unlit crossed";
    }
}

}  // namespace
}  // namespace sl::test
