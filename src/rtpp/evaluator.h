// Runs a parsed program: evaluates expressions, binds names, runs loops and branches, builds
// objects from their blocks and hands each top-level one to the emitter as soon as it is
// complete, so a million objects need not be held at once.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rtpp/ast.h"
#include "rtpp/emitter.h"
#include "rtpp/limits.h"
#include "rtpp/value.h"

namespace rtpp {

class Evaluator {
  public:
    Evaluator(const Limits& limits, Emitter& emitter);

    void run(const Block& program);
    // A -D definition (a one-statement block `let NAME = VALUE`), bound before the program:
    // a top-level let of NAME in it takes this value instead of its own.
    void define(const Stmt& definition);
    // One expression on its own (for tests): names are those bound so far.
    Value evaluate(const Expr& expr);

  private:
    // While a block runs, the object its statements fill in (nullptr at the top level).
    using Target = ObjectValue*;

    void run_block(const Block& block, Target target);
    void run_statement(const Stmt& stmt, Target target);
    void set_field(const Stmt& stmt, Target target);
    void transform(const Stmt& stmt, ObjectValue& target);
    void add_object(ObjectPtr object, Target target, SourcePos pos);
    void run_loop(const Stmt& stmt, Target target);

    ObjectPtr build_object(const Expr& expr);
    Value call(const Expr& expr);
    Value binary(const Expr& expr);
    // The value of `expr`, which must be a number (a vector); the message of a value of
    // another type names it as `what` followed by `what_more` (joined only then, since these
    // run for every operand).
    double number_of(const Expr& expr, std::string_view what, std::string_view what_more = {});
    rt::Vec3 vector_of(const Expr& expr, std::string_view what, std::string_view what_more = {});

    const Value* lookup(const std::string& name) const;
    std::string suggestion(const std::string& name) const;
    void bind(const std::string& name, Value value);
    // Counts `n` evaluation steps against Limits::steps.
    void step(SourcePos pos, long n = 1);

    const Limits& limits_;
    Emitter& emitter_;
    std::vector<std::pair<std::string, Value>> names_;    // innermost last
    std::vector<std::pair<std::string, Value>> defined_;  // by -D, in order
    long iterations_ = 0;
    long steps_ = 0;
    int depth_ = 0;
};

}  // namespace rtpp
