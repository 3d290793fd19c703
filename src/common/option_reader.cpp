#include "common/option_reader.h"

#include "common/message_text.h"

namespace rt {

OptionReader::OptionReader(const std::vector<std::string>& args, std::string_view short_with_value)
    : args_(args), short_with_value_(short_with_value) {}

bool OptionReader::next() {
    if (!options_ended_ && next_ < args_.size() && args_[next_] == "--") {
        options_ended_ = true;
        ++next_;
    }
    if (next_ >= args_.size()) return false;
    name_ = args_[next_++];
    has_joined_value_ = false;
    joined_value_.clear();
    is_option_ = !options_ended_ && name_.size() > 1 && name_[0] == '-';
    if (!is_option_) return true;
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

void OptionReader::unknown() const { throw UsageError{"unknown option " + quote_token(name_)}; }

}  // namespace rt
