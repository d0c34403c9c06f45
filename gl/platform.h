#pragma once
// One interface over the ways shaftlab gets an OpenGL 4.5 core context: headless through OSMesa
// (platform_osmesa.cpp) or EGL without a surface (platform_egl.cpp: a GPU's driver, or Mesa), and
// windowed through GLFW (platform_glfw.cpp). Creating a platform makes
// its context current, fills the GL function table and installs the KHR_debug callback.

#include <memory>
#include <string>

namespace sl::gl {

struct ContextInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    int major = 0;
    int minor = 0;
    bool core_profile = false;
};

class Platform {
public:
    virtual ~Platform() = default;
    virtual std::string backend() const = 0;
    virtual void make_current() = 0;
    ContextInfo info() const;
};

// Headless OSMesa (Mesa llvmpipe). Throws sl::Error when no 4.5 core context can be made. Only in
// builds configured with SHAFTLAB_WITH_OSMESA (the default).
std::unique_ptr<Platform> create_osmesa_platform();

// Headless EGL, surfaceless, on the first EGL device that makes a 4.5 core context (an NVIDIA GPU
// through its driver; Mesa's software device otherwise). Throws sl::Error when none does.
std::unique_ptr<Platform> create_egl_platform();

// The headless backend every command and test uses: the environment variable SHAFTLAB_GL picks
// `osmesa` or `egl`; unset, OSMesa where the build has it, else EGL. Throws sl::Error for any other
// value or when the backend cannot make a context.
std::unique_ptr<Platform> create_headless_platform();

class WindowPlatform : public Platform {
public:
    virtual bool should_close() const = 0;
    virtual void swap_buffers() = 0;
    virtual void poll_events() = 0;
    virtual void framebuffer_size(int& width, int& height) const = 0;
    // The native window (GLFWwindow*) for UI toolkits that need it.
    virtual void* native_window() const = 0;
};

// A GLFW window with a 4.5 core context; `visible = false` gives an offscreen window (needs a
// display all the same). Throws sl::Error when there is no display or no 4.5 core context.
std::unique_ptr<WindowPlatform> create_glfw_platform(int width, int height,
                                                     const std::string& title, bool visible);

// Called by every backend once its context is current.
void initialize_loaded_context(void* (*resolve)(const char*));

// Whether a GL_RENDERER string names a software rasterizer (Mesa's llvmpipe, softpipe, swrast;
// SwiftShader), where shading runs on the CPU in SIMD lanes instead of on a GPU.
bool is_software_renderer(const std::string& renderer);
// The same for the current context.
bool current_renderer_is_software();

}  // namespace sl::gl
