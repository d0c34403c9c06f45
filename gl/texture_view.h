#pragma once
// A texture a pass declares for inspection (the viewer's buffer previewer): 2D, float or depth
// (depth textures are read with comparison off). Valid until the next frame or prepare().

#include <string>
#include <vector>

#include "gl/functions.h"

namespace sl::gl {

struct TextureView {
    std::string name;  // "<owner>/<what>", e.g. "frame/shadow map", "march/intervals 0"
    GLuint texture = 0;
};
using TextureViews = std::vector<TextureView>;

}  // namespace sl::gl
