#pragma once
// GLSL programs from the embedded shader files. `#include "path"` lines (paths relative to the
// project root) are expanded from the same embedded set, so one header can be shared between
// C++ and GLSL (gl/shaders/frame_uniforms.h).

#include <string>
#include <vector>

#include <glm/vec3.hpp>

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

// Runs the bound compute program over `threads` in work groups of `local` (the shader's
// local_size), then makes its image and buffer writes visible to the passes after it.
void dispatch_compute(glm::ivec3 threads, glm::ivec3 local);

}  // namespace sl::gl
