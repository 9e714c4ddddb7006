// Reading the JSON files a user edits (baselines/*.json, render manifests):
// every error is one line naming the file, what is wrong and what is allowed.
#pragma once

#include "result.h"

#include <nlohmann/json.hpp>

#include <set>
#include <string>

namespace cavity {

// The parsed file, or "PATH: cannot be read" / "PATH: does not parse: ...".
Result<nlohmann::json> readJsonFile(const std::string& path);

// Fails on a key of `obj` outside `allowed`, listing the allowed ones.
Status onlyKeys(const std::string& path, const std::string& where, const nlohmann::json& obj,
                const std::set<std::string>& allowed);

}  // namespace cavity
