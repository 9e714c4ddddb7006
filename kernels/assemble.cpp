// Turns a kernel declaration and its GLSL body into one translation unit per
// stage, and its parameter values into the bytes of its uniform block. The
// preamble is generated from the declaration, so the GLSL and the C++ side can
// never disagree on a binding number or a uniform offset.
#include "kernel.h"
#include "package/package.h"

#include "workgroup_env.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

namespace cavity::kernels {

const std::map<std::string, std::string>& embeddedSources();   // kernel_sources.cpp

const std::string* sourceFile(const std::string& name) {
    const auto& files = embeddedSources();
    auto it = files.find(name);
    if (it != files.end()) return &it->second;
    const PackageSource* p = packageSource(name);
    return p ? &p->text : nullptr;
}

static bool isGlsl(const std::string& f) { return f.size() > 5 && f.compare(f.size() - 5, 5, ".glsl") == 0; }

Result<std::string> sourceKey(const std::string& name) {
    // The names the reports print are taken too: "kernels/<key>" for an
    // embedded source, the path on disk of a package's own file.
    if (name.rfind("kernels/", 0) == 0 && embeddedSources().count(name.substr(8))) return sourceKey(name.substr(8));
    if (const std::string key = packageKeyOfFile(name); !key.empty()) return key;
    if (sourceFile(name) && isGlsl(name)) return name;
    // A file name alone: the one source of that name, wherever its package
    // keeps it ("ssao_alchemy.glsl" for "ao/alchemy/ssao_alchemy.glsl").
    std::vector<std::string> keys;
    for (const auto& [key, text] : embeddedSources()) keys.push_back(key);
    for (const auto& p : packages())
        if (!p.builtIn) keys.insert(keys.end(), p.sourceKeys.begin(), p.sourceKeys.end());
    std::vector<std::string> found;   // GLSL alone: --kernel-source replaces shader text, not a kernel.toml
    for (const auto& key : keys)
        if (isGlsl(key) && key.size() > name.size() && key.compare(key.size() - name.size(), name.size(), name) == 0 &&
            key[key.size() - name.size() - 1] == '/' && name.find('/') == std::string::npos)
            found.push_back(key);
    // A bare name always meant a kernel's own file; the shared includes were
    // named with their folder ("include/composite.glsl").
    if (found.size() > 1)
        std::erase_if(found, [](const std::string& k) { return k.rfind("include/", 0) == 0; });
    if (found.size() == 1) return found[0];
    if (found.size() > 1) {
        std::string list;
        for (const auto& f : found) list += (list.empty() ? "" : ", ") + f;
        return badInput(name + ": more than one kernel source of that name (" + list + "); give one of those, or the file's path");
    }
    return badInput(name + ": no kernel source of that name (a .glsl file under kernels/ or in a --kernels package)");
}

std::string sourceLabel(const std::string& name) {
    if (embeddedSources().count(name)) return "kernels/" + name;
    const PackageSource* p = packageSource(name);
    return p ? p->label : "kernels/" + name;
}

// An include's key: a path relative to the including file's own folder when
// that file exists (a package's own includes), else relative to kernels/
// (the shared includes, "include/common.glsl").
std::string includeKey(const std::string& from, const std::string& path) {
    const auto slash = from.rfind('/');
    if (slash != std::string::npos) {
        const std::string local = from.substr(0, slash + 1) + path;
        if (sourceFile(local)) return local;
    }
    return path;
}

const KernelDecl* find(const std::string& name) {
    for (const auto& k : all())
        if (k.name == name) return &k;
    return nullptr;
}

ParamValues withDefaults(const KernelDecl& k, const ParamValues& given) {
    ParamValues v;
    for (const auto& p : k.params) {
        auto it = given.find(p.name());
        v[p.name()] = it == given.end() ? p.def : it->second;
    }
    return v;
}

namespace {


}  // namespace

Status validate(const KernelDecl& k, const ParamValues& values) {
    for (const auto& p : k.params)
        if (auto it = values.find(p.name()); it != values.end()) CAVITY_TRY(checkValue(*p.decl, it->second));
    return {};
}

std::vector<std::byte> packParams(const KernelDecl& k, const ParamValues& values) {
    // std140: scalars are 4 bytes with 4-byte alignment, vec4 arrays start on 16.
    std::vector<std::byte> bytes;
    auto put = [&](const void* p, size_t n) {
        const auto* b = static_cast<const std::byte*>(p);
        bytes.insert(bytes.end(), b, b + n);
    };
    const ParamValues full = withDefaults(k, values);
    for (const auto& p : k.params) {
        if (isIntegral(p.type())) {
            const int32_t i = intValue(full, p.name());
            put(&i, 4);
        } else {
            const float f = floatValue(full, p.name());
            put(&f, 4);
        }
    }
    if (k.params.empty() && k.arrays.empty()) bytes.resize(4);
    std::map<std::string, std::vector<float>> arrays;
    if (k.derive) k.derive(full, arrays);
    for (const auto& a : k.arrays) {
        bytes.resize((bytes.size() + 15) / 16 * 16);
        std::vector<float> data(size_t(a.vec4Count) * 4, 0.0f);
        auto it = arrays.find(a.name);
        if (it != arrays.end())
            std::memcpy(data.data(), it->second.data(), sizeof(float) * std::min(data.size(), it->second.size()));
        put(data.data(), data.size() * sizeof(float));
    }
    bytes.resize((bytes.size() + 15) / 16 * 16);
    return bytes;
}

int interleaveValue(const ParamValues& values) {
    return values.count("interleave") ? intValue(values, "interleave") : 1;
}

uint32_t storageBindingCount(const KernelDecl& k, gpu::Stage stage) {
    uint32_t n = 0;
    if (stage == gpu::Stage::Compute)
        for (const auto& o : k.outputs) n += uint32_t(o.oneDispatch ? o.mipLevels : 1);
    return n;
}

std::vector<gpu::BindingSlot> bindingLayout(const KernelDecl& k, gpu::Stage stage) {
    std::vector<gpu::BindingSlot> slots;
    slots.push_back({kFrameBinding, gpu::BindingKind::UniformBuffer, {}});
    slots.push_back({kParamsBinding, gpu::BindingKind::UniformBuffer, {}});
    uint32_t b = firstInputBinding(k, stage);
    for (size_t i = 0; i < k.inputs.size(); ++i) slots.push_back({b++, gpu::BindingKind::SampledImage, {}});
    b = kFirstImageBinding;
    if (stage == gpu::Stage::Compute)
        for (const auto& o : k.outputs)
            for (int l = 0; l < (o.oneDispatch ? o.mipLevels : 1); ++l)
                slots.push_back({b++, gpu::BindingKind::StorageImage, o.format});
    return slots;
}

namespace {

const char* imageQualifier(gpu::Format f) {
    switch (f) {
    case gpu::Format::R8: return "r8";
    case gpu::Format::R16F: return "r16f";
    case gpu::Format::R32F: return "r32f";
    case gpu::Format::RG16F: return "rg16f";
    case gpu::Format::RG32F: return "rg32f";
    case gpu::Format::RGBA8: return "rgba8";
    case gpu::Format::RGBA16F: return "rgba16f";
    case gpu::Format::RGBA32F: return "rgba32f";
    case gpu::Format::D32: return "r32f";
    }
    return "rgba32f";
}

// Expands `#include "path"` (relative to kernels/) once per file, with #line
// directives whose source numbers index `files`, so every diagnostic can name
// the kernel file and line.
Status expand(const std::string& name, const std::map<std::string, std::string>& overrides,
              std::set<std::string>& seen, std::vector<std::string>& files, std::string& out) {
    if (!seen.insert(name).second) return {};
    const std::string* text = nullptr;
    if (auto it = overrides.find(name); it != overrides.end()) text = &it->second;
    else text = sourceFile(name);
    if (!text) return badInput(sourceLabel(name) + ": no such kernel source (an #include of a file that is neither "
                                 "beside its includer nor under kernels/)");
    const size_t index = files.size();
    // A replacement read from a file names it on a first line of its own
    // (kReplacedFrom), so that a compile error points at the file given.
    std::string label = sourceLabel(name), body = *text;
    if (body.rfind(kReplacedFrom, 0) == 0) {
        const size_t eol = body.find('\n');
        label = body.substr(std::strlen(kReplacedFrom), eol == std::string::npos ? std::string::npos : eol - std::strlen(kReplacedFrom)) +
                " (replacing " + sourceLabel(name) + ")";
        body = eol == std::string::npos ? std::string() : body.substr(eol + 1);
    }
    files.push_back(label);
    out += "#line 1 " + std::to_string(index) + "\n";
    std::istringstream in(body);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        const auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
            const auto q0 = line.find('"'), q1 = line.rfind('"');
            if (q0 == std::string::npos || q1 <= q0)
                return badInput(label + ":" + std::to_string(lineNo) + ": malformed #include");
            const std::string path = line.substr(q0 + 1, q1 - q0 - 1), key = includeKey(name, path);
            // Paths out of a package's folder are not followed (docs/packages.md): say so, not "no such file".
            const bool outside = path.rfind("/", 0) == 0 || path.rfind("../", 0) == 0 || path.find("/../") != std::string::npos;
            if (!overrides.count(key) && !sourceFile(key))
                return badInput(label + ":" + std::to_string(lineNo) + ": #include \"" + path + "\": " +
                                (outside ? "a path out of the folder (absolute, or through ..) is not followed"
                                         : "no such file beside it nor under kernels/") +
                                " (a package includes files of its own folder, not links out of it, or kernels/include/...)");
            CAVITY_TRY(expand(key, overrides, seen, files, out));
            out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
            continue;
        }
        out += line + "\n";
    }
    return {};
}

