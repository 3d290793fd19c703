// The PLY reader: the header is read line by line into a description of the elements, the
// claimed counts are checked against the bytes that follow, and then one body reader (ASCII,
// little- or big-endian) walks the records, keeping x y z, nx ny nz and the face index lists.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "rt/error.h"
#include "scene/mesh_file.h"

namespace rt {

namespace {

using mesh_detail::parse_finite;
using mesh_detail::quoted_token;
using mesh_detail::text_place;

enum class Type : std::uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat, kDouble };

struct TypeName {
    std::string_view name;
    Type type;
};

// Both spellings of every scalar type: the original names and the sized ones.
constexpr TypeName kTypeNames[] = {
    {"char", Type::kInt8},      {"uchar", Type::kUint8},   {"short", Type::kInt16},
    {"ushort", Type::kUint16},  {"int", Type::kInt32},     {"uint", Type::kUint32},
    {"float", Type::kFloat},    {"double", Type::kDouble}, {"int8", Type::kInt8},
    {"uint8", Type::kUint8},    {"int16", Type::kInt16},   {"uint16", Type::kUint16},
    {"int32", Type::kInt32},    {"uint32", Type::kUint32}, {"float32", Type::kFloat},
    {"float64", Type::kDouble},
};

constexpr std::size_t size_of(Type t) {
    switch (t) {
        case Type::kInt8:
        case Type::kUint8:
            return 1;
        case Type::kInt16:
        case Type::kUint16:
            return 2;
        case Type::kInt32:
        case Type::kUint32:
        case Type::kFloat:
            return 4;
        case Type::kDouble:
            return 8;
    }
    return 1;
}

constexpr bool is_integer(Type t) { return t != Type::kFloat && t != Type::kDouble; }

constexpr std::int64_t lowest(Type t) {
    switch (t) {
        case Type::kInt8:
            return -128;
        case Type::kInt16:
            return -32768;
        case Type::kInt32:
            return -2147483648LL;
        default:
            return 0;
    }
}

constexpr std::int64_t highest(Type t) {
    switch (t) {
        case Type::kInt8:
            return 127;
        case Type::kUint8:
            return 255;
        case Type::kInt16:
            return 32767;
        case Type::kUint16:
            return 65535;
        case Type::kInt32:
            return 2147483647;
        default:
            return 4294967295LL;
    }
}

// What a property is used for: a coordinate of the position or the normal, the face's index
// list, or nothing.
enum Role : int { kX, kY, kZ, kNx, kNy, kNz, kIndices, kSkip };

struct Property {
    std::string name;
    bool list = false;
    Type count_type = Type::kUint8;
    Type type = Type::kFloat;
    std::string type_name;   // as spelled, for messages
    std::size_t offset = 0;  // of its header line's "property"
    Role role = kSkip;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    std::size_t offset = 0;  // of its header line's "element"
};

enum class Format { kAscii, kLittleEndian, kBigEndian };

struct Header {
    Format format = Format::kAscii;
    std::vector<Element> elements;
    std::size_t body = 0;  // the offset of the first byte after the header
    int vertex = -1;       // indices into elements, or -1
    int face = -1;
    bool normals = false;
};

std::string number_text(std::uint64_t n) { return std::to_string(n); }

// A header line's words: split at spaces and tabs.
struct Word {
    std::string_view text;
    std::size_t offset = 0;
};

class HeaderReader {
  public:
    HeaderReader(std::string_view bytes, const std::string& name, std::vector<std::string>& notes)
        : bytes_(bytes), name_(name), notes_(notes) {}

    Header read() {
        first_line();
        for (;;) {
            if (pos_ >= bytes_.size())
                fail(bytes_.size(), "expected 'end_header', found the end of the file");
            const std::size_t start = pos_;
            std::size_t end = start;
            while (end < bytes_.size() && bytes_[end] != '\n' && bytes_[end] != '\r') ++end;
            std::string_view terminator;
            if (end < bytes_.size()) {
                const bool crlf =
                    bytes_[end] == '\r' && end + 1 < bytes_.size() && bytes_[end + 1] == '\n';
                terminator = bytes_.substr(end, crlf ? 2 : 1);
            }
            pos_ = end + terminator.size();
            if (line(start, end)) break;
        }
        finish();
        return std::move(header_);
    }

