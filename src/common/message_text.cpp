// How messages show text that came from outside: a scene's tokens, file names, command-line
// values. Bytes that could drive a terminal are written as \xNN, so no input can move the
// cursor, retitle the window or hide what rt says.
#include "common/message_text.h"

#include <charconv>
#include <cstdint>
#include <cstdio>

namespace rt {

namespace {
// The length of the valid UTF-8 sequence at text[i] that encodes a printable character (not
// a C1 control, which some terminals obey), or 0.
std::size_t utf8_length(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    std::size_t n = 0;
    std::uint32_t code = 0;
    if (lead >= 0xc2 && lead <= 0xdf) {
        n = 2;
        code = lead & 0x1fu;
    } else if (lead >= 0xe0 && lead <= 0xef) {
        n = 3;
        code = lead & 0x0fu;
    } else if (lead >= 0xf0 && lead <= 0xf4) {
        n = 4;
        code = lead & 0x07u;
    } else {
        return 0;
    }
    if (i + n > text.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xc0u) != 0x80u) return 0;
        code = (code << 6) | (byte(i + k) & 0x3fu);
    }
    const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < least[n] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return 0;
    if (code >= 0x80 && code <= 0x9f) return 0;
    return n;
}

// The first bytes of text, escaped; `rest` is set to how many bytes were left out.
std::string escape_prefix(std::string_view text, std::size_t limit, std::size_t& rest) {
    std::string shown;
    std::size_t i = 0;
    while (i < text.size() && i < limit) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7f) {
            shown += static_cast<char>(c);
            ++i;
        } else if (const std::size_t n = utf8_length(text, i); n > 0) {
            shown.append(text.substr(i, n));
            i += n;
        } else {
            constexpr char kHex[] = "0123456789abcdef";
            shown += "\\x";
            shown += kHex[c >> 4];
            shown += kHex[c & 0xfu];
            ++i;
        }
    }
    rest = text.size() - i;
    return shown;
}

std::string length_note(std::string_view text) {
    return "... (" + std::to_string(text.size()) + " bytes)";
}
}  // namespace

std::string show_token(std::string_view text, std::size_t limit) {
    std::size_t rest = 0;
    std::string shown = escape_prefix(text, limit, rest);
    return rest > 0 ? shown + length_note(text) : shown;
}

std::string quote_token(std::string_view text, std::size_t limit) {
    std::size_t rest = 0;
    const std::string shown = escape_prefix(text, limit, rest);
    if (rest == 0) return "'" + shown + "'";
    return "'" + shown + "...'" + length_note(text).substr(3);
}

std::string printable_message(std::string_view message) {
    std::string shown;
    shown.reserve(message.size());
    std::size_t rest = 0;
    while (!message.empty()) {
        const std::size_t line_end = message.find('\n');
        shown += escape_prefix(message.substr(0, line_end), std::string_view::npos, rest);
        if (line_end == std::string_view::npos) break;
        shown += '\n';
        message.remove_prefix(line_end + 1);
    }
    return shown;
}

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string exact_number(double value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, value);
    return std::string(text, result.ptr);
}

}  // namespace rt
