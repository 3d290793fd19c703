#include "rtpp/parser.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <stdexcept>

#include "rtpp/lexer.h"

namespace rtpp {

namespace {

constexpr const char* kReservedWords[] = {"let",   "for", "to", "step", "if",   "else",  "include",
                                          "about", "and", "or", "not",  "true", "false", "pi"};

// Why an include cannot be read although something is there: not a regular file.
struct NotRegular {
    std::string kind;
};

std::string kind_of(const struct stat& st) {
    return S_ISFIFO(st.st_mode)   ? "a FIFO"
           : S_ISCHR(st.st_mode)  ? "a character device"
           : S_ISBLK(st.st_mode)  ? "a block device"
           : S_ISSOCK(st.st_mode) ? "a socket"
                                  : "not a file";
}

// Reads a whole file, as rt reads a texture: false when there is nothing to read (no such
// file, a directory, no permission), so that the next candidate is tried. Only a regular
// file is read, since a FIFO or a device could block rtpp for ever or feed it without end;
// it is checked again on the open file, which O_NONBLOCK keeps from blocking on a FIFO put
// there meanwhile. A file larger than the limit is refused before it is read.
bool read_source(const std::filesystem::path& path, std::size_t max_size, std::string& text) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || S_ISDIR(st.st_mode)) return false;
    if (!S_ISREG(st.st_mode)) throw NotRegular{kind_of(st)};
    if (static_cast<std::uintmax_t>(st.st_size) > max_size) throw std::length_error("too large");
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return false;
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    if (::fstat(fd, &st) != 0) return false;
    if (!S_ISREG(st.st_mode)) throw NotRegular{kind_of(st)};
    text.clear();
    char chunk[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) break;
        text.append(chunk, static_cast<std::size_t>(n));
        if (text.size() > max_size) {
            text.clear();
            throw std::length_error("too large");
        }
    }
    return true;
}

class Parser {
  public:
    Parser(SourceFiles& files, const ParseOptions& options, std::vector<std::string>& open_files)
        : files_(files), options_(options), open_files_(open_files) {}

    Block parse_file(const std::string& text, int file) {
        tokens_ = tokenize(text, file, options_.limits);
        next_ = 0;
        Block block;
        while (peek().kind != TokenKind::end) parse_statement(block, true);
        return block;
    }

  private:
    // Counts nesting while the parser recurses, so that no input can exhaust the stack.
    class Nest {
      public:
        Nest(Parser& parser, SourcePos pos) : parser_(parser) {
            if (++parser_.depth_ > parser_.options_.limits.nesting) parser_.too_deep(pos);
        }
        ~Nest() { --parser_.depth_; }
        Nest(const Nest&) = delete;
        Nest& operator=(const Nest&) = delete;

      private:
        Parser& parser_;
    };

    [[noreturn]] void too_deep(SourcePos pos) const {
        fail(pos, "nested more than " + std::to_string(options_.limits.nesting) +
                      " deep (blocks, parentheses, objects and operators count)");
    }

    // An expression built from its operands: its height is one more than its highest
    // operand's. A chain such as 1 + 1 + ... + 1, built by a loop rather than by recursion,
    // grows the tree as surely as parentheses do, so its height counts towards the nesting
    // limit together with the depth at which it is parsed.
    Expr finished(Expr e) const {
        int highest = 0;
        for (const Expr& arg : e.args) highest = std::max(highest, arg.height);
        e.height = highest + 1;
        if (depth_ + e.height > options_.limits.nesting) too_deep(e.pos);
        return e;
    }

    const Token& peek(std::size_t ahead = 0) const {
        return tokens_[std::min(next_ + ahead, tokens_.size() - 1)];
    }
    const Token& take() {
        const Token& token = tokens_[next_];
        if (next_ + 1 < tokens_.size()) ++next_;
        return token;
    }
    bool accept(std::string_view punct) {
        if (!peek().is(punct)) return false;
        take();
        return true;
    }
    const Token& expect(std::string_view punct, const std::string& what) {
        if (!peek().is(punct))
            fail(peek().pos,
                 "expected '" + std::string(punct) + "' " + what + ", got " + describe(peek()));
        return take();
    }
    std::string expect_name(const std::string& what) {
        if (peek().kind != TokenKind::name)
            fail(peek().pos, "expected " + what + ", got " + describe(peek()));
        return take().text;
    }
    bool accept_word(std::string_view word) {
        if (!peek().is_name(word)) return false;
        take();
        return true;
    }

