// The sections of a kernel.toml beside [[params]]: the kernel itself, its
// inputs, outputs, derived arrays, cost and place in the pipeline.
#include "package/toml_read.h"

#include "blur_weights.h"
#include "package/expression.h"
#include "screen_space_tables.h"

#include <filesystem>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <regex>

namespace cavity::kernels::toml_read {

namespace {

bool powerOfTwo(int64_t v) { return v > 0 && (v & (v - 1)) == 0; }

Status readWorkgroup(const toml::table& root, const Ctx& c, KernelDecl& k) {
    const toml::node* n = root.get("workgroup");
    if (!n) return {};
    const toml::array* a = n->as_array();
    const std::string allowed = "must be [W, H], powers of two with W x H from 32 to 1024";
    if (!a || a->size() != 2 || !a->is_homogeneous(toml::node_type::integer)) return c.fail(n, "workgroup", show(*n), allowed);
    const int64_t x = *a->get(0)->value<int64_t>(), y = *a->get(1)->value<int64_t>();
    if (!powerOfTwo(x) || !powerOfTwo(y) || x * y < 32 || x * y > 1024)
        return c.fail(n, "workgroup", "[" + std::to_string(x) + ", " + std::to_string(y) + "]", allowed);
    k.workgroup = {uint32_t(x), uint32_t(y)};
    return {};
}

Status readFlag(const toml::table& root, const Ctx& c, const char* key, bool& out) {
    const toml::node* n = root.get(key);
    if (!n) return {};
    if (!n->is_boolean()) return c.fail(n, key, show(*n), "must be true or false");
    out = *n->value<bool>();
    return {};
}

// Inputs a pass of the pipeline provides (harness/pipeline/pipelines.cpp),
// and the images the harness makes on the CPU (kernels/constants.cpp).
std::set<std::string> providedInputs() {
    std::set<std::string> names = {"position", "normal", "albedo", "linear_depth", "depth", "zmip", "zlayers"};
    for (const auto& c : constantImages()) names.insert(c.name);
    return names;
}

const std::map<std::string, gpu::Format>& outputFormats() {
    static const std::map<std::string, gpu::Format> formats = {
        {"R16F", gpu::Format::R16F},   {"R32F", gpu::Format::R32F},       {"RG32F", gpu::Format::RG32F},
        {"RGBA8", gpu::Format::RGBA8}, {"RGBA16F", gpu::Format::RGBA16F}, {"RGBA32F", gpu::Format::RGBA32F}};
    return formats;
}

}  // namespace

Status readTop(const toml::table& root, const Ctx& c, KernelDecl& k) {
    CAVITY_TRY(onlyKeys(c, root, "", {"name", "summary", "sources", "role", "file", "workgroup", "whole_workgroups",
                                      "interleaved", "params", "inputs", "outputs", "arrays", "cost", "pipeline",
                                      "expectations", "reference", "paths"}));
    CAVITY_ASSIGN(k.name, text(c, root, "", "name", true));
    static const std::regex ident("[a-z][a-z0-9_]{0,39}");
    if (!std::regex_match(k.name, ident))
        return c.fail(root.get("name"), "name", k.name, "must be a-z, then a-z, 0-9 or _ (40 at most)");
    if (c.in.nameTaken(k.name)) {
        const PackageInfo* owner = findPackage(k.name);
        return c.fail(root.get("name"), "name", k.name,
                      "is taken by " + (owner && !owner->builtIn ? "the package in " + owner->folder : std::string("a built-in kernel")) +
                          ": a package may not take the name of a built-in kernel or of a package loaded before");
    }
    CAVITY_ASSIGN(k.summary, text(c, root, "", "summary", true));
    if (const toml::node* s = root.get("sources")) {
        const toml::array* a = s->as_array();
        if (!a || !a->is_homogeneous(toml::node_type::string))
            return c.fail(s, "sources", show(*s), "must be a list of strings (the publications it follows)");
        for (auto&& v : *a) {
            const std::string source = *v.value<std::string>();
            if (source.find_first_not_of(' ') == std::string::npos)
                return c.fail(&v, "sources", show(v), "each source must name a publication (not empty)");
            k.sources.push_back(source);
        }
    }
    CAVITY_ASSIGN(const std::string role, text(c, root, "", "role", true));
    // A user's package is an AO estimator, which the harness builds its
    // pipeline around; the passes around it are the harness's own packages
    // (kernels/passes/), which the pipeline names.
    static const std::map<std::string, Role> roles = {
        {"ao", Role::Ao},           {"reference", Role::Reference}, {"gbuffer", Role::GBuffer},
        {"pyramid", Role::Pyramid}, {"downsample", Role::Downsample}, {"upsample", Role::Upsample},
        {"blur", Role::Blur},       {"indirect", Role::Indirect},   {"composite", Role::Composite}};
    const auto r = roles.find(role);
    if (!c.in.builtIn && role != "ao") return c.fail(root.get("role"), "role", role, "must be ao (an AO estimator)");
    if (r == roles.end())
        return c.fail(root.get("role"), "role", role,
                      "must be ao, reference, gbuffer, pyramid, downsample, upsample, blur, indirect or composite");
    k.role = r->second;
    CAVITY_ASSIGN(const std::string given, text(c, root, "", "file", true));
    // "./my_ao.glsl" is "my_ao.glsl".
    const std::string file = given.rfind("./", 0) == 0 ? std::filesystem::path(given).lexically_normal().generic_string() : given;
    // The package's own file, or as for an #include a source under kernels/
    // that several kernels share (hemisphere_cosine runs hemisphere's body).
    const bool shared = !c.in.hasFile(file) && sourceFile(file) && file.size() > 5 &&
                        file.compare(file.size() - 5, 5, ".glsl") == 0;
    if (file.empty() || file.find("..") != std::string::npos || file[0] == '/')
        return c.fail(root.get("file"), "file", file,
                      "must name a file in the package's folder by its own name (no '..', not an absolute path)");
    const bool glsl = file.size() > 5 && file.compare(file.size() - 5, 5, ".glsl") == 0;
    if (!glsl) return c.fail(root.get("file"), "file", file, "must name the kernel's GLSL source, a .glsl file");
    if (!c.in.hasFile(file) && !shared)
        return c.fail(root.get("file"), "file", file,
                      "no such file in the package's folder (the kernel's GLSL) nor under kernels/ (a file "
                      "reached through a link out of the folder is not the package's)");
    k.file = shared ? file : c.in.keyPrefix + file;
    CAVITY_ASSIGN(k.reference, text(c, root, "", "reference", false));
    if (!k.reference.empty() && !std::regex_match(k.reference, ident))
        return c.fail(root.get("reference"), "reference", k.reference,
                      "must name a CPU reference as harness/reference/ registers it (a-z, then a-z, 0-9 or _)");
    CAVITY_TRY(readWorkgroup(root, c, k));
    CAVITY_TRY(readFlag(root, c, "whole_workgroups", k.wholeWorkgroups));
    return readFlag(root, c, "interleaved", k.interleaved);
}

Status readInputs(const toml::table& root, const Ctx& c, KernelDecl& k) {
    CAVITY_ASSIGN(const toml::array* a, arrayOfTables(c, root, "inputs"));
    // An estimator reads what the pipeline makes before it; a pass of the
    // pipeline reads what the pipeline hands it (harness/pipeline/pipelines.cpp),
    // and the G-buffer pass nothing.
    const bool estimator = k.role == Role::Ao || k.role == Role::Reference;
    if ((!a || a->empty()) && estimator)
        return c.fail(&root, "inputs", "", "missing; a kernel reads at least one image ([[inputs]])");
    if (!a) return {};
    const auto provided = providedInputs();
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::table& t = *a->get(i)->as_table();
        const std::string where = "inputs[" + std::to_string(i) + "].";
        CAVITY_TRY(onlyKeys(c, t, where, {"name", "filter", "address", "mipmaps"}));
        InputDecl in;
        CAVITY_ASSIGN(in.name, text(c, t, where, "name", true));
        if (estimator && !provided.count(in.name))
            return c.fail(t.get("name"), where + "name", in.name, "no pass provides it; inputs are " + joined(provided));
        for (const auto& d : k.inputs)
            if (d.name == in.name) return c.fail(t.get("name"), where + "name", in.name, "read twice");
        CAVITY_ASSIGN(const std::string filter, text(c, t, where, "filter", false));
        if (!filter.empty() && filter != "nearest" && filter != "linear")
            return c.fail(t.get("filter"), where + "filter", filter, "must be nearest or linear");
        in.sampler.filter = filter == "linear" ? gpu::Filter::Linear : gpu::Filter::Nearest;
        CAVITY_ASSIGN(const std::string address, text(c, t, where, "address", false));
        if (!address.empty() && address != "clamp" && address != "repeat")
            return c.fail(t.get("address"), where + "address", address, "must be clamp or repeat");
        in.sampler.address = address == "repeat" ? gpu::Address::Repeat : gpu::Address::ClampToEdge;
        CAVITY_TRY(readFlag(t, c, "mipmaps", in.sampler.mipmaps));
        k.inputs.push_back(in);
    }
    return {};
}

