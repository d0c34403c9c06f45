#pragma once
// GLSL programs from the embedded shader files. `#include "path"` lines (paths relative to the
// project root) are expanded from the same embedded set, so one header can be shared between
// C++ and GLSL (gl/shaders/frame_uniforms.h).

#include <string>
#include <vector>

#include "gl/objects.h"

namespace sl::gl {

struct ShaderStage {
    GLenum type;       // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
    std::string path;  // embedded file, e.g. "frame/shaders/surface.frag"
};

// The source of an embedded file with its includes expanded and `defines` inserted after the
// #version line. Throws sl::Error for an unknown file or a circular include.
std::string shader_source(const std::string& path, const std::vector<std::string>& defines = {});

// Compiles and links; throws sl::Error with the info log and the file name on failure.
Program create_program(const std::vector<ShaderStage>& stages,
                       const std::vector<std::string>& defines = {});

}  // namespace sl::gl
