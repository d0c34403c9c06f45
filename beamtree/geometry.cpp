#include "beamtree/geometry.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sl::bt {

bool Plane::through(const dvec3& a, const dvec3& b, const dvec3& c, Plane& plane) {
    const dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) {
        return false;
    }
    plane.normal = n / length;
    plane.offset = -glm::dot(plane.normal, a);
    return true;
}

dvec3 area_vector(const Polygon& polygon) {
    dvec3 sum(0.0);
    const size_t n = polygon.size();
    if (n < 3) {
        return sum;
    }
    // Relative to the first vertex: smaller round-off far from the origin.
    const dvec3 origin = polygon.vertices[0];
    for (size_t i = 1; i + 1 < n; ++i) {
        sum += glm::cross(polygon.vertices[i] - origin, polygon.vertices[i + 1] - origin);
    }
    return 0.5 * sum;
}

double area(const Polygon& polygon) {
    return glm::length(area_vector(polygon));
}

bool area_exceeds(const Polygon& polygon, double threshold) {
    // area_vector's fan, its triangles' areas summed: for a convex polygon they all turn one way,
    // so the sum of their lengths is the length of their sum (to round-off).
    const size_t n = polygon.size();
    double sum = 0.0;
    for (size_t i = 1; i + 1 < n; ++i) {
        const dvec3& o = polygon.vertices[0];  // as area_vector: relative to the first vertex
        sum += 0.5 * glm::length(glm::cross(polygon.vertices[i] - o, polygon.vertices[i + 1] - o));
        if (sum > threshold) {
            return true;
        }
    }
    return false;
}

dvec3 centroid(const Polygon& polygon) {
    dvec3 sum(0.0);
    for (const dvec3& v : polygon.vertices) {
        sum += v;
    }
    return polygon.vertices.empty() ? sum : sum / double(polygon.size());
}

Ball bounding_ball(const Polygon& polygon) {
    Ball ball;
    if (polygon.vertices.empty()) {
        return ball;
    }
    ball.center = centroid(polygon);
    double farthest2 = 0.0, extent = 0.0;  // squared radius; largest coordinate's magnitude
    for (const dvec3& v : polygon.vertices) {
        const dvec3 r = v - ball.center;
        const double r2 = r.x * r.x + r.y * r.y + r.z * r.z;
        farthest2 = r2 > farthest2 ? r2 : farthest2;
        const double e = std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
        extent = e > extent ? e : extent;
    }
    // A vertex's distance to a unit-normal plane differs from the center's by at most the radius;
    // the pad here and Ball::side's cover the round-off of both distances (a few ulps of the
    // coordinates and of the plane's offset, far below 1e-12 of them), so that Ball::side never
    // decides where side() would not.
    ball.radius = std::sqrt(farthest2) * (1.0 + 1e-12) + 1e-12 * (1.0 + extent);
    return ball;
}

Side side(const Polygon& polygon, const Plane& plane, double epsilon) {
    bool any_front = false, any_back = false;
    for (const dvec3& v : polygon.vertices) {
        const double d = plane.distance(v);
        any_front |= d > epsilon;
        any_back |= d < -epsilon;
    }
    return any_front ? (any_back ? Side::straddling : Side::front)
                     : (any_back ? Side::back : Side::coplanar);
}

