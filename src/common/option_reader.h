// The command-line conventions rt, rtpp and rtimg share, read in one place, as getopt reads
// them: "--name=value" or "--name value", "-xVALUE" or "-x VALUE" for the short options that
// take a value, short options bundled ("-qr" is "-q -r"; in "-qoout.png" the rest after a
// letter that takes a value is its value), "--" ending the options, and "-" alone an operand
// (standard input or output). A misspelt option gets the nearest the program has suggested.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rt {

// The word among `candidates` nearest to `word` (edit distance at most 2, and less than half
// its length), or "" when none is near enough: for "did you mean" in messages.
std::string nearest_word(std::string_view word, const std::vector<std::string>& candidates);

// A mistake on the command line: the programs print it with a pointer to --help, exit 2.
struct UsageError {
    std::string message;
};

// The numbers options take, read by one rule in rt and rtimg: decimal, as std::from_chars
// reads it (no hexadecimal, infinity or NaN), with one leading '+' allowed before a digit or
// '.' (+5, +.5), as strtod would. A value out of range is refused saying so, however many
// digits it has. Both throw UsageError naming `option`.
int parse_whole_number(const std::string& option, const std::string& text, int min, int max);
// A number >= 0; one too close to 0 to be told from it (1e-400) is refused, not taken as 0.
double parse_nonnegative(const std::string& option, const std::string& text);

class OptionReader {
  public:
    // `short_with_value` lists the letters of the short options that take a value ("do" for
    // -d and -o), which may then be written joined to it (-d7).
    OptionReader(const std::vector<std::string>& args, std::string_view short_with_value);

    // Moves to the next argument; false when none is left. "--" itself is skipped.
    bool next();
    // Whether the argument is an option ("-x", "--name"); operands are not, nor is anything
    // after "--".
    bool is_option() const { return is_option_; }
    // The option's name without a value written with it, or the operand as given.
    const std::string& argument() const { return name_; }
    // The option's value: written with it, or else the next argument.
    std::string value();
    // Refuses a value written with an option that takes none (--quiet=1).
    void no_value() const;
    // The error for an option the program does not have; `help` is the program's --help
    // text, whose "--name" words are the options a near miss is matched against.
    [[noreturn]] void unknown(std::string_view help = {}) const;

  private:
    const std::vector<std::string>& args_;
    std::string_view short_with_value_;
    std::size_t next_ = 0;
    bool options_ended_ = false;
    bool is_option_ = false;
    std::string name_;
    std::string joined_value_;
    bool has_joined_value_ = false;
    std::string bundled_;  // short options still to come from one argument ("r" of "-qr")
    std::string written_;  // the argument as written, for messages
};

}  // namespace rt
