#pragma once
// Per-pixel lists of region-surface crossings (sampling/shaders/region_lists.glsl): each frame
// the lit and uncertain boundary meshes (beamtree/boundary.h) are rasterized once, every
// fragment appending its signed distance along the eye ray to its pixel's list. The hybrids read
// them: hybrid1 and hybrid2 to classify a plane sample (lit, uncertain, unlit) in a few compares,
// hybrid3 to march only the uncertain intervals. A list that overflows falls back to the tree.

#include <vector>

#include <glm/vec3.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "frame/volume_method.h"
#include "gl/objects.h"

namespace sl::sampling {

// The beam tree as beamtree/shaders/classify.glsl reads it (bt::GpuTree in two storage
// buffers): the hybrids classify plane samples with it, and fall back on it where a list
// overflows.
class GpuTreeBuffers {
public:
    void upload(const bt::GpuTree& tree);  // fresh buffers: the last frame's stay alive
    void bind() const;                     // at classify.glsl's bindings
private:
    gl::Buffer nodes_, planes_;
};

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
    size_t triangle_count(int surface) const { return size_t(meshes_[surface].index_count) / 3; }

private:
    gl::TriangleMesh meshes_[2];  // lit, uncertain
    gl::Program program_;
    gl::Buffer region_counts_, crossings_;
    int width_ = 0, height_ = 0;
};

}  // namespace sl::sampling
