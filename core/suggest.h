#pragma once
// "Did you mean …?" for a name that is not one of the known ones (an unknown key, method,
// parameter or scene): the known name nearest by edit distance, when it is near enough to be a
// slip of the keyboard rather than another word.

#include <string>
#include <string_view>
#include <vector>

namespace sl {

// The Damerau-Levenshtein distance (optimal string alignment: insertions, deletions,
// substitutions and swaps of neighbours each count 1).
size_t edit_distance(std::string_view a, std::string_view b);

// The known name nearest to `name`, if its distance is at most 2 and at most a third of the
// longer name's length; empty otherwise. Ties go to the first in `known`.
std::string nearest_name(std::string_view name, const std::vector<std::string>& known);

// " (did you mean 'NAME'?)" for nearest_name(), or "" when there is none: for the end of a
// message.
std::string did_you_mean(std::string_view name, const std::vector<std::string>& known);

}  // namespace sl
