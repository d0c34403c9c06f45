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
    double worst_volume = 0.0, worst_welded = 0.0, worst_length = 0.0;
    size_t lines = 0, faces = 0, piece_faces = 0, separating = 0;
    size_t merged_triangles = 0, fanned_triangles = 0, merged_planes = 0, unmerged_planes = 0;
    double worst_merged = 0.0;
    size_t dropped = 0;
    int worst_rounds = 0;
    for (const BoundaryCase& c : boundary_cases(library)) {
        const Scene& scene = c.scene;
        bt::VolumeLibrary scene_library({.max_outer_planes = scene.bounds.max_outer_planes,
                                         .automatic_inner = scene.bounds.automatic_inner});
        bt::VolumeLibrary& use = c.name.starts_with("seed") ? library : scene_library;
        const bt::BeamTree tree(scene.light, use.build(scene, nullptr));
        const bt::Regions regions = bt::extract_regions(tree);
        const double size = std::cbrt(regions.influence_volume);
        std::mt19937 rng(17);
        for (const bt::Region region : {bt::Region::lit, bt::Region::uncertain}) {
            bt::BoundaryStats stats;
            const std::vector<bt::BoundaryFace> boundary =
                bt::closed_boundary(tree, regions, region, &stats);
            faces += boundary.size();
            piece_faces += stats.piece_faces;
            const std::string what = fmt::format("{} {}", c.name, bt::to_string(region));
            // The mesh the GPU draws, the faces on each plane merged into maximal polygons, and
            // the faces fanned one by one: both watertight, the merged one with fewer triangles.
            bt::BoundaryStats merge_stats;
            const bt::RegionMesh merged = bt::boundary_mesh(tree, regions, region, &merge_stats);
            const bt::RegionMesh fanned =
                bt::boundary_mesh(tree, regions, region, nullptr, bt::BoundaryShape::fragments);
            EXPECT_EQ(unmatched_edges(merged), 0u) << what;
            EXPECT_EQ(unmatched_edges(fanned), 0u) << what;
            EXPECT_LE(merged.triangles.size(), fanned.triangles.size()) << what;
            merged_triangles += merged.triangles.size();
            fanned_triangles += fanned.triangles.size();
            merged_planes += merge_stats.merge.merged_planes;
            unmerged_planes += merge_stats.merge.unmerged_planes;
            dropped += merge_stats.merge.dropped_vertices;
            worst_rounds = std::max(worst_rounds, merge_stats.merge.rounds);
            std::vector<bt::Polygon> merged_faces;
            for (const glm::uvec3& t : merged.triangles) {
                merged_faces.push_back(
                    bt::Polygon({dvec3(merged.positions[t.x]), dvec3(merged.positions[t.y]),
                                 dvec3(merged.positions[t.z])}));
            }
            std::vector<const bt::Polygon*> merged_polygons;
            for (const bt::Polygon& face : merged_faces) {
                merged_polygons.push_back(&face);
            }
            dvec3 net(0.0);
            double enclosed = 0.0;
            std::vector<const bt::Polygon*> polygons;
            for (const bt::BoundaryFace& face : boundary) {
                net += bt::area_vector(face.polygon);
                enclosed +=
                    glm::dot(bt::centroid(face.polygon), bt::area_vector(face.polygon)) / 3.0;
                polygons.push_back(&face.polygon);
            }
            EXPECT_LT(glm::length(net), 1e-9 * size * size) << what;
            // Only where the region meets another type: along the face's normal through its
            // centroid, the tree's walk changes from the region to another type at the face
            // (within the 3e-2 ε that coincident planes are merged within); faces under
            // (100 ε)^2 skipped.
            for (size_t f = 0; f < boundary.size(); f += 1 + boundary.size() / 200) {
                const bt::Polygon& polygon = boundary[f].polygon;
                const double a = bt::area(polygon);
                if (a < 1e4 * tree.epsilon() * tree.epsilon()) {
                    continue;
                }
                const dvec3 n = bt::area_vector(polygon) / a;
                const double reach = 10.0 * tree.epsilon();
                std::vector<bt::RegionInterval> along;
                tree.trace(bt::centroid(polygon) - reach * n, n, 0.0, 2.0 * reach, along);
                bool separates = false;
                for (size_t k = 0; k + 1 < along.size(); ++k) {
                    if (std::abs(along[k].end - reach) <= 5e-2 * tree.epsilon()) {
                        separates |= along[k].region == region && along[k + 1].region != region;
                    }
                }
                ++separating;
                EXPECT_TRUE(separates) << what << " face " << f << " (area " << a
                                       << ") does not separate the region from another type";
            }
            const double volume = regions.volume[size_t(region)];
            // The polygons as cut (before the float mesh's welding) enclose the cells' volume
            // to round-off: 1e-9 of the region's volume, or of the influence volume for a
            // region too small for its own (a 1e-4 m^3 uncertain sliver has the same absolute
            // round-off as the rest).
            double cut = 0.0, area = 0.0;
            for (const bt::BoundaryFace& face : bt::boundary_faces(tree, regions, region)) {
                cut += glm::dot(bt::centroid(face.polygon), bt::area_vector(face.polygon)) / 3.0;
            }
            for (const bt::BoundaryFace& face : boundary) {
                area += bt::area(face.polygon);
            }
            const double relative = std::abs(cut - volume) / volume;
            worst_volume = std::max(worst_volume, relative);
            EXPECT_LT(std::abs(cut - volume), 1e-9 * std::max(volume, regions.influence_volume))
                << what << ": encloses " << cut << ", cells " << volume;
            // Welded and closed, it moves by at most the welding tolerance.
            worst_welded = std::max(worst_welded, std::abs(enclosed - volume) / volume);
            EXPECT_LE(std::abs(enclosed - volume), bt::Regions::kConformingTolerance * size * area)
                << what << ": closed, encloses " << enclosed << ", cells " << volume;
            std::vector<const bt::Polygon*> cell_faces;
            for (const bt::RegionPiece& piece : regions.pieces[size_t(region)]) {
                for (const bt::Polygon& face : piece.polyhedron.faces) {
                    cell_faces.push_back(&face);
                }
            }
            for (int i = 0; i < 120; ++i) {
                const dvec3 p = random_point(rng, scene.light), q = random_point(rng, scene.light);
                if (glm::length(q - p) < 1e-3 * size) {
                    continue;
                }
                // From far outside, through p and q.
                const dvec3 direction = glm::normalize(q - p);
                const dvec3 origin = p - 4.0 * double(scene.light.far) * direction;
                const double from_boundary = crossing_length(polygons, origin, direction);
                std::vector<bt::RegionInterval> intervals;
                tree.trace(origin, direction, 0.0, 8.0 * double(scene.light.far), intervals);
                double from_tree = 0.0;
                for (const bt::RegionInterval& interval : intervals) {
                    if (interval.region == region) {
                        from_tree += interval.end - interval.begin;
                    }
                }
                const double from_cells = crossing_length(cell_faces, origin, direction);
                const double error = std::max(std::abs(from_boundary - from_tree),
                                              std::abs(from_boundary - from_cells));
                worst_length = std::max(worst_length, error / size);
                EXPECT_LT(error, 1e-6 * size)
                    << what << " line " << i << ": boundary " << from_boundary << ", cells "
                    << from_cells << ", tree " << from_tree;
                // The merged mesh is the float mesh the GPU draws: its vertices are rounded to
                // float (6e-8 relative), which a line at a grazing angle to a face turns into a
                // larger shift of the crossing, so it is held to 1e-5 of the size.
                const double from_merged = crossing_length(merged_polygons, origin, direction);
                worst_merged = std::max(worst_merged, std::abs(from_merged - from_boundary) / size);
                EXPECT_LT(std::abs(from_merged - from_boundary), 1e-5 * size)
                    << what << " line " << i << ": boundary " << from_boundary << ", merged "
                    << from_merged;
                ++lines;
            }
        }
    }
    std::printf(
        "boundary: %zu lines, worst length error %.2e of the influence volume's size; "
        "worst relative volume error %.2e as cut, %.2e welded; %zu boundary faces for "
        "%zu cell faces\n",
        lines, worst_length, worst_volume, worst_welded, faces, piece_faces);
    std::printf(
        "maximal polygons: %zu triangles where the fans have %zu; %zu planes merged, %zu "
        "left fanned, %zu outline vertices dropped, at most %d rounds; worst length error "
        "of the merged float mesh %.2e of the size\n",
        merged_triangles, fanned_triangles, merged_planes, unmerged_planes, dropped, worst_rounds,
        worst_merged);
    EXPECT_GT(separating, 2000u);
    // The interiors go, and so do the outline vertices only two merged planes shared: 0.33 here
    // (0.64 with every outline vertex kept).
    EXPECT_LT(double(merged_triangles), 0.5 * double(fanned_triangles));
    EXPECT_LT(unmerged_planes * 100, merged_planes) << "nearly every plane should merge";
}

}  // namespace
}  // namespace sl::test
