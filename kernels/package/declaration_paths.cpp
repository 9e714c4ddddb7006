// [[paths]] of a kernel.toml: the code paths of a package that a parameter
// selects without being an option of its own (a remainder, a table size, a
// level under some size), each with the condition on a configuration under
// which it runs. The gate's coverage check (cavity kernels coverage) asks
// that some stored matrix compiles and judges each one.
#include "package/expression.h"
#include "package/toml_read.h"

#include <regex>

namespace cavity::kernels::toml_read {

Status readPaths(const toml::table& root, const Ctx& c, KernelDecl& k) {
    CAVITY_ASSIGN(const toml::array* ps, arrayOfTables(c, root, "paths"));
    if (!ps) return {};
    // A condition reads the kernel's parameters and the pass's place in the
    // configuration: its stage, its output size, and whether the
    // configuration runs at half resolution.
    std::set<std::string> names = {"compute", "width", "height", "half"};
    for (const auto& p : k.params) names.insert(p.name());
    static const std::regex ident("[a-z][a-z0-9_]{0,39}");
    for (size_t i = 0; i < ps->size(); ++i) {
        const toml::table& t = *ps->get(i)->as_table();
        const std::string where = "paths[" + std::to_string(i) + "].";
        CAVITY_TRY(onlyKeys(c, t, where, {"name", "when", "note"}));
        PathDecl path;
        CAVITY_ASSIGN(path.name, text(c, t, where, "name", true));
        if (!std::regex_match(path.name, ident))
            return c.fail(t.get("name"), where + "name", path.name, "must be a-z, then a-z, 0-9 or _ (40 at most)");
        for (const auto& other : k.paths)
            if (other.name == path.name) return c.fail(t.get("name"), where + "name", path.name, "is declared twice");
        CAVITY_ASSIGN(path.whenText, text(c, t, where, "when", true));
        auto parsed = Expression::parse(path.whenText, names);
        if (!parsed)
            return c.fail(t.get("when"), where + "when", "\"" + path.whenText + "\"",
                          parsed.error().message + " (names: the kernel's parameters, compute, width, height, half)");
        CAVITY_ASSIGN(path.note, text(c, t, where, "note", false));
        path.when = [e = *parsed](const ParamValues& v) { return e.evaluate(v) != 0; };
        k.paths.push_back(std::move(path));
    }
    return {};
}

}  // namespace cavity::kernels::toml_read
