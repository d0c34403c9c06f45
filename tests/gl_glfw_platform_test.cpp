// The windowed backend (run under Xvfb by ctest): a GLFW window gets a 4.5 core context, the same
// function table and debug output as the headless one.

#include <gtest/gtest.h>

#include "gl/debug.h"
#include "gl/functions.h"
#include "gl/platform.h"

namespace sl::test {
namespace {

// A hidden GLFW window has an OpenGL 4.5 core context with working entry points.
TEST(GlfwPlatform, WindowHasCore45Context) {
    const auto platform = gl::create_glfw_platform(64, 48, "shaftlab test", false);
    const gl::ContextInfo info = platform->info();
    EXPECT_TRUE(info.core_profile);
    EXPECT_GE(info.major * 10 + info.minor, 45) << info.version;
    int width = 0, height = 0;
    platform->framebuffer_size(width, height);
    EXPECT_EQ(width, 64);
    EXPECT_EQ(height, 48);
    gl::GL.Enable(0xFFFF);
    EXPECT_FALSE(gl::take_errors().empty()) << "KHR_debug reports errors in windowed contexts too";
}

}  // namespace
}  // namespace sl::test
