#include "rtpp/source.h"

namespace rtpp {

std::string SourceFiles::place(SourcePos pos) const {
    if (pos.file < 0) return "rtpp";
    return (*this)[pos.file].name + ":" + std::to_string(pos.line) + ":" +
           std::to_string(pos.column);
}

std::string SourceFiles::describe(SourcePos pos, const std::string& message) const {
    std::string text = place(pos) + ": " + message;
    for (SourcePos from = pos.file < 0 ? SourcePos{} : (*this)[pos.file].included_from;
         from.file >= 0; from = (*this)[from.file].included_from)
        text += "\n  included from " + place(from);
    return text;
}

}  // namespace rtpp
