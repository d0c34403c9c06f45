#include "gl/functions.h"

#include <string>

#include "core/error.h"

namespace sl::gl {

Api GL;

void load_api(ProcAddressFn resolve) {
    Api api;
    std::string missing;
#define SL_GL_LOAD(type, name)                                             \
    api.name = reinterpret_cast<type>(resolve("gl" #name));                \
    if (!api.name) {                                                       \
        missing += (missing.empty() ? "gl" : ", gl") + std::string(#name); \
    }
    SL_GL_FUNCTIONS(SL_GL_LOAD)
#undef SL_GL_LOAD
    if (!missing.empty()) {
        fail("OpenGL entry points not found: {}", missing);
    }
    GL = api;
}

}  // namespace sl::gl