// The layers of a kernel that declares `interleave` (KernelDecl::interleaved,
// OutputDecl::layered): k, each layer's size, and where pixel p lies in
// the atlas of the layers side by side.
std::string interleavePreamble(int k) {
    const std::string n = std::to_string(k);
    return "#define CAVITY_INTERLEAVE " + n + "\n"
           "ivec2 cavityLayerSize() { return (frame.size + " + std::to_string(k - 1) + ") / " + n + "; }\n"
           "ivec2 cavityLayerTexel(ivec2 p) { return (p % " + n + ") * cavityLayerSize() + p / " + n + "; }\n";
}

// main() around cavity_main: a compute invocation per pixel, or for an
// interleaved pass, invocation (layer l, texel q) of the layers laid side by
// side shading pixel q * k + l; a fragment per pixel. A kernel that declares
// wholeWorkgroups also gets the invocations past the image's edge.
std::string entryPoint(gpu::Stage stage, const KernelDecl& k, bool interleaved, const std::string& plant, Workgroup wg) {
    if (stage != gpu::Stage::Compute)
        return "void main() {\n    ivec2 pixel = ivec2(gl_FragCoord.xy);\n    cavity_main(pixel);\n" + plant + "}\n";
    const std::string pixel = interleaved
                                  ? "    ivec2 atlas = ivec2(gl_GlobalInvocationID.xy);\n"
                                    "    ivec2 layer = atlas / cavityLayerSize();\n"
                                    "    if (any(greaterThanEqual(layer, ivec2(CAVITY_INTERLEAVE)))) return;\n"
                                    "    ivec2 pixel = (atlas - layer * cavityLayerSize()) * CAVITY_INTERLEAVE + layer;\n"
                                  : "    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);\n";
    const std::string outside =
        k.wholeWorkgroups ? "" : "    if (pixel.x >= frame.size.x || pixel.y >= frame.size.y) return;\n";
    return "layout(local_size_x = " + std::to_string(wg.x) + ", local_size_y = " + std::to_string(wg.y) + ") in;\n"
           "void main() {\n" + pixel + outside +
           "    cavity_main(pixel);\n" + plant +
           "}\n";
}

}  // namespace

