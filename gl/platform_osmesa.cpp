// Headless OpenGL 4.5 core through OSMesa (Mesa's gallium llvmpipe). Rendering goes to
// framebuffer objects; the OSMesa colour buffer is a 1x1 placeholder that is never read.
// OSMesa is gone from Mesa >= 25.1: EGL surfaceless is the natural next backend (docs/design.md
// §8).

#include <GL/osmesa.h>

#include <array>

#include "core/error.h"
#include "gl/platform.h"

namespace sl::gl {

namespace {

class OsmesaPlatform final : public Platform {
public:
    OsmesaPlatform() {
        const int attributes[] = {OSMESA_FORMAT,
                                  OSMESA_RGBA,
                                  OSMESA_DEPTH_BITS,
                                  24,
                                  OSMESA_STENCIL_BITS,
                                  8,
                                  OSMESA_PROFILE,
                                  OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION,
                                  4,
                                  OSMESA_CONTEXT_MINOR_VERSION,
                                  5,
                                  0};
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!context_) {
            fail(
                "OSMesa could not create an OpenGL 4.5 core context (is Mesa's llvmpipe "
                "available? GALLIUM_DRIVER={})",
                getenv("GALLIUM_DRIVER") ? getenv("GALLIUM_DRIVER") : "unset");
        }
        make_current();
        initialize_loaded_context(
            [](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); });
    }
    ~OsmesaPlatform() override { OSMesaDestroyContext(context_); }
    OsmesaPlatform(const OsmesaPlatform&) = delete;
    OsmesaPlatform& operator=(const OsmesaPlatform&) = delete;

    std::string backend() const override { return "osmesa"; }
    void make_current() override {
        if (!OSMesaMakeCurrent(context_, placeholder_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
            fail("OSMesaMakeCurrent failed");
        }
    }

private:
    OSMesaContext context_ = nullptr;
    std::array<unsigned char, 4> placeholder_{};
};

}  // namespace

std::unique_ptr<Platform> create_osmesa_platform() {
    return std::make_unique<OsmesaPlatform>();
}

}  // namespace sl::gl