namespace {

// The two parts of a polygon that straddles a plane, from its vertices' distances `d`: cut
// exactly at distance 0, so that the two parts share the cut and conserve the area (ε only
// decided that there is a split at all). The cut points go to `cut` when given. A null `front` or
// `back`: that part is not made.
void cut_in_two(const Polygon& polygon, const double* d, bool cut_on_split_plane, Polygon* front,
                Polygon* back, std::vector<dvec3>* cut) {
    const size_t n = polygon.size();
    for (Polygon* part : {front, back}) {
        if (part) {
            part->vertices.reserve(n + 1);
        }
    }
    auto add = [](Polygon* p, const dvec3& v, bool edge_flag) {
        if (!p) {
            return;
        }
        if (edge_flag && p->vertices.size() < 64) {
            p->on_split_plane |= uint64_t(1) << p->vertices.size();
        }
        p->vertices.push_back(v);
    };
    for (size_t i = 0; i < n; ++i) {
        const size_t j = i + 1 == n ? 0 : i + 1;
        const dvec3& a = polygon.vertices[i];
        const dvec3& b = polygon.vertices[j];
        const bool edge_flag = polygon.edge_on_split_plane(i);
        const bool a_front = d[i] > 0.0, a_back = d[i] < 0.0;
        const bool b_front = d[j] > 0.0, b_back = d[j] < 0.0;
        // Vertex a and the flag of the edge leaving it: the original edge's, except for a vertex
        // on the plane whose edge dives to the other side, where the polygon continues along
        // the cut.
        if (!a_back && !a_front && cut) {
            cut->push_back(a);
        }
        if (!a_back) {
            add(front, a, (!a_front && b_back) ? cut_on_split_plane : edge_flag);
        }
        if (!a_front) {
            add(back, a, (!a_back && b_front) ? cut_on_split_plane : edge_flag);
        }
        if ((a_front && b_back) || (a_back && b_front)) {
            // From the back end of the edge whichever way the polygon walks it: the two faces of
            // a polyhedron that share this edge walk it in opposite directions and must get the
            // same point to the last bit, or the region meshes crack (pixels that see a front
            // face but not the back face behind it integrate G(z) alone).
            const bool from_a = a_back;
            const dvec3& origin = from_a ? a : b;
            const dvec3& target = from_a ? b : a;
            const double d_origin = from_a ? d[i] : d[j], d_target = from_a ? d[j] : d[i];
            const double t = d_origin / (d_origin - d_target);
            const dvec3 p = origin + t * (target - origin);
            // Leaving the front side, the front polygon continues from p along the cut; entering
            // it, the rest of the original edge follows. Likewise for the back polygon.
            add(front, p, a_front ? cut_on_split_plane : edge_flag);
            add(back, p, a_back ? cut_on_split_plane : edge_flag);
            if (cut) {
                cut->push_back(p);
            }
        }
    }
    // Emptied, not freed: a caller that reuses the parts keeps their storage.
    for (Polygon* part : {front, back}) {
        if (part && part->size() < 3) {
            part->clear();
        }
    }
}

// The vertices' distances to a plane, in a buffer on the stack for the usual few vertices.
class Distances {
public:
    Distances(const Polygon& polygon, const Plane& plane, double epsilon) {
        const size_t n = polygon.size();
        if (n > kInline) {
            heap_.resize(n);
        }
        double* d = data();
        for (size_t i = 0; i < n; ++i) {
            d[i] = plane.distance(polygon.vertices[i]);
            any_front |= d[i] > epsilon;
            any_back |= d[i] < -epsilon;
        }
    }
    double* data() { return heap_.empty() ? inline_ : heap_.data(); }
    bool any_front = false, any_back = false;

private:
    static constexpr size_t kInline = 32;
    double inline_[kInline];
    std::vector<double> heap_;
};

}  // namespace

Split split(const Polygon& polygon, const Plane& plane, double epsilon, bool cut_on_split_plane) {
    Split result;
    if (polygon.size() < 3) {
        return result;
    }
    Distances d(polygon, plane, epsilon);
    if (!d.any_front && !d.any_back) {
        result.coplanar = true;
        return result;
    }
    if (!d.any_back) {
        result.front = polygon;
        return result;
    }
    if (!d.any_front) {
        result.back = polygon;
        return result;
    }
    cut_in_two(polygon, d.data(), cut_on_split_plane, &result.front, &result.back, &result.cut);
    return result;
}

Side split_straddling(const Polygon& polygon, const Plane& plane, double epsilon,
                      bool cut_on_split_plane, Polygon& front, Polygon& back, uint64_t* touching,
                      double coincident, Parts parts) {
    Distances d(polygon, plane, epsilon);
    if (!(d.any_front && d.any_back)) {
        if (touching) {
            // Edge i runs from vertex i to vertex i + 1 (the last one closes to vertex 0).
            const size_t n = std::min<size_t>(polygon.size(), 64);
            const double* distance = d.data();
            uint64_t on = 0;
            for (size_t i = 0; i < n; ++i) {
                on |= uint64_t(std::abs(distance[i]) <= coincident) << i;
            }
            uint64_t next = on >> 1;
            if (polygon.size() <= 64) {
                next |= (on & 1u) << (n - 1);
            }
            *touching = on & next;
        }
        return d.any_front ? Side::front : d.any_back ? Side::back : Side::coplanar;
    }
    cut_in_two(polygon, d.data(), cut_on_split_plane, parts == Parts::back ? nullptr : &front,
               parts == Parts::front ? nullptr : &back, nullptr);
    return Side::straddling;
}

