#include "scenes/view_window.h"

#include <algorithm>
#include <array>
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
// cross the faces of the other. False when they do not meet.
bool intersection_bounds(const dvec3& eye, const std::array<dvec3, 4>& far, dvec3& lo, dvec3& hi) {
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
    if (!intersection_bounds(clip(dvec3(camera.position)), far, window.lo, window.hi)) {
        return std::nullopt;
    }
    widen(window.lo.x, window.hi.x, kLeast);
    widen(window.lo.y, window.hi.y, kLeast);
    window.lo.z = -1.0;  // from the entry plane: every occluder before what the camera sees
    widen(window.lo.z, window.hi.z, kLeast);
    return window;
}

}  // namespace sl
