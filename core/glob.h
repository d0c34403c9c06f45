#pragma once
// Glob patterns over names: '*' matches any run of characters, '?' any one; every other character
// itself. How scene files pick the parts of a model by their node or material name.

#include <string_view>

namespace sl {

bool glob_match(std::string_view pattern, std::string_view text);

}  // namespace sl
