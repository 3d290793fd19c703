// The values a program computes: numbers, vectors, strings, and objects (primitives, surfaces,
// lights, cameras, groups), which are immutable once built, so naming one and placing it many
// times shares it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rt/vec.h"
#include "rtpp/kinds.h"
#include "rtpp/source.h"
#include "rtpp/transform.h"

namespace rtpp {

struct ObjectValue;
using ObjectPtr = std::shared_ptr<const ObjectValue>;

struct Value {
    enum class Type { number, vector, string, object };
    Type type = Type::number;
    double number = 0;
    rt::Vec3 vector;
    std::string text;
    ObjectPtr object;

    static Value of(double n) { return {Type::number, n, {}, {}, {}}; }
    static Value of(const rt::Vec3& v) { return {Type::vector, 0, v, {}, {}}; }
};

// "a number", "a vector", "a string", "a sphere".
std::string describe(const Value& value);

struct FieldValue {
    const FieldSpec* spec;
    Value value;
    SourcePos pos;
    // Set in the braces being read, not inherited from the named object this one copies: a
    // second setting there is a mistake (major 1 major 2), an inherited one is overridden.
    bool set_here = true;
};

struct ObjectValue {
    const Kind* kind = nullptr;
    SourcePos pos;  // where it was written or last placed: errors and line markers name it
    std::vector<FieldValue> fields;
    std::vector<ObjectPtr> children;  // a group's members, a CSG's operands
    Frame transform;                  // its own transforms, in the order written
    // Levels of objects in this one, itself included: a name lets each level hold the one
    // before, so writing and freeing it would otherwise recurse without bound.
    int depth = 1;
    // The objects writing it writes: a group's or a CSG's operands, each counted as its own
    // parts (so sharing cannot hide millions), and held at one more than the limit.
    long parts = 1;

    const FieldValue* find(std::string_view name) const {
        for (const FieldValue& f : fields)
            if (name == f.spec->name) return &f;
        return nullptr;
    }
};

}  // namespace rtpp
