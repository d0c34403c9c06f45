// Regions as surfaces (beamtree/boundary.h) on the CPU: each region type's boundary is closed and
// outward, encloses the volume of its cells, separates the region from another type, and
// integrates along lines like the cells and the tree's own walk.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/bounding_volumes.h"
#include "beamtree/maximal_polygons.h"
#include "beamtree/regions.h"
#include "tests/beamtree_oracle.h"
#include "tests/random_scenes.h"
#include "tests/support.h"

namespace sl::test {
namespace {

// Regions as surfaces (beamtree/boundary.h). The length of a line's part inside a region, from
// its crossings of a closed surface: Σ ±t over the crossings (+ leaving, - entering), for a line
// that starts and ends outside it. The crossings are found in double precision against each
// polygon (any simple polygon: the crack fills are not convex), so a line a generic direction
// meets no edge.
double crossing_length(const std::vector<const bt::Polygon*>& polygons, const dvec3& origin,
                       const dvec3& direction) {
    double length = 0.0;
    for (const bt::Polygon* polygon : polygons) {
        const dvec3 area = bt::area_vector(*polygon);
        const double facing = glm::dot(area, direction);
        if (facing == 0.0) {
            continue;
        }
        const dvec3& v0 = polygon->vertices[0];
        const double t = glm::dot(area, v0 - origin) / facing;
        const dvec3 hit = origin + t * direction;
        // Point in polygon on the plane's dominant axis: the crossing number.
        const dvec3 a = glm::abs(area);
        const int drop = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
        const int i0 = (drop + 1) % 3, i1 = (drop + 2) % 3;
        bool inside = false;
        const std::vector<dvec3>& v = polygon->vertices;
        for (size_t k = 0, j = v.size() - 1; k < v.size(); j = k++) {
            if ((v[k][i1] > hit[i1]) != (v[j][i1] > hit[i1]) &&
                hit[i0] < (v[j][i0] - v[k][i0]) * (hit[i1] - v[k][i1]) / (v[j][i1] - v[k][i1]) +
                              v[k][i0]) {
                inside = !inside;
            }
        }
        if (inside) {
            length += facing > 0.0 ? t : -t;
        }
    }
    return length;
}

struct BoundaryCase {
    std::string name;
    Scene scene;
};

std::vector<BoundaryCase> boundary_cases(bt::VolumeLibrary& library) {
    std::vector<BoundaryCase> cases;
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        cases.push_back({name, load_canonical(name)});
    }
    // Random scenes with overlapping volumes, flat and edge-on polygons, shared faces and
    // objects around the light (every kind random_scene draws).
    for (int seed = 500; seed < 520; ++seed) {
        RandomScene random = random_scene(seed, library);
        cases.push_back(
            {fmt::format("seed {} (kinds {})", seed, random.kinds), std::move(random.scene)});
    }
    return cases;
}

// What the boundary test measures over every case, printed and bounded at its end.
struct BoundaryTotals {
    double worst_volume = 0.0, worst_welded = 0.0, worst_length = 0.0, worst_merged = 0.0;
    size_t lines = 0, faces = 0, piece_faces = 0, separating = 0;
    size_t merged_triangles = 0, fanned_triangles = 0, merged_planes = 0, unmerged_planes = 0;
    size_t dropped = 0;
    int worst_rounds = 0;
};

// One region of one case: its tree, regions, boundary as cut and as the merged float mesh.
struct RegionBoundary {
    const bt::BeamTree& tree;
    const bt::Regions& regions;
    bt::Region region;
    std::string what;
    double size;  // the influence volume's cube root
    std::vector<bt::BoundaryFace> boundary;
    bt::RegionMesh merged;
};

std::vector<const bt::Polygon*> pointers(const std::vector<bt::Polygon>& polygons) {
    std::vector<const bt::Polygon*> out;
    for (const bt::Polygon& p : polygons) {
        out.push_back(&p);
    }
    return out;
}

// The mesh the GPU draws, the faces on each plane merged into maximal polygons, and the faces
// fanned one by one: both watertight, the merged one with fewer triangles.
void check_merged_mesh(RegionBoundary& b, BoundaryTotals& totals) {
    bt::BoundaryStats merge_stats;
    b.merged = bt::boundary_mesh(b.tree, b.regions, b.region, &merge_stats);
    const bt::RegionMesh fanned =
        bt::boundary_mesh(b.tree, b.regions, b.region, nullptr, bt::BoundaryShape::fragments);
    EXPECT_EQ(unmatched_edges(b.merged), 0u) << b.what;
    EXPECT_EQ(unmatched_edges(fanned), 0u) << b.what;
    EXPECT_LE(b.merged.triangles.size(), fanned.triangles.size()) << b.what;
    totals.merged_triangles += b.merged.triangles.size();
    totals.fanned_triangles += fanned.triangles.size();
    totals.merged_planes += merge_stats.merge.merged_planes;
    totals.unmerged_planes += merge_stats.merge.unmerged_planes;
    totals.dropped += merge_stats.merge.dropped_vertices;
    totals.worst_rounds = std::max(totals.worst_rounds, merge_stats.merge.rounds);
}

// Only where the region meets another type: along the face's normal through its centroid, the
// tree's walk changes from the region to another type at the face (within the 3e-2 ε that
// coincident planes are merged within); faces under (100 ε)^2 skipped.
void check_faces_separate(const RegionBoundary& b, BoundaryTotals& totals) {
    const double epsilon = b.tree.epsilon();
    for (size_t f = 0; f < b.boundary.size(); f += 1 + b.boundary.size() / 200) {
        const bt::Polygon& polygon = b.boundary[f].polygon;
        const double a = bt::area(polygon);
        if (a < 1e4 * epsilon * epsilon) {
            continue;
        }
        const dvec3 n = bt::area_vector(polygon) / a;
        const double reach = 10.0 * epsilon;
        std::vector<bt::RegionInterval> along;
        b.tree.trace(bt::centroid(polygon) - reach * n, n, 0.0, 2.0 * reach, along);
        bool separates = false;
        for (size_t k = 0; k + 1 < along.size(); ++k) {
            if (std::abs(along[k].end - reach) <= 5e-2 * epsilon) {
                separates |= along[k].region == b.region && along[k + 1].region != b.region;
            }
        }
        ++totals.separating;
        EXPECT_TRUE(separates) << b.what << " face " << f << " (area " << a
                               << ") does not separate the region from another type";
    }
}

// Closed and outward: the area vectors sum to zero. The polygons as cut (before the float
// mesh's welding) enclose the cells' volume to round-off: 1e-9 of the region's volume, or of
// the influence volume for a region too small for its own (a 1e-4 m^3 uncertain sliver has the
// same absolute round-off as the rest). Welded and closed, it moves by at most the welding
// tolerance.
void check_volumes(const RegionBoundary& b, BoundaryTotals& totals) {
    dvec3 net(0.0);
    double enclosed = 0.0, cut = 0.0, area = 0.0;
    for (const bt::BoundaryFace& face : b.boundary) {
        net += bt::area_vector(face.polygon);
        enclosed += glm::dot(bt::centroid(face.polygon), bt::area_vector(face.polygon)) / 3.0;
        area += bt::area(face.polygon);
    }
    EXPECT_LT(glm::length(net), 1e-9 * b.size * b.size) << b.what;
    for (const bt::BoundaryFace& face : bt::boundary_faces(b.tree, b.regions, b.region)) {
        cut += glm::dot(bt::centroid(face.polygon), bt::area_vector(face.polygon)) / 3.0;
    }
    const double volume = b.regions.volume[size_t(b.region)];
    totals.worst_volume = std::max(totals.worst_volume, std::abs(cut - volume) / volume);
    EXPECT_LT(std::abs(cut - volume), 1e-9 * std::max(volume, b.regions.influence_volume))
        << b.what << ": encloses " << cut << ", cells " << volume;
    totals.worst_welded = std::max(totals.worst_welded, std::abs(enclosed - volume) / volume);
    EXPECT_LE(std::abs(enclosed - volume), bt::Regions::kConformingTolerance * b.size * area)
        << b.what << ": closed, encloses " << enclosed << ", cells " << volume;
}

// Along 120 random lines through the influence volume, the length inside the region from the
// boundary's crossings equals the same sum over every cell face and the tree's own walk to 1e-6
// of the size; the merged mesh's vertices are rounded to float (6e-8 relative), which a line at
// a grazing angle to a face turns into a larger shift of the crossing, so it is held to 1e-5.
void check_lines(const RegionBoundary& b, const SpotLight& light, std::mt19937& rng,
                 BoundaryTotals& totals) {
    std::vector<const bt::Polygon*> polygons, cell_faces;
    for (const bt::BoundaryFace& face : b.boundary) {
        polygons.push_back(&face.polygon);
    }
    for (const bt::RegionPiece& piece : b.regions.pieces[size_t(b.region)]) {
        for (const bt::Polygon& face : piece.polyhedron.faces) {
            cell_faces.push_back(&face);
        }
    }
    std::vector<bt::Polygon> merged_faces;
    for (const glm::uvec3& t : b.merged.triangles) {
        merged_faces.push_back(
            bt::Polygon({dvec3(b.merged.positions[t.x]), dvec3(b.merged.positions[t.y]),
                         dvec3(b.merged.positions[t.z])}));
    }
    const std::vector<const bt::Polygon*> merged_polygons = pointers(merged_faces);
    for (int i = 0; i < 120; ++i) {
        const dvec3 p = random_point(rng, light), q = random_point(rng, light);
        if (glm::length(q - p) < 1e-3 * b.size) {
            continue;
        }
        // From far outside, through p and q.
        const dvec3 direction = glm::normalize(q - p);
        const dvec3 origin = p - 4.0 * double(light.far) * direction;
        const double from_boundary = crossing_length(polygons, origin, direction);
        std::vector<bt::RegionInterval> intervals;
        b.tree.trace(origin, direction, 0.0, 8.0 * double(light.far), intervals);
        double from_tree = 0.0;
        for (const bt::RegionInterval& interval : intervals) {
            if (interval.region == b.region) {
                from_tree += interval.end - interval.begin;
            }
        }
        const double from_cells = crossing_length(cell_faces, origin, direction);
        const double error =
            std::max(std::abs(from_boundary - from_tree), std::abs(from_boundary - from_cells));
        totals.worst_length = std::max(totals.worst_length, error / b.size);
        EXPECT_LT(error, 1e-6 * b.size) << b.what << " line " << i << ": boundary " << from_boundary
                                        << ", cells " << from_cells << ", tree " << from_tree;
        const double from_merged = crossing_length(merged_polygons, origin, direction);
        totals.worst_merged =
            std::max(totals.worst_merged, std::abs(from_merged - from_boundary) / b.size);
        EXPECT_LT(std::abs(from_merged - from_boundary), 1e-5 * b.size)
            << b.what << " line " << i << ": boundary " << from_boundary << ", merged "
            << from_merged;
        ++totals.lines;
    }
}

// The boundary of each region type is closed and outward: as the float mesh the GPU draws,
// every directed edge is met by its opposite; its area vectors sum to zero; and the volume it
// encloses (divergence theorem over its polygons) equals the summed volume of the region's cells
// to 1e-9 of the region's volume (the boundary is cut from the same planes; what is left is
// the crack fills and the tolerance coincident split planes are merged within: 3e-2 ε).
// Along lines through the influence volume, the length inside the region from the boundary's
// crossings equals the same sum over every cell face, and the tree's own walk (trace()), line by
// line: the per-pixel integral of the analytic pass is that sum with G(z) for t, so its boundary
// and cell meshes integrate the same.
TEST(Boundary, IsClosedOutwardAndIntegratesLikeTheCells) {
    bt::VolumeLibrary library;
    BoundaryTotals totals;
    for (const BoundaryCase& c : boundary_cases(library)) {
        const Scene& scene = c.scene;
        bt::VolumeLibrary scene_library({.max_outer_planes = scene.bounds.max_outer_planes,
                                         .automatic_inner = scene.bounds.automatic_inner});
        bt::VolumeLibrary& use = c.name.starts_with("seed") ? library : scene_library;
        const bt::BeamTree tree(scene.light, use.build(scene, nullptr));
        const bt::Regions regions = bt::extract_regions(tree);
        std::mt19937 rng(17);
        for (const bt::Region region : {bt::Region::lit, bt::Region::uncertain}) {
            bt::BoundaryStats stats;
            RegionBoundary b{tree,
                             regions,
                             region,
                             fmt::format("{} {}", c.name, bt::to_string(region)),
                             std::cbrt(regions.influence_volume),
                             bt::closed_boundary(tree, regions, region, &stats),
                             {}};
            totals.faces += b.boundary.size();
            totals.piece_faces += stats.piece_faces;
            check_merged_mesh(b, totals);
            check_faces_separate(b, totals);
            check_volumes(b, totals);
            check_lines(b, scene.light, rng, totals);
        }
    }
    std::printf(
        "boundary: %zu lines, worst length error %.2e of the influence volume's size; "
        "worst relative volume error %.2e as cut, %.2e welded; %zu boundary faces for "
        "%zu cell faces\n",
        totals.lines, totals.worst_length, totals.worst_volume, totals.worst_welded, totals.faces,
        totals.piece_faces);
    std::printf(
        "maximal polygons: %zu triangles where the fans have %zu; %zu planes merged, %zu "
        "left fanned, %zu outline vertices dropped, at most %d rounds; worst length error "
        "of the merged float mesh %.2e of the size\n",
        totals.merged_triangles, totals.fanned_triangles, totals.merged_planes,
        totals.unmerged_planes, totals.dropped, totals.worst_rounds, totals.worst_merged);
    EXPECT_GT(totals.separating, 2000u);
    // The interiors go, and so do the outline vertices only two merged planes shared: 0.33 here
    // (0.64 with every outline vertex kept).
    EXPECT_LT(double(totals.merged_triangles), 0.5 * double(totals.fanned_triangles));
    EXPECT_LT(totals.unmerged_planes * 100, totals.merged_planes)
        << "nearly every plane should merge";
}

}  // namespace
}  // namespace sl::test