namespace {

// The outputs an estimator may write, in order: the pipeline's tail reads
// "ao" (or SSDO's "visibility" and "radiance"), and the separable blur the
// packed key beside it.
const std::vector<std::vector<std::string>>& estimatorOutputs() {
    static const std::vector<std::vector<std::string>> sets = {
        {"ao"}, {"ao", "ao_key"}, {"visibility", "radiance"}, {"visibility", "radiance", "ao_key"}};
    return sets;
}

}  // namespace

Status readOutputs(const toml::table& root, const Ctx& c, KernelDecl& k) {
    CAVITY_ASSIGN(const toml::array* a, arrayOfTables(c, root, "outputs"));
    if (!a || a->empty()) return c.fail(&root, "outputs", "", "missing; an AO kernel writes ao ([[outputs]])");
    std::string formats;
    for (const auto& [name, f] : outputFormats()) formats += (formats.empty() ? "" : ", ") + name;
    const bool estimator = k.role == Role::Ao || k.role == Role::Reference;
    std::vector<std::string> names;
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::table& t = *a->get(i)->as_table();
        const std::string where = "outputs[" + std::to_string(i) + "].";
        CAVITY_TRY(onlyKeys(c, t, where, estimator ? std::set<std::string>{"name", "format"}
                                                   : std::set<std::string>{"name", "format", "mip_levels", "one_dispatch",
                                                                           "layered"}));
        OutputDecl o;
        CAVITY_ASSIGN(o.name, text(c, t, where, "name", true));
        names.push_back(o.name);
        if (estimator) {
            const bool fits = std::any_of(estimatorOutputs().begin(), estimatorOutputs().end(), [&](const auto& set) {
                return set.size() >= names.size() && std::equal(names.begin(), names.end(), set.begin());
            });
            if (!fits)
                return c.fail(t.get("name"), where + "name", o.name,
                              "an AO kernel writes ao (then ao_key, the separable blur's key), or SSDO's visibility "
                              "and radiance (then ao_key), in that order");
        } else {
            for (size_t j = 0; j + 1 < names.size(); ++j)
                if (names[j] == o.name) return c.fail(t.get("name"), where + "name", o.name, "written twice");
        }
        CAVITY_ASSIGN(const std::string format, text(c, t, where, "format", true));
        const auto f = outputFormats().find(format);
        if (f == outputFormats().end())
            return c.fail(t.get("format"), where + "format", format, "no backend image of that format; one of " + formats);
        o.format = f->second;
        if (const toml::node* m = t.get("mip_levels")) {
            if (!m->is_integer() || *m->value<int64_t>() < 1 || *m->value<int64_t>() > 16)
                return c.fail(m, where + "mip_levels", show(*m), "must be 1 to 16");
            o.mipLevels = int(*m->value<int64_t>());
        }
        CAVITY_TRY(readFlag(t, c, "one_dispatch", o.oneDispatch));
        CAVITY_TRY(readFlag(t, c, "layered", o.layered));
        k.outputs.push_back(o);
    }
    if (estimator && std::none_of(estimatorOutputs().begin(), estimatorOutputs().end(),
                                  [&](const auto& set) { return set == names; }))
        return c.fail(&root, "outputs", "", "an AO kernel writes ao, or SSDO's visibility and radiance");
    return {};
}