  private:
    [[noreturn]] void fail(std::size_t offset, const std::string& what) const {
        const mesh_detail::TextPlace place = text_place(bytes_, offset);
        throw Error(name_ + ":" + number_text(place.line) + ":" + number_text(place.column) + ": " +
                    what);
    }

    void note(const std::string& text) {
        if (std::find(notes_.begin(), notes_.end(), text) == notes_.end()) notes_.push_back(text);
    }

    void first_line() {
        const std::string_view b = bytes_;
        if (b.substr(0, 4) == "ply\n") {
            eol_ = "\n";
        } else if (b.substr(0, 5) == "ply\r\n") {
            eol_ = "\r\n";
        } else if (b.substr(0, 4) == "ply\r") {
            eol_ = "\r";
        } else {
            std::size_t end = 0;
            while (end < b.size() && b[end] != '\n' && b[end] != '\r') ++end;
            fail(0, "expected the line 'ply', found " + quoted_token(b.substr(0, end)));
        }
        pos_ = 3 + eol_.size();
    }

    // Splits [start, end) into words; more than kMaxWords is an error at the first extra one.
    std::size_t split(std::size_t start, std::size_t end) {
        std::size_t n = 0;
        std::size_t i = start;
        for (;;) {
            while (i < end && (bytes_[i] == ' ' || bytes_[i] == '\t')) ++i;
            if (i == end) return n;
            const std::size_t word = i;
            while (i < end && bytes_[i] != ' ' && bytes_[i] != '\t') ++i;
            if (n == kMaxWords)
                fail(word, "expected the end of the line, found " +
                               quoted_token(bytes_.substr(word, i - word)));
            words_[n++] = {bytes_.substr(word, i - word), word};
        }
    }

    void expect_words(std::size_t have, std::size_t want, std::size_t end, const char* what) {
        if (have < want) fail(end, std::string("expected ") + what + ", found the end of the line");
        if (have > want)
            fail(words_[want].offset,
                 "expected the end of the line, found " + quoted_token(words_[want].text));
    }

    Type type_word(const Word& w, const char* what) const {
        for (const TypeName& t : kTypeNames)
            if (t.name == w.text) return t.type;
        fail(w.offset, std::string("expected ") + what +
                           " (char, uchar, short, ushort, int, uint, float, double, or int8 ... "
                           "float64), found " +
                           quoted_token(w.text));
    }

