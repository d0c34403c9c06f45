// Headless OpenGL 4.5 core through EGL without a surface: the display comes from
// EGL_EXT_platform_device (the first device that makes a 4.5 core context; on NVIDIA the GPU, on
// Mesa its software device), falling back to the default display. Rendering goes to framebuffer
// objects, so the context is made current with no surface (EGL_KHR_surfaceless_context).

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.h"
#include "gl/platform.h"

namespace sl::gl {

namespace {

std::string egl_error_text(EGLint code) {
    switch (code) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        default:
            return "EGL error " + std::to_string(code);
    }
}

bool has_extension(const char* list, const std::string& name) {
    if (!list)
        return false;
    const std::string all = std::string(" ") + list + " ";
    return all.find(" " + name + " ") != std::string::npos;
}

// The displays to try, best first: every EGL device, then the default display.
std::vector<EGLDisplay> candidate_displays() {
    std::vector<EGLDisplay> displays;
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (has_extension(client, "EGL_EXT_platform_device") &&
        has_extension(client, "EGL_EXT_device_enumeration")) {
        auto query_devices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
        EGLint count = 0;
        if (query_devices && platform_display && query_devices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
            query_devices(count, devices.data(), &count);
            for (EGLint i = 0; i < count; ++i) {
                const EGLDisplay display = platform_display(
                    EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
                if (display != EGL_NO_DISPLAY)
                    displays.push_back(display);
            }
        }
    }
    const EGLDisplay fallback = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (fallback != EGL_NO_DISPLAY)
        displays.push_back(fallback);
    return displays;
}

class EglPlatform final : public Platform {
public:
    EglPlatform() {
        std::string reasons;
        for (const EGLDisplay display : candidate_displays()) {
            if (try_display(display, reasons)) {
                make_current();
                initialize_loaded_context([](const char* name) {
                    return reinterpret_cast<void*>(eglGetProcAddress(name));
                });
                return;
            }
        }
        fail("EGL could not create a surfaceless OpenGL 4.5 core context{}",
             reasons.empty() ? std::string(" (no EGL display)") : ":" + reasons);
    }
    ~EglPlatform() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    EglPlatform(const EglPlatform&) = delete;
    EglPlatform& operator=(const EglPlatform&) = delete;

    std::string backend() const override { return "egl"; }
    void make_current() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
            fail("eglMakeCurrent failed: {}", egl_error_text(eglGetError()));
        }
    }

private:
    // Initializes `display` and makes a 4.5 core context on it; on failure appends why to
    // `reasons` and leaves nothing behind.
    bool try_display(EGLDisplay display, std::string& reasons) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            reasons += " eglInitialize: " + egl_error_text(eglGetError()) + ";";
            return false;
        }
        const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
        if (!has_extension(extensions, "EGL_KHR_surfaceless_context") ||
            !eglBindAPI(EGL_OPENGL_API)) {
            reasons += " a display without surfaceless desktop OpenGL;";
            eglTerminate(display);
            return false;
        }
        // Rendering goes to framebuffer objects: a context with no config where the display
        // allows it (EGL_KHR_no_config_context), else any config that can make pbuffers.
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
            const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                                EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
            EGLint configs = 0;
            if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1) {
                reasons += " no OpenGL config;";
                eglTerminate(display);
                return false;
            }
        }
        const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                             4,
                                             EGL_CONTEXT_MINOR_VERSION,
                                             5,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                             EGL_NONE};
        const EGLContext context =
            eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
        if (context == EGL_NO_CONTEXT) {
            reasons += " eglCreateContext: " + egl_error_text(eglGetError()) + ";";
            eglTerminate(display);
            return false;
        }
        display_ = display;
        context_ = context;
        return true;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<Platform> create_egl_platform() {
    return std::make_unique<EglPlatform>();
}

}  // namespace sl::gl
