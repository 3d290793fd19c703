#include "common/option_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "common/message_text.h"

namespace rt {

namespace {

// The text of a number without the leading '+' a user may write (+5); from_chars takes none.
std::string_view unsigned_text(const std::string& text) {
    std::string_view view(text);
    if (view.size() > 1 && view[0] == '+' && ((view[1] >= '0' && view[1] <= '9') || view[1] == '.'))
        view.remove_prefix(1);
    return view;
}

}  // namespace

int parse_whole_number(const std::string& option, const std::string& text, int min, int max) {
    const std::string_view digits = unsigned_text(text);
    long long value = 0;
    const char* end = digits.data() + digits.size();
    const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
    const std::string range = option + " " + show_token(text) + " is out of range (" +
                              std::to_string(min) + " to " + std::to_string(max) + ")";
    if (ec == std::errc::result_out_of_range && ptr == end) throw UsageError{range};
    if (ec != std::errc() || ptr != end || digits.empty())
        throw UsageError{option + " expects a whole number, got " + quote_token(text)};
    if (value < min || value > max) throw UsageError{range};
    return static_cast<int>(value);
}

double parse_nonnegative(const std::string& option, const std::string& text) {
    const std::string_view digits = unsigned_text(text);
    double value = 0;
    const char* end = digits.data() + digits.size();
    const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
    // Out of range is too large or, closer to 0 than a double can be and not 0, too small.
    if (ec == std::errc::result_out_of_range && ptr == end) {
        if (std::fabs(std::strtod(std::string(digits).c_str(), nullptr)) < 1)
            throw UsageError{option + " " + show_token(text) +
                             " is too small to tell from 0 (below about 4.9e-324); write 0"};
        throw UsageError{option + " " + show_token(text) +
                         " is out of range (above about 1.8e308)"};
    }
    if (ec != std::errc() || ptr != end || digits.empty() || !std::isfinite(value) || value < 0)
        throw UsageError{option + " expects a number >= 0, got " + quote_token(text)};
    return value;
}

OptionReader::OptionReader(const std::vector<std::string>& args, std::string_view short_with_value)
    : args_(args), short_with_value_(short_with_value) {}

bool OptionReader::next() {
    has_joined_value_ = false;
    joined_value_.clear();
    if (!bundled_.empty()) {
        // The next letter of a bundle: an option like any, its value the rest if it takes one.
        name_ = std::string("-") + bundled_[0];
        bundled_.erase(0, 1);
        is_option_ = true;
        if (short_with_value_.find(name_[1]) != std::string_view::npos && !bundled_.empty()) {
            joined_value_ = std::move(bundled_);
            bundled_.clear();
            has_joined_value_ = true;
        }
        return true;
    }
    if (!options_ended_ && next_ < args_.size() && args_[next_] == "--") {
        options_ended_ = true;
        ++next_;
    }
    if (next_ >= args_.size()) return false;
    name_ = args_[next_++];
    written_ = name_;
    is_option_ = !options_ended_ && name_.size() > 1 && name_[0] == '-';
    if (!is_option_) return true;
    if (name_[1] != '-' && name_.size() > 2 &&
        short_with_value_.find(name_[1]) == std::string_view::npos) {
        // "-qr": -q now, the rest next.
        bundled_ = name_.substr(2);
        name_.resize(2);
        return true;
    }
    if (name_[1] == '-') {
        if (const auto eq = name_.find('='); eq != std::string::npos) {
            joined_value_ = name_.substr(eq + 1);
            name_.resize(eq);
            has_joined_value_ = true;
        }
    } else if (name_.size() > 2 && short_with_value_.find(name_[1]) != std::string_view::npos) {
        joined_value_ = name_.substr(2);
        name_.resize(2);
        has_joined_value_ = true;
    }
    return true;
}

std::string OptionReader::value() {
    if (has_joined_value_) return joined_value_;
    if (next_ >= args_.size()) throw UsageError{show_token(name_) + " needs a value"};
    return args_[next_++];
}

void OptionReader::no_value() const {
    if (has_joined_value_) throw UsageError{show_token(name_) + " takes no value"};
}

std::string nearest_word(std::string_view word, const std::vector<std::string>& candidates) {
    // Edit distance with adjacent transpositions counting one ("bleu" is one from "blue"),
    // the optimal string alignment variant: words here are short, so a whole table is fine.
    const auto distance = [](std::string_view a, std::string_view b) {
        const std::size_t w = b.size() + 1;
        std::vector<std::size_t> d((a.size() + 1) * w);
        const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * w + j]; };
        for (std::size_t i = 0; i <= a.size(); ++i) at(i, 0) = i;
        for (std::size_t j = 0; j <= b.size(); ++j) at(0, j) = j;
        for (std::size_t i = 1; i <= a.size(); ++i)
            for (std::size_t j = 1; j <= b.size(); ++j) {
                at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1,
                                     at(i - 1, j - 1) + (a[i - 1] == b[j - 1] ? 0 : 1)});
                if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                    at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
            }
        return at(a.size(), b.size());
    };
    std::string best;
    std::size_t best_distance = 3;
    for (const std::string& candidate : candidates) {
        const std::size_t d = distance(word, candidate);
        if (d < best_distance && 2 * d < word.size()) {
            best = candidate;
            best_distance = d;
        }
    }
    return best;
}

void OptionReader::unknown(std::string_view help) const {
    std::string message = "unknown option " + quote_token(name_);
    if (written_ != name_ && written_.rfind("--", 0) != 0)
        message += " (in " + quote_token(written_) + ")";
    // The long options the help lists: every "--word" in it.
    std::vector<std::string> known;
    for (std::size_t at = help.find("--"); at != std::string_view::npos;
         at = help.find("--", at + 2)) {
        std::size_t end = at + 2;
        while (end < help.size() &&
               (std::isalnum(static_cast<unsigned char>(help[end])) != 0 || help[end] == '-'))
            ++end;
        if (end > at + 2) known.emplace_back(help.substr(at, end - at));
    }
    if (const std::string near = nearest_word(name_, known); !near.empty())
        message += "; did you mean '" + near + "'?";
    throw UsageError{message};
}

}  // namespace rt
