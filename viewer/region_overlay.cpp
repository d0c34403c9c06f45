#include "viewer/region_overlay.h"

#include <glm/gtc/type_ptr.hpp>

#include "gl/debug.h"
#include "gl/shaders.h"

namespace sl::viewer {

using gl::GL;

namespace {

glm::vec4 with_alpha(const std::array<float, 3>& c, float a) {
    return {c[0], c[1], c[2], a};
}

}  // namespace

gl::VertexArray RegionOverlay::colored_vertex_array(const gl::Buffer& buffer) {
    gl::VertexArray array = gl::create_vertex_array();
    const GLuint vao = array.id();
    GL.VertexArrayVertexBuffer(vao, 0, buffer.id(), 0, sizeof(ColoredVertex));
    GL.EnableVertexArrayAttrib(vao, 0);
    GL.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(ColoredVertex, position));
    GL.VertexArrayAttribBinding(vao, 0, 0);
    GL.EnableVertexArrayAttrib(vao, 1);
    GL.VertexArrayAttribFormat(vao, 1, 4, GL_FLOAT, GL_FALSE, offsetof(ColoredVertex, color));
    GL.VertexArrayAttribBinding(vao, 1, 0);
    return array;
}

namespace {

// The beams' lines and faces, as the overlay draws them.
struct BeamGeometry {
    std::vector<RegionOverlay::ColoredVertex> outlines, light, light_edges;
};

// Each beam's type from its pieces: open (lit only), solid (uncertain behind), blocker (unlit
// behind the stopper); its faces filled in the type's colour, a shade per beam (a hash of its
// index) so that neighbouring leaves of one type stay apart, and its edges in its region's.
BeamGeometry beam_geometry(const bt::Regions& regions) {
    std::vector<int> kind(regions.beam_count, 0);
    for (int r = 1; r < 3; ++r) {
        for (const bt::RegionPiece& piece : regions.pieces[size_t(r)]) {
            kind[piece.beam] = std::max(kind[piece.beam], r);
        }
    }
    BeamGeometry out;
    const glm::vec4 edge_colors[3] = {with_alpha(kRegionColors[0], 0.3f),
                                      with_alpha(kRegionColors[1], 0.4f),
                                      with_alpha(kUnlitOutline, 0.4f)};
    const glm::vec4 light_edge(0.05f, 0.05f, 0.05f, 1.0f);
    for (int r = 0; r < 3; ++r) {
        for (const bt::RegionPiece& piece : regions.pieces[size_t(r)]) {
            const float shade = 0.7f + 0.3f * float((piece.beam * 2654435761u) >> 24) / 255.0f;
            const auto& base =
                kind[piece.beam] == 2 ? kBlockerLeaf : kRegionColors[size_t(kind[piece.beam])];
            const glm::vec4 fill(shade * base[0], shade * base[1], shade * base[2], 1.0f);
            for (const bt::Polygon& face : piece.polyhedron.faces) {
                const size_t n = face.size();
                for (size_t i = 0; i < n; ++i) {
                    const glm::vec3 a(face.vertices[i]), b(face.vertices[(i + 1) % n]);
                    out.outlines.push_back({a, edge_colors[r]});
                    out.outlines.push_back({b, edge_colors[r]});
                    if (r == 0) {
                        out.light_edges.push_back({a, light_edge});
                        out.light_edges.push_back({b, light_edge});
                    }
                }
                for (size_t i = 1; i + 1 < n; ++i) {  // convex: a fan
                    out.light.push_back({glm::vec3(face.vertices[0]), fill});
                    out.light.push_back({glm::vec3(face.vertices[i]), fill});
                    out.light.push_back({glm::vec3(face.vertices[i + 1]), fill});
                }
            }
        }
    }
    return out;
}

}  // namespace