    std::shared_ptr<const Block> parse_braced_block(const std::string& what, SourcePos opened) {
        const Nest nest(*this, peek().pos);
        expect("{", "to open " + what);
        auto block = std::make_shared<Block>();
        while (!peek().is("}")) {
            if (peek().kind == TokenKind::end)
                fail(peek().pos, "end of file inside " + what + " begun at " +
                                     std::to_string(opened.line) + ":" +
                                     std::to_string(opened.column) + ": expected '}'");
            parse_statement(*block);
        }
        take();
        return block;
    }

    void parse_statement(Block& block, bool top_level = false) {
        if (accept(";")) return;
        const Token& first = peek();
        const SourcePos pos = first.pos;
        // A number where a top-level statement starts is most likely rt's numeric format,
        // which rt reads itself: say so, rather than only what was expected.
        if (first.kind == TokenKind::number && top_level)
            fail(pos, "expected a statement (a field, an object, let, for, if or include), got " +
                          describe(first) + "\n" + files_.place(pos) +
                          ": note: this looks like rt's numeric scene format, which rt reads as "
                          "it is: rt SCENE -o IMAGE (rtpp compiles the readable language)");
        if (first.kind != TokenKind::name)
            fail(pos, "expected a statement (a field, an object, let, for, if or include), got " +
                          describe(first));
        Stmt stmt;
        stmt.pos = pos;
        const std::string word = take().text;
        if (word == "let") {
            stmt.kind = Stmt::Kind::let;
            stmt.name = expect_name("a name after let");
            if (is_reserved_word(stmt.name))
                fail(pos, "'" + stmt.name + "' is a reserved word and cannot name a value");
            expect("=", "after let " + stmt.name);
            stmt.args.push_back(parse_expression());
        } else if (word == "for") {
            stmt.kind = Stmt::Kind::loop;
            stmt.name = expect_name("a loop variable after for");
            if (is_reserved_word(stmt.name))
                fail(pos, "'" + stmt.name + "' is a reserved word and cannot name a value");
            expect("=", "after for " + stmt.name);
            stmt.args.push_back(parse_bare_expression());
            if (!accept_word("to"))
                fail(peek().pos, "expected 'to' in the for loop, got " + describe(peek()));
            stmt.args.push_back(parse_bare_expression());
            if (accept_word("step")) stmt.args.push_back(parse_bare_expression());
            stmt.body = parse_braced_block("the for loop", pos);
        } else if (word == "if") {
            parse_if(stmt);
        } else if (word == "include") {
            parse_include(block, pos);
            return;
        } else if (is_reserved_word(word)) {
            fail(pos, "'" + word + "' cannot start a statement");
        } else if (peek().is("{")) {
            stmt.kind = Stmt::Kind::object;
            next_--;  // the name is the object expression's own
            stmt.args.push_back(parse_expression());
        } else {
            stmt.kind = Stmt::Kind::field;
            stmt.name = word;
            stmt.args.push_back(parse_expression());
            if (word == "rotate") {
                if (!accept_word("about"))
                    fail(peek().pos, "expected 'about' and an axis after rotate's angle, got " +
                                         describe(peek()));
                stmt.args.push_back(parse_expression());
            } else {
                while (accept(",")) stmt.args.push_back(parse_expression());
            }
        }
        block.push_back(std::move(stmt));
    }

    void parse_if(Stmt& stmt) {
        stmt.kind = Stmt::Kind::branch;
        stmt.args.push_back(parse_bare_expression());
        stmt.body = parse_braced_block("the if", stmt.pos);
        if (!accept_word("else")) return;
        if (peek().is_name("if")) {
            // else if: an else block holding one if, as deep in the tree as a braced block.
            const Nest nest(*this, peek().pos);
            Stmt nested;
            nested.pos = take().pos;
            parse_if(nested);
            auto block = std::make_shared<Block>();
            block->push_back(std::move(nested));
            stmt.else_body = std::move(block);
        } else {
            stmt.else_body = parse_braced_block("the else", stmt.pos);
        }
    }

