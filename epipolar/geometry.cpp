#include "epipolar/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace sl::epipolar {

namespace {

constexpr double kFarLight = 1e3;  // image diagonals: where a light at infinity is put

// The side lengths and starts along the perimeter: bottom, right, top, left.
struct Border {
    double w, h;
    double length(int side) const { return side % 2 == 0 ? w : h; }
    double start(int side) const {
        const double starts[4] = {0.0, w, w + h, 2.0 * w + h};
        return starts[side];
    }
    double perimeter() const { return 2.0 * (w + h); }
};

// The world direction of the eye ray through window position x (`clip_to_world`: the inverse of
// the camera's view-projection).
glm::dvec3 ray_direction(const Views& views, const glm::dmat4& clip_to_world, glm::dvec2 x) {
    const glm::dvec2 ndc = 2.0 * x / glm::dvec2(views.width, views.height) - 1.0;
    const glm::dvec4 far_point = clip_to_world * glm::dvec4(ndc, 1.0, 1.0);
    return glm::normalize(glm::dvec3(far_point) / far_point.w - views.camera);
}

// The range of λ for which p + λ d lies inside [lo, hi] on every axis (empty: first > second).
std::pair<double, double> slab(glm::dvec2 p, glm::dvec2 d, glm::dvec2 lo, glm::dvec2 hi) {
    double enter = -std::numeric_limits<double>::infinity();
    double leave = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 2; ++i) {
        if (d[i] == 0.0) {
            if (p[i] < lo[i] || p[i] > hi[i]) {
                return {1.0, 0.0};
            }
            continue;
        }
        double a = (lo[i] - p[i]) / d[i], b = (hi[i] - p[i]) / d[i];
        if (a > b) {
            std::swap(a, b);
        }
        enter = std::max(enter, a);
        leave = std::min(leave, b);
    }
    return {enter, leave};
}

// The shadow map's line of the epipolar plane with normal n through the camera: Chen et al.
// 2011 §4. A plane π through the light maps to light clip space as M^-T π, with no depth term
// (a perspective light's centre is the clip point (0, 0, B, 0); a sun's orthographic depth axis
// is its direction, which the plane contains), so in the map's [0, 1]² it is the line
// a (2u - 1) + b (2v - 1) + d = 0 (`plane_to_light_clip`: M^-T).
void map_line(const Views& views, const glm::dmat4& plane_to_light_clip, glm::dvec3 n, int texels,
              Slice& slice) {
    const glm::dvec4 plane(n, -glm::dot(n, views.camera));
    const glm::dvec4 clip = plane_to_light_clip * plane;
    const glm::dvec2 normal(2.0 * clip.x, 2.0 * clip.y);
    const double norm = glm::length(normal);
    if (!(norm > 0.0)) {
        return;
    }
    const glm::dvec2 unit = normal / norm;
    const double offset = (clip.w - clip.x - clip.y) / norm;
    const glm::dvec2 centre(0.5);
    const glm::dvec2 q = centre - (glm::dot(unit, centre) + offset) * unit;
    const glm::dvec2 along(-unit.y, unit.x);
    const auto [enter, leave] = slab(q, along, glm::dvec2(0.0), glm::dvec2(1.0));
    if (!(leave - enter > 1e-9)) {
        return;
    }
    slice.map_origin = q + enter * along;
    slice.map_step = (leave - enter) / double(texels) * along;
}

}  // namespace

glm::dvec2 light_screen_position(const Views& views) {
    const glm::dvec2 size(views.width, views.height);
    const glm::dvec2 centre = 0.5 * size;
    const double far = kFarLight * glm::length(size);
    const glm::dvec4 clip = views.view_projection * views.light;
    const glm::dvec2 scaled = glm::dvec2(clip) * 0.5 * size;  // pixels from the centre, times w
    if (std::abs(clip.w) * far > glm::length(scaled)) {
        return centre + scaled / clip.w;
    }
    if (glm::length(scaled) > 0.0) {
        return centre + far * glm::normalize(clip.w < 0.0 ? -scaled : scaled);
    }
    return centre;  // the light at the camera: every direction is degenerate
}

bool inside_image(glm::dvec2 p, int width, int height) {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= width && p.y <= height;
}

ExitArc exit_arc(glm::dvec2 p, int width, int height) {
    const Border border{double(width), double(height)};
    const bool facing[4] = {p.y<0.0, p.x> width, p.y > height, p.x < 0.0};
    if (!facing[0] && !facing[1] && !facing[2] && !facing[3]) {
        return {0.0, border.perimeter(), true};
    }
    // The facing sides are one or two neighbours; the arc is the others, from the first side
    // after them counter-clockwise.
    ExitArc arc{0.0, 0.0, false};
    for (int side = 0; side < 4; ++side) {
        if (!facing[side]) {
            arc.length += border.length(side);
            if (facing[(side + 3) % 4]) {
                arc.start = border.start(side);
            }
        }
    }
    return arc;
}

