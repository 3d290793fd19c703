// The parsed program: expressions and statements, each with its place. The parser builds it
// once (includes already spliced in); the evaluator runs it, as often as loops ask.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rtpp/source.h"

namespace rtpp {

struct Stmt;
using Block = std::vector<Stmt>;

struct Expr {
    enum class Kind {
        number,  // value
        string,  // text
        name,    // text: a named value
        vector,  // args: three components
        unary,   // text: "-", "+" or "not"; args: the operand
        binary,  // text: the operator; args: the two operands
        call,    // text: the function; args
        object,  // text: the kind or a named object; body: its fields and contents
        member,  // text: "x", "y" or "z"; args: the vector
    };
    Kind kind = Kind::number;
    SourcePos pos;
    double value = 0;
    std::string text;
    std::vector<Expr> args;
    std::shared_ptr<const Block> body;
    // The levels of expressions in this one, itself included: evaluating it and freeing it
    // recurse this deep, so the parser holds it to the nesting limit.
    int height = 1;
};

struct Stmt {
    enum class Kind {
        let,     // name = args[0]
        field,   // name args... (rotate: args[0] about args[1])
        object,  // args[0], an object expression, placed where the statement is
        loop,    // for name = args[0] to args[1] [step args[2]] { body }
        branch,  // if args[0] { body } [else { else_body }]
        block,   // body: an included file's statements, run in the including scope
    };
    Kind kind = Kind::let;
    SourcePos pos;
    std::string name;
    std::vector<Expr> args;
    std::shared_ptr<const Block> body;
    std::shared_ptr<const Block> else_body;
};

}  // namespace rtpp