    // Handles one header line; returns true at end_header.
    bool line(std::size_t start, std::size_t end) {
        // Comments may hold anything, so they are recognised before splitting.
        std::size_t i = start;
        while (i < end && (bytes_[i] == ' ' || bytes_[i] == '\t')) ++i;
        const std::string_view rest = bytes_.substr(i, end - i);
        const auto is_word = [&](std::string_view keyword) {
            return rest.substr(0, keyword.size()) == keyword &&
                   (rest.size() == keyword.size() || rest[keyword.size()] == ' ' ||
                    rest[keyword.size()] == '\t');
        };
        if (is_word("comment")) return false;
        if (is_word("obj_info")) {
            note("PLY obj_info lines ignored");
            return false;
        }
        const std::size_t n = split(start, end);
        if (n == 0) return false;  // A blank line says nothing; it is not worth refusing.
        const Word& keyword = words_[0];
        if (keyword.text == "format") {
            expect_words(n, 3, end, "a format and the version 1.0");
            if (have_format_) fail(keyword.offset, "expected one format line, found a second");
            have_format_ = true;
            const std::string_view f = words_[1].text;
            if (f == "ascii") {
                header_.format = Format::kAscii;
            } else if (f == "binary_little_endian") {
                header_.format = Format::kLittleEndian;
            } else if (f == "binary_big_endian") {
                header_.format = Format::kBigEndian;
            } else {
                fail(words_[1].offset,
                     "expected ascii, binary_little_endian or binary_big_endian, found " +
                         quoted_token(f));
            }
            if (words_[2].text != "1.0")
                fail(words_[2].offset, "expected the version 1.0, found " + quoted_token(words_[2].text));
        } else if (keyword.text == "element") {
            expect_words(n, 3, end, "an element name and a count");
            Element e;
            e.name = std::string(words_[1].text);
            e.offset = keyword.offset;
            const std::string_view c = words_[2].text;
            const auto r = std::from_chars(c.data(), c.data() + c.size(), e.count);
            if (c.empty() || c[0] == '-' || r.ec != std::errc() || r.ptr != c.data() + c.size())
                fail(words_[2].offset, "expected a count (a whole number), found " + quoted_token(c));
            for (const Element& other : header_.elements)
                if (other.name == e.name && (e.name == "vertex" || e.name == "face"))
                    fail(words_[1].offset, "expected one element '" + e.name + "', found a second");
            if ((e.name == "vertex" || e.name == "face") && e.count > kMaxMeshElements)
                fail(words_[2].offset, "expected at most " + number_text(kMaxMeshElements) +
                                           " records in element '" + e.name + "', found " +
                                           number_text(e.count));
            header_.elements.push_back(std::move(e));
        } else if (keyword.text == "property") {
            if (header_.elements.empty())
                fail(keyword.offset, "expected an element line before the first property");
            Property p;
            p.offset = keyword.offset;
            if (n >= 2 && words_[1].text == "list") {
                expect_words(n, 5, end, "a count type, a value type and a name");
                p.list = true;
                p.count_type = type_word(words_[2], "a count type");
                if (!is_integer(p.count_type))
                    fail(words_[2].offset,
                         "expected an integer count type, found " + quoted_token(words_[2].text));
                p.type = type_word(words_[3], "a value type");
                p.type_name = std::string(words_[3].text);
                p.name = std::string(words_[4].text);
            } else {
                expect_words(n, 3, end, "a type and a name");
                p.type = type_word(words_[1], "a type");
                p.type_name = std::string(words_[1].text);
                p.name = std::string(words_[2].text);
            }
            Element& e = header_.elements.back();
            for (const Property& other : e.properties)
                if (other.name == p.name)
                    fail(words_[n - 1].offset, "expected a new property name in element '" +
                                                   e.name + "', found " + quoted_token(p.name) +
                                                   " a second time");
            e.properties.push_back(std::move(p));
        } else if (keyword.text == "end_header") {
            expect_words(n, 1, end, "");
            if (!have_format_) fail(keyword.offset, "expected a format line before end_header");
            // A binary body may start with any byte, so the header's last line must end as the
            // first did: a CR that ends the line and an LF that starts the body could not be
            // told apart from a CRLF otherwise.
            if (header_.format != Format::kAscii && end < bytes_.size()) {
                if (bytes_.substr(end, eol_.size()) != eol_)
                    fail(end,
                         "expected end_header's line to end as the 'ply' line does (the "
                         "binary body may start with any byte), found another line end");
                pos_ = end + eol_.size();
            }
            header_.body = pos_;
            return true;
        } else {
            fail(keyword.offset,
                 "expected a header line (format, element, property, comment, obj_info or "
                 "end_header), found " +
                     quoted_token(keyword.text));
        }
        return false;
    }

    // Gives the properties their roles and checks the counts against the bytes left.
    void finish() {
        for (std::size_t i = 0; i < header_.elements.size(); ++i) {
            Element& e = header_.elements[i];
            if (e.name == "vertex") {
                header_.vertex = static_cast<int>(i);
                vertex_roles(e);
            } else if (e.name == "face") {
                header_.face = static_cast<int>(i);
                face_roles(e);
            } else {
                note("PLY element '" + e.name + "' ignored");
            }
        }
        check_sizes();
    }

