#include "gl/debug.h"

#include <fmt/format.h>

#include <mutex>

#include "core/error.h"
#include "gl/functions.h"

namespace sl::gl {

namespace {

std::mutex g_mutex;
std::vector<std::string> g_errors;

void APIENTRY on_debug_message(GLenum /*source*/, GLenum type, GLuint id, GLenum severity,
                               GLsizei length, const GLchar* message, const void* /*user*/) {
    const bool is_error = type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR ||
                          severity == GL_DEBUG_SEVERITY_HIGH;
    if (!is_error) {
        return;
    }
    std::lock_guard lock(g_mutex);
    g_errors.push_back(
        fmt::format("GL error {:#x}: {}", id,
                    length < 0 ? std::string(message) : std::string(message, length)));
}

}  // namespace

void install_debug_callback() {
    GL.Enable(GL_DEBUG_OUTPUT);
    GL.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    GL.DebugMessageCallback(on_debug_message, nullptr);
    GL.DebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

std::vector<std::string> take_errors() {
    std::vector<std::string> errors;
    {
        std::lock_guard lock(g_mutex);
        errors.swap(g_errors);
    }
    for (GLenum e = GL.GetError(); e != GL_NO_ERROR; e = GL.GetError()) {
        if (errors.empty()) {  // the debug message already names an error glGetError repeats
            errors.push_back(fmt::format("glGetError {:#x}", e));
        }
    }
    return errors;
}

void check_errors(const char* where) {
    const std::vector<std::string> errors = take_errors();
    if (!errors.empty()) {
        fail("{}: {}", where, fmt::join(errors, "; "));
    }
}

}  // namespace sl::gl
