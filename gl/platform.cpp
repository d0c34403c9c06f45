#include "gl/platform.h"

#include <cstdlib>
#include <string>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/functions.h"

namespace sl::gl {

ContextInfo Platform::info() const {
    auto text = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(GL.GetString(name));
        return std::string(s ? s : "");
    };
    ContextInfo info;
    info.vendor = text(GL_VENDOR);
    info.renderer = text(GL_RENDERER);
    info.version = text(GL_VERSION);
    GL.GetIntegerv(GL_MAJOR_VERSION, &info.major);
    GL.GetIntegerv(GL_MINOR_VERSION, &info.minor);
    GLint mask = 0;
    GL.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    info.core_profile = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    return info;
}

bool is_software_renderer(const std::string& renderer) {
    for (const char* name :
         {"llvmpipe", "softpipe", "Software Rasterizer", "swrast", "SwiftShader"}) {
        if (renderer.find(name) != std::string::npos) {
            return true;
        }
    }
    return false;
}

bool current_renderer_is_software() {
    const auto* renderer = reinterpret_cast<const char*>(GL.GetString(GL_RENDERER));
    return is_software_renderer(renderer ? renderer : "");
}

void initialize_loaded_context(void* (*resolve)(const char*)) {
    load_api(resolve);
    GLint major = 0, minor = 0;
    GL.GetIntegerv(GL_MAJOR_VERSION, &major);
    GL.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45) {
        fail("OpenGL 4.5 core is required, the context is {}.{}", major, minor);
    }
    install_debug_callback();
}

std::unique_ptr<Platform> create_headless_platform() {
    const char* variable = std::getenv("SHAFTLAB_GL");
    const std::string choice =
        variable && *variable ? variable : (SHAFTLAB_HAVE_OSMESA ? "osmesa" : "egl");
    if (choice == "egl")
        return create_egl_platform();
    if (choice == "osmesa") {
#if SHAFTLAB_HAVE_OSMESA
        return create_osmesa_platform();
#else
        fail(
            "SHAFTLAB_GL=osmesa, but this build has no OSMesa (configured with "
            "-DSHAFTLAB_WITH_OSMESA=OFF); use SHAFTLAB_GL=egl");
#endif
    }
    fail("SHAFTLAB_GL={}: expected 'osmesa' or 'egl'", quote(choice));
}

}  // namespace sl::gl
