#include "cli.h"

#include "kernel.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
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

namespace {

std::string number(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
}

// "0.5", or "0.5 (alchemy), 1 (hemisphere)" where kernels differ.
std::string defaults(const std::vector<std::pair<const kernels::KernelDecl*, const kernels::ParamDecl*>>& uses) {
    auto text = [](const kernels::ParamDecl& p) {
        return p.type == kernels::ParamType::Enum ? p.choices[size_t(p.def)] : number(p.def);
    };
    bool same = true;
    for (const auto& [k, p] : uses) same = same && p->def == uses.front().second->def;
    if (same) return text(*uses.front().second);
    std::string s;
    for (const auto& [k, p] : uses) s += (s.empty() ? "" : ", ") + text(*p) + " (" + k->name + ")";
    return s;
}

std::string range(const kernels::ParamDecl& p) {
    using kernels::ParamType;
    if (p.type == ParamType::Enum) {
        std::string s;
        for (const auto& c : p.choices) s += (s.empty() ? "" : "|") + c;
        return s;
    }
    if (p.type == ParamType::Bool) return "0|1";
    const std::string r = p.minExclusive ? "(" + number(p.min) + ", " + number(p.max) + "]"
                                         : number(p.min) + ".." + number(p.max);
    return (p.type == ParamType::Int ? "integer " : "") + r + (p.unit.empty() ? "" : " " + p.unit);
}

}  // namespace

std::vector<FlagSpec> kernelParamFlags(const std::set<std::string>& skip) {
    // Name order of first declaration; a shared name is one flag for every kernel.
    std::vector<std::string> names;
    std::map<std::string, std::vector<std::pair<const kernels::KernelDecl*, const kernels::ParamDecl*>>> uses;
    for (const auto& k : kernels::all())
        for (const auto& p : k.params) {
            if (skip.count(p.name)) continue;
            if (!uses.count(p.name)) names.push_back(p.name);
            uses[p.name].push_back({&k, &p});
        }
    std::vector<FlagSpec> out;
    for (const auto& name : names) {
        const auto& u = uses[name];
        const auto& p = *u.front().second;
        std::string who;
        for (const auto& [k, _] : u) who += (who.empty() ? "" : ", ") + k->name;
        FlagSpec f;
        f.name = "--" + name;
        f.valueName = p.type == kernels::ParamType::Enum ? "NAME[,NAME..]" : "V[,V..]";
        // Kernels that share a name may say in their own words what it does.
        std::string what = p.help;
        for (const auto& [k, q] : u)
            if (q->help != p.help) {
                what = "";
                for (const auto& [k2, q2] : u) what += (what.empty() ? "" : "; ") + k2->name + ": " + q2->help;
                break;
            }
        f.help = what + "; default " + defaults(u) + "; " + range(p) + (what == p.help ? "; kernels: " + who : "");
        f.group = "Kernel parameters (each takes a comma list and sweeps it)";
        out.push_back(std::move(f));
    }
    return out;
}

std::string kernelHelp() {
    std::string s = "Kernels (--kernel):\n";
    for (const auto& k : kernels::all()) {
        if (k.role != "ao" && k.role != "reference") continue;
        std::string name = "  " + k.name;
        name.resize(std::max<size_t>(name.size() + 1, 24), ' ');
        s += name + k.summary + (k.role == "reference" ? " [reference: never in an \"every AO kernel\" sweep]" : "") + "\n";
    }
    return s;
}

Result<std::string> defaultBaselines() {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (fs::path dir = fs::current_path(ec); !ec && !dir.empty(); dir = dir.parent_path()) {
        if (fs::is_regular_file(dir / "baselines" / "matrices.json", ec)) return (dir / "baselines").string();
        if (dir == dir.parent_path()) break;
    }
#ifdef CAVITY_SOURCE_DIR
    const fs::path built = fs::path(CAVITY_SOURCE_DIR) / "baselines";
    if (fs::is_regular_file(built / "matrices.json", ec)) return built.string();
#endif
    return badInput("--baselines: not given, and no baselines/matrices.json in the working directory or above it"
#ifdef CAVITY_SOURCE_DIR
                    " nor in " CAVITY_SOURCE_DIR
#endif
                    "; give --baselines DIR");
}

int exitCode(const Error& e) { return static_cast<int>(e.code); }

}  // namespace cavity::cli