    void vertex_roles(Element& e) {
        static constexpr std::string_view kNames[] = {"x", "y", "z", "nx", "ny", "nz"};
        Property* found[6] = {};
        for (Property& p : e.properties) {
            for (int r = 0; r < 6; ++r) {
                if (p.name != kNames[r]) continue;
                if (p.list)
                    fail(p.offset,
                         "expected vertex property '" + p.name + "' to be a scalar, found a list");
                found[r] = &p;
            }
        }
        for (int r = 0; r < 3; ++r)
            if (found[r] == nullptr)
                fail(e.offset, "expected element 'vertex' to have a property '" +
                                   std::string(kNames[r]) + "', found none");
        header_.normals = found[kNx] && found[kNy] && found[kNz];
        for (int r = 0; r < (header_.normals ? 6 : 3); ++r) found[r]->role = static_cast<Role>(r);
        for (const Property& p : e.properties)
            if (p.role == kSkip) note("PLY vertex property '" + p.name + "' ignored");
    }

    void face_roles(Element& e) {
        Property* indices = nullptr;
        for (Property& p : e.properties) {
            if (indices != nullptr || (p.name != "vertex_indices" && p.name != "vertex_index"))
                continue;
            if (!p.list)
                fail(p.offset,
                     "expected face property '" + p.name + "' to be a list, found a scalar");
            if (!is_integer(p.type))
                fail(p.offset, "expected an integer type for the vertex indices, found " +
                                   quoted_token(p.type_name));
            indices = &p;
        }
        if (indices == nullptr)
            fail(e.offset,
                 "expected element 'face' to have a list 'vertex_indices' (or 'vertex_index'), "
                 "found none");
        indices->role = kIndices;
        for (const Property& p : e.properties)
            if (p.role == kSkip) note("PLY face property '" + p.name + "' ignored");
    }

    // Every record needs at least so many bytes (a binary scalar its size, a list its count;
    // an ASCII value a character and a separator), so a count the file cannot hold is refused
    // here, before anything is reserved or read.
    void check_sizes() const {
        const bool ascii = header_.format == Format::kAscii;
        // The last ASCII value needs no separator after it.
        std::uint64_t budget = bytes_.size() - header_.body + (ascii ? 1 : 0);
        for (const Element& e : header_.elements) {
            std::uint64_t least = 0;
            for (const Property& p : e.properties)
                least += ascii ? 2 : size_of(p.list ? p.count_type : p.type);
            if (least == 0) continue;
            if (e.count > budget / least)
                fail(e.offset, "expected at most " + number_text(budget / least) +
                                   " records in element '" + e.name + "' (each needs at least " +
                                   number_text(least) + " bytes, and " +
                                   number_text(bytes_.size() - header_.body) +
                                   " bytes follow the header), found " + number_text(e.count));
            budget -= e.count * least;
        }
    }

    static constexpr std::size_t kMaxWords = 5;
    std::string_view bytes_;
    const std::string& name_;
    std::vector<std::string>& notes_;
    std::size_t pos_ = 0;
    std::string_view eol_;
    bool have_format_ = false;
    Word words_[kMaxWords];
    Header header_;
};

// Reads records of a binary body. Offsets in messages count from the start of the file.
template <bool kBigEndian>
class BinaryBody {
  public:
    BinaryBody(std::string_view bytes, std::size_t body, const std::string& name)
        : bytes_(bytes), p_(bytes.data() + body), end_(bytes.data() + bytes.size()), name_(name) {}

    void start(const Element& e, std::uint64_t index) {
        element_ = &e;
        index_ = index;
    }

    // A scalar as a finite double.
    double number(const Property& p) {
        value_ = p_;
        double v = 0;
        switch (p.type) {
            case Type::kInt8:
                v = load<std::int8_t>(p);
                break;
            case Type::kUint8:
                v = load<std::uint8_t>(p);
                break;
            case Type::kInt16:
                v = load<std::int16_t>(p);
                break;
            case Type::kUint16:
                v = load<std::uint16_t>(p);
                break;
            case Type::kInt32:
                v = load<std::int32_t>(p);
                break;
            case Type::kUint32:
                v = load<std::uint32_t>(p);
                break;
            case Type::kFloat:
                v = load<float>(p);
                break;
            case Type::kDouble:
                v = load<double>(p);
                break;
        }
        if (!std::isfinite(v))
            fail("expected a finite value of property '" + p.name + "', found " +
                 (std::isnan(v) ? "NaN"
                  : v > 0       ? "infinity"
                                : "-infinity"));
        return v;
    }

