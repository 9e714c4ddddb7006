#include "values.h"
#include "core/regex_guard.h"
#include "core/digest.h"

#include "kernel.h"
#include "core/text_table.h"

#include <algorithm>
#include <fstream>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

namespace cavity::flags {

Result<int> parseInt(const std::string& flag, const std::string& text, int lo, int hi) {
    int v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < lo || v > hi)
        return badInput(flag + " " + text + ": must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return v;
}

Result<double> parseNumber(const std::string& flag, const std::string& text, const std::function<bool(double)>& allowed,
                           const std::string& what) {
    double v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || !allowed(v))
        return badInput(flag + " '" + text + "': must be " + what);
    return v;
}

Result<double> parseNumber(const std::string& flag, const std::string& text, double lo, double hi) {
    std::ostringstream range;
    range << "a number in " << lo << ".." << hi;
    return parseNumber(flag, text, [&](double v) { return v >= lo && v <= hi; }, range.str());
}

Status addKernelSource(const std::string& value, SourceOverrides& overrides, std::vector<ReplacedSource>& replaced) {
    namespace fs = std::filesystem;
    const auto eq = value.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == value.size())
        return badInput("--kernel-source '" + value + "': must be NAME=FILE, e.g. ssao_alchemy.glsl=broken.glsl");
    const std::string file = value.substr(eq + 1), given = "--kernel-source " + value;
    auto key = kernels::sourceKey(value.substr(0, eq));
    if (!key) return badInput("--kernel-source " + key.error().message);
    const std::string name = *key;
    if (overrides.count(name)) return badInput(given + ": kernels/" + name + " is already replaced (give each NAME once)");
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        return badInput(given + ": " + (fs::exists(file, ec) ? "not a file" : "no such file"));
    constexpr uintmax_t kMaxBytes = 1 << 20;
    if (fs::file_size(file, ec) > kMaxBytes) return badInput(given + ": over 1 MiB (a GLSL source is expected)");
    std::ifstream in(file, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    if (!in && !in.eof()) return badInput(given + ": cannot be read");
    if (const auto nul = text.find('\0'); nul != std::string::npos)
        return badInput(given + ": not a text file (a NUL byte at offset " + std::to_string(nul) + "; a GLSL source is expected)");
    // Recorded by its absolute path: baselines update --with-kernel-source
    // reads it again, perhaps from another working folder.
    const fs::path where = fs::absolute(file, ec).lexically_normal();
    replaced.push_back({name, ec ? file : where.string(), digestText(fnv1a64(text.data(), text.size()))});
    overrides[name] = kernels::kReplacedFrom + file + "\n" + text;
    return {};
}

Result<std::regex> parseFilter(const std::string& flag, const std::string& text) {
    if (const std::string why = core::nestedQuantifierError(flag, text); !why.empty()) return badInput(why);
    try {
        return std::regex(text);
    } catch (const std::regex_error& e) {
        return badInput(flag + " " + text + ": not a regular expression (" + e.what() + ")");
    }
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

std::string range(const kernels::ParamDecl& p) {
    using kernels::ParamType;
    if (p.type == ParamType::Enum) {
        std::string s;
        for (const auto& c : p.choices) s += (s.empty() ? "" : "|") + c;
        return s;
    }
    if (p.type == ParamType::Bool) return "0|1";
    std::string r = p.type == ParamType::Int ? "integer " : "";
    r += p.minExclusive ? "(" : "";
    r += kernels::valueText(p, p.min);
    r += p.minExclusive ? ", " : "..";
    r += kernels::valueText(p, p.max);
    r += p.minExclusive ? "]" : "";
    if (!p.unit.empty()) r += " " + p.unit;
    return r;
}

}  // namespace

std::vector<FlagSpec> kernelParamFlags(const std::set<std::string>& skip) {
    // One flag per declaration (kernels/params.cpp), in its order; the
    // kernels that read it, their defaults where they differ from the
    // declaration's, and their notes on what they do with it.
    std::vector<FlagSpec> out;
    for (const auto& p : kernels::paramDecls()) {
        if (skip.count(p.name)) continue;
        std::string who, own;
        // Notes in order of first use, each with the kernels that give it.
        std::vector<std::pair<std::string, std::string>> notes;
        for (const auto& k : kernels::all())
            for (const auto& u : k.params) {
                if (u.decl != &p) continue;
                if (!who.empty()) who += ", ";
                who += k.name;
                if (u.def != p.def) own += ", " + kernels::valueText(p, u.def) + " (" + k.name + ")";
                if (u.note.empty()) continue;
                auto it = std::find_if(notes.begin(), notes.end(), [&](const auto& n) { return n.first == u.note; });
                if (it == notes.end()) notes.emplace_back(u.note, k.name);
                else it->second += ", " + k.name;
            }
        std::string noteText;
        for (const auto& [note, kernels] : notes) {
            noteText += noteText.empty() ? " (" : "; ";
            noteText += kernels + ": " + note;
        }
        if (!noteText.empty()) noteText += ")";
        if (who.empty()) continue;
        FlagSpec f;
        f.name = "--" + p.name;
        f.valueName = p.type == kernels::ParamType::Enum ? "NAME[,NAME..]" : "V[,V..]";
        f.help = p.help + noteText + "; default " + kernels::valueText(p, p.def) + own +
                 "; " + range(p) + "; kernels: " + who;
        f.group = "Kernel parameters (each takes a comma list and sweeps it)";
        out.push_back(std::move(f));
    }
    return out;
}

std::string kernelHelp(const std::string& heading) {
    TextTable table({{"", TextTable::Align::Left}, {"", TextTable::Align::Left}}, "  ");
    for (const auto& k : kernels::all()) {
        if (k.role != kernels::Role::Ao && k.role != kernels::Role::Reference) continue;
        std::string text = k.summary;
        for (size_t i = 0; i < k.sources.size(); ++i) {
            text += i == 0 ? " [after " : "; ";
            text += k.sources[i];
        }
        if (!k.sources.empty()) text += "]";
        if (k.role == kernels::Role::Reference) text += " [reference: never in an \"every AO kernel\" sweep]";
        table.add({"  " + k.name, text});
    }
    return heading + ", each with its one-line summary and the published sources it follows\n(docs/kernels.md, \"Sources\"):\n" + table.str();
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

FlagSpec storeFlag() {
    return {"--store", "DIR|URL",
            "the image store that holds the references approved per device class: a folder or an http(s):// URL "
            "(default $CAVITY_STORE, else <baselines>/store; docs/store.md)"};
}

FlagSpec storeCacheFlag() {
    return {"--store-cache", "DIR",
            "where an HTTP store's objects are cached (default $CAVITY_STORE_CACHE, else ~/.cache/cavity/store)"};
}

int exitCode(const Error& e) { return static_cast<int>(e.code); }

int fail(const std::string& program, const Error& e) {
    std::cerr << program << ": " << printable(e.message) << "\n";
    return exitCode(e);
}

}  // namespace cavity::flags
