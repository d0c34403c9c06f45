#pragma once
// The Beam Tree (Nilsson ch. 4, §5.2, appendix B): a BSP tree whose splitting planes all pass
// through the light L, built over the outer bounding volumes' light-facing polygons and augmented
// with the inner volumes' stopper polygons. Every leaf is a beam (a convex cone from L):
//   out      outside the influence pyramid;
//   open     sees the backplate: lit from the near range to the far range;
//   solid    first hits an outer volume on its occluder plane: lit in front of it, uncertain
//            behind it;
//   blocker  a solid beam that also hits an inner volume: unlit behind the stopper plane.
//
// Polygons may be inserted in any order, so outer volumes may overlap (Nilsson could not do
// this): a fragment that reaches a solid leaf is split by the leaf's occluder plane, and the
// part nearer to L than the occluder subdivides the leaf (his ch. 8). The visible set is thus
// the lower envelope of all light-facing polygons, whatever the order. Stoppers fix up blocker
// leaves the same way, keeping the nearest stopper.
//
// Tolerance: planes have a thickness ε (Nilsson §4.3), ε = kRelativeEpsilon × far range (10 µm
// for a 10 m light): far above double round-off over the tree's depth, far below any feature.

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "beamtree/bounding_volumes.h"
#include "beamtree/geometry.h"
#include "core/check.h"
#include "scenes/scene.h"
#include "scenes/view_window.h"

namespace sl::bt {

enum class Region : uint8_t { lit = 0, uncertain = 1, unlit = 2 };

// The influence pyramid circumscribing the light's cone (the shadow map's square frustum) as
// outward planes: four sides (right, left, up, down), the near range, the far range. With a
// `window` (parallel beams alone: scenes/view_window.h), the part of the box in it: the sides at
// the window's bounds across the beams, the far range at its far side, and after the far range
// a side per cut of the window's corners.
std::vector<Plane> influence_planes(const SpotLight& light,
                                    const std::optional<ViewWindow>& window = std::nullopt);
// The plane through L (for parallel beams: containing them) of the beams at coordinate m along
// the light's right (axis 0) or up vector (axis 1), in units of the pyramid's half-width at the
// same depth, its front side the beams beyond m: at m = 1 the pyramid's right or upper side, at
// m = -1 the left or lower one flipped, and between them the lines of a grid of sub-beams.
Plane beam_plane(const SpotLight& light, int axis, double m);
const char* to_string(Region region);

// A piece of a segment in one region type: t in [begin, end] along origin + t·direction.
struct RegionInterval {
    Region region = Region::unlit;
    double begin = 0.0;
    double end = 0.0;
};

// The tree as the GPU reads it (beamtree/shaders/classify.glsl, std430): every plane relative to
// the light (q = p - L), where float keeps the tree's ε (a 10 m range in 32-bit float resolves a
// micrometre at the light, the plane's value grows only with |q|).
struct GpuTreeNode {
    glm::vec4 plane;  // xyz normal, w offset: distance = dot(xyz, q) + w
    glm::ivec4 link;  // x front child, y back child, z kind (classify.glsl's KIND_*), w stopper
};
// The order of the GPU tree's nodes (docs/design.md §14). build: as the tree grew (a split leaf's
// children appended at the end, so a deep descent jumps across the buffer); depth_first:
// preorder, back child first (the side behind a split's occluder, where a descent spends its
// steps), so that a descent's next node is often the next one in memory and every subtree is one
// contiguous run. Both hold the same tree: nodes 0-3 stay the influence pyramid's sides.
enum class GpuTreeLayout { depth_first, build };
struct GpuTree {
    std::vector<GpuTreeNode> nodes;  // 0-3 the influence pyramid's sides, each back the next
    std::vector<glm::vec4> planes;   // 0 near range, 1 far range, then the stoppers (link.w)
};

struct BeamTreeStats {
    size_t nodes = 0;
    size_t open_leaves = 0;
    size_t solid_leaves = 0;
    size_t blocker_leaves = 0;
    size_t outer_polygons = 0;    // light-facing outer-volume polygons inserted
    size_t stopper_polygons = 0;  // light-facing inner-volume polygons inserted
    // Light-facing exact occluders (a mesh's coplanar triangles joined: coplanar_faces.h), each
    // an occluder and a stopper.
    size_t exact_polygons = 0;
    // Light-facing exact faces left out because their object's or their cluster's box, or the
    // face itself (TreeBuild::ask_faces), was wholly hidden behind what was in already, or the
    // box lay outside the influence (they would have changed nothing).
    size_t hidden_polygons = 0;
    size_t max_depth = 0;
};

// One leaf inside the influence pyramid: the planes that cut it into regions.
struct Beam {
    bool has_occluder = false;
    Plane occluder;  // front side (towards L) lit
    bool has_stopper = false;
    Plane stopper;  // back side unlit
};

// How a tree is built; the regions it decides do not depend on it. The tree's top is the
// nearest polygons' edges, which leaves it deep and lopsided where many small polygons crowd
// the beam; an offer of at least `grid_from` polygons therefore first cuts the beam into a grid
// of sub-beams by planes through L (about `polygons_per_cell` polygons a cell, at most
// `max_grid` cells a side), a balanced top above the leaves the polygons then fill, as if those
// planes had been the first edges inserted (docs/design.md §4). With `ask_faces`, an exact face
// is first asked whether it is hidden behind what is in (BeamTree::hidden_beyond) and left out
// where it is; the tree is the same node for node without.
struct TreeBuild {
    size_t grid_from = 16384;
    size_t polygons_per_cell = 64;
    int max_grid = 48;
    bool ask_faces = true;
    // The grid's cells a side for an offer of `polygons` (1: no grid).
    int grid(size_t polygons) const;
};

class BeamTree {
public:
    static constexpr double kRelativeEpsilon = 1e-6;
    // An edge whose ends lie within kCoincident·ε of a plane on a fragment's path lies on it (a
    // neighbour's shared edge made the plane): it gets no plane of its own. Far above the
    // round-off of a shared vertex (1e-16 of its coordinates) and far below ε, so that the beam
    // it leaves out is a sliver of 1e-3 ε where the edge and the plane part.
    static constexpr double kCoincident = 1e-3;
    // What an inserted polygon is: an outer volume's face (lit in front, uncertain behind), an
    // inner volume's face (unlit behind), or an exact triangle, both at once (unlit behind).
    enum class Role : uint8_t { occluder, stopper, opaque };