void RegionOverlay::create_programs() {
    thickness_program_ =
        gl::create_program({{GL_VERTEX_SHADER, "viewer/shaders/region_thickness.vert"},
                            {GL_FRAGMENT_SHADER, "viewer/shaders/region_thickness.frag"}});
    composite_program_ =
        gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                            {GL_FRAGMENT_SHADER, "viewer/shaders/region_composite.frag"}});
    lines_program_ = gl::create_program({{GL_VERTEX_SHADER, "viewer/shaders/lines.vert"},
                                         {GL_FRAGMENT_SHADER, "viewer/shaders/lines.frag"}});
    empty_array_ = gl::create_vertex_array();
}

void RegionOverlay::upload_volumes(const bt::Regions& regions) {
    // Volumes: every region's faces with the region as a vertex attribute.
    std::vector<float> vertices;  // x, y, z, region
    std::vector<glm::uvec3> triangles;
    for (int r = 0; r < 3; ++r) {
        const bt::RegionMesh mesh = regions.mesh(bt::Region(r));
        const auto base = uint32_t(vertices.size() / 4);
        for (const glm::vec3& p : mesh.positions) {
            vertices.insert(vertices.end(), {p.x, p.y, p.z, float(r)});
        }
        for (const glm::uvec3& t : mesh.triangles) {
            triangles.push_back(t + glm::uvec3(base));
        }
    }
    index_count_ = GLsizei(triangles.size() * 3);
    volume_array_ = gl::create_vertex_array();
    if (index_count_ == 0) {
        return;
    }
    volume_vertices_ = gl::create_buffer(vertices.data(), vertices.size() * sizeof(float));
    volume_indices_ = gl::create_buffer(triangles.data(), triangles.size() * sizeof(glm::uvec3));
    const GLuint vao = volume_array_.id();
    GL.VertexArrayVertexBuffer(vao, 0, volume_vertices_.id(), 0, 4 * sizeof(float));
    GL.VertexArrayElementBuffer(vao, volume_indices_.id());
    GL.EnableVertexArrayAttrib(vao, 0);
    GL.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    GL.VertexArrayAttribBinding(vao, 0, 0);
    GL.EnableVertexArrayAttrib(vao, 1);
    GL.VertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, 3 * sizeof(float));
    GL.VertexArrayAttribBinding(vao, 1, 0);
}

void RegionOverlay::upload(const bt::Regions& regions, float far) {
    if (!thickness_program_) {
        create_programs();
    }
    density_ = {1.5f / far, 12.0f / far, 12.0f / far};
    upload_volumes(regions);
    const BeamGeometry beams = beam_geometry(regions);
    auto upload_colored = [](const std::vector<ColoredVertex>& data, gl::Buffer& buffer,
                             gl::VertexArray& array, GLsizei& count) {
        count = GLsizei(data.size());
        buffer = data.empty() ? gl::Buffer()
                              : gl::create_buffer(data.data(), data.size() * sizeof(data[0]));
        array = data.empty() ? gl::create_vertex_array() : colored_vertex_array(buffer);
    };
    upload_colored(beams.outlines, outline_vertices_, outline_array_, outline_count_);
    upload_colored(beams.light, light_vertices_, light_array_, light_count_);
    upload_colored(beams.light_edges, light_edge_vertices_, light_edge_array_, light_edge_count_);
    gl::check_errors("uploading the region overlay");
}