    // A list's count; the caller checks it against the bytes left (list_fits).
    std::int64_t count(const Property& p) {
        value_ = p_;
        return integer(p, p.count_type);
    }

    // One integer value of a list.
    std::int64_t item(const Property& p) {
        value_ = p_;
        return integer(p, p.type);
    }

    void check_list(const Property& p, std::int64_t n) {
        if (n < 0) fail("expected a list count, found " + std::to_string(n));
        const auto size = static_cast<std::uint64_t>(n) * size_of(p.type);
        if (size > static_cast<std::uint64_t>(end_ - p_))
            fail("expected " + number_text(size) + " bytes for the " + number_text(n) +
                 " values of list '" + p.name + "', found " +
                 number_text(static_cast<std::uint64_t>(end_ - p_)));
    }

    void skip(const Property& p) {
        if (!p.list) {
            value_ = p_;
            advance(p, size_of(p.type));
            return;
        }
        const std::int64_t n = count(p);
        check_list(p, n);
        p_ += static_cast<std::uint64_t>(n) * size_of(p.type);
    }

    // What is left after the last element, for a note.
    std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }
    // The fewest bytes a face of one triangle takes: its count and three indices.
    static std::size_t least_triangle_face(const Property& p) {
        return size_of(p.count_type) + 3 * size_of(p.type);
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw Error(name_ + ": " + element_->name + " " + number_text(index_) + ", byte " +
                    number_text(static_cast<std::uint64_t>(value_ - bytes_.data())) + ": " + what);
    }

  private:
    void advance(const Property& p, std::size_t size) {
        if (static_cast<std::size_t>(end_ - p_) < size)
            fail("expected " + number_text(size) + " bytes of property '" + p.name + "' (" +
                 p.type_name + "), found " +
                 (p_ == end_ ? std::string("the end of the file")
                             : number_text(end_ - p_) + " before the end of the file"));
        p_ += size;
    }

    template <typename T>
    T load(const Property& p) {
        const char* at = p_;
        advance(p, sizeof(T));
        unsigned char raw[sizeof(T)];
        std::memcpy(raw, at, sizeof(T));
        // The file's order differs from the machine's: reverse the bytes.
        if constexpr (kBigEndian != (std::endian::native == std::endian::big))
            std::reverse(raw, raw + sizeof(T));
        T v;
        std::memcpy(&v, raw, sizeof(T));
        return v;
    }

    std::int64_t integer(const Property& p, Type t) {
        switch (t) {
            case Type::kInt8:
                return load<std::int8_t>(p);
            case Type::kUint8:
                return load<std::uint8_t>(p);
            case Type::kInt16:
                return load<std::int16_t>(p);
            case Type::kUint16:
                return load<std::uint16_t>(p);
            case Type::kInt32:
                return load<std::int32_t>(p);
            default:
                return load<std::uint32_t>(p);  // the header admits no other
        }
    }

    std::string_view bytes_;
    const char* p_;
    const char* end_;
    const char* value_ = nullptr;  // where the value being read starts
    const std::string& name_;
    const Element* element_ = nullptr;
    std::uint64_t index_ = 0;
};

bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// Reads records of an ASCII body: values separated by any white space (records need not keep
// to their lines). Values of float type are read as doubles: the decimal as written, without
// rounding it to float.
class AsciiBody {
  public:
    AsciiBody(std::string_view bytes, std::size_t body, const std::string& name)
        : bytes_(bytes), p_(bytes.data() + body), end_(bytes.data() + bytes.size()), name_(name) {}

    void start(const Element& e, std::uint64_t index) {
        element_ = &e;
        index_ = index;
    }

