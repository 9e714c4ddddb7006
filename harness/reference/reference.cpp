// reference::run: looks the kernel up among the references and checks what
// goes in and comes out, so each ref_*.cpp can assume a well-formed context.
#include "reference/refs.h"

#include "package/package.h"

#include <algorithm>
#include <cmath>

namespace cavity::reference {

namespace {

std::vector<RefEntry> firstSliceRefs() {
    return {{"gbuffer_sdf", gbufferSdf}, {"alchemy", alchemy}, {"blur_bilateral", blurBilateral}, {"composite", composite}};
}

}  // namespace

std::vector<HostImage> makeOutputs(const Context& ctx) {
    std::vector<HostImage> out;
    // An atlas of interleaved layers is rounded up to whole layers.
    const int k = kernels::interleaveValue(ctx.params);
    for (const auto& o : ctx.kernel.outputs)
        out.emplace_back(kernels::outputExtent(o, ctx.frame.size[0], k), kernels::outputExtent(o, ctx.frame.size[1], k),
                         gpu::channelCount(o.format));
    return out;
}

int intParam(const Context& ctx, const std::string& name) { return kernels::intValue(ctx.params, name); }

float floatParam(const Context& ctx, const std::string& name) { return kernels::floatValue(ctx.params, name); }

const std::vector<float>& array(const Context& ctx, const std::string& name) {
    static const std::vector<float> empty;
    auto it = ctx.arrays.find(name);
    return it == ctx.arrays.end() ? empty : it->second;
}

Status requireInputs(const Context& ctx, std::initializer_list<int> minChannels) {
    size_t i = 0;
    for (int channels : minChannels) {
        const HostImage& in = *ctx.inputs.at(i);
        const std::string what = "reference " + ctx.kernel.name + ": input '" + ctx.kernel.inputs[i].name + "' ";
        if (in.width != ctx.frame.size[0] || in.height != ctx.frame.size[1])
            return internal(what + "is " + std::to_string(in.width) + "x" + std::to_string(in.height) + ", the output " +
                            std::to_string(ctx.frame.size[0]) + "x" + std::to_string(ctx.frame.size[1]));
        if (in.channels < channels)
            return internal(what + "has " + std::to_string(in.channels) + " channels, needs " + std::to_string(channels));
        ++i;
    }
    return {};
}

namespace {

std::vector<RefEntry> allRefs() {
    std::vector<RefEntry> table = firstSliceRefs();
    for (const auto& e : screenSpaceRefs()) table.push_back(e);
    for (const auto& e : sdfAoRefs()) table.push_back(e);
    for (const auto& e : fastRefs()) table.push_back(e);
    return table;
}

}  // namespace

bool hasReference(const std::string& kernel) {
    const auto* k = kernels::find(kernel);
    if (!k || !isReference(k->reference)) return false;
    // A reference is C++ kept equal to the built-in shader it names: a
    // user's package (a copy of a built-in one keeps its reference line)
    // runs other code, so it has none.
    const auto& loaded = kernels::packages();
    return std::any_of(loaded.begin(), loaded.end(), [&](const auto& p) { return p.name == kernel && p.builtIn; });
}

bool isReference(const std::string& name) {
    for (const auto& e : allRefs())
        if (name == e.kernel) return true;
    return false;
}

std::vector<std::string> referenceNames() {
    std::vector<std::string> names;
    for (const auto& e : allRefs()) names.push_back(e.kernel);
    return names;
}

Result<std::vector<HostImage>> run(const Context& ctx) {
    const std::string& name = ctx.kernel.name;
    if (ctx.inputs.size() != ctx.kernel.inputs.size())
        return internal("reference " + name + ": " + std::to_string(ctx.inputs.size()) + " inputs given, the kernel reads " +
                        std::to_string(ctx.kernel.inputs.size()));
    for (size_t i = 0; i < ctx.inputs.size(); ++i)
        if (!ctx.inputs[i] || ctx.inputs[i]->width <= 0 || ctx.inputs[i]->height <= 0)
            return internal("reference " + name + ": input '" + ctx.kernel.inputs[i].name + "' is missing or empty");
    for (const auto& p : ctx.kernel.params)
        if (!ctx.params.count(p.name()))
            return internal("reference " + name + ": parameter '" + p.name() + "' has no value (use withDefaults)");

    for (const auto& entry : allRefs()) {
        if (ctx.kernel.reference.empty() || ctx.kernel.reference != entry.kernel) continue;
        CAVITY_ASSIGN(auto out, entry.fn(ctx));
        if (out.size() != ctx.kernel.outputs.size())
            return internal("reference " + name + " returned " + std::to_string(out.size()) + " images");
        return out;
    }
    return internal("no CPU reference for kernel '" + name + "'" +
                    (ctx.kernel.reference.empty() ? std::string(" (its package names none)")
                                                  : " (its package names '" + ctx.kernel.reference +
                                                        "', which harness/reference/ does not register)"));
}

}  // namespace cavity::reference