    void parse_include(Block& block, SourcePos pos) {
        if (peek().kind != TokenKind::string)
            fail(peek().pos, "expected a \"file name\" after include, got " + describe(peek()));
        const std::string written = take().text;
        if (written.empty()) fail(pos, "include needs a file name");
        if (static_cast<int>(open_files_.size()) >= options_.limits.include_depth)
            fail(pos, "includes nested more than " + std::to_string(options_.limits.include_depth) +
                          " deep");
        if (files_.includes_read >= options_.limits.includes)
            fail(pos, "more than " + std::to_string(options_.limits.includes) +
                          " includes read in all (a file included twice counts twice)");
        // The including file's directory first, then each -I directory in order.
        std::vector<std::filesystem::path> candidates;
        const std::filesystem::path as_written(written);
        if (as_written.is_absolute()) {
            candidates.push_back(as_written);
        } else {
            candidates.push_back(files_[pos.file].path.parent_path() / as_written);
            for (const auto& dir : options_.include_dirs) candidates.push_back(dir / as_written);
        }
        for (const auto& candidate : candidates) {
            std::string text;
            try {
                if (!read_source(candidate, options_.limits.file_size, text)) continue;
            } catch (const std::length_error&) {
                fail(pos, "included file '" + candidate.string() + "' is larger than " +
                              std::to_string(options_.limits.file_size) + " bytes");
            } catch (const NotRegular& e) {
                fail(pos, "included file '" + candidate.string() + "' is not a regular file (" +
                              e.kind + ")");
            }
            if (!files_.count_text(text.size(), options_.limits.source_total))
                fail(pos, "more than " + std::to_string(options_.limits.source_total) +
                              " bytes of source read in all (a file included twice counts "
                              "twice)");
            ++files_.includes_read;
            std::error_code ec;
            std::filesystem::path canonical = std::filesystem::weakly_canonical(candidate, ec);
            if (ec) canonical = candidate;
            for (const std::string& open : open_files_)
                if (open == canonical.string())
                    fail(pos, "include cycle: '" + written + "' is already being read");
            const int file = files_.add({candidate.lexically_normal().string(), candidate, pos});
            open_files_.push_back(canonical.string());
            Parser inner(files_, options_, open_files_);
            inner.depth_ = depth_;
            Stmt stmt;
            stmt.kind = Stmt::Kind::block;
            stmt.pos = pos;
            stmt.body = std::make_shared<const Block>(inner.parse_file(text, file));
            open_files_.pop_back();
            block.push_back(std::move(stmt));
            return;
        }
        std::string looked;
        for (const auto& candidate : candidates)
            looked += (looked.empty() ? "" : ", ") + ("'" + candidate.string() + "'");
        fail(pos, "cannot read included file '" + written + "' (looked for " + looked + ")");
    }

    // An expression in which `name {` is not an object: an if's condition or a loop's bounds,
    // which a block follows.
    Expr parse_bare_expression() {
        const bool saved = objects_allowed_;
        objects_allowed_ = false;
        Expr e = parse_expression();
        objects_allowed_ = saved;
        return e;
    }

    Expr parse_expression() {
        const Nest nest(*this, peek().pos);
        return parse_or();
    }

    Expr binary(std::string op, Expr lhs, Expr rhs, SourcePos pos) const {
        Expr e;
        e.kind = Expr::Kind::binary;
        e.pos = pos;
        e.text = std::move(op);
        e.args.push_back(std::move(lhs));
        e.args.push_back(std::move(rhs));
        return finished(std::move(e));
    }

    Expr parse_or() {
        Expr lhs = parse_and();
        while (peek().is_name("or")) {
            const SourcePos pos = take().pos;
            lhs = binary("or", std::move(lhs), parse_and(), pos);
        }
        return lhs;
    }
    Expr parse_and() {
        Expr lhs = parse_not();
        while (peek().is_name("and")) {
            const SourcePos pos = take().pos;
            lhs = binary("and", std::move(lhs), parse_not(), pos);
        }
        return lhs;
    }
    Expr parse_not() {
        if (!peek().is_name("not")) return parse_comparison();
        const Nest nest(*this, peek().pos);
        Expr e;
        e.kind = Expr::Kind::unary;
        e.pos = take().pos;
        e.text = "not";
        e.args.push_back(parse_not());
        return finished(std::move(e));
    }
    Expr parse_comparison() {
        Expr lhs = parse_sum();
        for (const char* op : {"<", "<=", ">", ">=", "==", "!="}) {
            if (peek().is(op)) {
                const SourcePos pos = take().pos;
                return binary(op, std::move(lhs), parse_sum(), pos);
            }
        }
        return lhs;
    }
    Expr parse_sum() {
        Expr lhs = parse_product();
        while (peek().is("+") || peek().is("-")) {
            const Token& op = take();
            const std::string text = op.text;
            lhs = binary(text, std::move(lhs), parse_product(), op.pos);
        }
        return lhs;
    }
    Expr parse_product() {
        Expr lhs = parse_unary();
        while (peek().is("*") || peek().is("/") || peek().is("%")) {
            const Token& op = take();
            const std::string text = op.text;
            lhs = binary(text, std::move(lhs), parse_unary(), op.pos);
        }
        return lhs;
    }
    // Unary minus binds looser than ^, as in mathematics: -2^2 is -4.
    Expr parse_unary() {
        if (!peek().is("-") && !peek().is("+")) return parse_power();
        const Nest nest(*this, peek().pos);
        Expr e;
        e.kind = Expr::Kind::unary;
        e.pos = peek().pos;
        e.text = take().text;
        e.args.push_back(parse_unary());
        return finished(std::move(e));
    }
    // ^ is right-associative: 2^3^2 is 2^9.
    Expr parse_power() {
        Expr base = parse_postfix();
        if (!peek().is("^")) return base;
        const SourcePos pos = take().pos;
        const Nest nest(*this, pos);
        return binary("^", std::move(base), parse_unary(), pos);
    }
    Expr parse_postfix() {
        Expr e = parse_primary();
        while (peek().is(".")) {
            const SourcePos pos = take().pos;
            Expr member;
            member.kind = Expr::Kind::member;
            member.pos = pos;
            member.text = expect_name("x, y or z after '.'");
            if (member.text != "x" && member.text != "y" && member.text != "z")
                fail(pos, "a vector has components x, y and z, not '" + member.text + "'");
            member.args.push_back(std::move(e));
            e = finished(std::move(member));
        }
        return e;
    }