Status readArrays(const toml::table& root, const Ctx& c, KernelDecl& k) {
    CAVITY_ASSIGN(const toml::array* a, arrayOfTables(c, root, "arrays"));
    if (!a) return {};
    // The tables the CPU makes: each a function of the kernel's own parameters.
    const std::map<std::string, std::vector<std::string>> generators = {
        {"gaussian_weights", {"blur"}}, {"hemisphere_kernel", {"samples"}}, {"cosine_kernel", {"samples", "steps"}},
        {"spiral", {}}, {"sky_sh", {}}};
    std::vector<std::pair<std::string, std::string>> derived;
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::table& t = *a->get(i)->as_table();
        const std::string where = "arrays[" + std::to_string(i) + "].";
        CAVITY_TRY(onlyKeys(c, t, where, {"name", "vec4", "derive"}));
        ArrayDecl d;
        CAVITY_ASSIGN(d.name, text(c, t, where, "name", true));
        static const std::regex ident("[a-z][a-z0-9_]{0,31}");
        if (!std::regex_match(d.name, ident) || reservedName(d.name, false))
            return c.fail(t.get("name"), where + "name", d.name, "must be a GLSL name (a-z, then a-z, 0-9 or _; 32 at "
                          "most) that GLSL and the harness do not keep");
        if (declares(k, d.name) || std::any_of(k.arrays.begin(), k.arrays.end(), [&](const auto& o) { return o.name == d.name; }))
            return c.fail(t.get("name"), where + "name", d.name, "is taken by a parameter or array of this kernel");
        const toml::node* n = t.get("vec4");
        if (!n || !n->is_integer() || *n->value<int64_t>() < 1 || *n->value<int64_t>() > 1024)
            return c.fail(n ? n : &t, where + "vec4", n ? show(*n) : "", "must be the array's vec4 count, 1 to 1024");
        d.vec4Count = int(*n->value<int64_t>());
        CAVITY_ASSIGN(const std::string gen, text(c, t, where, "derive", true));
        const auto g = generators.find(gen);
        if (g == generators.end())
            return c.fail(t.get("derive"), where + "derive", gen,
                          "must be gaussian_weights, hemisphere_kernel, cosine_kernel, spiral or sky_sh");
        for (const auto& p : g->second)
            if (!declares(k, p))
                return c.fail(t.get("derive"), where + "derive", gen, "reads the parameter " + p + ", which this kernel "
                              "does not declare");
        k.arrays.push_back(d);
        derived.emplace_back(d.name, gen);
    }
    k.derive = [derived](const ParamValues& v, std::map<std::string, std::vector<float>>& arrays) {
        for (const auto& [name, gen] : derived) {
            if (gen == "gaussian_weights") arrays[name] = gaussianWeights(intValue(v, "blur"));
            else if (gen == "hemisphere_kernel") arrays[name] = hemisphereKernel(intValue(v, "samples"));
            else if (gen == "cosine_kernel") arrays[name] = cosineKernel(intValue(v, "samples"), intValue(v, "steps"));
            else if (gen == "spiral") arrays[name] = spiralTable();
            else arrays[name] = skySh();
        }
    };
    return {};
}

