// Kernel parameters: each name declared once (kernels/params.cpp), every
// kernel referring to that declaration, and one parse that makes an integer
// parameter an integer.
#include "harness_names.h"
#include "core/config.h"
#include "kernel.h"
#include "package/declaration.h"
#include "pipeline/pipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <map>
#include <set>

using namespace cavity::harness;

namespace cavity::kernels {
const std::map<std::string, std::string>& embeddedSources();   // kernel_sources.cpp
}

namespace {

using namespace cavity;
using kernels::ParamType;

TEST(Params, EachNameIsDeclaredOnce) {
    std::set<std::string> names;
    for (const auto& p : kernels::paramDecls()) EXPECT_TRUE(names.insert(p.name).second) << p.name << " declared twice";
    EXPECT_GE(names.size(), 20u);
}

TEST(Params, EveryKernelRefersToTheOneDeclaration) {
    std::set<const kernels::ParamDecl*> used;
    for (const auto& k : kernels::all()) {
        std::set<std::string> seen;
        for (const auto& u : k.params) {
            ASSERT_NE(u.decl, nullptr) << k.name;
            // The address, not a copy: range, unit and help cannot drift apart.
            EXPECT_EQ(u.decl, kernels::findParam(u.name())) << k.name << " --" << u.name();
            EXPECT_TRUE(seen.insert(u.name()).second) << k.name << " reads --" << u.name() << " twice";
            // A kernel's own default is still inside the one range.
            EXPECT_TRUE(kernels::checkValue(*u.decl, u.def).ok()) << k.name << " --" << u.name() << " default " << u.def;
            used.insert(u.decl);
        }
    }
    // A declaration no kernel reads would be a flag that does nothing.
    for (const auto& p : kernels::paramDecls()) EXPECT_TRUE(used.count(&p)) << "--" << p.name << " is read by no kernel";
}

TEST(Params, SharedNamesAreSharedAndKernelsMayKeepTheirOwnDefault) {
    int samples = 0;
    for (const auto& k : kernels::all())
        for (const auto& u : k.params)
            if (u.name() == "samples") ++samples;
    EXPECT_GE(samples, 8);   // alchemy, hemisphere, ssdo, the SDF family...
    auto defaultOf = [](const std::string& kernel, const std::string& name) {
        for (const auto& u : kernels::find(kernel)->params)
            if (u.name() == name) return u.def;
        return -1.0;
    };
    EXPECT_EQ(defaultOf("alchemy", "radius"), 0.5);
    EXPECT_EQ(defaultOf("sdf_classic", "radius"), 0.13);
    EXPECT_EQ(defaultOf("alchemy", "contrast"), 1.5);
    EXPECT_EQ(defaultOf("hemisphere", "contrast"), 1.0);
    EXPECT_EQ(defaultOf("hemisphere_cosine", "step_jitter"), 1.0);
}

TEST(Params, OneParseMakesAnIntegerAnInteger) {
    const auto& samples = *kernels::findParam("samples");
    ASSERT_EQ(samples.type, ParamType::Int);
    auto v = kernels::parseValue(samples, "32");
    ASSERT_TRUE(v.ok());
    EXPECT_EQ(*v, 32.0);
    EXPECT_EQ(kernels::intValue({{"samples", *v}}, "samples"), 32);
    for (const char* bad : {"16.5", "0", "257", "abc", "", "nan"}) {
        auto r = kernels::parseValue(samples, bad);
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("--samples"), std::string::npos) << r.error().message;
        EXPECT_NE(r.error().message.find("an integer in 1..256 (samples)"), std::string::npos) << r.error().message;
    }
    const auto& scene = *kernels::findParam("scene");
    EXPECT_EQ(*kernels::parseValue(scene, "slats"), 1.0);
    EXPECT_FALSE(kernels::parseValue(scene, "kitchen").ok());
}

