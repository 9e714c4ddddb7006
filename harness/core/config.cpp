#include "core/config.h"

#include <cctype>
#include <charconv>
#include <filesystem>

namespace cavity::core {

using kernels::findParam;

double RunConfig::param(const std::string& name) const {
    if (auto it = params.find(name); it != params.end()) return it->second;
    if (const auto* k = kernels::find(kernel))
        for (const auto& p : k->params)
            if (p.name() == name) return p.def;
    const auto* p = findParam(name);
    return p ? p->def : 0.0;
}

std::string RunConfig::scene() const {
    return kernels::valueText(*findParam("scene"), param("scene"));
}
int RunConfig::samples() const { return kernels::asInt(param("samples")); }
int RunConfig::blur() const { return kernels::asInt(param("blur")); }
std::string RunConfig::gbufferSource() const { return imported() ? "import" : raster ? "raster" : "sdf"; }

std::string importStem(const std::string& path) {
    std::string stem = std::filesystem::path(path).stem().string();
    for (char& ch : stem)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '_' && ch != '-') ch = '_';
    return stem;
}

Result<std::pair<int, int>> parseResolution(const std::string& flag, const std::string& text) {
    const std::string allowed = ": must be WIDTHxHEIGHT with each in 1.." + std::to_string(kMaxResolution);
    const auto x = text.find('x');
    if (x == std::string::npos) return badInput(flag + " " + text + allowed);
    int w = 0, h = 0;
    const char* b = text.data();
    auto r1 = std::from_chars(b, b + x, w);
    auto r2 = std::from_chars(b + x + 1, b + text.size(), h);
    if (r1.ec != std::errc() || r1.ptr != b + x || r2.ec != std::errc() || r2.ptr != b + text.size() || w < 1 ||
        h < 1 || w > kMaxResolution || h > kMaxResolution)
        return badInput(flag + " " + text + allowed);
    return std::pair{w, h};
}

bool isKernelParam(const std::string& name) { return findParam(name) != nullptr; }

Status setParam(RunConfig& c, const std::string& name, const std::string& text) {
    const auto* p = findParam(name);
    if (!p) return badInput("--" + name + ": unknown flag");
    CAVITY_ASSIGN(c.params[name], kernels::parseValue(*p, text));
    return {};
}

}  // namespace cavity::core