Status readPipeline(const toml::table& root, const Ctx& c, const KernelDecl& k) {
    const toml::node* n = root.get("pipeline");
    if (!n) return {};
    const toml::table* t = n->as_table();
    if (!t) return c.fail(n, "pipeline", show(*n), "must be a table ([pipeline])");
    CAVITY_TRY(onlyKeys(c, *t, "pipeline.", {"blur"}));
    CAVITY_ASSIGN(const std::string blur, text(c, *t, "pipeline.", "blur", false));
    if (blur.empty()) return {};
    // The pipeline follows from the outputs and inputs (pipelines.cpp); a
    // stated blur must be the one they give.
    const bool key = k.outputs.back().name == "ao_key", noise = std::any_of(k.inputs.begin(), k.inputs.end(), [](const auto& i) {
        return i.name == "noise4x4";
    });
    const std::string follows = key ? "separable" : noise ? "box" : "bilateral";
    if (blur != "bilateral" && blur != "separable" && blur != "box")
        return c.fail(t->get("blur"), "pipeline.blur", blur, "must be bilateral, separable or box");
    if (blur != follows)
        return c.fail(t->get("blur"), "pipeline.blur", blur,
                      "this kernel gets the " + follows + " blur: separable follows an ao_key output, box a noise4x4 "
                      "input, bilateral otherwise");
    return {};
}

Status readExpectations(const toml::table& root, const Ctx& c, KernelDecl& k) {
    const toml::node* n = root.get("expectations");
    if (!n) return {};
    const toml::table* t = n->as_table();
    if (!t) return c.fail(n, "expectations", show(*n), "must be a table ([expectations])");
    CAVITY_TRY(onlyKeys(c, *t, "expectations.", {"open_worst", "open_mean", "crease", "narrow_gap"}));
    for (const char* key : {"open_worst", "open_mean", "crease"}) {
        const toml::node* v = t->get(key);
        if (!v) continue;
        // A seed kept as published departs from the truth at a crease.
        if (std::string(key) == "crease" && v->is_string() && *v->value<std::string>() == "seed") {
            k.expectations[key] = "seed";
            continue;
        }
        // An integer as TOML holds it (64 bits): value<double>() has none for
        // one a double cannot hold exactly. NaN fails the range too.
        const double x = !v->is_number() ? NAN : v->is_integer() ? double(*v->value<int64_t>()) : *v->value<double>();
        if (!(x >= 0 && x <= 1))
            return c.fail(v, std::string("expectations.") + key, show(*v),
                          std::string("must be a number in 0..1") + (std::string(key) == "crease" ? ", or \"seed\"" : ""));
        k.expectations[key] = std::to_string(x);
    }
    CAVITY_ASSIGN(const std::string gap, text(c, *t, "expectations.", "narrow_gap", false));
    if (!gap.empty() && gap != "layer" && gap != "seed")
        return c.fail(t->get("narrow_gap"), "expectations.narrow_gap", gap,
                      "must be layer (as dark as one depth layer shows) or seed (brighter: the gap read as open)");
    if (!gap.empty()) k.expectations["narrow_gap"] = gap;
    return {};
}

}  // namespace cavity::kernels::toml_read
