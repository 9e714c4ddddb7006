#include "compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <tuple>
#include <regex>
#include <sstream>

namespace cavity::kernels {

namespace {

EShLanguage toGlslang(gpu::Stage s) {
    switch (s) {
    case gpu::Stage::Compute: return EShLangCompute;
    case gpu::Stage::Vertex: return EShLangVertex;
    case gpu::Stage::Fragment: return EShLangFragment;
    }
    return EShLangCompute;
}

// glslang keeps global tables; initialise once per process and never finalise,
// since the backends compile from more than one thread in the tests.
void initOnce() {
    static std::once_flag flag;
    std::call_once(flag, [] { glslang::InitializeProcess(); });
}

}  // namespace

std::string nameSourceLines(const std::string& log, const std::vector<std::string>& files) {
    // glslang: "ERROR: 2:45: ..."; Mesa: "2:45(7): error: ..."; NVIDIA: "2(45) : error ...".
    static const std::regex ref(R"((^|[\s])(\d+)([:(])(\d+))");
    std::string out;
    std::sregex_iterator it(log.begin(), log.end(), ref), end;
    size_t last = 0;
    for (; it != end; ++it) {
        const auto& m = *it;
        size_t k = std::stoul(m[2].str());
        out.append(log, last, m.position(0) - last);
        out += m[1].str();
        if (k < files.size()) {
            out += files[k] + ":" + m[4].str();
        } else {
            out += m[0].str().substr(m[1].length());
        }
        last = m.position(0) + m.length(0);
    }
    out.append(log, last, std::string::npos);
    return out;
}

namespace {

// glslang's log in one line, for a message that is one line: its errors
// joined, without the closing counts ("2 compilation errors. No code
// generated.", "compilation terminated").
std::string oneLine(const std::string& log) {
    std::string out, line;
    std::istringstream in(log);
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
        if (line.empty() || line.find("compilation terminated") != std::string::npos ||
            line.find("compilation errors") != std::string::npos)
            continue;
        out += (out.empty() ? "" : " | ") + line;
    }
    return out;
}

Result<std::vector<uint32_t>> compileUncached(const gpu::ShaderSource& src, gpu::Api target);

}  // namespace

// Compiled SPIR-V by (API, stage, source text). A benchmark repetition, a
// camera view and a gate configuration rebuild the same pipelines; glslang
// takes tens of milliseconds a kernel, during which a GPU sits idle and
// lowers its clock. Failures are not kept, so their message comes every time.
Result<std::vector<uint32_t>> compileToSpirv(const gpu::ShaderSource& src, gpu::Api target) {
    static std::mutex mutex;
    static std::map<std::tuple<int, int, std::string>, std::vector<uint32_t>> cache;
    const auto key = std::make_tuple(int(target), int(src.stage), src.glsl);
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (auto it = cache.find(key); it != cache.end()) return it->second;
    }
    CAVITY_ASSIGN(auto words, compileUncached(src, target));
    std::lock_guard<std::mutex> lock(mutex);
    cache.emplace(key, words);
    return words;
}

namespace {

// Parses and links one stage for the client API; the error names the files.
Status parseAndLink(glslang::TShader& shader, glslang::TProgram& program, const gpu::ShaderSource& src,
                    gpu::Api target) {
    initOnce();
    const EShLanguage stage = toGlslang(src.stage);
    const char* text = src.glsl.c_str();
    shader.setStrings(&text, 1);
    if (target == gpu::Api::Vulkan) {
        shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
        shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
        shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
    } else {
        shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientOpenGL, 100);
        shader.setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
        shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
    }
    const auto messages = static_cast<EShMessages>(unsigned(EShMsgSpvRules) |
        (target == gpu::Api::Vulkan ? unsigned(EShMsgVulkanRules) : 0u));
    const std::string who = src.name + " (" + (target == gpu::Api::Vulkan ? "vk" : "gl") + ")";
    // A shader of ours that does not compile is our bug; one that holds a
    // file the user gave (a replacement, a package from disk: its label is
    // not under kernels/) is the user's input.
    const bool given = src.fromUser || std::any_of(src.files.begin(), src.files.end(), [](const std::string& f) {
        return !f.empty() && f[0] != '<' && f.rfind("kernels/", 0) != 0;
    });
    const auto fail = [&](const std::string& what) { return given ? badInput(what) : internal(what); };
    if (!shader.parse(GetDefaultResources(), 450, false, messages)) {
        return fail("compile " + who + ": " + oneLine(nameSourceLines(shader.getInfoLog(), src.files)));
    }
    program.addShader(&shader);
    if (!program.link(messages)) {
        return fail("link " + who + ": " + oneLine(nameSourceLines(program.getInfoLog(), src.files)));
    }
    return {};
}

Result<std::vector<uint32_t>> compileUncached(const gpu::ShaderSource& src, gpu::Api target) {
    const EShLanguage stage = toGlslang(src.stage);
    glslang::TShader shader(stage);
    glslang::TProgram program;
    CAVITY_TRY(parseAndLink(shader, program, src, target));
    const std::string who = src.name + " (" + (target == gpu::Api::Vulkan ? "vk" : "gl") + ")";
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    options.validate = true;
    spv::SpvBuildLogger logger;
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &logger, &options);
    if (spirv.empty()) return internal("SPIR-V generation " + who + ": " + logger.getAllMessages());
    return spirv;
}

}  // namespace

Result<std::vector<std::string>> activeUniforms(const gpu::ShaderSource& src, gpu::Api target) {
    glslang::TShader shader(toGlslang(src.stage));
    glslang::TProgram program;
    CAVITY_TRY(parseAndLink(shader, program, src, target));
    if (!program.buildReflection(EShReflectionDefault)) return internal("reflection of " + src.name + " failed");
    std::vector<std::string> names;
    for (int i = 0; i < program.getNumUniformVariables(); ++i) names.push_back(program.getUniform(i).name);
    return names;
}

}  // namespace cavity::kernels
