#include "scenes/view_window.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/check.h"

namespace sl {

namespace {

using glm::dvec3;
using glm::dvec4;

constexpr double kInside = 1e-9;  // slack of the inside tests, in the box's clip units
constexpr double kMargin = 0.02;  // of each fitted extent, on each side
constexpr double kLeast = 1e-3;   // the least width of a fitted extent, in clip units

// An inward plane of the view pyramid: dot(n, p) + d >= 0 inside.
struct HalfSpace {
    dvec3 n{0.0};
    double d = 0.0;
    double at(const dvec3& p) const { return glm::dot(n, p) + d; }
};

HalfSpace through(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& inside) {
    HalfSpace h;
    h.n = glm::cross(b - a, c - a);
    h.d = -glm::dot(h.n, a);
    if (h.at(inside) < 0.0) {
        h.n = -h.n;
        h.d = -h.d;
    }
    return h;
}

bool in_box(const dvec3& p) {
    return std::abs(p.x) <= 1.0 + kInside && std::abs(p.y) <= 1.0 + kInside &&
           std::abs(p.z) <= 1.0 + kInside;
}

// The part of the box's clip cube [-1, 1]³ inside the view pyramid (eye, far corners in order
// around the far plane, all in the box's clip space), as the bounds of its vertices: the
// pyramid's corners in the cube, the cube's corners in the pyramid, and where the edges of each
// cross the faces of the other, into `points`. False when they do not meet.
bool intersection_bounds(const dvec3& eye, const std::array<dvec3, 4>& far, dvec3& lo, dvec3& hi,
                         std::vector<dvec3>& points) {
    dvec3 centre = eye;
    for (const dvec3& f : far) {
        centre += f;
    }
    centre /= 5.0;
    std::vector<HalfSpace> pyramid;
    for (int i = 0; i < 4; ++i) {
        pyramid.push_back(through(eye, far[size_t(i)], far[size_t((i + 1) % 4)], centre));
    }
    pyramid.push_back(through(far[0], far[1], far[2], centre));
    const auto in_pyramid = [&](const dvec3& p) {
        const double scale = 1.0 + glm::length(p);
        return std::all_of(pyramid.begin(), pyramid.end(), [&](const HalfSpace& h) {
            return h.at(p) >= -kInside * scale * glm::length(h.n);
        });
    };
    lo = dvec3(std::numeric_limits<double>::infinity());
    hi = -lo;
    bool any = false;
    const auto take = [&](const dvec3& p) {
        points.push_back(p);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        any = true;
    };
    std::vector<std::pair<dvec3, dvec3>> pyramid_edges;
    for (int i = 0; i < 4; ++i) {
        pyramid_edges.emplace_back(eye, far[size_t(i)]);
        pyramid_edges.emplace_back(far[size_t(i)], far[size_t((i + 1) % 4)]);
    }
    if (in_box(eye)) {
        take(eye);
    }
    for (const dvec3& f : far) {
        if (in_box(f)) {
            take(f);
        }
    }
    // The pyramid's edges through the cube's faces (axis k at ±1).
    for (const auto& [a, b] : pyramid_edges) {
        for (int k = 0; k < 3; ++k) {
            for (const double s : {-1.0, 1.0}) {
                const double da = a[k] - s, db = b[k] - s;
                if ((da < 0.0) == (db < 0.0) || da == db) {
                    continue;
                }
                dvec3 p = a + da / (da - db) * (b - a);
                p[k] = s;
                if (in_box(p)) {
                    take(p);
                }
            }
        }
    }
    // The cube's corners in the pyramid, and its edges through the pyramid's faces.
    for (int corner = 0; corner < 8; ++corner) {
        const dvec3 c(corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0);
        if (in_pyramid(c)) {
            take(c);
        }
        for (int k = 0; k < 3; ++k) {
            if (c[k] > 0.0) {
                continue;  // each edge once, from its corner at -1 along axis k
            }
            dvec3 e = c;
            e[k] = 1.0;
            for (const HalfSpace& h : pyramid) {
                const double da = h.at(c), db = h.at(e);
                if ((da < 0.0) == (db < 0.0) || da == db) {
                    continue;
                }
                const dvec3 p = c + da / (da - db) * (e - c);
                if (in_pyramid(p)) {
                    take(p);
                }
            }
        }
    }
    return any;
}

// [lo, hi] widened by the margin, at least `least` wide, inside [-1, 1].
void widen(double& lo, double& hi, double least) {
    const double pad = kMargin * (hi - lo) + 0.5 * least;
    lo = std::max(-1.0, lo - pad);
    hi = std::min(1.0, hi + pad);
}

// Twice the signed area of the triangle o, a, b in x, y: > 0 when it turns counter-clockwise.
double turn(const dvec3& o, const dvec3& a, const dvec3& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// The convex hull of the points' x, y, counter-clockwise (Andrew's monotone chain), without
// collinear vertices.
std::vector<dvec3> hull_across(std::vector<dvec3> points) {
    std::sort(points.begin(), points.end(), [](const dvec3& a, const dvec3& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    if (points.size() < 3) {
        return points;
    }
    std::vector<dvec3> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {  // the lower chain
        while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) {
            --k;
        }
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {  // the upper chain
        while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i - 1]) <= 0.0) {
            --k;
        }
        hull[k++] = points[i - 1];
    }
    hull.resize(k - 1);  // the last is the first
    return hull;
}

// The cuts of `window` (its rectangle already widened): each edge of the hull of the points
// across the beams, moved out by `pad`, where it cuts a corner off the rectangle. An edge within
// 1e-3 of a side's direction is left to that side.
void add_cuts(const std::vector<dvec3>& points, double pad, ViewWindow& window) {
    const std::vector<dvec3> hull = hull_across(points);
    for (size_t i = 0; hull.size() >= 3 && i < hull.size(); ++i) {
        const dvec3& a = hull[i];
        const dvec3& b = hull[(i + 1) % hull.size()];
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        if (!(length > 0.0)) {
            continue;
        }
        // Counter-clockwise: the outward normal is the edge turned clockwise.
        const double nx = (b.y - a.y) / length, ny = (a.x - b.x) / length;
        if (std::abs(nx) < 1e-3 || std::abs(ny) < 1e-3) {
            continue;
        }
        const double c = std::max(nx * a.x + ny * a.y, nx * b.x + ny * b.y) + pad;
        // The rectangle's corner farthest out along the normal: cut only when it lies beyond.
        const double corner = nx * (nx > 0.0 ? window.hi.x : window.lo.x) +
                              ny * (ny > 0.0 ? window.hi.y : window.lo.y);
        if (corner > c) {
            window.cuts.emplace_back(nx, ny, c);
        }
    }
}

}  // namespace

std::optional<ViewWindow> view_window(const SpotLight& light, const Camera& camera, float aspect) {
    SL_CHECK(light.parallel());
    const glm::dmat4 whole = glm::dmat4(light.projection()) * glm::dmat4(light.view());
    // The view pyramid in the box's clip space (an affine map: the box is orthographic).
    const glm::dmat4 to_world =
        glm::inverse(glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view()));
    const auto clip = [&](const dvec3& world) { return dvec3(whole * dvec4(world, 1.0)); };
    std::array<dvec3, 4> far;
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (size_t i = 0; i < 4; ++i) {
        const dvec4 p = to_world * dvec4(corners[i][0], corners[i][1], 1.0, 1.0);
        far[i] = clip(dvec3(p) / p.w);
    }
    ViewWindow window;
    std::vector<dvec3> points;
    if (!intersection_bounds(clip(dvec3(camera.position)), far, window.lo, window.hi, points)) {
        return std::nullopt;
    }
    const double extent = std::max(window.hi.x - window.lo.x, window.hi.y - window.lo.y);
    widen(window.lo.x, window.hi.x, kLeast);
    widen(window.lo.y, window.hi.y, kLeast);
    add_cuts(points, kMargin * extent + 0.5 * kLeast, window);
    window.lo.z = -1.0;  // from the entry plane: every occluder before what the camera sees
    widen(window.lo.z, window.hi.z, kLeast);
    return window;
}

}  // namespace sl
