#include "batch/depfile.h"

#include "rt/error.h"

namespace rt {

std::string make_escape(std::string_view path) {
    std::string out;
    std::size_t backslashes = 0;  // the run just copied
    for (const char c : path) {
        if (c == '\n' || c == '%')
            throw Error("-M: cannot write '" + std::string(path) +
                        "' in a make rule: a newline or '%' in a name has no escape there");
        if (c == '\\') {
            ++backslashes;
            out += c;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '#' || c == ':' || c == '*' || c == '?' || c == '[') {
            out.append(backslashes, '\\');  // a backslash before an escape is doubled
            out += '\\';
        } else if (c == '$') {
            out += '$';
        }
        out += c;
        backslashes = 0;
    }
    out.append(backslashes, '\\');  // a trailing backslash must not escape what follows
    return out;
}

std::string make_rule(std::string_view target, const std::vector<std::string>& dependencies) {
    // Appended piece by piece: g++ 12 warns falsely about "literal" + std::string.
    std::string rule = make_escape(target);
    rule += ':';
    for (const std::string& dependency : dependencies) {
        rule += " \\\n  ";
        rule += make_escape(dependency);
    }
    rule += '\n';
    for (const std::string& dependency : dependencies) {
        rule += '\n';
        rule += make_escape(dependency);
        rule += ":\n";
    }
    return rule;
}

}  // namespace rt
