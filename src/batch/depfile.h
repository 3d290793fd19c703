// The make rule that -M writes: the image depends on the scene and its textures.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rt {

// A path as make reads it in a rule: blanks, '#', ':', wildcards and the backslashes before
// them escaped with a backslash, '$' doubled. Throws rt::Error for a newline or '%', which
// no rule can hold as a plain name (a '%' target is a pattern rule).
std::string make_escape(std::string_view path);

// "TARGET: DEP...", then an empty rule "DEP:" for each dependency (as cc -MP writes), so
// that make does not stop when a dependency is deleted or renamed.
std::string make_rule(std::string_view target, const std::vector<std::string>& dependencies);

}  // namespace rt