glm::dvec2 border_point(double s, int width, int height) {
    const Border border{double(width), double(height)};
    s = std::fmod(s, border.perimeter());
    if (s < 0.0) {
        s += border.perimeter();
    }
    const double w = width, h = height;
    if (s < w) {
        return {s, 0.0};
    }
    if (s < w + h) {
        return {w, s - w};
    }
    if (s < 2.0 * w + h) {
        return {w - (s - w - h), h};
    }
    return {0.0, h - (s - 2.0 * w - h)};
}

double perimeter_position(glm::dvec2 b, int width, int height) {
    const double w = width, h = height;
    const double distance[4] = {std::abs(b.y), std::abs(b.x - w), std::abs(b.y - h), std::abs(b.x)};
    const int side = int(std::min_element(distance, distance + 4) - distance);
    switch (side) {
        case 0:
            return std::clamp(b.x, 0.0, w);
        case 1:
            return w + std::clamp(b.y, 0.0, h);
        case 2:
            return w + h + (w - std::clamp(b.x, 0.0, w));
        default:
            return 2.0 * w + h + (h - std::clamp(b.y, 0.0, h));
    }
}

glm::dvec2 exit_point(glm::dvec2 p, glm::dvec2 x, int width, int height) {
    const glm::dvec2 d = x - p;
    const auto range = slab(p, d, glm::dvec2(0.0), glm::dvec2(width, height));
    return p + range.second * d;
}

std::vector<Slice> make_slices(const Views& views, int slices, int map_texels) {
    const glm::dvec2 p = light_screen_position(views);
    const ExitArc arc = exit_arc(p, views.width, views.height);
    const bool inside = inside_image(p, views.width, views.height);
    // The epipolar planes contain the camera and the light: the direction to it (a sun's plane
    // contains its beams, which an orthographic map sees as one line, as a point light's plane
    // through its centre is one line of its perspective map).
    const glm::dvec3 to_light = glm::dvec3(views.light) - views.light.w * views.camera;
    const glm::dmat4 clip_to_world = glm::inverse(views.view_projection);
    const glm::dmat4 plane_to_light_clip =
        glm::transpose(glm::inverse(views.light_view_projection));
    std::vector<Slice> result(size_t(std::max(slices, 0)));
    for (int s = 0; s < slices; ++s) {
        Slice& slice = result[size_t(s)];
        slice.exit = border_point(arc.start + arc.length * (double(s) + 0.5) / double(slices),
                                  views.width, views.height);
        slice.entry = p;
        if (!inside) {
            const auto range =
                slab(p, slice.exit - p, glm::dvec2(0.0), glm::dvec2(views.width, views.height));
            slice.entry = range.first < range.second && range.first < 1.0
                              ? p + range.first * (slice.exit - p)
                              : slice.exit;
        }
        // The epipolar plane: the camera, the light and the exit point's ray (the light's screen
        // position's ray where the light is at the camera's position or on that ray).
        const glm::dvec3 exit_ray = ray_direction(views, clip_to_world, slice.exit);
        glm::dvec3 n = glm::cross(exit_ray, to_light);
        if (!(glm::length(n) > 1e-9 * glm::length(to_light))) {
            n = glm::cross(exit_ray, ray_direction(views, clip_to_world, p));
        }
        if (!(glm::length(n) > 1e-12)) {
            n = glm::cross(exit_ray,
                           std::abs(exit_ray.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0));
        }
        map_line(views, plane_to_light_clip, glm::normalize(n), map_texels, slice);
    }
    return result;
}

double slice_coordinate(glm::dvec2 p, const ExitArc& arc, glm::dvec2 x, int slices, int width,
                        int height) {
    const double perimeter = 2.0 * (double(width) + double(height));
    double along = std::fmod(
        perimeter_position(exit_point(p, x, width, height), width, height) - arc.start, perimeter);
    if (along < 0.0) {
        along += perimeter;
    }
    if (!arc.periodic && along > 0.5 * (arc.length + perimeter)) {
        along -= perimeter;  // just before the arc's start
    }
    return along / arc.length * double(slices) - 0.5;
}

int map_texels(int map_size) {
    int texels = 64;
    while (texels < map_size && texels < 8192) {
        texels *= 2;
    }
    return texels;
}

}  // namespace sl::epipolar
