#pragma once
// The beam tree on the GPU (docs/design.md §14): the flattened tree in two storage buffers, read by
// classify.glsl (a point's region) and walk.glsl (a segment's regions), and the choice every
// region method offers between the two routes from the tree to its GPU passes:
//   walk  the GPU walks the tree per eye ray; the CPU builds the tree and nothing else;
//   mesh  the CPU extracts the region pieces and the lit and uncertain boundary meshes, which the
//         GPU rasterizes (Nilsson §3.2.2 for the lit integral, the per-pixel region lists).
// Both give the same image (tests/beamtree_boundary_gpu_test.cpp, BoundaryOnTheGpu).

#include "beamtree/beam_tree.h"
#include "frame/volume_method.h"
#include "gl/objects.h"

namespace sl::analytic {

// The beam tree as beamtree/shaders/classify.glsl and walk.glsl read it (bt::GpuTree).
class GpuTreeBuffers {
public:
    void upload(const bt::GpuTree& tree);  // fresh buffers: the last frame's stay alive
    void bind() const;                     // at classify.glsl's bindings

private:
    gl::Buffer nodes_, planes_;
};

// The `route` choices, in declaration order. `automatic` ("auto") walks an animated scene on a
// GPU and meshes otherwise: still, the meshes are built once; moving, they cost the CPU 10-100
// times the tree every frame, more than a GPU's walk, but on a software rasterizer the
// full-screen walk costs more than that (results/moving.md, results/animated).
enum class RegionRoute { automatic, walk, mesh };
// The `route` parameter of the region methods: its choices and description.
const std::vector<std::string>& region_route_choices();
const char* region_route_description();
// Whether `route` walks the tree for `scene`; `software`: the GL is a software rasterizer
// (gl::current_renderer_is_software(), asked on the GL thread).
bool walks(RegionRoute route, const Scene& scene, bool software);

}  // namespace sl::analytic