Result<Workgroup> workgroupSize(const KernelDecl& k) {
    CAVITY_ASSIGN(const auto shape, gpu::workgroupOverride());
    if (!shape) return k.workgroup;
    return Workgroup{shape->first, shape->second};
}

namespace {

// CAVITY_CONST_<name> for each compileTime parameter, and for a count from 1
// to 64 CAVITY_REPEAT_<name>(F), F(0) F(1) ... F(count - 1): a loop written
// out by the preprocessor (ssao_alchemy_fast.glsl says where, and why).
void defineCompileTime(std::ostream& p, const KernelDecl& k, const ParamValues& all) {
    for (const auto& name : k.compileTime) {
        if (!all.count(name)) continue;
        const int v = intValue(all, name);
        p << "#define CAVITY_CONST_" << name << " " << v << "\n";
        if (v < 1 || v > 64) continue;
        p << "#define CAVITY_REPEAT_" << name << "(F)";
        for (int i = 0; i < v; ++i) p << " F(" << i << ")";
        p << "\n";
    }
}

// The stage, and for compute the workgroup's shape (a tile in workgroup
// memory is sized by it: include/blur_separable.glsl).
void defineStage(std::ostream& p, gpu::Stage stage, Workgroup wg) {
    if (stage != gpu::Stage::Compute) {
        p << "#define CAVITY_STAGE_FRAGMENT 1\n";
        return;
    }
    p << "#define CAVITY_STAGE_COMPUTE 1\n#define CAVITY_WORKGROUP_X " << wg.x << "\n#define CAVITY_WORKGROUP_Y " << wg.y
      << "\n";
}

}  // namespace