void RegionOverlay::draw(GLuint framebuffer, GLuint surface_depth, int width, int height,
                         const glm::mat4& view_projection, const OverlaySettings& settings) {
    if (width != width_ || height != height_) {
        thickness_ = gl::create_texture_2d(GL_RGBA32F, width, height, GL_NEAREST);
        thickness_.label("region thickness");
        thickness_framebuffer_ = gl::create_framebuffer();
        GL.NamedFramebufferTexture(thickness_framebuffer_.id(), GL_COLOR_ATTACHMENT0,
                                   thickness_.id(), 0);
        width_ = width;
        height_ = height;
    }
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "region overlay");
    GL.Viewport(0, 0, width, height);
    GL.Disable(GL_DEPTH_TEST);
    GL.DepthMask(GL_FALSE);
    GL.Disable(GL_CULL_FACE);
    GL.BindTextureUnit(0, surface_depth);
    if (settings.volumes && index_count_ > 0) {
        GL.BindFramebuffer(GL_FRAMEBUFFER, thickness_framebuffer_.id());
        const float zero[4] = {0, 0, 0, 0};
        GL.ClearNamedFramebufferfv(thickness_framebuffer_.id(), GL_COLOR, 0, zero);
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.UseProgram(thickness_program_.id());
        GL.BindVertexArray(volume_array_.id());
        GL.DrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);

        GL.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        GL.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        const GLuint program = composite_program_.id();
        glm::vec3 density;
        for (int r = 0; r < 3; ++r) {
            density[r] = settings.regions[size_t(r)] ? density_[size_t(r)] * settings.opacity : 0;
        }
        GL.ProgramUniform3fv(program, 0, 1, glm::value_ptr(density));
        for (int r = 0; r < 3; ++r) {
            GL.ProgramUniform3fv(program, 1 + r, 1, kRegionColors[size_t(r)].data());
        }
        GL.UseProgram(program);
        GL.BindTextureUnit(0, thickness_.id());
        GL.BindVertexArray(empty_array_.id());
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
        GL.BindTextureUnit(0, surface_depth);
    }
    if (settings.outlines && outline_count_ > 0) {
        GL.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        const GLuint program = lines_program_.id();
        GL.UseProgram(program);
        GL.ProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, glm::value_ptr(view_projection));
        GL.ProgramUniform1i(program, 1, 1);
        GL.BindVertexArray(outline_array_.id());
        GL.DrawArrays(GL_LINES, 0, outline_count_);
    }
    GL.Disable(GL_BLEND);
    GL.DepthMask(GL_TRUE);
    GL.PopDebugGroup();
    gl::check_errors("drawing the region overlay");
}

void RegionOverlay::draw_light_view(const glm::mat4& light_view_projection, int size) {
    if (size != light_size_) {
        light_color_ = gl::create_texture_2d(GL_RGBA8, size, size, GL_LINEAR);
        light_color_.label("light view of the leaves");
        light_depth_ = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, size, size, GL_NEAREST);
        light_framebuffer_ = gl::create_framebuffer();
        GL.NamedFramebufferTexture(light_framebuffer_.id(), GL_COLOR_ATTACHMENT0, light_color_.id(),
                                   0);
        GL.NamedFramebufferTexture(light_framebuffer_.id(), GL_DEPTH_ATTACHMENT, light_depth_.id(),
                                   0);
        light_size_ = size;
    }
    GL.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "light view of the leaves");
    GL.BindFramebuffer(GL_FRAMEBUFFER, light_framebuffer_.id());
    GL.Viewport(0, 0, size, size);
    const float outside[4] = {0.05f, 0.08f, 0.2f, 1.0f};
    const float far_depth = 1.0f;
    GL.ClearNamedFramebufferfv(light_framebuffer_.id(), GL_COLOR, 0, outside);
    GL.ClearNamedFramebufferfv(light_framebuffer_.id(), GL_DEPTH, 0, &far_depth);
    GL.Disable(GL_BLEND);
    GL.Enable(GL_DEPTH_TEST);
    GL.DepthFunc(GL_LEQUAL);
    GL.DepthMask(GL_TRUE);
    const GLuint program = lines_program_.id();
    GL.UseProgram(program);
    GL.ProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, glm::value_ptr(light_view_projection));
    GL.ProgramUniform1i(program, 1, 0);
    GL.BindVertexArray(light_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, light_count_);
    GL.Disable(GL_DEPTH_TEST);  // every outline shows: they are the beams' cross-sections
    GL.BindVertexArray(light_edge_array_.id());
    GL.DrawArrays(GL_LINES, 0, light_edge_count_);
    GL.PopDebugGroup();
    gl::check_errors("drawing the light view");
}

}  // namespace sl::viewer
