#pragma once
// Regions (Nilsson §5.2.1, figure 5.4): every beam of the tree cut into its lit part (from the
// near range to the occluder plane, or to the backplate for open beams), its uncertain part
// (from the occluder plane to the stopper plane or the backplate) and its unlit rest (behind
// the stopper). Each is a closed convex polyhedron with outward faces; together they tile the
// influence volume, ready to upload as one mesh per region type.

#include <array>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "beamtree/beam_tree.h"

namespace sl::bt {

struct RegionPiece {
    uint32_t beam;
    Polyhedron polyhedron;
};

// One region type as a triangle mesh for the GPU: float positions, outward-wound triangles and
// the beam each triangle bounds. The faces are conforming (beamtree/conforming.h: no vertex of
// one in the middle of another's edge) and fanned around their centroids, so a rasterizer covers
// each pixel centre with exactly one of the faces on either side of a shared edge.
struct RegionMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    std::vector<uint32_t> beams;  // per triangle

    // Appends a conforming face, fanned (bt::fan_triangles: around its centroid where it has a
    // T-vertex), its triangles bounding `beam`. Faces welded below three vertices add nothing.
    void add_fanned(const Polygon& face, uint32_t beam);
};

struct Regions {
    // Vertices within this fraction of the influence volume's size of each other are welded, and
    // of another face's edge are T-junctions of the GPU mesh (bt::make_conforming).
    static constexpr double kConformingTolerance = 1e-7;
    // The pieces are cut with planes this fraction of the tree's ε thick: well below it, so that
    // the cells keep the tree's geometry.
    static constexpr double kCutEpsilon = 1e-3;

    size_t beam_count = 0;
    std::array<std::vector<RegionPiece>, 3> pieces;  // indexed by Region
    std::array<double, 3> volume{};
    double influence_volume = 0.0;

    size_t face_count(Region region) const;
    // The GPU mesh of one region type: the faces of every piece drawn(), made conforming.
    RegionMesh mesh(Region region) const;
    // False for lit slivers (thinner than 1e-5 of the influence volume's size), which the GPU
    // mesh leaves out (regions.cpp says why); true for every other piece.
    bool drawn(Region region, const RegionPiece& piece) const;
};

Regions extract_regions(const BeamTree& tree);

// Binary little-endian PLY: vertices, then faces with `uchar region` (0 lit, 1 uncertain, 2 unlit)
// and `int beam`. Written to `path` directly; callers stage it (core/output_files.h).
void write_regions_ply(const Regions& regions, const std::filesystem::path& path);

}  // namespace sl::bt
