// `epipolar`'s slice geometry on the CPU (epipolar/geometry.h): the slices tile the image and the
// unwarp finds them, and every eye ray of a slice projects onto the slice's shadow-map line, for
// every placement of the light (on screen, beyond each side, behind the camera), a spot light's
// and a sun's (its point at infinity: an orthographic shadow map, whose lines are those of the
// planes that contain the sun's direction).

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "epipolar/geometry.h"
#include "tests/support.h"

namespace sl::test {
namespace {

using namespace sl::epipolar;

Views views_of(const Scene& scene, int width, int height) {
    return {.view_projection = glm::dmat4(scene.camera.projection(float(width) / float(height)) *
                                          scene.camera.view()),
            .light_view_projection = glm::dmat4(scene.light.projection() * scene.light.view()),
            .camera = glm::dvec3(scene.camera.position),
            .light = scene.light.parallel() ? glm::dvec4(-glm::dvec3(scene.light.direction()), 0.0)
                                            : glm::dvec4(glm::dvec3(scene.light.position), 1.0),
            .width = width,
            .height = height};
}

// Every placement of a spot light and of a sun (Yusov's light at infinity).
std::vector<std::pair<std::string, Scene>> placements() {
    std::vector<std::pair<std::string, Scene>> scenes = light_placements();
    for (auto& placed : sun_placements()) {
        scenes.push_back(std::move(placed));
    }
    return scenes;
}

double cross2(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

// The slices, for every placement of the light: each exit point lies on the image border and
// each entry inside the image; the unwarp (slice_coordinate) of every point of slice s is s; and
// every pixel centre lies between the two slices its coordinate names (the pixel's direction
// from the light's screen position turns the same way from the first as to the second).
TEST(EpipolarGeometry, SlicesTileTheImageAndTheUnwarpFindsThem) {
    const int width = 160, height = 90, n = 64;
    for (const auto& [name, scene] : placements()) {
        const Views views = views_of(scene, width, height);
        const glm::dvec2 p = light_screen_position(views);
        const ExitArc arc = exit_arc(p, width, height);
        const std::vector<Slice> slices = make_slices(views, n, 1024);
        ASSERT_EQ(slices.size(), size_t(n));
        for (int s = 0; s < n; ++s) {
            const Slice& slice = slices[size_t(s)];
            const double to_border =
                std::min({slice.exit.x, slice.exit.y, width - slice.exit.x, height - slice.exit.y});
            EXPECT_NEAR(to_border, 0.0, 1e-9) << name << " slice " << s;
            EXPECT_TRUE(inside_image(slice.entry, width, height)) << name << " slice " << s;
            for (const double lambda : {0.1, 0.5, 0.99}) {
                const glm::dvec2 x = slice.entry + lambda * (slice.exit - slice.entry);
                if (glm::length(x - p) < 1e-3 || slice.entry == slice.exit) {
                    continue;
                }
                EXPECT_NEAR(slice_coordinate(p, arc, x, n, width, height), double(s), 1e-6)
                    << name << " slice " << s << " at " << lambda;
            }
        }
        int checked = 0;
        for (int y = 0; y < height; y += 3) {
            for (int x = 0; x < width; x += 3) {
                const glm::dvec2 pixel(x + 0.5, y + 0.5);
                const double c = slice_coordinate(p, arc, pixel, n, width, height);
                ASSERT_TRUE(std::isfinite(c)) << name;
                EXPECT_GE(c, -0.5 - 1e-9) << name;
                EXPECT_LE(c, n - 0.5 + 1e-9) << name;
                const int s0 = int(std::floor(c));
                if (!arc.periodic && (s0 < 0 || s0 + 1 >= n)) {
                    continue;  // beyond the first or last slice: the unwarp clamps
                }
                const glm::dvec2 a = slices[size_t((s0 + n) % n)].exit - p;
                const glm::dvec2 b = slices[size_t((s0 + 1) % n)].exit - p;
                const glm::dvec2 d = pixel - p;
                EXPECT_GE(cross2(a, d) * cross2(d, b),
                          -1e-9 * glm::length(a) * glm::length(b) * glm::dot(d, d))
                    << name << " pixel " << x << "," << y << " c " << c;
                ++checked;
            }
        }
        EXPECT_GT(checked, 1000) << name;
    }
}

// Chen et al.'s rectification: every point of every eye ray of slice s (through a point of its
// segment) that the light sees projects onto the slice's line in the shadow map, to 1e-5 of the
// map (a 2048² map's texel is 5e-4; the camera's matrices are float, and the eye they imply is
// the camera's position to 1e-7, which the light's projection magnifies where the eye is half a
// metre from it); and the line's part inside the map is what the slice records. A light in the
// camera's plane projects to infinity and its screen position is moved to 1e3 image diagonals,
// which turns the slices by up to 1e-3 rad: there the points lie within 1e-4 of the map (a fifth of
// a texel; the march projects each point onto the line, so this is harmless).
TEST(EpipolarGeometry, EveryEyeRayOfASliceProjectsOntoItsShadowMapLine) {
    const int width = 160, height = 90, n = 48;
    for (const auto& [name, scene] : placements()) {
        const Views views = views_of(scene, width, height);
        const glm::dmat4 inverse = glm::inverse(views.view_projection);
        const std::vector<Slice> slices = make_slices(views, n, 1024);
        const double tolerance =
            name == "light in the camera's plane" || name == "sun in the camera's plane" ? 1e-4
                                                                                         : 1e-5;
        int projected = 0;
        for (const Slice& slice : slices) {
            if (slice.map_step == glm::dvec2(0.0) || slice.entry == slice.exit) {
                continue;
            }
            const glm::dvec2 along = glm::normalize(slice.map_step);
            const glm::dvec2 end = slice.map_origin + 1024.0 * slice.map_step;
            for (const auto lo : {slice.map_origin, end}) {
                EXPECT_GE(std::min(lo.x, lo.y), -1e-9) << name;
                EXPECT_LE(std::max(lo.x, lo.y), 1.0 + 1e-9) << name;
            }
            for (const double lambda : {0.0, 0.3, 0.7, 1.0}) {
                const glm::dvec2 x = slice.entry + lambda * (slice.exit - slice.entry);
                const glm::dvec2 ndc = 2.0 * x / glm::dvec2(width, height) - 1.0;
                const glm::dvec4 far = inverse * glm::dvec4(ndc, 1.0, 1.0);
                const glm::dvec3 direction = glm::normalize(glm::dvec3(far) / far.w - views.camera);
                for (double t = 0.05; t < 40.0; t *= 1.3) {
                    const glm::dvec4 clip =
                        views.light_view_projection * glm::dvec4(views.camera + t * direction, 1.0);
                    if (clip.w <= 0.0) {
                        continue;
                    }
                    const glm::dvec2 uv = 0.5 * glm::dvec2(clip) / clip.w + 0.5;
                    if (std::min(uv.x, uv.y) < 0.0 || std::max(uv.x, uv.y) > 1.0) {
                        continue;
                    }
                    EXPECT_NEAR(cross2(along, uv - slice.map_origin), 0.0, tolerance)
                        << name << " t " << t;
                    ++projected;
                }
            }
        }
        EXPECT_GT(projected, 20) << name;
    }
}

}  // namespace
}  // namespace sl::test
