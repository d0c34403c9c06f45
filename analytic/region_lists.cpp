#include "analytic/region_lists.h"

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "analytic/shaders/analytic_interface.h"
#include "beamtree/shaders/region_lists_interface.h"
#include "core/check.h"
#include "gl/functions.h"
#include "gl/shaders.h"

namespace sl::analytic {

namespace {

using gl::GL;

}  // namespace

void RegionLists::upload(const bt::RegionMesh& lit, const bt::RegionMesh& uncertain) {
    if (!program_) {
        program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/world_position.vert"},
                                       {GL_FRAGMENT_SHADER, "analytic/shaders/region_lists.frag"}});
    }
    meshes_[0] = create_region_faces(lit.positions, lit.triangles);
    meshes_[1] = create_region_faces(uncertain.positions, uncertain.triangles);
}

void RegionLists::begin_build(const frame::VolumeInputs& inputs, bool mark_stencil) {
    if (inputs.width != width_ || inputs.height != height_) {
        width_ = inputs.width;
        height_ = inputs.height;
        const size_t slots = size_t(width_) * height_ * 2;
        region_counts_ = gl::create_buffer(nullptr, slots * sizeof(GLuint), GL_DYNAMIC_STORAGE_BIT);
        crossings_ = gl::create_buffer(nullptr, slots * SL_REGION_LIST_SIZE * sizeof(float),
                                       GL_DYNAMIC_STORAGE_BIT);
        region_counts_.label("region list counts");
        crossings_.label("region list crossings");
    }
    const GLuint zero = 0;
    GL.ClearNamedBufferData(region_counts_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_REGION_COUNTS_BINDING, region_counts_.id());
    GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_REGION_CROSSINGS_BINDING, crossings_.id());
    GL.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GL.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    GL.Disable(GL_BLEND);
    if (mark_stencil) {
        GLint framebuffer = 0;
        GL.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
        GL.ClearNamedFramebufferfi(GLuint(framebuffer), GL_DEPTH_STENCIL, 0, 1.0f, 0);
        GL.Enable(GL_STENCIL_TEST);
        GL.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    }
}

void RegionLists::end_build(bool mark_stencil) {
    GL.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (mark_stencil) {
        GL.StencilMask(0xff);
        GL.Disable(GL_STENCIL_TEST);
    }
    GL.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void RegionLists::build(const frame::VolumeInputs& inputs, bool mark_stencil) {
    begin_build(inputs, mark_stencil);
    GL.Enable(GL_DEPTH_CLAMP);  // faces in front of the near plane still cross the ray
    GL.UseProgram(program_.id());
    for (int s = 0; s < 2; ++s) {
        if (meshes_[s].index_count() == 0) {
            continue;
        }
        if (mark_stencil) {
            const GLuint bit = s == 0 ? kLitStencilBit : kUncertainStencilBit;
            GL.StencilFunc(GL_ALWAYS, GLint(bit), bit);
            GL.StencilMask(bit);
        }
        GL.ProgramUniform1i(program_.id(), SL_REGION_LISTS_SURFACE, s);
        meshes_[s].bind();
        GL.DrawElements(GL_TRIANGLES, meshes_[s].index_count(), GL_UNSIGNED_INT, nullptr);
    }
    GL.Disable(GL_DEPTH_CLAMP);
    end_build(mark_stencil);
}

void RegionLists::walk(const frame::VolumeInputs& inputs, const GpuTreeBuffers& tree,
                       bool mark_stencil, GLuint mark_bits, int stack_entries) {
    SL_CHECK(stack_entries >= 0);
    if (!walk_program_ || stack_entries != walk_stack_) {
        std::vector<std::string> defines;
        if (stack_entries > 0) {
            defines.push_back(fmt::format("SL_WALK_STACK {}", stack_entries));
        }
        walk_program_ =
            gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                {GL_FRAGMENT_SHADER, "analytic/shaders/region_lists_walk.frag"}},
                               defines);
        walk_stack_ = stack_entries;
    }
    if (!empty_vertex_array_) {
        empty_vertex_array_ = gl::create_vertex_array();
    }
    begin_build(inputs, mark_stencil);
    if (mark_stencil) {
        const GLuint both = kLitStencilBit | kUncertainStencilBit;
        GL.StencilFunc(GL_ALWAYS, GLint(both), both);
        GL.StencilMask(both);
    }
    tree.bind();
    GL.BindTextureUnit(SL_ANALYTIC_SURFACE_DEPTH_UNIT, inputs.surface_depth);
    GL.UseProgram(walk_program_.id());
    // region_lists_walk.frag's mark_surfaces: bit 0 lit, bit 1 uncertain, as the stencil's bits.
    static_assert(kLitStencilBit == 1 && kUncertainStencilBit == 2);
    GL.ProgramUniform1i(walk_program_.id(), SL_REGION_LISTS_MARK_SURFACES, GLint(mark_bits));
    GL.BindVertexArray(empty_vertex_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    end_build(mark_stencil);
}

gl::Texture RegionLists::attach_marks(GLuint framebuffer, int width, int height) {
    gl::Texture marks = gl::create_texture_2d(GL_DEPTH24_STENCIL8, width, height, GL_NEAREST);
    GL.NamedFramebufferTexture(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, marks.id(), 0);
    return marks;
}

RegionLists::MarkedPixelsOnly::MarkedPixelsOnly(GLuint bits) {
    GL.Enable(GL_STENCIL_TEST);
    GL.StencilMask(0);
    GL.StencilFunc(GL_NOTEQUAL, 0, bits);
}

RegionLists::MarkedPixelsOnly::~MarkedPixelsOnly() {
    GL.StencilMask(0xff);
    GL.Disable(GL_STENCIL_TEST);
}

size_t RegionLists::overflows() const {
    if (!region_counts_) {
        return 0;
    }
    std::vector<GLuint> counts(size_t(width_) * height_ * 2);
    GL.GetNamedBufferSubData(region_counts_.id(), 0, GLsizeiptr(counts.size() * sizeof(GLuint)),
                             counts.data());
    return size_t(std::count_if(counts.begin(), counts.end(),
                                [](GLuint n) { return n > GLuint(SL_REGION_LIST_SIZE); }));
}

}  // namespace sl::analytic
