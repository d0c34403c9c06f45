#pragma once
// Outer and inner bounding volumes of the scene's objects (Nilsson §5.1, docs/design.md §4).
// Outer: the convex hull of the mesh (CGAL), optionally reduced to at most K planes while still
// enclosing it. Inner: convex boxes strictly inside the mesh, explicit from the scene file or
// found automatically, and in both cases verified (winding number and triangle/box overlap).
// Volumes are computed once per mesh in its local frame and mapped into the world: an affine map
// keeps a convex set convex and an inner set inside.

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>

#include "beamtree/closed_surface.h"
#include "beamtree/convex_volume.h"
#include "beamtree/coplanar_faces.h"
#include "beamtree/face_clusters.h"
#include "beamtree/geometry.h"
#include "core/check.h"
#include "scenes/scene.h"

namespace sl::bt {

// The volumes of one object in world space, or of one convex piece of it: an object cut into
// pieces gives one entry per piece (its hull and the inner volumes inside it).
struct ObjectVolumes {
    int object = 0;  // index into Scene::objects
    std::string name;
    int piece = 0;  // which piece of the object, of `pieces`
    int pieces = 1;
    ConvexVolume outer;
    std::vector<ConvexVolume> inner;
    // Exact occluders ([beamtree] occluders = triangles, or auto for an object without an inner
    // volume): the object's triangles in world space, each unlit behind it, neighbours on one
    // plane joined into convex polygons (beamtree/coplanar_faces.h). Then `outer` and `inner`
    // are empty.
    std::vector<Polygon> triangles;
    // Found with the faces (VolumeLibrary), so that a tree per light move need not: each face's
    // plane through its first three corners as wound (a zero normal where they span none), and
    // a box holding every corner (lo > hi: not known). Empty planes: the tree finds them.
    std::vector<Plane> face_planes;
    std::pair<dvec3, dvec3> face_bounds{dvec3(1.0), dvec3(-1.0)};
    // Likewise the ball around each face (bounding_ball), which decides most of a face's planes
    // in the tree without a vertex. Empty: the tree finds them.
    std::vector<Ball> face_balls;
    size_t mesh_triangles = 0;  // the triangles of the mesh they came from
    // Per face of `triangles`: 1 where it lies on a closed component of its mesh
    // (closed_surface.h), then wound outward in world space: while the light is outside the
    // object's bounds, such a face facing away from it may be left out of the tree. Empty where
    // no face does.
    std::vector<uint8_t> closed_faces;
    // Every face does: the whole mesh is a closed surface.
    bool closed = false;
    // The faces cut into clusters of spatial neighbours (face_clusters.h), for the tree to leave
    // out the rest of a cluster hidden behind what is in. Empty where not found (a few faces).
    FaceClusters clusters;
    // Why they are triangles: "occluders = triangles", "no inner volume (...)" or "loose: inner
    // volumes fill N % of its hull" (auto).
    std::string why_triangles;
};

// How many objects entered the tree as exact triangles, and those triangles.
struct ExactOccluders {
    size_t triangles = 0;  // of every object in `list`
    size_t polygons = 0;   // those triangles joined into coplanar faces: what the tree takes
    struct Object {
        std::string name;
        size_t triangles = 0;
        std::string why;  // ObjectVolumes::why_triangles
    };
    std::vector<Object> list;  // each object that went in as triangles, in scene order
};
ExactOccluders exact_occluders(const std::vector<ObjectVolumes>& volumes);

// One convex piece of a mesh: its hull and the inner boxes found inside it.
struct LocalPiece {
    ConvexVolume outer;
    std::vector<ConvexVolume> inner;
};

// Volumes of a mesh in its local frame.
struct LocalVolumes {
    ConvexVolume outer;                         // the hull of the whole mesh
    std::vector<ConvexVolume> automatic_inner;  // empty when the mesh is open or too thin
    bool closed = false;                        // closed once welded and its T-junctions split
    bool self_inner = false;  // a flat convex mesh that covers its hull is its own inner volume
    std::vector<LocalPiece> pieces;  // empty: `outer` is tight, the mesh is one piece
    int cells = 0;                   // cells before merging (beamtree/pieces.h)
    int empty_voxels_whole = 0;      // empty voxels inside `outer`
    int empty_voxels_pieces = 0;     // ... inside the pieces' hulls, summed
    std::string no_inner;            // why there is no automatic inner volume ("" if there is)
    size_t piece_count() const { return pieces.empty() ? 1 : pieces.size(); }
};

// The box lies strictly inside a closed mesh: its centre is inside and no triangle touches it.
bool box_inside_mesh(const Mesh& mesh, const Box& box);
// An axis-aligned box strictly inside a closed mesh, grown as large as a few binary searches find.
std::optional<Box> inscribed_box(const Mesh& mesh);

// Where a mesh's LocalVolumes came from (VolumeLibrary::stats).
struct VolumeLibraryStats {
    size_t memory = 0;    // this library had them, or another one in this process
    size_t disk = 0;      // read from the cache on disk
    size_t computed = 0;  // hulls, reduced hulls and inner boxes computed (and written to disk)
    bool operator==(const VolumeLibraryStats&) const = default;
};

// The static half of the beam tree's per-frame work (docs/design.md §10): LocalVolumes are computed
// once per mesh, keyed by the mesh's content and the options, and kept in this process and on
// disk (core/cache.h, folder `volumes`), so that every later frame, scene or run that shows the
// mesh only transforms them. The verification of explicit inner boxes is cached the same way.
// Thread-safe: the pipelined frame loop builds on a worker thread.
// An object of a scene that gets no automatic inner volume, and why (LocalVolumes::no_inner).
struct MissingInner {
    std::string object;
    std::string reason;
};

// One line that sums them up by reason, most common first: "90 of 116 objects have no automatic
// inner volume: 89 because the mesh is not closed ...; 1 because no box fits inside it ...";
// empty when there are none. `objects` counts the scene's objects.
std::string missing_inner_summary(const std::vector<MissingInner>& missing, size_t objects);

class VolumeLibrary {
public:
    // Pieces are cut from full hulls (the scene reader refuses them with reduced hulls).
    explicit VolumeLibrary(BoundsSettings options = {}) : options_(options) {
        SL_CHECK(!(options.pieces && options.max_outer_planes > 0));
    }
    VolumeLibrary(const VolumeLibrary&) = delete;
    VolumeLibrary& operator=(const VolumeLibrary&) = delete;

