#include "json_input.h"


namespace cavity {

using nlohmann::json;

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
