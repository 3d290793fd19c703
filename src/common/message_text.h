// How messages show text that came from outside (a scene's tokens, file names, command-line
// values): bytes that could drive a terminal (control characters, invalid UTF-8, C1
// controls) written as \xNN; valid UTF-8 kept.
#pragma once

#include <string>
#include <string_view>

namespace rt {

// The limit that shows text whole: file names, since a user needs all of one.
inline constexpr std::size_t kShowWhole = std::string_view::npos;

// A token as messages show it, in single quotes, cut to its first `limit` bytes (with its
// length said). The default is enough to recognise a token and too little to copy much of a
// file that is not a scene onto the terminal.
std::string quote_token(std::string_view text, std::size_t limit = 40);
// The same without the quotes, for numbers shown as written.
std::string show_token(std::string_view text, std::size_t limit = 40);

// A number rt computed as messages show it (%g: six significant digits); numbers read are
// shown as written.
std::string format_number(double value);
// The shortest text that reads back as exactly `value`, for records that must say what was
// used (the Options an image's metadata gives), where six digits would not do.
std::string exact_number(double value);

// A whole message made safe for a terminal, as the programs print every message: its lines
// kept, anything else escaped. Text already escaped is unchanged.
std::string printable_message(std::string_view message);

}  // namespace rt
