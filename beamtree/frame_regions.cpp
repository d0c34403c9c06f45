#include "beamtree/frame_regions.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "beamtree/boundary.h"
#include "beamtree/bounding_volumes.h"

namespace sl::bt {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// Where polygons meet a side of a point light's face (a plane through the apex, L), for
// shared_sides: their edges on the plane, each with the side its polygon lies on, and the
// segments along which polygons that cross the plane meet it (both sides at once). Only the half
// of the plane ahead of the face (along `axis`) is its side: the other half is two other faces'
// (an edge there is theirs). Within `tolerance` of the plane is on it, 1e-4
// of the distance from the apex, so that a shadow's edge the trees' planes (ε = 1e-6 of the
// scene) could put on the plane is caught wherever it lies.
class PlaneContacts {
public:
    PlaneContacts(const Plane& plane, const dvec3& apex, const dvec3& axis)
        : plane_(plane), apex_(apex), axis_(axis) {}

    size_t size() const { return edges_.size(); }
    void add(const Polygon& polygon) {
        const size_t n = polygon.size();
        bool front = false, back = false;
        for (const dvec3& v : polygon.vertices) {
            const double d = plane_.distance(v);
            front = front || d > tolerance(v);
            back = back || d < -tolerance(v);
        }
        if (!front && !back) {
            return;  // in the plane: edge-on to the light, it shadows nothing
        }
        if (front && back) {  // across it: its segment on the plane, for both sides
            const std::vector<dvec3> cut = split(polygon, plane_, 0.0).cut;
            if (cut.size() >= 2) {
                crossings_.push_back({cut.front(), cut.back()});
            }
            return;
        }
        for (size_t i = 0; i < n; ++i) {
            const dvec3& a = polygon.vertices[i];
            const dvec3& b = polygon.vertices[i + 1 == n ? 0 : i + 1];
            if (on(a) && on(b) && (ahead(a) || ahead(b))) {
                edges_.push_back({{a, b}, front});
            }
        }
    }
    // Every edge on the plane has a polygon on the plane's other side along it too (an edge there,
    // or a polygon across the plane): rays on either side that pass it meet a polygon there, so it
    // ends a shadow on neither side alone. A shadow's edge on the plane is an edge with polygons
    // on one side of it only.
    bool every_edge_covered() const {
        for (const Edge& e : edges_) {
            auto covers = [&](const Segment& f) { return within(e.segment, f); };
            const bool edge = std::any_of(edges_.begin(), edges_.end(), [&](const Edge& f) {
                return f.front != e.front && covers(f.segment);
            });
            if (!edge && std::none_of(crossings_.begin(), crossings_.end(), covers)) {
                return false;
            }
        }
        return true;
    }

private:
    struct Segment {
        dvec3 a, b;
    };
    struct Edge {
        Segment segment;
        bool front;  // its polygon lies in front of the plane
    };
    double tolerance(const dvec3& v) const { return 1e-4 * glm::length(v - apex_); }
    bool on(const dvec3& v) const { return std::abs(plane_.distance(v)) <= tolerance(v); }
    bool ahead(const dvec3& v) const { return glm::dot(v - apex_, axis_) >= -tolerance(v); }
    // Both ends of `e` lie on `f`, to the tolerance.
    bool within(const Segment& e, const Segment& f) const {
        auto near_segment = [&](const dvec3& p) {
            const dvec3 d = f.b - f.a;
            const double length2 = glm::dot(d, d);
            const double t =
                length2 > 0.0 ? std::clamp(glm::dot(p - f.a, d) / length2, 0.0, 1.0) : 0.0;
            return glm::length(p - (f.a + t * d)) <= tolerance(p);
        };
        return near_segment(e.a) && near_segment(e.b);
    }

    const Plane& plane_;
    dvec3 apex_, axis_;
    std::vector<Edge> edges_;
    std::vector<Segment> crossings_;
};

}  // namespace

std::array<bool, 4> shared_sides(const SpotLight& light,
                                 const std::vector<ObjectVolumes>& volumes) {
    std::array<bool, 4> shared{};
    if (!light.cube_face) {
        return shared;
    }
    const std::vector<Plane> planes = influence_planes(light);
    // Beyond this many edges on one plane the pairs are not searched: the side is not shared.
    constexpr size_t kMostEdges = 4096;
    for (size_t k = 0; k < shared.size(); ++k) {
        PlaneContacts contacts(planes[k], dvec3(light.position),
                               glm::normalize(dvec3(light.direction())));
        auto add = [&](const std::vector<Polygon>& polygons) {
            for (const Polygon& polygon : polygons) {
                contacts.add(polygon);
            }
        };
        for (const ObjectVolumes& object : volumes) {
            add(object.outer.faces);
            add(object.triangles);
            for (const ConvexVolume& inner : object.inner) {
                add(inner.faces);
            }
            if (contacts.size() > kMostEdges) {
                break;
            }
        }
        shared[k] = contacts.size() <= kMostEdges && contacts.every_edge_covered();
    }
    return shared;
}

std::vector<std::pair<std::string, double>> RegionStageTimes::named() const {
    return {{"volumes", volumes},          {"tree", tree},
            {"regions", regions},          {"lit mesh", lit},
            {"uncertain mesh", uncertain}, {"gpu tree", gpu_tree}};
}

FrameRegions build_frame_regions(const Scene& scene, const RegionRequest& request) {
    FrameRegions out;
    Clock::time_point t = Clock::now();
    auto lap = [&](double& stage) {
        const Clock::time_point now = Clock::now();
        stage = ms_between(t, now);
        t = now;
    };
    VolumeLibrary& library = VolumeLibrary::shared(scene.bounds);
    const std::shared_ptr<const std::vector<ObjectVolumes>> shared = library.build_shared(scene);
    const std::vector<ObjectVolumes>& volumes = *shared;
    out.exact = exact_occluders(volumes);
    lap(out.ms.volumes);
    const std::optional<ViewWindow> window =
        request.view_dependent(scene) ? view_window(scene.light, scene.camera, request.view_aspect)
                                      : std::nullopt;
    // A view that misses the sun's box sees none of its light: the whole box stands in for it.
    auto tree = std::make_shared<const BeamTree>(scene.light, volumes, TreeBuild{}, window);
    lap(out.ms.tree);
    if (request.lit || request.uncertain || request.pieces) {
        auto pieces = std::make_shared<const Regions>(extract_regions(*tree));
        const Regions& regions = *pieces;
        lap(out.ms.regions);
        if (request.pieces) {
            out.regions = pieces;
        }
        if (request.lit) {
            out.shared_sides = shared_sides(scene.light, volumes);
            out.lit = request.cells
                          ? regions.mesh(Region::lit)
                          : boundary_mesh(*tree, regions, Region::lit, nullptr, request.shape);
            lap(out.ms.lit);
        }
        if (request.uncertain) {
            out.uncertain =
                boundary_mesh(*tree, regions, Region::uncertain, nullptr, request.shape);
            lap(out.ms.uncertain);
        }
    }
    if (request.gpu_tree) {
        out.gpu = tree->gpu_tree(request.layout);
        lap(out.ms.gpu_tree);
    }
    out.tree = std::move(tree);
    return out;
}

}  // namespace sl::bt
