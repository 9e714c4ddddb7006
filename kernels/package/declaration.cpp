#include "package/declaration.h"

#include "nearest.h"

#include "package/toml_read.h"

#include "blur_weights.h"
#include "package/expression.h"
#include "params.h"
#include "screen_space_tables.h"


#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace cavity::kernels {

namespace {

using namespace toml_read;

// ---- [[params]] ----------------------------------------------------------

const std::map<std::string, ParamType>& paramTypes() {
    static const std::map<std::string, ParamType> types = {
        {"int", ParamType::Int}, {"float", ParamType::Float}, {"bool", ParamType::Bool}, {"enum", ParamType::Enum}};
    return types;
}

Result<double> number(const Ctx& c, const toml::table& t, const std::string& where, const std::string& key) {
    const toml::node* n = t.get(key);
    if (!n) return c.fail(&t, where + key, "", "missing; a number is required");
    if (!n->is_number()) return c.fail(n, where + key, show(*n), "must be a number");
    // An integer as TOML holds it (64 bits); value<double>() has none for
    // one a double cannot hold exactly.
    const double v = n->is_integer() ? double(*n->value<int64_t>()) : *n->value<double>();
    if (!std::isfinite(v)) return c.fail(n, where + key, show(*n), "must be a finite number");
    return v;
}

// The range a declared int or float may span: what the shader's 32-bit
// uniform holds.
Status checkRange(const Ctx& c, const toml::table& t, const std::string& where, const ParamDecl& p) {
    // A float bound that rounds to the largest float is that float: the
    // shortest text of FLT_MAX (3.4028235e38) reads back a little above it.
    const double limit = p.type == ParamType::Int ? 2147483647.0
                                                  : double(std::numeric_limits<float>::max()) * (1.0 + std::ldexp(1.0, -25));
    for (const char* key : {"min", "max"}) {
        const double v = std::string(key) == "min" ? p.min : p.max;
        if (p.type == ParamType::Int && v != std::floor(v))
            return c.fail(t.get(key), where + key, show(*t.get(key)), "must be an integer");
        if (v > limit || v < -limit - (p.type == ParamType::Int ? 1 : 0))
            return c.fail(t.get(key), where + key, show(*t.get(key)),
                          std::string("outside what a 32-bit ") + (p.type == ParamType::Int ? "int" : "float") +
                              " holds (" + (p.type == ParamType::Int ? "-2147483648..2147483647" : "+-3.4e38") + ")");
    }
    return {};
}

// A parameter the harness does not know: its whole declaration.
Result<ParamDecl> newParam(const Ctx& c, const toml::table& t, const std::string& where, const std::string& name) {
    ParamDecl p;
    p.name = name;
    CAVITY_ASSIGN(const std::string type, text(c, t, where, "type", true));
    const auto ty = paramTypes().find(type);
    if (ty == paramTypes().end())
        return c.fail(t.get("type"), where + "type", type, "must be int, float, bool or enum");
    p.type = ty->second;
    // What each type takes: a key that does not apply is a mistake, not a no-op.
    for (const char* key : {"min", "max", "choices"}) {
        const bool applies = std::string(key) == "choices" ? p.type == ParamType::Enum
                                                           : p.type == ParamType::Int || p.type == ParamType::Float;
        if (t.get(key) && !applies)
            return c.fail(t.get(key), where + key, show(*t.get(key)), "does not apply to a parameter of type " + type +
                          " (int and float take min and max, enum takes choices, bool neither)");
    }
    CAVITY_ASSIGN(p.help, text(c, t, where, "help", true));
    CAVITY_ASSIGN(p.unit, text(c, t, where, "unit", false));
    if (p.type == ParamType::Bool) {
        p.min = 0, p.max = 1;
    } else if (p.type == ParamType::Enum) {
        const auto* ch = t.get("choices") ? t.get("choices")->as_array() : nullptr;
        if (!ch || ch->empty() || !ch->is_homogeneous(toml::node_type::string))
            return c.fail(t.get("choices") ? t.get("choices") : &t, where + "choices", "", "an enum needs a list of names");
        for (auto&& v : *ch) {
            const std::string choice = *v.value<std::string>();
            // Each must be givable as a flag's value, tell one from another,
            // and stay one segment of a configuration id, which is a path
            // under --out and the baselines.
            static const std::regex word("[A-Za-z0-9][A-Za-z0-9_+-]{0,31}");
            if (!std::regex_match(choice, word) || std::find(p.choices.begin(), p.choices.end(), choice) != p.choices.end())
                return c.fail(&v, where + "choices", show(v), "each choice must be a distinct name of letters, digits, _, + "
                                                             "or - (32 at most, starting with a letter or digit)");
            p.choices.push_back(choice);
        }
        p.min = 0, p.max = double(p.choices.size() - 1);
    } else {
        CAVITY_ASSIGN(p.min, number(c, t, where, "min"));
        CAVITY_ASSIGN(p.max, number(c, t, where, "max"));
        if (p.min > p.max) return c.fail(t.get("max"), where + "max", show(*t.get("max")), "must be at least min");
        CAVITY_TRY(checkRange(c, t, where, p));
    }
    return p;
}

// Reads the default, given as a number, a bool or (enum) a choice's name.
Result<double> defaultValue(const Ctx& c, const toml::node& n, const ParamDecl& p, const std::string& key) {
    if (p.type == ParamType::Enum && n.is_string()) {
        const std::string name = *n.value<std::string>();
        for (size_t i = 0; i < p.choices.size(); ++i)
            if (p.choices[i] == name) return double(i);
        return c.fail(&n, key, name, "must be " + allowedValues(p));
    }
    if (p.type == ParamType::Enum) return c.fail(&n, key, show(n), "must be " + allowedValues(p) + ", in quotes");
    if (p.type == ParamType::Bool) {   // as on the command line, 0 and 1 too
        if (n.is_integer() && (*n.value<int64_t>() == 0 || *n.value<int64_t>() == 1)) return double(*n.value<int64_t>());
        if (!n.is_boolean()) return c.fail(&n, key, show(n), "must be true or false (or 0 or 1)");
        return *n.value<bool>() ? 1.0 : 0.0;
    }
    if (!n.is_number()) return c.fail(&n, key, show(n), "must be a number");
    // An integer as TOML holds it (64 bits): value<double>() has none for
    // one a double cannot hold exactly.
    return n.is_integer() ? double(*n.value<int64_t>()) : *n.value<double>();
}

// One declaration a name, whoever made it: another package's kernel may
// declare it again only as it stands. Its type first: a line that changes
// it is the one to mend, not a key the new type lacks.
Status checkRedeclared(const Ctx& c, const toml::table& t, const std::string& where, const std::string& name,
                       const ParamDecl& decl) {
    const auto otherwise = [&](const char* at) {
        return c.fail(t.get(at), where + at, show(*t.get(at)),
                      "'" + name + "' is declared already, as " + allowedValues(decl) +
                          " (cavity run --help): declare it exactly so, set only its default and note, or "
                          "name a parameter of your own");
    };
    const auto* typeText = t.get("type")->as_string();
    const auto ty = typeText ? paramTypes().find(typeText->get()) : paramTypes().end();
    if (ty != paramTypes().end() && ty->second != decl.type) return otherwise("type");
    CAVITY_ASSIGN(const ParamDecl again, newParam(c, t, where, name));
    // Said at the first key that differs, so that the line is the one to change.
    const char* differs = again.type != decl.type                                           ? "type"
                          : again.min != decl.min || again.minExclusive != decl.minExclusive ? "min"
                          : again.max != decl.max                                            ? "max"
                          : again.choices != decl.choices                                    ? "choices"
                          : again.unit != decl.unit                                          ? "unit"
                                                                                             : nullptr;
    if (differs) return otherwise(t.get(differs) ? differs : "type");
    return {};
}

struct ParamsOut {
    std::deque<ParamDecl> added;   // new declarations, registered only when the file is good
};

Status readParam(const Ctx& c, const toml::table& t, size_t i, KernelDecl& k, ParamsOut& out) {
    const std::string where = "params[" + std::to_string(i) + "].";
    CAVITY_ASSIGN(const std::string name, text(c, t, where, "name", true));
    static const std::regex ident("[a-z][a-z0-9_]{0,31}");
    if (!std::regex_match(name, ident))
        return c.fail(t.get("name"), where + "name", name, "must be a GLSL name: a-z, then a-z, 0-9 or _ (32 at most)");
    for (const auto& p : k.params)
        if (p.name() == name) return c.fail(t.get("name"), where + "name", name, "declared twice in this kernel");
    if (!findParam(name) && reservedName(name, true))
        return c.fail(t.get("name"), where + "name", name,
                      "is reserved: a flag of cavity run, gate, quality, cavity_bench or cavity_render, a word of the cost and "
                      "paths formulas (compute, width, height, workgroup_x, workgroup_y) or a word GLSL "
                      "keeps; name the parameter otherwise");
    const ParamDecl* decl = findParam(name);
    const bool fresh = !decl, redeclared = !fresh && t.get("type");
    if (redeclared) {
        CAVITY_TRY(checkRedeclared(c, t, where, name, *decl));
    } else if (!fresh) {
        for (const char* key : {"min", "max", "unit", "help", "choices"})
            if (t.get(key))
                return c.fail(t.get(key), where + key, show(*t.get(key)),
                              "'" + name + "' is declared already (cavity run --help): without its type a package "
                              "sets only its default and note");
    } else if (!t.get("type")) {
        std::vector<std::string> known;
        for (const auto& p : paramDecls()) known.push_back(p.name);
        const std::string near = nearestWord(name, known);
        return c.fail(t.get("name"), where + "name", name,
                      "no parameter of that name" + (near.empty() ? std::string() : " (did you mean " + near + "?)") +
                          "; a new one needs its type, default and help (and min and max, or choices)");
    }
    CAVITY_TRY(onlyKeys(c, t, where, fresh || redeclared ? std::set<std::string>{"name", "default", "note", "compiled_in", "type",
                                                                                 "min", "max", "unit", "help", "choices"}
                                                         : std::set<std::string>{"name", "default", "note", "compiled_in"}));
    if (fresh) {
        CAVITY_ASSIGN(ParamDecl added, newParam(c, t, where, name));
        out.added.push_back(std::move(added));
        decl = &out.added.back();
    }
    KernelParam kp{decl, decl->def, ""};
    CAVITY_ASSIGN(kp.note, text(c, t, where, "note", false));
    if (const toml::node* d = t.get("default")) {
        CAVITY_ASSIGN(kp.def, defaultValue(c, *d, *decl, where + "default"));
    } else if (fresh) {
        return c.fail(&t, where + "default", "", "missing; a new parameter needs its default");
    }
    if (const Status s = checkValue(*decl, kp.def); !s)
        return c.fail(t.get("default") ? t.get("default") : &t, where + "default",
                      t.get("default") ? show(*t.get("default")) : valueText(*decl, kp.def),
                      (decl->type == ParamType::Int && kp.def != std::floor(kp.def) ? "not a whole number: must be "
                                                                                     : "outside the parameter's range: must be ") +
                          allowedValues(*decl));
    if (fresh) out.added.back().def = kp.def;
    if (const toml::node* ci = t.get("compiled_in")) {
        if (!ci->is_boolean()) return c.fail(ci, where + "compiled_in", show(*ci), "must be true or false");
        if (*ci->value<bool>()) {
            if (decl->type == ParamType::Float)
                return c.fail(ci, where + "compiled_in", "true", "only an int, bool or enum parameter can be compiled in");
            k.compileTime.push_back(name);
        }
    }
    k.params.push_back(kp);
    return {};
}

// Interleaved layers are sized by the interleave parameter and read from
// the zlayers input: without either the switch would do nothing, silently.
Status checkInterleaved(const std::string& label, const KernelDecl& k) {
    if (!k.interleaved) return {};
    const bool param = std::any_of(k.params.begin(), k.params.end(), [](const KernelParam& p) { return p.name() == "interleave"; });
    const bool input = std::any_of(k.inputs.begin(), k.inputs.end(), [](const InputDecl& i) { return i.name == "zlayers"; });
    if (param && input) return {};
    std::string what = !param && !input ? "the interleave parameter and a zlayers input"
                       : !param         ? "the interleave parameter ([[params]] name = \"interleave\")"
                                        : "a zlayers input ([[inputs]] name = \"zlayers\")";
    return badInput(label + ": interleaved = true: needs " + what + " (docs/packages.md), or leave the line out");
}

}  // namespace

