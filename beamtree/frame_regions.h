#pragma once
// The per-frame CPU work of the region methods (docs/design.md §10): from the scene as it stands
// this frame, the beam tree and what the GPU draws from it. The static half (each mesh's hulls,
// reduced hulls and inner boxes) comes from VolumeLibrary::shared, computed once per mesh and
// cached on disk; what is left per frame is to transform the volumes, build the tree, extract
// the regions and build the surfaces asked for. No GL: it runs on the pipelined frame loop's
// worker thread (frame/frame_loop.h) while the GPU draws the previous frame.

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/regions.h"

namespace sl::bt {

// What a method needs built.
struct RegionRequest {
    bool lit = false;        // the lit region's mesh
    bool uncertain = false;  // the uncertain region's boundary mesh
    bool cells = false;      // lit: every lit cell's faces (the per-cell mesh), not the boundary
    bool gpu_tree = false;   // the tree as the GPU's classify reads it
    GpuTreeLayout layout = GpuTreeLayout::depth_first;  // and the order of its nodes
    bool pieces = false;  // keep the region pieces (FrameRegions::regions: PLY, statistics)
    // The boundary meshes' triangles: maximal polygons, or each face fanned (for comparison).
    BoundaryShape shape = BoundaryShape::maximal;
    // Over 0: the frames are drawn at this width / height, and a sun's tree covers only the part
    // of its box that the scene's camera sees at it (BeamTree's window): the regions are then the
    // camera's alone, and change with it (view_dependent). 0: the whole box, for any camera.
    float view_aspect = 0.0f;
    // Whether the regions built for `scene` depend on its camera.
    bool view_dependent(const Scene& scene) const {
        return view_aspect > 0.0f && scene.light.parallel();
    }
};

// CPU milliseconds of each stage (one thread, wall clock).
struct RegionStageTimes {
    double volumes = 0.0;    // the cached local volumes transformed into the world
    double tree = 0.0;       // the beam tree
    double regions = 0.0;    // the region pieces
    double lit = 0.0;        // the lit mesh
    double uncertain = 0.0;  // the uncertain boundary mesh
    double gpu_tree = 0.0;   // the GPU's tree buffers
    double total() const { return volumes + tree + regions + lit + uncertain + gpu_tree; }
    // (stage, ms) in pipeline order, the stage as a statistic's name ("lit_mesh").
    std::vector<std::pair<std::string, double>> named() const;
};

// A face of a point light (SpotLight::cube_face), per side of its pyramid (influence_planes'
// order: right, left, up, down): true where no shadow can end on the side's plane, so that the
// neighbouring face's lit region meets the plane in the same set as this face's: then the lit
// faces the two put on the plane cancel in pairs, and the region pass may leave both out
// (AnalyticRegionPass::upload_mesh). A shadow ends on the plane only along an edge that lies on
// it (within 1e-4 of its distance from L) of a polygon the trees take (a volume's face, an exact
// face) with no polygon on the plane's other side along the same edge (a room's corner, where
// two walls meet on the plane, ends none). Every face finds the same answer for the plane it
// shares: the test reads the whole scene. All false for any other light.
std::array<bool, 4> shared_sides(const SpotLight& light, const std::vector<ObjectVolumes>& volumes);

struct FrameRegions {
    std::shared_ptr<const BeamTree> tree;
    std::shared_ptr<const Regions> regions;  // with RegionRequest::pieces
    RegionMesh lit, uncertain;
    GpuTree gpu;
    RegionStageTimes ms;
    ExactOccluders exact;                // [beamtree] occluders
    std::array<bool, 4> shared_sides{};  // with RegionRequest::lit: shared_sides()
};

// Throws sl::Error as BeamTree's constructor and VolumeLibrary::build do.
FrameRegions build_frame_regions(const Scene& scene, const RegionRequest& request);

}  // namespace sl::bt