// Values the shader cannot tell apart (its uniforms are 32-bit floats) are
// one value, so one configuration and one id; decimals stay as written.
TEST(Params, ValuesAreTheShadersThirtyTwoBitFloats) {
    const auto& radius = *kernels::findParam("radius");
    EXPECT_EQ(*kernels::parseValue(radius, "0.50000001"), 0.5);
    EXPECT_EQ(*kernels::parseValue(radius, "0.60000001"), 0.6);
    for (const char* kept : {"0.6", "0.03", "1.5", "0.1", "2"})
        EXPECT_EQ(*kernels::parseValue(radius, kept), std::stod(kept)) << kept;
    EXPECT_EQ(kernels::valueText(radius, *kernels::parseValue(radius, "0.30000001")), "0.3");
    const auto& bias = *kernels::findParam("bias");
    const double zero = *kernels::parseValue(bias, "-0");
    EXPECT_FALSE(std::signbit(zero)) << "-0 names the configuration of 0";
    EXPECT_EQ(kernels::valueText(bias, zero), "0");
    for (const char* bad : {"16.0", "1e1", "+16"})
        EXPECT_FALSE(kernels::parseValue(*kernels::findParam("samples"), bad).ok()) << bad << ": an integer in digits";
}

TEST(Params, SetParamRejectsAnOutOfRangeValueAtParseTime) {
    RunConfig c;
    auto s = setParam(c, "blur", "33");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message.rfind("--blur 33: must be an integer in 0..32", 0), 0u) << s.error().message;
    EXPECT_TRUE(c.params.empty());
    EXPECT_FALSE(setParam(c, "radiuss", "1").ok());
    ASSERT_TRUE(setParam(c, "radius", "0.25").ok());
    EXPECT_EQ(c.params.at("radius"), 0.25);
    // A value set in code is checked by validate() against the same declaration.
    c.params["samples"] = 16.5;
    EXPECT_FALSE(validate(c).ok());
}

}  // namespace

namespace cavity::test {
namespace {

// Every compute pass's storage images fit the 8 image units the NVIDIA
// driver's GL has (GL_MAX_IMAGE_UNITS; Mesa has more, so only this check
// sees a pass that would fail there): storage images are bound first, from
// kFirstImageBinding, and the sampled inputs after them, in texture units.
TEST(Bindings, StorageImagesFitEightGlImageUnits) {
    for (const auto& k : kernels::all()) {
        const auto layout = kernels::bindingLayout(k, gpu::Stage::Compute);
        std::set<uint32_t> used;
        for (const auto& slot : layout) {
            EXPECT_TRUE(used.insert(slot.binding).second) << k.name << ": binding " << slot.binding << " twice";
            if (slot.kind == gpu::BindingKind::StorageImage) {
                EXPECT_LT(slot.binding, 8u) << k.name << ": storage image at image unit " << slot.binding;
            }
        }
    }
}

// The harness's own packages skip the count check at start
// (DeclarationInput::checkCounts): here each is read with it, so a cost
// formula that gives infinity or a negative count somewhere in a built-in's
// parameter range still fails.
TEST(Params, BuiltInCostsAreFiniteOverEveryParameterRange) {
    kernels::all();
    int read = 0;
    for (const auto& [key, text] : kernels::embeddedSources()) {
        if (key.size() < 12 || key.compare(key.size() - 12, 12, "/kernel.toml") != 0) continue;
        const std::string folder = key.substr(0, key.size() - 11);
        kernels::PackageInfo info;
        const kernels::DeclarationInput in{text, "kernels/" + key, folder,
                                           [&](const std::string& f) { return kernels::embeddedSources().count(folder + f) > 0; },
                                           [](const std::string&) { return false; }, key.rfind("ao/", 0) == 0 || key.rfind("passes/", 0) == 0,
                                           true};
        const auto k = kernels::readDeclaration(in, info);
        EXPECT_TRUE(static_cast<bool>(k)) << key << ": " << (k ? "" : k.error().message);
        ++read;
    }
    EXPECT_GE(read, 10);
}

}  // namespace
}  // namespace cavity::test