Result<KernelDecl> readDeclaration(const DeclarationInput& in, PackageInfo& info) {
    using namespace toml_read;
    const Ctx c{in};
    toml::table root;
    try {
        root = toml::parse(in.text, in.label);
    } catch (const toml::parse_error& e) {
        return badInput(in.label + ":" + std::to_string(e.source().begin.line) + ": not TOML: " +
                        std::string(e.description()));
    }
    KernelDecl k;
    CAVITY_TRY(readTop(root, c, k));
    ParamsOut params;
    CAVITY_ASSIGN(const toml::array* ps, arrayOfTables(c, root, "params"));
    if (ps)
        for (size_t i = 0; i < ps->size(); ++i) CAVITY_TRY(readParam(c, *ps->get(i)->as_table(), i, k, params));
    CAVITY_TRY(readInputs(root, c, k));
    CAVITY_TRY(readOutputs(root, c, k));
    CAVITY_TRY(readArrays(root, c, k));
    CAVITY_TRY(readCost(root, c, k));
    CAVITY_TRY(readPipeline(root, c, k));
    CAVITY_TRY(readExpectations(root, c, k));
    CAVITY_TRY(readPaths(root, c, k));
    CAVITY_TRY(checkInterleaved(in.label, k));
    // Good: the new parameters join the harness's, and the kernel points at them.
    for (auto& p : k.params) {
        for (const auto& a : params.added)
            if (p.decl == &a) {
                p.decl = declareParam(a);
                info.addedParams.push_back(a.name);
            }
    }
    info.name = k.name;
    info.declaration = in.label;
    return k;
}

}  // namespace cavity::kernels