    Expr parse_primary() {
        const Token& token = peek();
        Expr e;
        e.pos = token.pos;
        switch (token.kind) {
            case TokenKind::number:
                e.kind = Expr::Kind::number;
                e.value = take().number;
                return e;
            case TokenKind::string:
                e.kind = Expr::Kind::string;
                e.text = take().text;
                return e;
            case TokenKind::name:
                return parse_name();
            case TokenKind::end:
                fail(token.pos, "expected a value, got end of file");
            case TokenKind::punct:
                break;
        }
        if (accept("(")) {
            const bool saved = objects_allowed_;
            objects_allowed_ = true;
            e = parse_expression();
            objects_allowed_ = saved;
            expect(")", "to close the '(' at " + std::to_string(token.pos.line) + ":" +
                            std::to_string(token.pos.column));
            return e;
        }
        if (accept("<")) {
            // Components are sums, not comparisons, so the closing '>' is never read as
            // "greater than"; parenthesise a comparison to use one inside a vector.
            e.kind = Expr::Kind::vector;
            const Nest nest(*this, e.pos);
            for (int i = 0; i < 3; ++i) {
                if (i > 0) expect(",", "between a vector's components");
                e.args.push_back(parse_sum());
            }
            if (peek().is(","))
                fail(peek().pos, "a vector has three components <x, y, z>, not more");
            expect(">", "to close the vector");
            return finished(std::move(e));
        }
        fail(token.pos, "expected a value, got " + describe(token));
    }

    Expr parse_name() {
        Expr e;
        e.pos = peek().pos;
        e.text = take().text;
        if (e.text == "true" || e.text == "false") {
            e.kind = Expr::Kind::number;
            e.value = e.text == "true" ? 1 : 0;
            return e;
        }
        if (is_reserved_word(e.text) && e.text != "pi")
            fail(e.pos, "expected a value, got the word '" + e.text + "'");
        if (accept("(")) {
            e.kind = Expr::Kind::call;
            if (!accept(")")) {
                const bool saved = objects_allowed_;
                objects_allowed_ = true;
                do e.args.push_back(parse_expression());
                while (accept(","));
                objects_allowed_ = saved;
                expect(")", "to close the arguments of " + e.text);
            }
            return finished(std::move(e));
        }
        if (objects_allowed_ && peek().is("{")) {
            e.kind = Expr::Kind::object;
            e.body = parse_braced_block(e.text, e.pos);
            return e;
        }
        e.kind = Expr::Kind::name;
        return e;
    }

    SourceFiles& files_;
    const ParseOptions& options_;
    std::vector<std::string>& open_files_;  // canonical paths of the files being read
    std::vector<Token> tokens_;
    std::size_t next_ = 0;
    int depth_ = 0;
    bool objects_allowed_ = true;
};

}  // namespace

bool is_reserved_word(const std::string& word) {
    for (const char* reserved : kReservedWords)
        if (word == reserved) return true;
    return false;
}

Block parse_program(const std::string& text, const std::string& name,
                    const std::filesystem::path& dir, SourceFiles& files,
                    const ParseOptions& options) {
    if (text.size() > options.limits.file_size)
        throw CompileError(name + ": larger than " + std::to_string(options.limits.file_size) +
                           " bytes");
    if (!files.count_text(text.size(), options.limits.source_total))
        throw CompileError(name + ": more than " + std::to_string(options.limits.source_total) +
                           " bytes of source read in all");
    const std::filesystem::path path = dir / std::filesystem::path(name).filename();
    const int file = files.add({name, path, SourcePos{}});
    std::vector<std::string> open_files;
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(path, ec);
    open_files.push_back(ec ? path.string() : canonical.string());
    Parser parser(files, options, open_files);
    return parser.parse_file(text, file);
}

}  // namespace rtpp
