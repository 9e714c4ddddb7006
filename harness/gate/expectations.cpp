#include "gate/expectations.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace cavity::gate {

namespace fs = std::filesystem;

namespace {

std::optional<std::regex> compile(const std::string& text) {
    try {
        return std::regex(text);
    } catch (const std::regex_error&) {
        return std::nullopt;
    }
}

}  // namespace

Result<ExpectationFile> parseExpectationFile(const std::string& path, const std::string& text) {
    ExpectationFile f;
    f.path = path;
    bool haveDevice = false;
    std::istringstream lines(text);
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n) {
        const std::string at = path + ":" + std::to_string(n);
        if (const auto hash = line.find('#'); hash != std::string::npos && line.find_first_not_of(" \t") == hash) continue;
        std::istringstream words(line);
        std::string kind, pattern, reason;
        if (!(words >> kind)) continue;   // blank
        words >> pattern;
        std::getline(words >> std::ws, reason);
        while (!reason.empty() && (reason.back() == ' ' || reason.back() == '\t' || reason.back() == '\r')) reason.pop_back();
        if (kind == "device") {
            if (haveDevice) return badInput(at + ": a second device line (one per file)");
            if (!f.entries.empty()) return badInput(at + ": the device line must come before the entries");
            if (pattern.empty() || !reason.empty())
                return badInput(at + ": must be `device REGEX` (one regex on the device name, no spaces)");
            auto re = compile(pattern);
            if (!re) return badInput(at + ": device regex '" + pattern + "' is not a regular expression");
            f.devicePattern = pattern;
            f.device = *re;
            haveDevice = true;
            continue;
        }
        if (kind != "fail" && kind != "flake")
            return badInput(at + ": '" + kind + "': must be `device REGEX`, `fail REGEX REASON` or `flake REGEX REASON`");
        if (!haveDevice) return badInput(at + ": entry before the file's `device REGEX` line");
        if (pattern.empty() || reason.empty())
            return badInput(at + ": must be `" + kind + " REGEX REASON` (the reason is required)");
        auto re = compile(pattern);
        if (!re) return badInput(at + ": id regex '" + pattern + "' is not a regular expression");
        f.entries.push_back({kind, pattern, *re, reason, at});
    }
    if (!haveDevice) return badInput(path + ": no `device REGEX` line (which devices the file is for)");
    return f;
}

Result<Expectations> loadExpectations(const std::string& dir) {
    Expectations e;
    std::error_code ec;
    if (!fs::exists(dir, ec)) return e;
    if (!fs::is_directory(dir, ec)) return badInput(dir + ": expectations must be a folder of *.txt files");
    std::vector<fs::path> paths;
    for (const auto& entry : fs::directory_iterator(dir, ec))
        if (entry.path().extension() == ".txt") paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());
    for (const auto& p : paths) {
        std::ifstream in(p);
        if (!in) return badInput(p.string() + ": cannot be read");
        std::ostringstream text;
        text << in.rdbuf();
        CAVITY_ASSIGN(auto f, parseExpectationFile(p.string(), text.str()));
        e.files.push_back(std::move(f));
    }
    return e;
}

const Expectation* Expectations::find(const std::string& device, const std::string& id) const {
    for (const auto& f : files) {
        if (!std::regex_search(device, f.device)) continue;
        for (const auto& x : f.entries)
            if (std::regex_search(id, x.re)) return &x;
    }
    return nullptr;
}

void applyExpectations(GateRun& run, const Expectations& e) {
    for (auto& r : run.results)
        if (const Expectation* x = e.find(r.device, r.id)) {
            r.expected = x->kind;
            r.expectedWhy = x->where + ": " + x->reason;
        }
}

}  // namespace cavity::gate