    // One library per option set for the whole process (what the methods build with).
    static VolumeLibrary& shared(BoundsSettings options);
    // Off: this library computes every mesh's volumes itself, sharing nothing with the process
    // or the disk (oracles in tests, the uncached cost in benchmarks).
    void set_caching(bool enabled) { caching_ = enabled; }
    // Empties what this process keeps across libraries, so that a new library reads the disk
    // (what a fresh process does; benchmarks and tests of the disk cache).
    static void forget_process_volumes();

    const LocalVolumes& local(const std::shared_ptr<const Mesh>& mesh);
    // World-space volumes of every object. Throws sl::Error naming the object when an explicit
    // inner box is not strictly inside its mesh. Each object that gets no automatic inner
    // volume (an open mesh, one too thin for a box) is listed in `missing` with the reason.
    std::vector<ObjectVolumes> build(const Scene& scene, std::vector<MissingInner>* missing);
    // build(scene, nullptr), shared: the six faces of a point light, and every light of one
    // scene state, ask for the same world-space volumes in turn (each face is its own tree), and
    // get the last answer again while the objects' meshes, transforms, names, inner boxes and
    // shadow casting and the scene's occluder settings are unchanged (with caching off, each
    // call builds anew).
    std::shared_ptr<const std::vector<ObjectVolumes>> build_shared(const Scene& scene);
    VolumeLibraryStats stats() const;

private:
    struct Entry {
        std::weak_ptr<const Mesh> mesh;  // expired: the address may belong to another mesh
        std::shared_ptr<const LocalVolumes> volumes;
        uint64_t key = 0;
        double inner_fill = 1.0;  // the share of the outer volumes the inner ones fill, once
    };
    LocalVolumes compute(const Mesh& mesh) const;
    const Entry& entry(const std::shared_ptr<const Mesh>& mesh);
    bool box_verified(const Mesh& mesh, uint64_t key, const Box& box);
    // Computes (in parallel) the volumes of the scene's meshes this library has not seen.
    void compute_missing(const Scene& scene);
    // The world-space volumes of scene object `index`: one per convex piece, or its hull.
    void append_volumes(const Object& object, int index, std::vector<ObjectVolumes>& result);
    // Scene object `index` as its triangles (exact occluders).
    ObjectVolumes triangles_of(const Object& object, int index);
    // What the triangles of one mesh need, once per mesh.
    struct MeshSurface {
        ClosedSurface closed;
        CoplanarFaces faces;
    };
    std::shared_ptr<const MeshSurface> surface_of(const std::shared_ptr<const Mesh>& mesh);
    // Which objects enter the tree as triangles under the scene's [beamtree] occluders, and why
    // (ObjectVolumes::why_triangles; empty: its volumes).
    std::vector<std::string> exact_objects(const Scene& scene);

    // What build_shared's last answer was built from (the scene's parts build() reads).
    struct SceneState {
        struct Part {
            std::string name;
            std::shared_ptr<const Mesh> mesh;  // held: the address names this mesh
            glm::mat4 transform;
            std::vector<Box> inner_boxes;
            bool casts_shadow;
            bool operator==(const Part&) const = default;
        };
        std::vector<Part> parts;
        Occluders occluders;
        int max_triangles;
        double min_inner_fill;
        bool operator==(const SceneState&) const = default;
    };
    static SceneState state_of(const Scene& scene);

    BoundsSettings options_;
    bool caching_ = true;
    SceneState last_state_;
    std::shared_ptr<const std::vector<ObjectVolumes>> last_volumes_;
    mutable std::mutex mutex_;
    std::map<const Mesh*, Entry> cache_;
    // Each mesh's closed_surface() and coplanar_faces(), once per mesh (for the objects that go
    // in as triangles).
    std::map<const Mesh*, std::pair<std::weak_ptr<const Mesh>, std::shared_ptr<const MeshSurface>>>
        surfaces_;
    std::set<std::pair<uint64_t, uint64_t>> verified_boxes_;
    VolumeLibraryStats stats_;
};

// The content key of a mesh's volumes under `options` (FNV-1a of its vertices, triangles and the
// options, with the cache format's version).
uint64_t volumes_key(const Mesh& mesh, const BoundsSettings& options);

}  // namespace sl::bt
