// The cost section of a kernel.toml: per-pixel counts as formulas of the
// kernel's parameters and its pass's shape.
#include "package/toml_read.h"

#include "package/expression.h"

#include <cmath>
#include <map>
#include <regex>
#include <sstream>

namespace cavity::kernels::toml_read {

namespace {

std::string quoted(const std::string& text) {
    std::string out = "\"";
    out += text;
    out += '"';
    return out;
}

// Every count must be finite and >= 0 wherever the kernel runs: a count of
// infinity reaches the benchmark's JSON as a bare Infinity, which JSON
// readers refuse. Tried at the defaults, then one parameter at a time over
// its values (each of an enum, a bool or an int of at most 257; a float's
// min, max and default), in a compute pass and a fragment one.
Status checkCounts(const toml::table& t, const Ctx& c, const KernelDecl& k, const std::vector<std::string>& keys) {
    ParamValues base;
    for (const auto& p : k.params) base[p.name()] = p.def;
    std::vector<std::pair<std::string, ParamValues>> trials = {{"the defaults", base}};
    for (const auto& p : k.params) {
        const ParamDecl& d = *p.decl;
        std::vector<double> xs = {d.min, d.max};
        if (d.type != ParamType::Float && d.max - d.min <= 256)
            for (double x = d.min + 1; x < d.max; ++x) xs.push_back(x);
        for (const double x : xs) {
            if (!checkValue(d, x)) continue;
            ParamValues v = base;
            v[p.name()] = x;
            trials.emplace_back(p.name() + " = " + valueText(d, x), std::move(v));
        }
    }
    for (const auto& [what, values] : trials)
        for (const bool compute : {true, false}) {
            const Cost cost = k.cost(values, PassShape{compute, k.workgroup, 0, 0});
            const double got[] = {cost.fetchesPerPixel, cost.bytesPerPixel, cost.fetchSlotsPerPixel, cost.dramBytesPerPixel};
            for (size_t i = 0; i < keys.size(); ++i) {
                if (std::isfinite(got[i]) && got[i] >= 0) continue;
                std::ostringstream why;
                why << "gives " << got[i] << " at " << what << (compute ? "" : " (fragment stage)")
                    << ": a count per pixel must be finite and >= 0";
                const toml::node* at = t.get(keys[i]);
                return c.fail(at, "cost." + keys[i], show(*at), why.str());
            }
        }
    return {};
}

}  // namespace

Status readCost(const toml::table& root, const Ctx& c, KernelDecl& k) {
    const toml::node* n = root.get("cost");
    if (!n) return {};
    const toml::table* t = n->as_table();
    if (!t) return c.fail(n, "cost", show(*n), "must be a table ([cost])");
    const std::vector<std::string> keys = {"fetches", "bytes", "fetch_slots", "dram_bytes"};
    std::set<std::string> allowedKeys(keys.begin(), keys.end());
    allowedKeys.insert("let");
    CAVITY_TRY(onlyKeys(c, *t, "cost.", allowedKeys));
    // A formula reads the kernel's parameters, the pass's shape (a compute
    // pass's workgroup may share a tile of its inputs) and the named terms
    // of [cost.let], which may read each other but not in a circle.
    std::set<std::string> names = {"compute", "workgroup_x", "workgroup_y"};
    for (const auto& p : k.params) names.insert(p.name());
    std::vector<std::pair<std::string, Expression>> lets;
    if (const toml::node* ln = t->get("let")) {
        const toml::table* lt = ln->as_table();
        if (!lt) return c.fail(ln, "cost.let", show(*ln), "must be a table of named formulas ([cost.let])");
        static const std::regex ident("[a-z][a-z0-9_]{0,31}");
        for (auto&& [key, v] : *lt) {
            const std::string name(key.str());
            if (!std::regex_match(name, ident) || names.count(name))
                return c.fail(&v, "cost.let." + name, show(v),
                              "a term's name is a-z, then a-z, 0-9 or _, and not a parameter's or compute, workgroup_x, "
                              "workgroup_y");
        }
        std::set<std::string> all = names;
        for (auto&& [key, v] : *lt) all.insert(std::string(key.str()));
        std::map<std::string, Expression> pending;
        for (auto&& [key, v] : *lt) {
            const std::string name(key.str());
            if (!v.is_string()) return c.fail(&v, "cost.let." + name, show(v), "must be a formula in quotes");
            auto parsed = Expression::parse(*v.value<std::string>(), all);
            if (!parsed) return c.fail(&v, "cost.let." + name, show(v), parsed.error().message);
            pending.emplace(name, *parsed);
        }
        // In an order where each term follows the terms it reads.
        std::set<std::string> known = names;
        while (!pending.empty()) {
            auto ready = std::find_if(pending.begin(), pending.end(), [&](const auto& e) {
                const auto used = e.second.names();
                return std::all_of(used.begin(), used.end(), [&](const std::string& u) {
                    return known.count(u) || !pending.count(u);
                });
            });
            if (ready == pending.end())
                return c.fail(lt->get(pending.begin()->first), "cost.let." + pending.begin()->first,
                              quoted(pending.begin()->second.text()), "the terms read each other in a circle");
            known.insert(ready->first);
            lets.emplace_back(ready->first, ready->second);
            pending.erase(ready);
        }
        names = std::move(known);
    }
    std::vector<Expression> e;
    for (const auto& key : keys) {
        CAVITY_ASSIGN(const std::string formula, text(c, *t, "cost.", key, true));
        auto parsed = Expression::parse(formula, names);
        if (!parsed) return c.fail(t->get(key), "cost." + key, show(*t->get(key)), parsed.error().message);
        e.push_back(*parsed);
    }
    k.cost = [e, lets](const ParamValues& given, const PassShape& shape) {
        ParamValues v = given;
        v["compute"] = shape.compute ? 1 : 0;
        v["workgroup_x"] = shape.workgroup.x;
        v["workgroup_y"] = shape.workgroup.y;
        for (const auto& [name, formula] : lets) v[name] = formula.evaluate(v);
        return Cost{e[0].evaluate(v), e[1].evaluate(v), e[2].evaluate(v), e[3].evaluate(v)};
    };
    if (!c.in.checkCounts) return {};
    return checkCounts(*t, c, k, keys);
}


}  // namespace cavity::kernels::toml_read
