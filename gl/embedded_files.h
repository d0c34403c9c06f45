#pragma once
// Files embedded into the binary at build time (cmake/embed_files.cmake), keyed by their path
// relative to the project root, e.g. "frame/shaders/surface.frag".

#include <map>
#include <string_view>

namespace sl::gl {

const std::map<std::string_view, std::string_view>& embedded_files();

}  // namespace sl::gl
