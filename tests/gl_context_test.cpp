// The GL platform layer: context, function table, debug output, RAII objects, shader embedding.

#include <cstddef>
#include <cstdlib>
#include <type_traits>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/platform.h"
#include "gl/shaders.h"
#include "gl/shaders/frame_uniforms.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using GlContext = GlTest;

// The headless context is OpenGL 4.5 (or later) with the core profile, from the backend that
// SHAFTLAB_GL names (OSMesa's llvmpipe when unset).
TEST_F(GlContext, HeadlessContextIsCoreProfile45) {
    const gl::ContextInfo info = headless_gl().info();
    EXPECT_TRUE(info.core_profile);
    EXPECT_GE(info.major * 10 + info.minor, 45) << info.version;
    EXPECT_FALSE(info.renderer.empty());
    const char* chosen = std::getenv("SHAFTLAB_GL");
    EXPECT_EQ(headless_gl().backend(), chosen && *chosen ? chosen : "osmesa");
}

// A GL error raised by the driver reaches the KHR_debug callback and becomes an sl::Error.
TEST_F(GlContext, DebugCallbackTurnsGlErrorsIntoExceptions) {
    gl::GL.Enable(0xFFFF);  // GL_INVALID_ENUM
    EXPECT_THROW(gl::check_errors("enabling a bogus capability"), Error);
    gl::GL.BindTextureUnit(0, 0xDEAD);  // GL_INVALID_OPERATION: no such texture
    const std::vector<std::string> errors = gl::take_errors();
    ASSERT_FALSE(errors.empty());
    EXPECT_NE(errors.front().find("GL error"), std::string::npos) << errors.front();
    EXPECT_NO_THROW(gl::check_errors("after taking the errors"));
}

// GL objects are move-only; a moved-from object holds 0 and the owner deletes the name.
TEST_F(GlContext, ObjectsAreMoveOnlyAndDeleteTheirName) {
    static_assert(!std::is_copy_constructible_v<gl::Buffer>);
    static_assert(!std::is_copy_assignable_v<gl::Texture>);
    static_assert(std::is_nothrow_move_constructible_v<gl::Framebuffer>);
    GLuint name = 0;
    {
        gl::Buffer buffer = gl::create_buffer(nullptr, 64);
        name = buffer.id();
        ASSERT_NE(name, 0u);
        EXPECT_TRUE(gl::GL.IsBuffer(name));
        gl::Buffer moved = std::move(buffer);
        EXPECT_EQ(buffer.id(), 0u);  // NOLINT(bugprone-use-after-move): the property tested
        EXPECT_EQ(moved.id(), name);
        gl::Texture texture = gl::create_texture_2d(GL_RGBA8, 4, 4, GL_NEAREST);
        const GLuint texture_name = texture.id();
        texture = gl::Texture();  // move-assigning deletes the old name
        EXPECT_FALSE(gl::GL.IsTexture(texture_name));
    }
    EXPECT_FALSE(gl::GL.IsBuffer(name));
}

// Embedded shaders expand their includes; unknown files are a clear error, not a GL failure.
TEST_F(GlContext, ShaderSourcesAreEmbeddedWithIncludesExpanded) {
    const std::string source = gl::shader_source("frame/shaders/surface.frag", {"EXTRA 1"});
    EXPECT_TRUE(source.starts_with("#version 450 core\n#define EXTRA 1\n"));
    EXPECT_NE(source.find("SL_UNIFORM_BLOCK(FrameUniforms"), std::string::npos);
    EXPECT_NE(source.find("float cone_factor"), std::string::npos);
    EXPECT_EQ(source.find("#include \""), std::string::npos) << "every project include expanded";
    EXPECT_THROW(gl::shader_source("gl/shaders/missing.frag"), Error);
}

// The uniform block has the same size and member offsets in GLSL (std140) as in C++.
TEST_F(GlContext, FrameUniformsLayoutMatchesBetweenCppAndGlsl) {
    const gl::Program program =
        gl::create_program({{GL_VERTEX_SHADER, "frame/shaders/surface.vert"},
                            {GL_FRAGMENT_SHADER, "frame/shaders/surface.frag"}});
    const GLuint block = gl::GL.GetUniformBlockIndex(program.id(), "FrameUniforms");
    ASSERT_NE(block, GL_INVALID_INDEX);
    GLint size = 0;
    gl::GL.GetActiveUniformBlockiv(program.id(), block, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
    EXPECT_EQ(size_t(size), sizeof(gl::shared::FrameUniforms));

    using U = gl::shared::FrameUniforms;
    const std::pair<const char*, size_t> members[] = {
        {"FrameUniforms.light_view_projection", offsetof(U, light_view_projection)},
        {"FrameUniforms.light_position", offsetof(U, light_position)},
        {"FrameUniforms.light_cone", offsetof(U, light_cone)},
        {"FrameUniforms.medium_sigma_t", offsetof(U, medium_sigma_t)},
        {"FrameUniforms.shadow", offsetof(U, shadow)},
        {"FrameUniforms.display", offsetof(U, display)},
    };
    for (const auto& [name, offset] : members) {
        GLuint index = GL_INVALID_INDEX;
        gl::GL.GetUniformIndices(program.id(), 1, &name, &index);
        if (index == GL_INVALID_INDEX) {
            continue;  // not referenced by this program, so not active
        }
        GLint gl_offset = -1;
        gl::GL.GetActiveUniformsiv(program.id(), 1, &index, GL_UNIFORM_OFFSET, &gl_offset);
        EXPECT_EQ(size_t(gl_offset), offset) << name;
    }
}

// route = auto (analytic/gpu_tree.h) meshes on a software rasterizer: the renderer strings of
// Mesa's and Google's software GLs are told from GPUs', and the suite's own GL is one.
TEST(GlPlatform, TellsSoftwareRasterizersFromGpus) {
    EXPECT_TRUE(gl::is_software_renderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_TRUE(gl::is_software_renderer("softpipe"));
    EXPECT_TRUE(gl::is_software_renderer("Mesa OffScreen / Software Rasterizer"));
    EXPECT_TRUE(gl::is_software_renderer("Google SwiftShader"));
    EXPECT_FALSE(gl::is_software_renderer("NVIDIA H100 80GB HBM3/PCIe/SSE2"));
    EXPECT_FALSE(
        gl::is_software_renderer("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6)"));
    EXPECT_FALSE(gl::is_software_renderer("Mesa Intel(R) UHD Graphics 630 (CFL GT2)"));
}

}  // namespace
}  // namespace sl::test