    // Throws sl::Error when the light is inside (or within ε of) an outer bounding volume.
    // With a `window` (a sun's, for one camera's view: scenes/view_window.h), the tree covers
    // only the part of the box in it (influence_planes): exact there, where every point the
    // camera sees lies and every occluder of such a point, and unlit beyond, as outside the box.
    // It leaves out the objects wholly beyond, and the tree is smaller by what they would add.
    BeamTree(const SpotLight& light, const std::vector<ObjectVolumes>& volumes,
             const TreeBuild& build = {}, const std::optional<ViewWindow>& window = std::nullopt);

    // Lit, uncertain or unlit; points outside the influence volume are unlit. `margin`, when
    // given, receives the smallest distance from p to a plane the answer depended on.
    Region classify(const dvec3& p, double* margin = nullptr) const;

    // The regions along the segment origin + t·direction, t in [t0, t1], in order of t:
    // consecutive intervals of `out` differ in region and cover [t0, t1] (t0 < t1). Each leaf
    // the segment crosses is visited once, so a ray costs its path through the tree instead of
    // one descent per sample; every interval's interior is what classify() says of its points.
    void trace(const dvec3& origin, const dvec3& direction, double t0, double t1,
               std::vector<RegionInterval>& out) const;

    struct Partition {
        std::vector<Polygon> lit, uncertain, unlit;
    };
    // Appendix B `partition`, extended with blocker leaves and the near and far ranges.
    Partition partition(const Polygon& polygon) const;

