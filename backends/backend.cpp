#include "backend.h"
#include "workgroup_env.h"

#include <cstdio>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

namespace cavity::gpu {

double registerCount(const std::vector<ShaderStat>& stats) {
    double most = -1;
    for (const auto& s : stats) {
        std::string name = s.name;
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return std::tolower(ch); });
        if (name.find("register") != std::string::npos || name == "vgprs") most = std::max(most, s.value);
    }
    return most;
}

// Each implementation file defines its factory; nothing else of theirs leaks.
Result<std::unique_ptr<Backend>> createGlBackend(const BackendOptions&);
Result<std::unique_ptr<Backend>> createVkBackend(const BackendOptions&);

const char* apiName(Api api) { return api == Api::OpenGL ? "gl" : "vk"; }

std::string missingUsage(const ImageDesc& desc, ImageUsage use) {
    if (!desc.usage || (desc.usage & use)) return {};
    const char* name = use == ImageSampled       ? "ImageSampled"
                       : use == ImageStorage     ? "ImageStorage"
                       : use == ImageColorTarget ? "ImageColorTarget"
                       : use == ImageDepthTarget ? "ImageDepthTarget"
                                                 : "ImageTransfer";
    return "'" + desc.label + "' was created without " + name;
}

std::string hexUuid(const unsigned char (&bytes)[16]) {
    static const char digits[] = "0123456789abcdef";
    std::string s;
    for (unsigned char b : bytes) {
        s += digits[b >> 4];
        s += digits[b & 15];
    }
    return s;
}

int channelCount(Format f) {
    switch (f) {
    case Format::RG16F:
    case Format::RG32F: return 2;
    case Format::RGBA8:
    case Format::RGBA16F:
    case Format::RGBA32F: return 4;
    default: return 1;
    }
}

const char* formatName(Format f) {
    switch (f) {
    case Format::R8: return "R8";
    case Format::R16F: return "R16F";
    case Format::R32F: return "R32F";
    case Format::RG16F: return "RG16F";
    case Format::RG32F: return "RG32F";
    case Format::RGBA8: return "RGBA8";
    case Format::RGBA16F: return "RGBA16F";
    case Format::RGBA32F: return "RGBA32F";
    case Format::D32: return "D32";
    }
    return "?";
}

Result<BackendOptions> withEnvironment(const BackendOptions& options) {
    BackendOptions o = options;
    // Checked here, where every command that renders checks its environment
    // before it writes anything; the kernels apply it (kernels/kernel.h).
    if (auto wg = workgroupOverride(); !wg) return wg.error();
    // Each variable is 0 or 1 (unset: 0); a value that is neither is an
    // error, so that a typo never runs the ordinary barriers unnoticed.
    for (const auto& [name, flag] : {std::pair{"CAVITY_FULL_BARRIERS", &o.fullBarriers},
                                     std::pair{"CAVITY_NO_BARRIERS", &o.noBarriers}}) {
        const char* v = std::getenv(name);
        if (!v || std::string(v) == "0" || std::string(v).empty()) continue;
        if (std::string(v) != "1") return badInput(std::string(name) + "=" + v + ": must be 0 or 1");
        *flag = true;
    }
    // Read by the GL backend itself; checked with the others.
    if (const char* v = std::getenv("CAVITY_GL_FORCE_GLSL"); v && *v && std::string(v) != "0" && std::string(v) != "1")
        return badInput(std::string("CAVITY_GL_FORCE_GLSL=") + v + ": must be 0 or 1");
    if (o.fullBarriers && o.noBarriers)
        return badInput("CAVITY_FULL_BARRIERS and CAVITY_NO_BARRIERS: set one of them (every barrier the widest, or none)");
    return o;
}

Result<std::unique_ptr<Backend>> createBackend(Api api, const BackendOptions& options) {
    CAVITY_ASSIGN(const BackendOptions o, withEnvironment(options));
    return api == Api::OpenGL ? createGlBackend(o) : createVkBackend(o);
}

}  // namespace cavity::gpu
