// Reading the JSON files a user edits (baselines/*.json, render manifests):
// every error is one line naming the file, what is wrong and what is allowed.
#pragma once

#include "json_file.h"
#include "result.h"

#include <nlohmann/json.hpp>

#include <set>
#include <string>

namespace cavity {

// readJsonFile (json_file.h) reads them.

// Fails on a key of `obj` outside `allowed`, listing the allowed ones.
Status onlyKeys(const std::string& path, const std::string& where, const nlohmann::json& obj,
                const std::set<std::string>& allowed);

}  // namespace cavity
