#pragma once
// Outer and inner bounding volumes of the scene's objects (Nilsson §5.1, DESIGN.md §4).
// Outer: the convex hull of the mesh (CGAL), optionally reduced to at most K planes while still
// enclosing it. Inner: convex boxes strictly inside the mesh, explicit from the scene file or
// found automatically, and in both cases verified (winding number and triangle/box overlap).
// Volumes are computed once per mesh in its local frame and mapped into the world: an affine map
// keeps a convex set convex and an inner set inside.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "beamtree/geometry.h"
#include "scenes/scene.h"

namespace sl::bt {

// A convex volume as outward faces and their planes. A flat volume (a convex polygon, e.g. the
// floor) has two faces, one per orientation, and zero volume.
struct ConvexVolume {
    std::vector<Polygon> faces;
    std::vector<Plane> planes;  // planes[i] is the plane of faces[i], normal outward
    bool flat = false;

    bool empty() const { return faces.empty(); }
    // True when p is inside by more than `margin` from every face plane. A flat volume has no
    // inside: with a negative margin, true when p is within -margin of the polygon.
    bool contains(const dvec3& p, double margin) const;
    ConvexVolume transformed(const glm::dmat4& transform) const;
    double volume() const;
};

struct BoundingVolumeOptions {
    int max_outer_planes = 0;     // 0: the full convex hull; else at most this many planes (>= 8)
    bool automatic_inner = true;  // find an inner box for closed meshes without explicit ones
};

// The volumes of one object in world space.
struct ObjectVolumes {
    int object = 0;  // index into Scene::objects
    std::string name;
    ConvexVolume outer;
    std::vector<ConvexVolume> inner;
};

// Volumes of a mesh in its local frame.
struct LocalVolumes {
    ConvexVolume outer;
    std::vector<ConvexVolume> automatic_inner;  // empty when the mesh is open or too thin
    bool closed = false;
    bool self_inner = false;  // a flat convex mesh that covers its hull is its own inner volume
};

// The hull of a mesh's vertices; max_planes > 0 keeps the 6 axis-aligned support planes plus the
// largest hull faces, up to max_planes planes in all.
ConvexVolume convex_hull(const Mesh& mesh, int max_planes);
// Inside by the winding number (robust for closed meshes).
bool point_inside_mesh(const Mesh& mesh, const dvec3& p);
// The box lies strictly inside a closed mesh: its centre is inside and no triangle touches it.
bool box_inside_mesh(const Mesh& mesh, const Box& box);
// An axis-aligned box strictly inside a closed mesh, grown as large as a few binary searches find.
std::optional<Box> inscribed_box(const Mesh& mesh);
ConvexVolume box_volume(const Box& box);

// Computes and caches LocalVolumes per mesh (keyed by the mesh object), so that scenes sharing a
// mesh, or many scenes built from one, pay for hulls and inner boxes once.
class VolumeLibrary {
public:
    explicit VolumeLibrary(BoundingVolumeOptions options = {}) : options_(options) {}
    const LocalVolumes& local(const std::shared_ptr<const Mesh>& mesh);
    // World-space volumes of every object. Throws sl::Error naming the object when an explicit
    // inner box is not strictly inside its mesh. Open meshes get no automatic inner volume and
    // a line in `warnings`.
    std::vector<ObjectVolumes> build(const Scene& scene, std::vector<std::string>* warnings);

private:
    LocalVolumes compute(const Mesh& mesh) const;

    BoundingVolumeOptions options_;
    std::map<const Mesh*, std::pair<std::shared_ptr<const Mesh>, LocalVolumes>> cache_;
};

}  // namespace sl::bt