    // Where a region piece's face lies (beamtree/boundary.h): on an influence plane, the
    // piece's occluder or stopper, or the plane of a split node on its path (the highest one).
    struct FacePlane {
        int32_t split = -1;           // the split node whose plane holds the face, or -1
        bool piece_in_front = false;  // the piece lies on that plane's front side
        Plane plane;                  // that node's plane
    };
    const Plane& node_plane(int32_t index) const { return at(index).plane; }
    // The highest split node on the path to the leaf holding `interior` (a point strictly inside
    // a piece) whose plane holds every vertex of `face` within `tolerance`.
    FacePlane face_plane(const dvec3& interior, const Polygon& face, double tolerance) const;

    // Splits `cell` (a polyhedron inside the influence pyramid) down the tree into each leaf's
    // part of it with the leaf's beam, in depth-first order (front before back): every node
    // clips once. Subtrees are split on several threads; the order does not depend on them.
    struct LeafCell {
        Polyhedron cell;
        Beam beam;
    };
    std::vector<LeafCell> split_cells(Polyhedron cell, double epsilon) const;
    // The influence pyramid: four sides, near range, far range, then the window's cuts (outward
    // planes; influence_planes above).
    const std::vector<Plane>& influence_planes() const { return influence_; }
    double epsilon() const { return epsilon_; }
    // The light's position; for parallel beams, the point of the axis on the entry plane.
    const dvec3& apex() const { return apex_; }
    BeamTreeStats stats() const;
    // The nodes and planes for the GPU's classify (kinds: 0 split, 1 out, 2 open, 3 solid,
    // 4 blocker), in the order `layout` says (GpuTreeLayout).
    GpuTree gpu_tree(GpuTreeLayout layout = GpuTreeLayout::depth_first) const;

private:
    enum class Kind : uint8_t { split, out, open, solid, blocker };
    static constexpr float kUnbounded = std::numeric_limits<float>::infinity();
    // 48 bytes: the descent is bound by memory traffic, so leaves reuse the split fields.
    struct Node {
        Plane plane;         // split: the splitting plane through L; solid, blocker: occluder
        int32_t front = -1;  // split: children
        int32_t back = -1;   // split: children; blocker: index into stoppers_
        Kind kind = Kind::open;
        // The reach of the node's cone: beyond this distance from L every point of it is
        // unlit behind a stopper, so a polygon farther away changes nothing below the node and
        // is dropped without descending. A blocker leaf's is the farthest corner of the
        // fragment that made its stopper (the stopper crosses each ray of the leaf nearer than
        // that); a split's, the larger of its children's; open and solid leaves are unbounded.
        // Rounded up to float (it fits in the padding).
        float reach = kUnbounded;
    };
    struct Leaf {
        Kind kind;
        Plane occluder;
        int32_t stopper = -1;  // index into stoppers_
        float reach = kUnbounded;
        // The stopper is the fragment being attached: its reach is at most that fragment's
        // farthest corner (a nearer stopper leaves the old reach valid, so the smaller holds).
        bool stopped_here = false;
    };
    // The node at `index`, checked in debug builds (the descent is the hot path).
    const Node& at(int32_t index) const {
        SL_DCHECK_INDEX(index, nodes_.size());
        return nodes_[size_t(index)];
    }
    Node& at(int32_t index) {
        SL_DCHECK_INDEX(index, nodes_.size());
        return nodes_[size_t(index)];
    }
    const Plane& stopper_of(const Node& leaf) const {
        SL_DCHECK(leaf.kind == Kind::blocker);
        SL_DCHECK_INDEX(leaf.back, stoppers_.size());
        return stoppers_[size_t(leaf.back)];
    }
    void split_cells(int32_t node, Polyhedron cell, double epsilon, int depth,
                     std::vector<LeafCell>& out) const;
    // A stretch [begin, end] of a traced ray that reached `node`.
    struct TracePiece {
        int32_t node;
        double begin, end;
    };
    // Appends the intervals of a piece that reached leaf `node` to `out`.
    void trace_leaf(const Node& node, const dvec3& origin, const dvec3& direction,
                    const TracePiece& piece, std::vector<RegionInterval>& out) const;
    // classify()'s answer at a point inside the near and far ranges that reached `leaf`.
    Region leaf_region(const Node& leaf, const dvec3& p) const;
    void set_leaf(int32_t index, const Leaf& leaf);

