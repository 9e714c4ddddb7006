#include "cli.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace cavity::cli {

Result<std::string> Args::value(const std::string& flag) {
    if (done() || (a_[i_].rfind("--", 0) == 0 && a_[i_].size() > 2))
        return badInput(flag + ": missing value");
    if (!seen_.insert(flag).second && !repeatable_.count(flag))
        return badInput(flag + ": given twice (give one value, or one comma-separated list where the flag takes a list)");
    if (a_[i_].empty()) return badInput(flag + " '': empty value");
    return next();
}

Result<int> parseInt(const std::string& flag, const std::string& text, int lo, int hi) {
    int v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < lo || v > hi)
        return badInput(flag + " " + text + ": must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return v;
}

Result<double> parseNumber(const std::string& flag, const std::string& text, double lo, double hi) {
    double v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || v < lo ||
        v > hi) {
        std::ostringstream range;
        range << lo << ".." << hi;
        return badInput(flag + " '" + text + "': must be a number in " + range.str());
    }
    return v;
}

Result<std::vector<std::string>> splitList(const std::string& flag, const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    while (true) {
        const size_t comma = text.find(',', start);
        std::string item = text.substr(start, comma - start);
        if (item.empty()) return badInput(flag + " '" + text + "': empty item in the list (give VALUE[,VALUE...])");
        if (std::find(out.begin(), out.end(), item) != out.end())
            return badInput(flag + " '" + text + "': " + item + " given twice");
        out.push_back(std::move(item));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

Result<std::pair<int, int>> parseShard(const std::string& text) {
    const auto slash = text.find('/');
    const std::string msg = "--shard " + text + ": must be I/N with 0 <= I < N";
    if (slash == std::string::npos) return badInput(msg);
    auto i = parseInt("--shard", text.substr(0, slash), 0, 1 << 20);
    auto n = parseInt("--shard", text.substr(slash + 1), 1, 1 << 20);
    if (!i || !n || *i >= *n) return badInput(msg);
    return std::pair{*i, *n};
}

int exitCode(const Error& e) { return static_cast<int>(e.code); }

}  // namespace cavity::cli