    double number(const Property& p) {
        const std::string_view w = word(p);
        if (is_integer(p.type)) return static_cast<double>(integer(p, p.type, w));
        double v = 0;
        if (parse_finite(w.data(), w.data() + w.size(), v) != w.data() + w.size())
            fail("expected a finite number for property '" + p.name + "', found " + quoted_token(w));
        return v;
    }

    std::int64_t count(const Property& p) { return integer(p, p.count_type, word(p)); }
    std::int64_t item(const Property& p) { return integer(p, p.type, word(p)); }

    void check_list(const Property& p, std::int64_t n) {
        // Every value needs at least a character and a separator; the last needs no separator.
        const auto left = static_cast<std::uint64_t>(end_ - p_);
        if (static_cast<std::uint64_t>(n) > (left + 1) / 2)
            fail("expected at most " + number_text((left + 1) / 2) + " values in list '" + p.name +
                 "' (" + number_text(left) + " bytes are left), found " + number_text(n));
    }

    void skip(const Property& p) {
        if (!p.list) {
            word(p);
            return;
        }
        const std::int64_t n = count(p);
        check_list(p, n);
        for (std::int64_t i = 0; i < n; ++i) word(p);
    }

    std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }
    // The fewest bytes a face of one triangle takes: four values and their separators.
    static std::size_t least_triangle_face(const Property&) { return 8; }

    // Whether anything but white space follows the last element, for a note.
    bool text_left() {
        while (p_ < end_ && is_space(*p_)) ++p_;
        return p_ < end_;
    }

    [[noreturn]] void fail(const std::string& what) const {
        const mesh_detail::TextPlace place =
            text_place(bytes_, static_cast<std::size_t>(value_ - bytes_.data()));
        throw Error(name_ + ":" + number_text(place.line) + ":" + number_text(place.column) + ": " +
                    element_->name + " " + number_text(index_) + ": " + what);
    }

  private:
    std::string_view word(const Property& p) {
        while (p_ < end_ && is_space(*p_)) ++p_;
        value_ = p_;
        if (p_ == end_)
            fail("expected a value of property '" + p.name + "' (" + p.type_name +
                 "), found the end of the file");
        const char* start = p_;
        while (p_ < end_ && !is_space(*p_)) ++p_;
        return {start, static_cast<std::size_t>(p_ - start)};
    }

    std::int64_t integer(const Property& p, Type t, std::string_view w) const {
        const char* b = w.data();
        const char* e = b + w.size();
        if (b < e && *b == '+') ++b;
        std::int64_t v = 0;
        const auto r = std::from_chars(b, e, v);
        if (b == e || (w[0] == '+' && *b == '-') || r.ec != std::errc() || r.ptr != e ||
            v < lowest(t) || v > highest(t))
            fail("expected an integer from " + std::to_string(lowest(t)) + " to " +
                 std::to_string(highest(t)) + " for property '" + p.name + "', found " + quoted_token(w));
        return v;
    }

    std::string_view bytes_;
    const char* p_;
    const char* end_;
    const char* value_ = nullptr;
    const std::string& name_;
    const Element* element_ = nullptr;
    std::uint64_t index_ = 0;
};

template <typename Body>
void read_vertices(Body& body, const Element& e, bool normals, MeshFile& mesh) {
    mesh.positions.reserve(e.count);
    if (normals) mesh.normals.reserve(e.count);
    double v[6] = {};
    for (std::uint64_t i = 0; i < e.count; ++i) {
        body.start(e, i);
        for (const Property& p : e.properties) {
            if (p.role == kSkip)
                body.skip(p);
            else
                v[p.role] = body.number(p);
        }
        mesh.positions.push_back({v[kX], v[kY], v[kZ]});
        if (normals) mesh.normals.push_back({v[kNx], v[kNy], v[kNz]});
    }
}

template <typename Body>
std::uint32_t read_index(Body& body, const Property& p, std::uint64_t vertex_count) {
    const std::int64_t k = body.item(p);
    if (k < 0 || static_cast<std::uint64_t>(k) >= vertex_count)
        body.fail(vertex_count == 0
                      ? "expected no vertex index (the file has no vertices), found " +
                            std::to_string(k)
                      : "expected a vertex index from 0 to " + number_text(vertex_count - 1) +
                            ", found " + std::to_string(k));
    return static_cast<std::uint32_t>(k);
}