Result<gpu::ShaderSource> assemble(const KernelDecl& k, gpu::Stage stage,
                                   const std::map<std::string, std::string>& overrides, const ParamValues* values,
                                   int plantedFmas) {
    gpu::ShaderSource src;
    src.name = k.name;
    src.stage = stage;
    src.files.push_back("<preamble of " + k.name + ">");
    const PackageInfo* package = findPackage(k.name);
    src.fromUser = package && !package->builtIn;
    std::ostringstream p;
    p << "#version 450\n";
    // CAVITY_UNROLL: SPIR-V's Unroll hint on a loop, where the compiler
    // takes the attribute. NVIDIA's Vulkan driver honours it; its GL driver
    // keeps loops rolled whatever the hint (docs/kernels.md).
    p << "#extension GL_EXT_control_flow_attributes : enable\n"
         "#ifdef GL_EXT_control_flow_attributes\n#define CAVITY_UNROLL [[unroll]]\n#else\n#define CAVITY_UNROLL\n#endif\n";
    CAVITY_ASSIGN(const Workgroup wg, workgroupSize(k));
    if (firstInputBinding(k, stage) + k.inputs.size() > kFrameBinding)
        return internal("kernel " + k.name + ": " + std::to_string(storageBindingCount(k, stage)) + " storage images and " +
                        std::to_string(k.inputs.size()) + " inputs need more than the " + std::to_string(kFrameBinding) +
                        " bindings below its uniform blocks (kernel.h, kFrameBinding)");
    defineStage(p, stage, wg);
    // The precision contract (include/common.glsl): `precise` on the values
    // that feed discrete decisions, unless the kernel declares `exact` and
    // runs with it 0, its default.
    const int interleave = values ? interleaveValue(*values) : 1;
    const ParamValues all = withDefaults(k, values ? *values : ParamValues{});
    if (values) defineCompileTime(p, k, all);
    const bool exact = !all.count("exact") || intValue(all, "exact") != 0;
    p << (exact ? "#define EXACT precise\n" : "#define EXACT\n#define CAVITY_INEXACT 1\n");
    p << "layout(std140, binding = " << kFrameBinding << ") uniform Frame {\n"
         "    mat4 proj;\n    mat4 invProj;\n    vec4 camera;\n"
         "    ivec2 size;\n    ivec2 srcSize;\n    vec2 invSize;\n    int level;\n    int pad_;\n} frame;\n";
    p << "layout(std140, binding = " << kParamsBinding << ") uniform Params {\n";
    for (const auto& prm : k.params) p << "    " << (isIntegral(prm.type()) ? "int " : "float ") << prm.name() << ";\n";
    if (k.params.empty() && k.arrays.empty()) p << "    int unused_;\n";
    for (const auto& a : k.arrays) p << "    vec4 " << a.name << "[" << a.vec4Count << "];\n";
    p << "} P;\n";
    if (declares(k, "interleave")) p << interleavePreamble(interleave);
    uint32_t b = firstInputBinding(k, stage);
    for (const auto& in : k.inputs) p << "layout(binding = " << b++ << ") uniform sampler2D in_" << in.name << ";\n";
    b = kFirstImageBinding;
    int location = 0;
    for (const auto& o : k.outputs) {
        if (stage == gpu::Stage::Compute && o.oneDispatch && o.mipLevels > 1) {
            // A binding per level; write_<name> stores level 0.
            p << "#define CAVITY_LEVELS_" << o.name << " " << o.mipLevels << "\n";
            for (int l = 0; l < o.mipLevels; ++l)
                p << "layout(binding = " << b++ << ", " << imageQualifier(o.format) << ") uniform writeonly image2D out_"
                  << o.name << "_" << l << ";\n";
            p << "void write_" << o.name << "(ivec2 pixel, vec4 v) { imageStore(out_" << o.name << "_0, pixel, v); }\n"
              << "void write_" << o.name << "_level(int level, ivec2 pixel, vec4 v) {\n";
            for (int l = 0; l < o.mipLevels; ++l)
                p << "    " << (l ? "else if" : "if") << " (level == " << l << ") imageStore(out_" << o.name << "_" << l
                  << ", pixel, v);\n";
            p << "}\n";
        } else if (stage == gpu::Stage::Compute) {
            p << "layout(binding = " << b++ << ", " << imageQualifier(o.format) << ") uniform writeonly image2D out_"
              << o.name << ";\n"
              << "void write_" << o.name << "(ivec2 pixel, vec4 v) { imageStore(out_" << o.name << ", pixel, v); }\n";
        } else {
            p << "layout(location = " << location++ << ") out vec4 out_" << o.name << ";\n"
              << "void write_" << o.name << "(ivec2 pixel, vec4 v) { out_" << o.name << " = v; }\n";
        }
    }
    src.glsl = p.str();
    std::set<std::string> seen;
    CAVITY_TRY(expand(k.file, overrides, seen, src.files, src.glsl));
    // A planted slowdown: a chain of dependent FMAs the compiler cannot fold
    // (it starts from the pixel and the frame's uniforms) and whose result
    // reaches a write only if it were negative, which it never is.
    std::string plant;
    if (plantedFmas > 0 && !k.outputs.empty())
        plant = "    float plant_ = float(pixel.x + pixel.y) * frame.invSize.x;\n"
                "    for (int i = 0; i < " + std::to_string(plantedFmas) + "; ++i) plant_ = fma(plant_, 0.9999, frame.invSize.y);\n"
                "    if (plant_ < 0.0) write_" + k.outputs[0].name + "(pixel, vec4(plant_));\n";
    // The two thin entry points around the one body.
    src.glsl += "#line 1 0\n" + entryPoint(stage, k, k.interleaved && interleave > 1, plant, wg);
    return src;
}

gpu::ShaderSource fullscreenVertex() {
    gpu::ShaderSource src;
    src.name = "fullscreen_triangle";
    src.stage = gpu::Stage::Vertex;
    src.files = {"<fullscreen triangle>"};
    // One triangle covering the viewport: vertices (-1,-1), (3,-1), (-1,3).
    // glslang defines VULKAN for Vulkan semantics; GL (SPIR-V or GLSL) has gl_VertexID.
    src.glsl =
        "#version 450\n"
        "void main() {\n"
        "#ifdef VULKAN\n"
        "    int id = gl_VertexIndex;\n"
        "#else\n"
        "    int id = gl_VertexID;\n"
        "#endif\n"
        "    vec2 p = vec2((id << 1) & 2, id & 2);\n"
        "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
        "}\n";
    return src;
}

}  // namespace cavity::kernels
