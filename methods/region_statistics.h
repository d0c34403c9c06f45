#pragma once
// The region statistics of a view: how its eye rays cross the beam tree's regions, what the
// region passes can at best cost on them, and what the tree and regions cost to build. `render`
// and the harness report them beside every region method's timings.

#include <array>
#include <cstddef>
#include <string>

#include "scenes/scene.h"

namespace sl::methods {

// How the view's eye rays cross the beam-tree regions (docs/design.md §6 "region statistics"), in
// two quantities with one name each everywhere (CSV, tables, viewer):
//   eye-ray fraction  of the eye-ray length inside the light's cone and range, in front of the
//                     first surface, the share in lit, uncertain and unlit regions (exact, from
//                     each ray's walk through the tree, on a grid of at most 160 rays across);
//   volume fraction   of the influence volume, the share of each region type.
// And what the region passes can at best cost, on the same rays:
//   lit crossings     per pixel, twice the maximal lit intervals of the whole eye ray (the
//                     fewest fragments an analytic pass that shades every face in front of the
//                     eye can: it enters and leaves each interval once), and of the eye ray up
//                     to the first surface (what a depth-tested pass could get down to);
//   uncertain span    the length from the first entry into the uncertain region to the last exit
//                     (up to the first surface), over the uncertain length itself: what marching
//                     one spanning interval per pixel walks for each metre of uncertain space.
struct RegionStatistics {
    std::array<double, 3> ray_fraction{};     // indexed by bt::Region
    std::array<double, 3> volume_fraction{};  // indexed by bt::Region
    double lit_crossings = 0.0;               // per pixel, whole eye ray
    double lit_crossings_visible = 0.0;       // per pixel, up to the first surface
    double uncertain_span_ratio = 0.0;  // spanning length / uncertain length (0: none uncertain)
    size_t beams = 0;
    size_t region_faces = 0;  // faces of all region polyhedra
    double build_ms = 0.0;    // beam tree build + region extraction
    double ms = 0.0;          // the whole computation
    // Empty, or why the scene has no beam tree (the light inside an outer volume): the
    // statistics are then left empty, and only the methods that use the tree refuse the scene.
    std::string unavailable;
};
RegionStatistics region_statistics(const Scene& scene, int width, int height);

}  // namespace sl::methods