template <typename Body>
void read_faces(Body& body, const Element& e, std::uint64_t vertex_count, MeshFile& mesh) {
    // Room for as many triangles as the faces and the bytes left can hold, whichever is
    // fewer: faces of fewer than three indices take a byte or two and give none.
    for (const Property& p : e.properties)
        if (p.role == kIndices)
            mesh.triangles.reserve(
                std::min<std::uint64_t>(e.count, body.left() / Body::least_triangle_face(p)));
    std::uint64_t short_faces = 0;
    for (std::uint64_t i = 0; i < e.count; ++i) {
        body.start(e, i);
        for (const Property& p : e.properties) {
            if (p.role == kSkip) {
                body.skip(p);
                continue;
            }
            const std::int64_t n = body.count(p);
            body.check_list(p, n);
            if (n < 3) {
                for (std::int64_t k = 0; k < n; ++k) read_index(body, p, vertex_count);
                ++short_faces;
                continue;
            }
            const std::uint32_t first = read_index(body, p, vertex_count);
            std::uint32_t previous = read_index(body, p, vertex_count);
            for (std::int64_t k = 2; k < n; ++k) {
                const std::uint32_t next = read_index(body, p, vertex_count);
                if (mesh.triangles.size() >= kMaxMeshElements)
                    body.fail("expected at most " + number_text(kMaxMeshElements) +
                              " triangles, found more");
                mesh.triangles.push_back({first, previous, next});
                previous = next;
            }
        }
    }
    if (short_faces > 0)
        mesh.notes.push_back("PLY faces of fewer than 3 vertices skipped (" +
                             number_text(short_faces) + ")");
}

template <typename Body>
void read_body(Body& body, const Header& h, MeshFile& mesh) {
    const std::uint64_t vertex_count =
        h.vertex < 0 ? 0 : h.elements[static_cast<std::size_t>(h.vertex)].count;
    for (std::size_t i = 0; i < h.elements.size(); ++i) {
        const Element& e = h.elements[i];
        if (static_cast<int>(i) == h.vertex) {
            read_vertices(body, e, h.normals, mesh);
        } else if (static_cast<int>(i) == h.face) {
            read_faces(body, e, vertex_count, mesh);
        } else if (!e.properties.empty()) {
            for (std::uint64_t r = 0; r < e.count; ++r) {
                body.start(e, r);
                for (const Property& p : e.properties) body.skip(p);
            }
        }
    }
}

}  // namespace

bool is_ply(std::string_view bytes) {
    return bytes.substr(0, 4) == "ply\n" || bytes.substr(0, 4) == "ply\r";
}

MeshFile read_mesh_file(std::string_view bytes, const std::string& display_name) {
    return is_ply(bytes) ? read_ply(bytes, display_name) : read_obj(bytes, display_name);
}

MeshFile read_ply(std::string_view bytes, const std::string& display_name) {
    MeshFile mesh;
    const Header h = HeaderReader(bytes, display_name, mesh.notes).read();
    if (h.format == Format::kAscii) {
        AsciiBody body(bytes, h.body, display_name);
        read_body(body, h, mesh);
        if (body.text_left()) mesh.notes.push_back("PLY text after the last element ignored");
    } else if (h.format == Format::kLittleEndian) {
        BinaryBody<false> body(bytes, h.body, display_name);
        read_body(body, h, mesh);
        if (body.left() > 0)
            mesh.notes.push_back("PLY bytes after the last element ignored (" +
                                 number_text(body.left()) + ")");
    } else {
        BinaryBody<true> body(bytes, h.body, display_name);
        read_body(body, h, mesh);
        if (body.left() > 0)
            mesh.notes.push_back("PLY bytes after the last element ignored (" +
                                 number_text(body.left()) + ")");
    }
    return mesh;
}

}  // namespace rt