    // What the tree is built from, nearest first (tree_build.cpp).
    struct Offer;
    // Cuts the root's open leaf into grid × grid sub-beams (TreeBuild), each an open leaf.
    void add_grid(const SpotLight& light, int grid, const ViewWindow& window);
    // Offers the object's clusters of exact faces (tree_build.cpp's OfferedCluster), each that
    // lies inside the influence and has a face the tree takes; `index`: the object's place in
    // the volumes, `object_box` its box's in the offer.
    void offer_clusters(const ObjectVolumes& object, uint32_t index, int32_t object_box,
                        bool outward_only, Offer& offer) const;
    // Inserts the offered polygons in its order, the clusters' faces among them, leaving out the
    // rest of an object once its box is hidden behind what is in, and a cluster whose box is;
    // counts what went in and what was left out. `volumes`: what the offer was made of;
    // `ask_faces`: TreeBuild's.
    void insert_offer(const Offer& offer, const std::vector<ObjectVolumes>& volumes,
                      bool ask_faces);

    struct Inserted {
        Role role;
        Plane plane;
        int32_t stopper = -1;  // stopper, opaque: its index into stoppers_
        double nearest = 0.0;  // the polygon's distance from L: no fragment of it is nearer
    };
    // What insert() did with a polygon.
    enum class Outcome {
        left_out,  // before its descent: edge-on, a sliver, beyond the far range
        hidden,    // asked about and found hidden (hidden_beyond): it would change nothing
        inserted,  // sent down the tree
    };
    // Its descent starts at node `start`, which must lie on the path every part of the polygon
    // would take from the root (deepest_holding). `nearest`, where known (not negative), is
    // nearest_to_light(polygon): used unless the far range clips the polygon. With `ask_hidden`,
    // what is left of it after the far range is first asked about (hidden_beyond), and left out
    // where it is hidden: the same tree, without the descent. `ball`, where known, bounds the
    // polygon (bounding_ball).
    Outcome insert(const Polygon& polygon, const Plane& plane, Role role, int32_t start = 0,
                   double nearest = -1.0, bool ask_hidden = false, const Ball* ball = nullptr);
    // From node `start` down, the deepest node whose every ancestor's plane has the whole box
    // farther than 2ε on one side: every polygon in the box descends through it, with no split and
    // no edge on those planes. Splits never change once made, so it stays such a node as the
    // tree grows.
    int32_t deepest_holding(const std::pair<dvec3, dvec3>& box, int32_t start) const;
    // True when every vertex lies outside one side of the influence pyramid or beyond its far
    // range: what the polygons bound casts no shadow inside it.
    bool outside_influence(const std::vector<Polygon>& polygons) const;
    // The same of a box (least and greatest corners) and whatever lies in it.
    bool box_outside_influence(const std::pair<dvec3, dvec3>& box) const;
    // A fragment of an inserted polygon waiting to go down the subtree at `node`; `ball` bounds
    // the polygon it was cut from, and so the fragment.
    struct Pending {
        int32_t node = 0;
        Polygon fragment;
        Ball ball;
    };
    // True when every ray through `polygons` (the light-facing faces of a box around what is
    // still to come) is unlit, in the tree as it stands, beyond `nearest` or from the polygons
    // on: then nothing that lies in the box beyond that depth can change the tree.
    bool hidden_beyond(const std::vector<Polygon>& polygons, double nearest) const;
    // The same of one polygon (`ball` bounds it), from node `start` down (as insert's).
    bool hidden_beyond(const Polygon& polygon, const Ball& ball, double nearest,
                       int32_t start) const;
    // True when every vertex lies behind the plane by more than ε (`ball` bounds the polygon:
    // it usually tells without a vertex).
    bool wholly_behind(const Polygon& polygon, const Ball& ball, const Plane& plane) const;
    // Objects of fewer exact faces are not asked about: inserting them costs about as much.
    static constexpr size_t kHidingFaces = 16;
    // Takes `fragment` down from node `index` to its leaf, pushing the far parts of straddled
    // splits onto `stack`; -1 where nothing of it is left to attach.
    int32_t descend(int32_t index, double nearest, Polygon& fragment, const Ball& ball,
                    std::vector<Pending>& stack) const;
    // What a fragment does to the leaf it reached; a part that must go down the subtree the
    // leaf has become is pushed onto `stack`.
    void insert_at_leaf(int32_t index, const Polygon& fragment, const Ball& ball,
                        const Inserted& inserted, std::vector<Pending>& stack);
    void attach(int32_t node, const Polygon& fragment, const Leaf& inside, const Leaf& outside);
    // The planes through L and the fragment's edges (corners merged, edges on a path plane
    // skipped), fragment behind; false where the fragment is edge-on to the light.
    bool edge_planes(const std::vector<dvec3>& corners, const std::vector<char>& on_split,
                     std::vector<Plane>& edges) const;
    // Attaches the part of the fragment nearer to L than `current` (Nilsson ch. 8's fix-up).
    void attach_nearer(int32_t node, const Polygon& fragment, const Plane& current,
                       const Leaf& inside, const Leaf& outside);
    int32_t add_leaf(const Leaf& leaf, int32_t parent);
    // After the reach of node `index` fell, its ancestors' (each the larger of its children's).
    void lower_reach_above(int32_t index);

