#pragma once
// The viewer's picture of the beam tree (Nilsson figure 5.4): the lit, uncertain and unlit
// regions drawn as translucent media over the frame, the pieces' edges as wireframe, and a small
// view from the light with every leaf beam coloured by its type. Needs a current GL context and,
// for draw(), the frame's uniform block bound (SceneRenderer::draw leaves it bound).

#include <array>

#include <glm/mat4x4.hpp>

#include "beamtree/regions.h"
#include "gl/objects.h"

namespace sl::viewer {

struct OverlaySettings {
    bool volumes = true;                            // translucent region volumes
    bool outlines = false;                          // the pieces' edges
    std::array<bool, 3> regions{true, true, true};  // lit, uncertain, unlit
    float opacity = 1.0f;                           // scales every region's density
};

// Nilsson figure 5.4's colours (linear display values), and the outline colour of unlit pieces,
// which black would hide.
inline constexpr std::array<std::array<float, 3>, 3> kRegionColors = {
    {{1.0f, 0.82f, 0.1f}, {0.55f, 0.55f, 0.55f}, {0.0f, 0.0f, 0.0f}}};
inline constexpr std::array<float, 3> kUnlitOutline = {0.35f, 0.45f, 1.0f};
inline constexpr std::array<float, 3> kBlockerLeaf = {0.5f, 0.25f, 0.75f};

class RegionOverlay {
public:
    // Uploads the regions; `far` (the light's range) sets the densities: the lit air lets a
    // light-length through at e^-1.5, uncertain and unlit 8x denser so thin volumes show.
    void upload(const bt::Regions& regions, float far);
    // Composites the regions over `framebuffer` (w x h) with premultiplied alpha; the eye rays
    // stop at `surface_depth`. `view_projection` is the frame's (for the outlines).
    void draw(GLuint framebuffer, GLuint surface_depth, int width, int height,
              const glm::mat4& view_projection, const OverlaySettings& settings);
    // Renders the light's view of the leaves into light_view() (size x size): open beams yellow,
    // solid ones grey (uncertain behind the occluder), blocker ones purple (unlit behind the
    // stopper; black would hide them) over a dark blue "outside", each beam in its own shade of
    // its colour, with the beams' outlines.
    void draw_light_view(const glm::mat4& light_view_projection, int size);
    GLuint light_view() const { return light_color_.id(); }
    GLuint thickness() const { return thickness_.id(); }
    size_t triangle_count() const { return size_t(index_count_) / 3; }
    size_t edge_count() const { return size_t(outline_count_) / 2; }

    // A vertex of the beams' outlines and of the light view's faces.
    struct ColoredVertex {
        glm::vec3 position;
        glm::vec4 color;
    };

private:
    static gl::VertexArray colored_vertex_array(const gl::Buffer& buffer);
    void create_programs();
    // The regions' boundary meshes with the region as a vertex attribute (volume_array_).
    void upload_volumes(const bt::Regions& regions);

    gl::Program thickness_program_, composite_program_, lines_program_;
    gl::Buffer volume_vertices_, volume_indices_;
    gl::VertexArray volume_array_;
    GLsizei index_count_ = 0;
    gl::Buffer outline_vertices_, light_vertices_, light_edge_vertices_;
    gl::VertexArray outline_array_, light_array_, light_edge_array_;
    GLsizei outline_count_ = 0, light_count_ = 0, light_edge_count_ = 0;
    gl::VertexArray empty_array_;
    std::array<float, 3> density_{};

    gl::Texture thickness_;
    gl::Framebuffer thickness_framebuffer_;
    int width_ = 0, height_ = 0;
    gl::Texture light_color_, light_depth_;
    gl::Framebuffer light_framebuffer_;
    int light_size_ = 0;
};

}  // namespace sl::viewer
