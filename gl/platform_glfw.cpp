// Windowed OpenGL 4.5 core through GLFW (X11/GLX here), for the interactive viewer.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>

#include "core/error.h"
#include "gl/platform.h"

namespace sl::gl {

namespace {

std::string g_last_glfw_error;

class GlfwPlatform final : public WindowPlatform {
public:
    GlfwPlatform(int width, int height, const std::string& title, bool visible) {
        glfwSetErrorCallback([](int, const char* message) { g_last_glfw_error = message; });
        if (!glfwInit()) {
            fail("GLFW could not initialise (no display?): {}", g_last_glfw_error);
        }
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
        glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
        window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
        if (!window_) {
            glfwTerminate();
            fail("GLFW could not create a window with an OpenGL 4.5 core context: {}",
                 g_last_glfw_error);
        }
        make_current();
        initialize_loaded_context(
            [](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); });
    }
    ~GlfwPlatform() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    GlfwPlatform(const GlfwPlatform&) = delete;
    GlfwPlatform& operator=(const GlfwPlatform&) = delete;

    std::string backend() const override { return "glfw"; }
    void make_current() override { glfwMakeContextCurrent(window_); }
    bool should_close() const override { return glfwWindowShouldClose(window_); }
    void swap_buffers() override { glfwSwapBuffers(window_); }
    void poll_events() override { glfwPollEvents(); }
    void framebuffer_size(int& width, int& height) const override {
        glfwGetFramebufferSize(window_, &width, &height);
    }
    void* native_window() const override { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<WindowPlatform> create_glfw_platform(int width, int height,
                                                     const std::string& title, bool visible) {
    return std::make_unique<GlfwPlatform>(width, height, title, visible);
}

}  // namespace sl::gl
