// Character classes of the plain-text formats rt reads (its scene format, and PPM and PFM
// headers), which are ASCII whatever the locale, unlike <cctype>'s.
#pragma once

namespace rt {

// Space, tab, line feed, carriage return, vertical tab, form feed: C's isspace in the "C"
// locale, and the whitespace of PPM and PFM headers.
inline bool is_ascii_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

}  // namespace rt
