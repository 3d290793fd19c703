#include "rtpp/evaluator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "common/option_reader.h"  // nearest_word
#include "rtpp/parser.h"

namespace rtpp {

namespace {

// Keeps the names a block binds to that block: they are dropped when it ends.
class Scope {
  public:
    explicit Scope(std::vector<std::pair<std::string, Value>>& names)
        : names_(names), size_(names.size()) {}
    ~Scope() { names_.resize(size_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    std::vector<std::pair<std::string, Value>>& names_;
    std::size_t size_;
};

std::string show(double value) {
    char text[32];
    // Whole numbers in full (a loop pass 8333334, not 8.33333e+06); 15 digits otherwise.
    std::snprintf(text, sizeof text, "%.15g", value);
    return text;
}

double finite(double value, SourcePos pos) {
    if (!std::isfinite(value)) fail(pos, "the result is not a finite number");
    return value;
}

rt::Vec3 finite(const rt::Vec3& v, SourcePos pos) {
    finite(v.x, pos);
    finite(v.y, pos);
    finite(v.z, pos);
    return v;
}

constexpr double kDegrees = 180 / std::numbers::pi;

}  // namespace

std::string describe(const Value& value) {
    switch (value.type) {
        case Value::Type::number:
            return "a number";
        case Value::Type::vector:
            return "a vector";
        case Value::Type::string:
            return "a string";
        case Value::Type::object:
            return std::string("a ") + value.object->kind->keyword;
    }
    return "a value";
}

Evaluator::Evaluator(const Limits& limits, Emitter& emitter) : limits_(limits), emitter_(emitter) {
    // The axes, so that `rotate 90 about y` reads as it is said.
    bind("x", Value::of(rt::Vec3{1, 0, 0}));
    bind("y", Value::of(rt::Vec3{0, 1, 0}));
    bind("z", Value::of(rt::Vec3{0, 0, 1}));
}

void Evaluator::run(const Block& program) { run_block(program, nullptr); }

void Evaluator::define(const Stmt& definition) {
    if (definition.kind != Stmt::Kind::let)
        fail(definition.pos, "a definition is NAME=VALUE, VALUE an expression");
    if (find_kind(definition.name) != nullptr)
        fail(definition.pos, "'" + definition.name + "' is an object kind and cannot name a value");
    Value value = evaluate(definition.args[0]);
    // Visible to the later definitions and to the program (outside every scope).
    names_.emplace_back(definition.name, value);
    defined_.emplace_back(definition.name, std::move(value));
}

const Value* Evaluator::lookup(const std::string& name) const {
    for (auto it = names_.rbegin(); it != names_.rend(); ++it)
        if (it->first == name) return &it->second;
    return nullptr;
}

void Evaluator::bind(const std::string& name, Value value) {
    names_.emplace_back(name, std::move(value));
}

void Evaluator::step(SourcePos pos, long n) {
    if (n > limits_.steps - steps_)
        fail(pos, "more than " + std::to_string(limits_.steps) +
                      " evaluation steps (each expression evaluated, each statement run and "
                      "each field copied from a named object counts one)");
    steps_ += n;
}

void Evaluator::run_block(const Block& block, Target target) {
    const Scope scope(names_);
    for (const Stmt& stmt : block) run_statement(stmt, target);
}

void Evaluator::run_statement(const Stmt& stmt, Target target) {
    step(stmt.pos);
    switch (stmt.kind) {
        case Stmt::Kind::let:
            if (find_kind(stmt.name) != nullptr)
                fail(stmt.pos, "'" + stmt.name + "' is an object kind and cannot name a value");
            // The command line's -D wins over the program's own top-level value.
            if (target == nullptr)
                for (const auto& [name, value] : defined_)
                    if (name == stmt.name) return bind(stmt.name, value);
            bind(stmt.name, evaluate(stmt.args[0]));
            return;
        case Stmt::Kind::field:
            set_field(stmt, target);
            return;
        case Stmt::Kind::object:
            add_object(build_object(stmt.args[0]), target, stmt.pos);
            return;
        case Stmt::Kind::loop:
            run_loop(stmt, target);
            return;
        case Stmt::Kind::branch:
            if (number_of(stmt.args[0], "an if's condition") != 0)
                run_block(*stmt.body, target);
            else if (stmt.else_body)
                run_block(*stmt.else_body, target);
            return;
        case Stmt::Kind::block:
            // An included file: its names stay bound for the rest of the including block.
            for (const Stmt& inner : *stmt.body) run_statement(inner, target);
            return;
    }
}

void Evaluator::run_loop(const Stmt& stmt, Target target) {
    const double from = number_of(stmt.args[0], "a loop's start");
    const double to = number_of(stmt.args[1], "a loop's end");
    const double step = stmt.args.size() > 2 ? number_of(stmt.args[2], "a loop's step") : 1;
    if (step == 0) fail(stmt.args[2].pos, "a loop's step must not be 0");
    // The count is decided before the loop runs, and each value is from + k step (not a sum,
    // which would drift): "for t = 0 to 1 step 0.1" runs 11 times and ends at exactly 1.
    const double span = (to - from) / step;
    const double count = span < -1e-9 ? 0 : std::floor(span + 1e-9) + 1;
    if (count > static_cast<double>(limits_.loop_iterations - iterations_))
        fail(stmt.pos, "this loop would run " + show(count) + " times, more than the " +
                           std::to_string(limits_.loop_iterations) +
                           " loop iterations allowed in all");
    const long n = static_cast<long>(count);
    iterations_ += n;
    for (long k = 0; k < n; ++k) {
        const Scope scope(names_);
        const double value = k == n - 1 && std::fabs(from + static_cast<double>(k) * step - to) <
                                               1e-9 * std::fmax(1, std::fabs(to))
                                 ? to
                                 : from + static_cast<double>(k) * step;
        bind(stmt.name, Value::of(value));
        try {
            for (const Stmt& inner : *stmt.body) run_statement(inner, target);
        } catch (SourceError& e) {
            // Which pass failed matters as much as where: the body is the same on every one.
            e.notes.emplace_back(stmt.pos,
                                 "in this loop, where " + stmt.name + " = " + show(value));
            throw;
        }
    }
}

void Evaluator::add_object(ObjectPtr object, Target target, SourcePos pos) {
    // A surface written inside an object is that object's surface.
    if (object->kind->category == Category::surface && target != nullptr &&
        target->kind->takes_surface()) {
        const FieldSpec* spec = target->kind->field("surface");
        for (FieldValue& f : target->fields)
            if (f.spec == spec) {
                f.value.object = std::move(object);
                f.pos = pos;
                return;
            }
        Value value;
        value.type = Value::Type::object;
        value.object = std::move(object);
        target->fields.push_back({spec, std::move(value), pos});
        return;
    }
    if (target == nullptr) return emitter_.place(*object);
    const Category category = target->kind->category;
    if (category != Category::csg && category != Category::group)
        fail(pos, std::string("a ") + target->kind->keyword +
                      " cannot hold other objects (a group, union, intersection or difference "
                      "can)");
    if (target->children.size() >= static_cast<std::size_t>(limits_.list_items))
        fail(pos, "more than " + std::to_string(limits_.list_items) + " objects in one " +
                      target->kind->keyword);
    target->children.push_back(std::move(object));
}

void Evaluator::set_field(const Stmt& stmt, Target target) {
    const std::string& name = stmt.name;
    if (target == nullptr) {
        if (name == "default_surface") {
            const Value v = evaluate(stmt.args[0]);
            if (v.type != Value::Type::object || v.object->kind->category != Category::surface)
                fail(stmt.args[0].pos, "default_surface needs a surface, got " + describe(v));
            emitter_.default_surface(*v.object, stmt.pos);
            return;
        }
        if (is_transform(name))
            fail(stmt.pos, name + " belongs inside an object's or a group's braces");
        if (find_kind(name) != nullptr) fail(stmt.pos, "expected '{' after " + name);
        fail(stmt.pos, "unknown statement '" + name +
                           "' (fields such as this belong inside an object's braces)");
    }
    const Kind& kind = *target->kind;
    if (is_transform(name)) {
        const Category c = kind.category;
        if (c == Category::camera || c == Category::viewer || c == Category::ambient ||
            c == Category::background)
            fail(stmt.pos, std::string("a ") + kind.keyword + " cannot be transformed");
        return transform(stmt, *target);
    }
    const FieldSpec* spec = kind.field(name);
    if (spec == nullptr) {
        std::string known = kind.field_names();
        if (kind.category != Category::camera && kind.category != Category::viewer &&
            kind.category != Category::ambient && kind.category != Category::background)
            known += std::string(known.empty() ? "" : "; ") + "translate, rotate, scale, frame";
        std::vector<std::string> fields;
        for (const FieldSpec& f : kind.fields) fields.emplace_back(f.name);
        const std::string near = rt::nearest_word(name, fields);
        fail(stmt.pos, std::string("a ") + kind.keyword + " has no field '" + name + "'" +
                           (near.empty() ? "" : "; did you mean '" + near + "'?") + " (" +
                           (known.empty() ? "it has no fields" : "it has: " + known) + ")");
    }
    const std::size_t want = spec->type == FieldType::size ? 2 : 1;
    if (stmt.args.size() != want)
        fail(stmt.pos, name + " takes " + (want == 1 ? "one value" : "two values (width, height)") +
                           ", got " + std::to_string(stmt.args.size()));
    const std::string what = std::string(kind.keyword) + " " + name;
    Value value;
    switch (spec->type) {
        case FieldType::number:
        case FieldType::flag:
            value = Value::of(number_of(stmt.args[0], what));
            break;
        case FieldType::vector:
            value = Value::of(vector_of(stmt.args[0], what));
            break;
        case FieldType::colour: {
            value = evaluate(stmt.args[0]);
            if (value.type == Value::Type::number)
                value = Value::of(rt::Vec3{value.number, value.number, value.number});
            else if (value.type != Value::Type::vector)
                fail(stmt.args[0].pos,
                     what + " must be a vector or a number, got " + describe(value));
            break;
        }
        case FieldType::surface:
            value = evaluate(stmt.args[0]);
            if (value.type != Value::Type::object ||
                value.object->kind->category != Category::surface)
                fail(stmt.args[0].pos, what + " must be a surface, got " + describe(value));
            break;
        case FieldType::string:
            value = evaluate(stmt.args[0]);
            if (value.type != Value::Type::string)
                fail(stmt.args[0].pos, what + " must be a string, got " + describe(value));
            break;
        case FieldType::size: {
            double wh[2];
            for (int i = 0; i < 2; ++i) {
                wh[i] = number_of(stmt.args[static_cast<std::size_t>(i)], what);
                if (wh[i] != std::floor(wh[i]) || wh[i] < 1 || wh[i] > rt::kMaxResolution)
                    fail(stmt.args[static_cast<std::size_t>(i)].pos,
                         what + " must be whole numbers from 1 to " +
                             std::to_string(rt::kMaxResolution) + ", got " + show(wh[i]));
            }
            value = Value::of(rt::Vec3{wh[0], wh[1], 0});
            break;
        }
    }
    if (!spec->repeated) {
        for (FieldValue& f : target->fields)
            if (f.spec == spec) {
                if (f.set_here)
                    fail(stmt.pos, std::string("'") + name + "' is given twice in this " +
                                       kind.keyword + " (first at " + emitter_.where(f.pos) +
                                       "); give each field once");
                f.value = std::move(value);
                f.pos = stmt.pos;
                f.set_here = true;
                return;
            }
    } else if (target->fields.size() >= static_cast<std::size_t>(limits_.list_items)) {
        fail(stmt.pos,
             "more than " + std::to_string(limits_.list_items) + " fields in one " + kind.keyword);
    }
    target->fields.push_back({spec, std::move(value), stmt.pos});
}

void Evaluator::transform(const Stmt& stmt, ObjectValue& target) {
    const std::string& name = stmt.name;
    Frame step;
    if (name == "translate") {
        step = translation(vector_of(stmt.args[0], "translate"));
    } else if (name == "rotate") {
        const double angle = number_of(stmt.args[0], "rotate's angle");
        const rt::Vec3 axis = vector_of(stmt.args[1], "rotate's axis");
        if (!(rt::length(axis) > 0)) fail(stmt.args[1].pos, "rotate's axis must not be zero");
        step = rotation(angle, axis);
    } else if (name == "scale") {
        const Value v = evaluate(stmt.args[0]);
        if (v.type == Value::Type::number)
            step = scaling({v.number, v.number, v.number});
        else if (v.type == Value::Type::vector)
            step = scaling(v.vector);
        else
            fail(stmt.args[0].pos, "scale needs a number or a vector, got " + describe(v));
    } else {  // frame O, X, Y, Z: the contract's own four vectors
        if (stmt.args.size() != 4)
            fail(stmt.pos, "frame takes four vectors: origin, x axis, y axis, z axis");
        step = {vector_of(stmt.args[0], "frame origin"), vector_of(stmt.args[1], "frame x axis"),
                vector_of(stmt.args[2], "frame y axis"), vector_of(stmt.args[3], "frame z axis")};
    }
    if (name != "frame" && stmt.args.size() != (name == "rotate" ? 2u : 1u))
        fail(stmt.pos, name + " takes one value");
    target.transform = compose(step, target.transform);
}

// "; did you mean 'blue'?" for the name in scope (or keyword) nearest to a mistyped one.
std::string Evaluator::suggestion(const std::string& name) const {
    std::vector<std::string> candidates{"pi"};
    for (const auto& [known, value] : names_) candidates.push_back(known);
    for (const Kind& kind : all_kinds()) candidates.emplace_back(kind.keyword);
    const std::string near = rt::nearest_word(name, candidates);
    return near.empty() ? "" : "; did you mean '" + near + "'?";
}

ObjectPtr Evaluator::build_object(const Expr& expr) {
    ObjectValue object;
    if (const Value* named = lookup(expr.text)) {
        if (named->type != Value::Type::object)
            fail(expr.pos, "'" + expr.text + "' is " + describe(*named) + ", not an object");
        step(expr.pos,
             static_cast<long>(named->object->fields.size() + named->object->children.size()));
        object = *named->object;
        for (FieldValue& field : object.fields) field.set_here = false;
    } else if (const Kind* kind = find_kind(expr.text)) {
        object.kind = kind;
    } else {
        fail(expr.pos, "unknown object kind '" + expr.text + "'");
    }
    object.pos = expr.pos;
    if (++depth_ > limits_.nesting) fail(expr.pos, "objects nested too deep");
    run_block(*expr.body, &object);
    --depth_;
    if (object.kind->category == Category::csg || object.kind->category == Category::group) {
        object.depth = 1;
        object.parts = 0;
        for (const ObjectPtr& child : object.children) {
            object.depth = std::max(object.depth, child->depth + 1);
            object.parts = std::min(object.parts + child->parts, limits_.objects + 1);
        }
        if (object.depth > limits_.nesting)
            fail(expr.pos, "objects nested more than " + std::to_string(limits_.nesting) +
                               " deep (each group or CSG holding another counts, named ones too)");
    }
    return std::make_shared<const ObjectValue>(std::move(object));
}

double Evaluator::number_of(const Expr& expr, std::string_view what, std::string_view what_more) {
    const Value v = evaluate(expr);
    if (v.type != Value::Type::number)
        fail(expr.pos,
             std::string(what) + std::string(what_more) + " must be a number, got " + describe(v));
    return v.number;
}

rt::Vec3 Evaluator::vector_of(const Expr& expr, std::string_view what, std::string_view what_more) {
    const Value v = evaluate(expr);
    if (v.type != Value::Type::vector)
        fail(expr.pos, std::string(what) + std::string(what_more) +
                           " must be a vector <x, y, z>, got " + describe(v));
    return v.vector;
}

Value Evaluator::evaluate(const Expr& expr) {
    step(expr.pos);
    switch (expr.kind) {
        case Expr::Kind::number:
            return Value::of(expr.value);
        case Expr::Kind::string: {
            Value v;
            v.type = Value::Type::string;
            v.text = expr.text;
            return v;
        }
        case Expr::Kind::name: {
            if (expr.text == "pi") return Value::of(std::numbers::pi);
            if (const Value* v = lookup(expr.text)) return *v;
            if (find_kind(expr.text) != nullptr)
                fail(expr.pos,
                     "'" + expr.text + "' is an object kind: write " + expr.text + " { ... }");
            fail(expr.pos, "unknown name '" + expr.text + "'" + suggestion(expr.text));
        }
        case Expr::Kind::vector:
            return Value::of(rt::Vec3{number_of(expr.args[0], "a vector's x"),
                                      number_of(expr.args[1], "a vector's y"),
                                      number_of(expr.args[2], "a vector's z")});
        case Expr::Kind::unary: {
            if (expr.text == "not") return Value::of(number_of(expr.args[0], "not's operand") == 0);
            const Value v = evaluate(expr.args[0]);
            if (v.type == Value::Type::number)
                return Value::of(expr.text == "-" ? -v.number : v.number);
            if (v.type == Value::Type::vector)
                return Value::of(expr.text == "-" ? -v.vector : v.vector);
            fail(expr.pos,
                 "unary " + expr.text + " needs a number or a vector, got " + describe(v));
        }
        case Expr::Kind::binary:
            return binary(expr);
        case Expr::Kind::call:
            return call(expr);
        case Expr::Kind::object: {
            Value v;
            v.type = Value::Type::object;
            v.object = build_object(expr);
            return v;
        }
        case Expr::Kind::member: {
            const rt::Vec3 v = vector_of(expr.args[0], ".", expr.text);
            return Value::of(expr.text == "x" ? v.x : expr.text == "y" ? v.y : v.z);
        }
    }
    fail(expr.pos, "cannot evaluate this");
}

Value Evaluator::binary(const Expr& expr) {
    // Compared as a view, whose literals' lengths are known when compiled: most comparisons
    // end at the length (a std::string against a char* measured it every time).
    const std::string_view op = expr.text;
    if (op == "and" || op == "or") {
        // Short-circuit, as people expect of `i > 0 and n / i > 2`.
        const bool lhs = number_of(expr.args[0], op, "'s operand") != 0;
        if (op == "and" && !lhs) return Value::of(0.0);
        if (op == "or" && lhs) return Value::of(1.0);
        return Value::of(number_of(expr.args[1], op, "'s operand") != 0 ? 1.0 : 0.0);
    }
    const Value a = evaluate(expr.args[0]);
    const Value b = evaluate(expr.args[1]);
    using T = Value::Type;
    const SourcePos pos = expr.pos;
    if (a.type == T::number && b.type == T::number) {
        const double x = a.number, y = b.number;
        if (op == "+") return Value::of(finite(x + y, pos));
        if (op == "-") return Value::of(finite(x - y, pos));
        if (op == "*") return Value::of(finite(x * y, pos));
        if (op == "/") {
            if (y == 0) fail(pos, "division by zero");
            return Value::of(finite(x / y, pos));
        }
        if (op == "%") {
            if (y == 0) fail(pos, "remainder of division by zero");
            // The sign of the divisor, as in mathematics: -1 % 3 is 2.
            const double r = std::fmod(x, y);
            return Value::of(r != 0 && (r < 0) != (y < 0) ? r + y : r);
        }
        if (op == "^") return Value::of(finite(std::pow(x, y), pos));
        if (op == "<") return Value::of(x < y);
        if (op == "<=") return Value::of(x <= y);
        if (op == ">") return Value::of(x > y);
        if (op == ">=") return Value::of(x >= y);
        if (op == "==") return Value::of(x == y);
        if (op == "!=") return Value::of(x != y);
    }
    if (a.type == T::vector && b.type == T::vector) {
        const rt::Vec3 u = a.vector, v = b.vector;
        if (op == "+") return Value::of(finite(u + v, pos));
        if (op == "-") return Value::of(finite(u - v, pos));
        // Component by component: handy for scaling a vector by another.
        if (op == "*") return Value::of(finite(rt::Vec3{u.x * v.x, u.y * v.y, u.z * v.z}, pos));
        if (op == "==") return Value::of(u == v);
        if (op == "!=") return Value::of(!(u == v));
    }
    if (a.type == T::vector && b.type == T::number) {
        if (op == "*") return Value::of(finite(a.vector * b.number, pos));
        if (op == "/") {
            if (b.number == 0) fail(pos, "division by zero");
            const rt::Vec3 u = a.vector;
            return Value::of(finite(rt::Vec3{u.x / b.number, u.y / b.number, u.z / b.number}, pos));
        }
    }
    if (a.type == T::number && b.type == T::vector && op == "*")
        return Value::of(finite(b.vector * a.number, pos));
    fail(pos, "cannot apply " + expr.text + " to " + describe(a) + " and " + describe(b));
}

Value Evaluator::call(const Expr& expr) {
    const std::string_view name = expr.text;  // compared as binary() compares its operator
    const auto args = [&](std::size_t n) {
        if (expr.args.size() != n)
            fail(expr.pos, expr.text + " takes " + std::to_string(n) +
                               (n == 1 ? " argument" : " arguments") + ", got " +
                               std::to_string(expr.args.size()));
    };
    const auto num = [&](std::size_t i) { return number_of(expr.args[i], name, "'s argument"); };
    const auto vec = [&](std::size_t i) { return vector_of(expr.args[i], name, "'s argument"); };
    const auto result = [&](double v) { return Value::of(finite(v, expr.pos)); };
    if (name == "sin") return args(1), result(sin_degrees(num(0)));
    if (name == "cos") return args(1), result(cos_degrees(num(0)));
    if (name == "tan") {
        args(1);
        const double angle = num(0);
        if (cos_degrees(angle) == 0)
            fail(expr.pos, "tan of an odd multiple of 90 degrees is infinite");
        return result(tan_degrees(angle));
    }
    if (name == "asin") return args(1), result(std::asin(num(0)) * kDegrees);
    if (name == "acos") return args(1), result(std::acos(num(0)) * kDegrees);
    if (name == "atan") return args(1), result(std::atan(num(0)) * kDegrees);
    if (name == "atan2") return args(2), result(std::atan2(num(0), num(1)) * kDegrees);
    if (name == "sqrt") {
        args(1);
        const double x = num(0);
        if (x < 0) fail(expr.pos, "sqrt of a negative number");
        return result(std::sqrt(x));
    }
    if (name == "pow") return args(2), result(std::pow(num(0), num(1)));
    if (name == "exp") return args(1), result(std::exp(num(0)));
    if (name == "log") {
        args(1);
        const double x = num(0);
        if (!(x > 0)) fail(expr.pos, "log needs a number > 0");
        return result(std::log(x));
    }
    if (name == "abs") return args(1), result(std::fabs(num(0)));
    if (name == "floor") return args(1), result(std::floor(num(0)));
    if (name == "ceil") return args(1), result(std::ceil(num(0)));
    if (name == "round") {
        // round(x) to a whole number, round(x, n) to n decimals: the double nearest the
        // decimal that the exact value of x rounds to (as printf rounds it, and Python's
        // round), not round(x * 10^n) / 10^n, whose multiplication can move a value across
        // a rounding boundary.
        if (expr.args.size() == 1) return result(std::round(num(0)));
        args(2);
        const double digits = num(1);
        if (digits != std::floor(digits) || digits < 0 || digits > 15)
            fail(expr.args[1].pos, "round's decimals must be a whole number from 0 to 15");
        char text[400];
        std::snprintf(text, sizeof text, "%.*f", static_cast<int>(digits), num(0));
        return result(std::strtod(text, nullptr));
    }
    if (name == "min" || name == "max") {
        if (expr.args.empty()) fail(expr.pos, expr.text + " needs at least one argument");
        double best = num(0);
        for (std::size_t i = 1; i < expr.args.size(); ++i)
            best = name == "min" ? std::fmin(best, num(i)) : std::fmax(best, num(i));
        return Value::of(best);
    }
    if (name == "length") return args(1), result(rt::length(vec(0)));
    if (name == "normalize") {
        args(1);
        const rt::Vec3 v = vec(0);
        if (!(rt::length(v) > 0)) fail(expr.pos, "normalize of a zero vector");
        return Value::of(finite(unit(v), expr.pos));
    }
    if (name == "cross") return args(2), Value::of(finite(rt::cross(vec(0), vec(1)), expr.pos));
    if (name == "dot") return args(2), result(rt::dot(vec(0), vec(1)));
    fail(expr.pos, "unknown function '" + expr.text + "'");
}

}  // namespace rtpp
