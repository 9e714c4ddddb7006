// Reading the JSON files a user or another tool wrote (baselines/*.json,
// gate.json, results.json, render manifests): one reader checks every field's
// type, finiteness and range, and every failure is one line naming the file,
// the key, the value and what is allowed:
//   baselines/matrices.json: ci.frames = "3": must be an integer in 1..100000
#pragma once

#include "core/json_file.h"
#include "result.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace cavity::core {

// readJsonFile (json_file.h) reads the file; this reads what is in it.

// Fails on a key of `obj` outside `allowed`, listing the allowed ones.
Status onlyKeys(const std::string& path, const std::string& where, const nlohmann::json& obj,
                const std::set<std::string>& allowed);

// One JSON object of a file. `where` is its key path ("" at the top level).
class JsonObject {
public:
    // An error unless `j` is an object.
    static Result<JsonObject> of(const std::string& path, const std::string& where, const nlohmann::json& j);

    bool has(const std::string& key) const { return j_->contains(key); }
    const nlohmann::json& raw() const { return *j_; }
    // "where.key", or "key" at the top level.
    std::string name(const std::string& key) const { return where_.empty() ? key : where_ + "." + key; }
    // A one-line error about `key`'s value.
    Error bad(const std::string& key, const std::string& allowed) const;
    Status onlyKeys(const std::set<std::string>& allowed) const { return cavity::core::onlyKeys(path_, where_.empty() ? "the top level" : where_, *j_, allowed); }

    // Each read fails when the key is missing, unless a fallback is given.
    Result<std::string> str(const std::string& key) const;
    Result<std::string> str(const std::string& key, const std::string& fallback) const;
    Result<bool> boolean(const std::string& key) const;
    Result<double> number(const std::string& key, double lo, double hi) const;   // finite, in [lo, hi]
    Result<double> number(const std::string& key, double lo, double hi, double fallback) const;
    // A number or null (a NaN written by a writer that had no other way).
    Result<std::optional<double>> numberOrNull(const std::string& key, double lo, double hi) const;
    Result<int> integer(const std::string& key, int lo, int hi) const;
    Result<int> integer(const std::string& key, int lo, int hi, int fallback) const;
    Result<JsonObject> object(const std::string& key) const;
    Result<std::vector<JsonObject>> objects(const std::string& key) const;   // a list of objects
    Result<std::vector<std::string>> strings(const std::string& key) const;
    Result<std::vector<int>> integers(const std::string& key, int lo, int hi) const;
    // A list of numbers; null entries are kept as NaN when `nullAsNaN`, refused otherwise.
    Result<std::vector<double>> numbers(const std::string& key, double lo, double hi, bool nullAsNaN = false) const;

private:
    JsonObject(std::string path, std::string where, const nlohmann::json* j)
        : path_(std::move(path)), where_(std::move(where)), j_(j) {}
    Result<const nlohmann::json*> get(const std::string& key) const;

    std::string path_, where_;
    const nlohmann::json* j_;
};

// A JSON value as a user reads it in a message, cut to 60 characters.
std::string shortDump(const nlohmann::json& v);

}  // namespace cavity::core