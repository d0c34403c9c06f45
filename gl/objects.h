#pragma once
// Move-only owners of GL objects (Magnum style): each owns its name, deletes it in its destructor,
// and a moved-from object holds 0. Creation goes through the DSA entry points, so an object is
// complete without ever being bound.

#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "gl/functions.h"

namespace sl::gl {

template <typename Kind>
class GlObject {
public:
    GlObject() = default;
    explicit GlObject(GLuint id) : id_(id) {}
    ~GlObject() { reset(); }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_ != 0) {
            Kind::destroy(id_);
            id_ = 0;
        }
    }
    // Names the object in debug output and GL debuggers.
    void label(const std::string& name) const {
        GL.ObjectLabel(Kind::identifier, id_, GLsizei(name.size()), name.c_str());
    }

private:
    GLuint id_ = 0;
};

struct BufferKind {
    static constexpr GLenum identifier = GL_BUFFER;
    static void destroy(GLuint id) { GL.DeleteBuffers(1, &id); }
};
struct TextureKind {
    static constexpr GLenum identifier = GL_TEXTURE;
    static void destroy(GLuint id) { GL.DeleteTextures(1, &id); }
};
struct FramebufferKind {
    static constexpr GLenum identifier = GL_FRAMEBUFFER;
    static void destroy(GLuint id) { GL.DeleteFramebuffers(1, &id); }
};
struct VertexArrayKind {
    static constexpr GLenum identifier = GL_VERTEX_ARRAY;
    static void destroy(GLuint id) { GL.DeleteVertexArrays(1, &id); }
};
struct ProgramKind {
    static constexpr GLenum identifier = GL_PROGRAM;
    static void destroy(GLuint id) { GL.DeleteProgram(id); }
};
struct ShaderKind {
    static constexpr GLenum identifier = GL_SHADER;
    static void destroy(GLuint id) { GL.DeleteShader(id); }
};
struct SamplerKind {
    static constexpr GLenum identifier = GL_SAMPLER;
    static void destroy(GLuint id) { GL.DeleteSamplers(1, &id); }
};
struct QueryKind {
    static constexpr GLenum identifier = GL_QUERY;
    static void destroy(GLuint id) { GL.DeleteQueries(1, &id); }
};

using Buffer = GlObject<BufferKind>;
using Texture = GlObject<TextureKind>;
using Framebuffer = GlObject<FramebufferKind>;
using VertexArray = GlObject<VertexArrayKind>;
using Program = GlObject<ProgramKind>;
using Shader = GlObject<ShaderKind>;
using Query = GlObject<QueryKind>;
using Sampler = GlObject<SamplerKind>;

// An immutable-storage buffer holding `bytes` (flags: e.g. GL_DYNAMIC_STORAGE_BIT for updates).
Buffer create_buffer(const void* data, size_t bytes, GLbitfield flags = 0);
// A buffer with no storage yet, for data re-specified with NamedBufferData (streamed per frame).
Buffer create_mutable_buffer();
// An immutable 2D texture of one level, clamped, filtered with `filter`.
Texture create_texture_2d(GLenum internal_format, int width, int height, GLenum filter);
// An immutable 3D texture of one level, clamped on every axis, filtered with `filter`.
Texture create_texture_3d(GLenum internal_format, int width, int height, int depth, GLenum filter);
Framebuffer create_framebuffer();
VertexArray create_vertex_array();
Query create_query(GLenum target);
// A sampler that reads any 2D texture as plain values: clamped, `filter`, depth comparison off.
Sampler create_plain_sampler(GLenum filter);

// A picture a method draws for the previewer (a wireframe, an overlay): an RGBA8 texture of the
// frame's size and a framebuffer on it, made again when the size changes. bind_cleared() makes or
// keeps them, clears the picture to opaque black and binds its framebuffer with a viewport over it.
class PictureTarget {
public:
    void bind_cleared(int width, int height, const char* label);
    GLuint texture() const { return texture_.id(); }
    explicit operator bool() const { return bool(texture_); }

private:
    Texture texture_;
    Framebuffer framebuffer_;
    int width_ = 0, height_ = 0;
};

// An indexed triangle mesh of positions alone (attribute 0, vec3), ready for DrawElements with
// GL_UNSIGNED_INT indices; empty (no objects, index_count 0) for no triangles.
struct TriangleMesh {
    Buffer vertices, indices;
    VertexArray vertex_array;
    GLsizei index_count = 0;
};
TriangleMesh create_triangle_mesh(const std::vector<glm::vec3>& positions,
                                  const std::vector<glm::uvec3>& triangles);

}  // namespace sl::gl
