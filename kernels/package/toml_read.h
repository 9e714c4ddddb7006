// What reading a kernel.toml shares between its two files: where an error
// is, and the typed reads of a value, each failing with one line that names
// the file, the line, the key, the value and what is allowed.
#pragma once

#include "printable.h"
#include "package/declaration.h"

#include <toml++/toml.h>

#include <set>
#include <sstream>
#include <string>

namespace cavity::kernels::toml_read {

// Where an error is: the file and the line of the value (or of the table
// that lacks a key), and the key's dotted path.
struct Ctx {
    const DeclarationInput& in;
    Error fail(const toml::node* at, const std::string& key, const std::string& value, const std::string& allowed) const {
        const auto line = at ? at->source().begin.line : 1;
        // A value is shown whole up to a line's worth; longer, its start.
        const std::string shown = value.size() > 80 ? value.substr(0, 60) + "... (" + std::to_string(value.size()) + " characters)" : value;
        return badInput(in.label + ":" + std::to_string(line) + ": " + key + (value.empty() ? "" : " = " + shown) +
                        ": " + allowed);
    }
};

inline std::string show(const toml::node& n) {
    std::ostringstream s;
    if (const auto* str = n.as_string()) s << '"' << printable(str->get()) << '"';   // quoted, on one line
    else if (n.is_table()) s << "{...}";
    else if (const auto* a = n.as_array()) s << "[" << a->size() << " values]";
    else n.visit([&](auto&& v) { s << v; });
    return s.str();
}

inline std::string joined(const std::set<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

inline Status onlyKeys(const Ctx& c, const toml::table& t, const std::string& where, const std::set<std::string>& allowed) {
    for (auto&& [k, v] : t) {
        const std::string key(k.str());
        if (!allowed.count(key))
            return c.fail(&v, where + key, show(v), "unknown key; allowed here: " + joined(allowed));
    }
    return {};
}

inline Result<std::string> text(const Ctx& c, const toml::table& t, const std::string& where, const std::string& key,
                         bool required) {
    const toml::node* n = t.get(key);
    if (!n) {
        if (required) return c.fail(&t, where + key, "", "missing; a string is required");
        return std::string();
    }
    if (!n->is_string()) return c.fail(n, where + key, show(*n), "must be a string");
    std::string value(*n->value<std::string>());
    // Every string of a declaration is printed on one line of a table or
    // a message: no line break, no terminal escape.
    if (hasControlChar(value))
        return c.fail(n, where + key, show(*n), "must be one line of printable text (no control characters)");
    if (value.find_first_not_of(' ') == std::string::npos)
        return c.fail(n, where + key, show(*n), required ? "must not be empty" : "must not be empty (leave the key out)");
    return value;
}

inline Result<const toml::array*> arrayOfTables(const Ctx& c, const toml::table& t, const std::string& key) {
    const toml::node* n = t.get(key);
    if (!n) return static_cast<const toml::array*>(nullptr);
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables())
        return c.fail(n, key, show(*n), "must be an array of tables ([[" + key + "]] blocks)");
    return a;
}

// The sections of a kernel.toml beside [[params]] (declaration_parts.cpp).
Status readTop(const toml::table& root, const Ctx& c, KernelDecl& k);
Status readInputs(const toml::table& root, const Ctx& c, KernelDecl& k);
Status readOutputs(const toml::table& root, const Ctx& c, KernelDecl& k);
Status readArrays(const toml::table& root, const Ctx& c, KernelDecl& k);
Status readCost(const toml::table& root, const Ctx& c, KernelDecl& k);
Status readPipeline(const toml::table& root, const Ctx& c, const KernelDecl& k);
Status readExpectations(const toml::table& root, const Ctx& c, KernelDecl& k);
Status readPaths(const toml::table& root, const Ctx& c, KernelDecl& k);   // declaration_paths.cpp
// A name a new parameter or array may not take (reserved_names.cpp).
bool reservedName(const std::string& name, bool asFlag);

}  // namespace cavity::kernels::toml_read
