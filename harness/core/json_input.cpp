#include "core/json_input.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace cavity::core {

using nlohmann::json;

Status onlyKeys(const std::string& path, const std::string& where, const json& obj, const std::set<std::string>& allowed) {
    if (!obj.is_object()) return badInput(path + ": " + where + " must be an object, not " + shortDump(obj));
    for (const auto& [k, v] : obj.items())
        if (!allowed.count(k)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            return badInput(path + ": unknown key '" + k + "' in " + where + " (allowed: " + list + ")");
        }
    return {};
}

std::string shortDump(const json& v) {
    std::string s = core::jsonText(v);
    return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

namespace {

// Whole bounds in full (0..16384, 0..9007199254740992), others as %g.
std::string boundText(double x) {
    std::ostringstream s;
    if (x == std::floor(x) && std::fabs(x) < 1e16) s << std::fixed << std::setprecision(0);
    s << x;
    return s.str();
}

std::string rangeText(double lo, double hi) { return boundText(lo) + ".." + boundText(hi); }

}  // namespace

Result<JsonObject> JsonObject::of(const std::string& path, const std::string& where, const json& j) {
    if (!j.is_object())
        return badInput(path + ": " + (where.empty() ? "the top level" : where) + " = " + shortDump(j) + ": must be an object");
    return JsonObject(path, where, &j);
}

Error JsonObject::bad(const std::string& key, const std::string& allowed) const {
    const std::string value = has(key) ? " = " + shortDump((*j_)[key]) : "";
    return badInput(path_ + ": " + name(key) + value + ": " + allowed);
}

Result<const json*> JsonObject::get(const std::string& key) const {
    auto it = j_->find(key);
    if (it == j_->end()) return badInput(path_ + ": " + name(key) + ": missing");
    return &*it;
}

Result<std::string> JsonObject::str(const std::string& key) const {
    CAVITY_ASSIGN(const json* v, get(key));
    if (!v->is_string()) return bad(key, "must be a string");
    return v->get<std::string>();
}

Result<std::string> JsonObject::str(const std::string& key, const std::string& fallback) const {
    return has(key) ? str(key) : Result<std::string>(fallback);
}

Result<bool> JsonObject::boolean(const std::string& key) const {
    CAVITY_ASSIGN(const json* v, get(key));
    if (!v->is_boolean()) return bad(key, "must be true or false");
    return v->get<bool>();
}

Result<double> JsonObject::number(const std::string& key, double lo, double hi) const {
    CAVITY_ASSIGN(const json* v, get(key));
    const double x = v->is_number() ? v->get<double>() : NAN;
    if (!std::isfinite(x) || x < lo || x > hi) return bad(key, "must be a number in " + rangeText(lo, hi));
    return x;
}

Result<double> JsonObject::number(const std::string& key, double lo, double hi, double fallback) const {
    return has(key) ? number(key, lo, hi) : Result<double>(fallback);
}

Result<std::optional<double>> JsonObject::numberOrNull(const std::string& key, double lo, double hi) const {
    CAVITY_ASSIGN(const json* v, get(key));
    if (v->is_null()) return std::optional<double>();
    CAVITY_ASSIGN(const double x, number(key, lo, hi));
    return std::optional<double>(x);
}

Result<int> JsonObject::integer(const std::string& key, int lo, int hi) const {
    CAVITY_ASSIGN(const json* v, get(key));
    // 3.0 is an integer as JSON writes it; 3.5, "3" and 1e999 are not.
    const double x = v->is_number() ? v->get<double>() : NAN;
    if (!std::isfinite(x) || x != std::floor(x) || x < lo || x > hi)
        return bad(key, "must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return int(x);
}

Result<int> JsonObject::integer(const std::string& key, int lo, int hi, int fallback) const {
    return has(key) ? integer(key, lo, hi) : Result<int>(fallback);
}

Result<JsonObject> JsonObject::object(const std::string& key) const {
    CAVITY_ASSIGN(const json* v, get(key));
    return of(path_, name(key), *v);
}

Result<std::vector<JsonObject>> JsonObject::objects(const std::string& key) const {
    CAVITY_ASSIGN(const json* v, get(key));
    if (!v->is_array()) return bad(key, "must be a list");
    std::vector<JsonObject> out;
    for (size_t i = 0; i < v->size(); ++i) {
        CAVITY_ASSIGN(auto o, of(path_, name(key) + "[" + std::to_string(i) + "]", (*v)[i]));
        out.push_back(o);
    }
    return out;
}

Result<std::vector<std::string>> JsonObject::strings(const std::string& key) const {
    CAVITY_ASSIGN(const json* v, get(key));
    if (!v->is_array()) return bad(key, "must be a list of strings");
    std::vector<std::string> out;
    for (const auto& e : *v) {
        if (!e.is_string()) return bad(key, "must be a list of strings; " + shortDump(e) + " is not one");
        out.push_back(e.get<std::string>());
    }
    return out;
}

Result<std::vector<int>> JsonObject::integers(const std::string& key, int lo, int hi) const {
    CAVITY_ASSIGN(const json* v, get(key));
    const std::string allowed = "must be a list of integers in " + std::to_string(lo) + ".." + std::to_string(hi);
    if (!v->is_array()) return bad(key, allowed);
    std::vector<int> out;
    for (const auto& e : *v) {
        const double x = e.is_number() ? e.get<double>() : NAN;
        if (!std::isfinite(x) || x != std::floor(x) || x < lo || x > hi) return bad(key, allowed + "; " + shortDump(e) + " is not");
        out.push_back(int(x));
    }
    return out;
}

Result<std::vector<double>> JsonObject::numbers(const std::string& key, double lo, double hi, bool nullAsNaN) const {
    CAVITY_ASSIGN(const json* v, get(key));
    const std::string allowed = "must be a list of numbers in " + rangeText(lo, hi);
    if (!v->is_array()) return bad(key, allowed);
    std::vector<double> out;
    for (const auto& e : *v) {
        if (e.is_null() && nullAsNaN) {
            out.push_back(NAN);
            continue;
        }
        const double x = e.is_number() ? e.get<double>() : NAN;
        // A bare NaN or Infinity reads as null (json_file.h): named as both.
        const std::string shown = e.is_null() ? "null (or a NaN or Infinity)" : shortDump(e);
        if (!std::isfinite(x) || x < lo || x > hi) return bad(key, allowed + "; " + shown + " is not");
        out.push_back(x);
    }
    return out;
}

}  // namespace cavity::core