#include "json_input.h"

#include <fstream>

namespace cavity {

using nlohmann::json;

Result<json> readJsonFile(const std::string& path) {
    std::ifstream f(path);
    if (!f) return badInput(path + ": cannot be read");
    try {
        return json::parse(f);
    } catch (const json::parse_error& e) {
        return badInput(path + ": does not parse: " + e.what());
    }
}

Status onlyKeys(const std::string& path, const std::string& where, const json& obj, const std::set<std::string>& allowed) {
    if (!obj.is_object()) return badInput(path + ": " + where + " must be an object");
    for (const auto& [k, v] : obj.items())
        if (!allowed.count(k)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            return badInput(path + ": unknown key '" + k + "' in " + where + " (allowed: " + list + ")");
        }
    return {};
}

}  // namespace cavity