    // The light's signed distance from a plane (> 0: the plane faces it), in length units; for
    // parallel beams the sine of their angle with the plane times the influence box's depth
    // (so that ε compares with it as with a distance). Asked of every face offered: inline.
    double light_side(const Plane& plane) const {
        return parallel_ ? -glm::dot(plane.normal, axis_) * scale_ : plane.distance(apex_);
    }
    // How far along the light's beams p lies: its distance from L, or for parallel beams its
    // depth past the entry plane.
    double depth(const dvec3& p) const;
    // The least depth() over a convex polygon.
    double nearest_to_light(const Polygon& polygon) const;
    // The least depth() over the box around the polygons.
    double depth_of_box(const std::vector<Polygon>& polygons) const;
    // The least depth() over a box (least and greatest corners).
    double depth_of_box(const std::pair<dvec3, dvec3>& box) const;
    // The plane through L and the edge a-b (for parallel beams: containing the edge and the
    // beams' direction); false where the edge points at the light.
    bool edge_plane(const dvec3& a, const dvec3& b, Plane& plane) const;

    // The light's position (for parallel beams: the axis's point on the entry plane), the
    // origin of the GPU tree's plane offsets.
    dvec3 apex_;
    bool parallel_ = false;  // SpotLight::parallel: beams along axis_
    dvec3 axis_;
    double scale_ = 1.0;  // the far range: light_side's unit for parallel beams
    double epsilon_;
    std::vector<Plane> influence_;
    // The root chain's nodes, 0 to chain() - 1: the four sides and the window's cuts.
    int32_t chain() const { return int32_t(influence_.size()) - 2; }
    std::vector<Node> nodes_;
    std::vector<int32_t> parents_;  // per node, -1 at the root: for lower_reach_above()
    std::vector<Plane> stoppers_;
    size_t outer_polygons_ = 0;
    size_t stopper_polygons_ = 0;
    size_t exact_polygons_ = 0;
    size_t hidden_polygons_ = 0;
};

// The beam tree of a scene's light over its objects' bounding volumes, built with the scene's
// own [beamtree] settings (what every method that uses regions builds in prepare()).
BeamTree build_scene_beam_tree(const Scene& scene);

}  // namespace sl::bt
