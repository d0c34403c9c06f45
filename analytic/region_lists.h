#pragma once
// Per-pixel lists of region-surface crossings (beamtree/shaders/region_lists.glsl): each frame
// the lit and uncertain boundary meshes (beamtree/boundary.h) are rasterized once, every
// fragment appending its signed distance along the eye ray to its pixel's list (the mesh route),
// or every eye ray walks the beam tree and writes its crossings (the walk route,
// analytic/gpu_tree.h). The hybrids read them: hybrid1 and hybrid2 to classify a plane sample
// (lit, uncertain, unlit) in a few compares, hybrid3 to march only the uncertain intervals; on the
// walk route, the lit integral of beamtree, hybrid2 and hybrid3 sums the lit ones
// (AnalyticRegionPass::draw_walk). A list that overflows falls back to the tree.

#include <vector>

#include <glm/vec3.hpp>

#include "analytic/gpu_tree.h"
#include "analytic/region_faces.h"
#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "frame/volume_method.h"
#include "gl/objects.h"

namespace sl::analytic {

class RegionLists {
public:
    // The surfaces (float positions, outward triangles) of the lit and the uncertain union.
    void upload(const bt::RegionMesh& lit, const bt::RegionMesh& uncertain);
    // Clears and fills the lists for the frame's view into buffers of its size, then binds them
    // at the readers' bindings (region_lists.glsl). The current framebuffer's colour writes are
    // off while it draws; with `mark_stencil`, its stencil (a marks texture, below) is cleared
    // and gets bit kLitStencilBit where a ray crosses the lit surface and kUncertainStencilBit
    // where it crosses the uncertain one, so that a later pass can skip the pixels that have
    // neither before shading them (MarkedPixelsOnly).
    static constexpr GLuint kLitStencilBit = 1, kUncertainStencilBit = 2;
    void build(const frame::VolumeInputs& inputs, bool mark_stencil = false);
    // The same lists by the walk route: a full-screen pass walks `tree` along every eye ray up to
    // its surface (analytic/shaders/region_lists_walk.frag). With `mark_stencil`, both bits are
    // set where the ray crosses a surface of `mark_bits` (the bits the reader will test).
    // `stack_entries`: the walk's short stack (SL_WALK_STACK of beamtree/shaders/walk.glsl; 0,
    // its default).
    void walk(const frame::VolumeInputs& inputs, const GpuTreeBuffers& tree, bool mark_stencil,
              GLuint mark_bits, int stack_entries = 0);

    // A stencil for the marks, `width` × `height`, attached to `framebuffer`.
    static gl::Texture attach_marks(GLuint framebuffer, int width, int height);

    // While alive, fragments drawn to the current framebuffer pass only where its marks hold one
    // of `bits`; the marks are read, not written.
    class MarkedPixelsOnly {
    public:
        explicit MarkedPixelsOnly(GLuint bits);
        ~MarkedPixelsOnly();
        MarkedPixelsOnly(const MarkedPixelsOnly&) = delete;
        MarkedPixelsOnly& operator=(const MarkedPixelsOnly&) = delete;
    };
    // Pixels whose list of a surface overflowed in the last build (reads the counts back).
    size_t overflows() const;
    size_t triangle_count(int surface) const { return size_t(meshes_[surface].index_count()) / 3; }

private:
    // The build's common half: the lists sized for the view and cleared, bound, colour writes
    // off; the stencil cleared and enabled with `mark_stencil`. end_build() undoes the state.
    void begin_build(const frame::VolumeInputs& inputs, bool mark_stencil);
    void end_build(bool mark_stencil);

    RegionFaces meshes_[2];  // lit, uncertain
    gl::Program program_;
    gl::Program walk_program_;
    int walk_stack_ = 0;  // walk_program_'s stack_entries
    gl::VertexArray empty_vertex_array_;
    gl::Buffer region_counts_, crossings_;
    int width_ = 0, height_ = 0;
};

}  // namespace sl::analytic
