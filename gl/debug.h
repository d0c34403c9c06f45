#pragma once
// KHR_debug: every GL error the driver reports is recorded (synchronously, in the call that caused
// it) and turned into an sl::Error by check_errors(); tests fail on any recorded error. The
// callback never throws itself: an exception must not unwind through the driver's C frames.

#include <string>
#include <vector>

namespace sl::gl {

void install_debug_callback();

// Errors recorded since the last call (and glGetError's, for drivers that report only there).
std::vector<std::string> take_errors();

// Throws sl::Error listing the recorded errors, prefixed with `where`, if there are any.
void check_errors(const char* where);

}  // namespace sl::gl
