#include "gl/objects.h"

#include <initializer_list>

namespace sl::gl {

Buffer create_buffer(const void* data, size_t bytes, GLbitfield flags) {
    GLuint id = 0;
    GL.CreateBuffers(1, &id);
    GL.NamedBufferStorage(id, GLsizeiptr(bytes), data, flags);
    return Buffer(id);
}

Buffer create_mutable_buffer() {
    GLuint id = 0;
    GL.CreateBuffers(1, &id);
    return Buffer(id);
}

namespace {

// Filtered with `filter`, clamped on each of `wraps`.
void set_sampling(GLuint texture, GLenum filter, std::initializer_list<GLenum> wraps) {
    GL.TextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GLint(filter));
    GL.TextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GLint(filter));
    for (const GLenum wrap : wraps) {
        GL.TextureParameteri(texture, wrap, GL_CLAMP_TO_EDGE);
    }
}

}  // namespace

Texture create_texture_2d(GLenum internal_format, int width, int height, GLenum filter) {
    GLuint id = 0;
    GL.CreateTextures(GL_TEXTURE_2D, 1, &id);
    GL.TextureStorage2D(id, 1, internal_format, width, height);
    set_sampling(id, filter, {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T});
    return Texture(id);
}

Texture create_texture_3d(GLenum internal_format, int width, int height, int depth, GLenum filter) {
    GLuint id = 0;
    GL.CreateTextures(GL_TEXTURE_3D, 1, &id);
    GL.TextureStorage3D(id, 1, internal_format, width, height, depth);
    set_sampling(id, filter, {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R});
    return Texture(id);
}

Framebuffer create_framebuffer() {
    GLuint id = 0;
    GL.CreateFramebuffers(1, &id);
    return Framebuffer(id);
}

void PictureTarget::bind_cleared(int width, int height, const char* label) {
    if (width != width_ || height != height_) {
        texture_ = create_texture_2d(GL_RGBA8, width, height, GL_LINEAR);
        texture_.label(label);
        framebuffer_ = create_framebuffer();
        GL.NamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, texture_.id(), 0);
        width_ = width;
        height_ = height;
    }
    const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    GL.ClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, clear);
    GL.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    GL.Viewport(0, 0, width, height);
}

VertexArray create_vertex_array() {
    GLuint id = 0;
    GL.CreateVertexArrays(1, &id);
    return VertexArray(id);
}

TriangleMesh create_triangle_mesh(const std::vector<glm::vec3>& positions,
                                  const std::vector<glm::uvec3>& triangles) {
    TriangleMesh mesh;
    if (triangles.empty()) {
        return mesh;
    }
    mesh.index_count = GLsizei(triangles.size() * 3);
    mesh.vertices = create_buffer(positions.data(), positions.size() * sizeof(glm::vec3));
    mesh.indices = create_buffer(triangles.data(), triangles.size() * sizeof(glm::uvec3));
    mesh.vertex_array = create_vertex_array();
    const GLuint vao = mesh.vertex_array.id();
    GL.VertexArrayVertexBuffer(vao, 0, mesh.vertices.id(), 0, sizeof(glm::vec3));
    GL.VertexArrayElementBuffer(vao, mesh.indices.id());
    GL.EnableVertexArrayAttrib(vao, 0);
    GL.VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    GL.VertexArrayAttribBinding(vao, 0, 0);
    return mesh;
}

Query create_query(GLenum target) {
    GLuint id = 0;
    if (target == GL_FRAGMENT_SHADER_INVOCATIONS) {
        // Mesa's glCreateQueries rejects the pipeline-statistics targets its glBeginQuery
        // accepts (ARB_pipeline_statistics_query): name it now, create it at the first begin.
        GL.GenQueries(1, &id);
    } else {
        GL.CreateQueries(target, 1, &id);
    }
    return Query(id);
}

Sampler create_plain_sampler(GLenum filter) {
    GLuint id = 0;
    GL.CreateSamplers(1, &id);
    Sampler sampler(id);
    GL.SamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GLint(filter));
    GL.SamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GLint(filter));
    GL.SamplerParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    GL.SamplerParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    GL.SamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return sampler;
}

}  // namespace sl::gl