Polygon convex_polygon_on_plane(std::vector<dvec3> points, const Plane& plane, double epsilon) {
    // Graham scan around the centroid. The angular order needs no primary axis: a monotone chain
    // sorted along one axis misorders the points of an edge parallel to the other axis as soon as
    // their coordinates differ in the last bit (cut points of a clipped cell do), and then drops
    // corners. Interior, repeated and collinear points (within epsilon) drop out.
    if (points.size() < 3) {
        return Polygon();
    }
    const dvec3 n = plane.normal;
    const dvec3 u = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, dvec3(1, 0, 0))
                                                       : glm::cross(n, dvec3(0, 1, 0)));
    const dvec3 v = glm::cross(n, u);
    dvec3 center(0.0);
    for (const dvec3& p : points) {
        center += p;
    }
    center /= double(points.size());
    struct Polar {
        double angle, radius;
        dvec3 point;
    };
    std::vector<Polar> polar;
    polar.reserve(points.size());
    for (const dvec3& p : points) {
        const dvec3 d = p - center;
        polar.push_back({std::atan2(glm::dot(d, v), glm::dot(d, u)), glm::length(d), p});
    }
    // Counter-clockwise around n, starting at the point farthest from the centroid: a hull vertex.
    std::sort(polar.begin(), polar.end(), [](const Polar& a, const Polar& b) {
        return a.angle < b.angle || (a.angle == b.angle && a.radius < b.radius);
    });
    const auto first =
        std::max_element(polar.begin(), polar.end(),
                         [](const Polar& a, const Polar& b) { return a.radius < b.radius; });
    std::rotate(polar.begin(), first, polar.end());
    // A left turn by more than epsilon (as a distance from the chord) keeps the middle point.
    auto left_turn = [&](const dvec3& o, const dvec3& a, const dvec3& b) {
        const double chord = glm::length(b - o);
        return glm::dot(glm::cross(a - o, b - o), n) > epsilon * chord;
    };
    std::vector<dvec3> hull;
    hull.reserve(polar.size() + 1);
    for (size_t i = 0; i <= polar.size(); ++i) {
        const dvec3& p = polar[i % polar.size()].point;  // closes on the first point
        while (hull.size() >= 2 && !left_turn(hull[hull.size() - 2], hull.back(), p)) {
            hull.pop_back();
        }
        hull.push_back(p);
    }
    hull.pop_back();  // the first point again
    if (hull.size() < 3) {
        return Polygon();
    }
    return Polygon(std::move(hull));
}

Polyhedron clip(const Polyhedron& polyhedron, const Plane& plane, double epsilon) {
    // Decided as split() decides for polygons, so that clip(P, plane) and clip(P, flipped)
    // partition P: within ε of one side means wholly on it; otherwise every face is cut exactly.
    bool any_front = false, any_back = false;
    for (const Polygon& face : polyhedron.faces) {
        for (const dvec3& v : face.vertices) {
            const double d = plane.distance(v);
            any_front |= d > epsilon;
            any_back |= d < -epsilon;
        }
    }
    if (!any_front) {
        return polyhedron;
    }
    if (!any_back) {
        return Polyhedron();
    }
    Polyhedron result;
    std::vector<dvec3> cap_points;
    for (const Polygon& face : polyhedron.faces) {
        Split parts = split(face, plane, 0.0);
        if (parts.coplanar) {
            continue;  // on the cap
        }
        if (parts.back.empty()) {
            // Wholly in front, but it may touch the plane at vertices on it.
            for (const dvec3& v : face.vertices) {
                if (plane.distance(v) == 0.0)
                    cap_points.push_back(v);
            }
            continue;
        }
        if (parts.front.empty()) {
            for (const dvec3& v : face.vertices) {
                if (plane.distance(v) == 0.0)
                    cap_points.push_back(v);
            }
        }
        cap_points.insert(cap_points.end(), parts.cut.begin(), parts.cut.end());
        result.faces.push_back(std::move(parts.back));
    }
    // The cap spans exactly the points where the faces meet the plane.
    Polygon cap = convex_polygon_on_plane(std::move(cap_points), plane, epsilon);
    if (!cap.empty()) {
        result.faces.push_back(std::move(cap));
    }
    if (result.faces.size() < 4) {
        return Polyhedron();
    }
    return result;
}

double volume(const Polyhedron& polyhedron) {
    // Divergence theorem over fan triangles, relative to one vertex for accuracy.
    if (polyhedron.empty()) {
        return 0.0;
    }
    const dvec3 origin = polyhedron.faces[0].vertices[0];
    double sum = 0.0;
    for (const Polygon& face : polyhedron.faces) {
        const dvec3 a = face.vertices[0] - origin;
        for (size_t i = 1; i + 1 < face.size(); ++i) {
            sum +=
                glm::dot(a, glm::cross(face.vertices[i] - origin, face.vertices[i + 1] - origin));
        }
    }
    return sum / 6.0;
}

Polyhedron polyhedron_from_planes(const std::vector<Plane>& planes, double bounds_radius,
                                  double epsilon) {
    // Start from a cube of half-size bounds_radius and clip by every plane.
    const double r = bounds_radius;
    Polyhedron cube;
    const dvec3 corner[8] = {{-r, -r, -r}, {r, -r, -r}, {r, r, -r}, {-r, r, -r},
                             {-r, -r, r},  {r, -r, r},  {r, r, r},  {-r, r, r}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    for (const auto& f : faces) {
        cube.faces.emplace_back(
            std::vector<dvec3>{corner[f[0]], corner[f[1]], corner[f[2]], corner[f[3]]});
    }
    Polyhedron result = cube;
    for (const Plane& plane : planes) {
        result = clip(result, plane, epsilon);
        if (result.empty()) {
            break;
        }
    }
    return result;
}

}  // namespace sl::bt
