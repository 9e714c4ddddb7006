// Every kernel parameter, declared once (params.h). A name is one flag with
// one value for every kernel of a pipeline, so its range, unit and help are
// the same wherever it is read; what each kernel does with it is the kernel's
// note (its package's kernel.toml: kernels/ao/, kernels/passes/).
#include "params.h"

#include "kernel.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cavity::kernels {

namespace {

ParamDecl make(std::string name, ParamType type, double def, double min, double max, std::string unit,
               std::string help, bool minExclusive = false) {
    ParamDecl p;
    p.name = std::move(name);
    p.type = type;
    p.def = def;
    p.min = min;
    p.max = max;
    p.unit = std::move(unit);
    p.help = std::move(help);
    p.minExclusive = minExclusive;
    return p;
}

ParamDecl flag(std::string name, bool def, std::string help) {
    return make(std::move(name), ParamType::Bool, def ? 1 : 0, 0, 1, "", std::move(help));
}

ParamDecl choice(std::string name, std::vector<std::string> choices, std::string help) {
    ParamDecl p = make(std::move(name), ParamType::Enum, 0, 0, double(choices.size()) - 1, "", std::move(help));
    p.choices = std::move(choices);
    return p;
}

// The hemisphere kernel array has room for the largest `samples` (256), so
// every allowed sample count is honoured as given, none clamped: 4 KiB of
// uniforms, well inside the 16 KiB every GL and Vulkan device offers
// (the hemisphere kernels' packages).
constexpr double kMaxSamples = 256;

// The fast pipelines' switches: each picks another way to compute the same
// (or, stated, nearly the same) image.
std::vector<ParamDecl> declareSwitches() {
    using T = ParamType;
    return {
        // The precision contract (include/common.glsl, docs/kernels.md): the
        // CPU reference bit for bit, or the hardware's own arithmetic and a
        // stated tolerance.
        flag("exact", false,
             "the fast kernels' arithmetic: 0, the GPU's own (fma, its division and sine), held to a stated "
             "tolerance of the CPU reference; 1, the CPU reference's bit for bit (precise, portable division and "
             "sine), slower"),
        // The depth pyramid of the fast kernels: one dispatch (depth_pyramid_single)
        // or one per level, a barrier apart (depth_pyramid): the same levels.
        flag("pyramid_per_level", false,
             "build the fast kernels' depth pyramid a dispatch per level (depth_pyramid), not in one (depth_pyramid_single)"),
        // Interleaved layers (docs/kernels.md, "Interleaved layers"): the AO
        // pass as k x k layers of every k-th pixel, one dispatch over all of
        // them, each layer with one sample phase, reading the depth split into
        // those layers; as HBAO+ and ASSAO render AO, for cache coherence.
        make("interleave", T::Int, 1, 1, 4, "layers per axis",
             "run the AO pass as k x k interleaved layers of every k-th pixel, one sample phase per layer, reading "
             "the depth split into layers (1: every pixel its own phase, one plain dispatch)"),
        // The half-resolution tail as two passes (upsample_bilateral, then
        // composite) or fused into one (upsample_composite): the same image.
        flag("fused_tail", false,
             "at half resolution, upsample and composite in one full-resolution pass (upsample_composite)"),
    };
}

std::vector<ParamDecl> declare() {
    using T = ParamType;
    std::vector<ParamDecl> decls = {
        // The scene and camera pose: read by the G-buffer kernels and by every
        // kernel that evaluates the signed-distance scene itself (the SDF AO
        // family), so one --scene drives them all. Order is
        // kernels/include/sdf_scenes.glsl's.
        choice("scene", {"corner", "slats", "open", "contact", "grille", "plates"},
               "scene: corner (floor, two walls, a sphere at the crease), slats (a cabinet of 30 slats "
               "with recesses), open (a bare floor), contact (objects resting on a table), grille (a "
               "perforated panel before a cavity), plates (three stacked plates)"),
        make("view", T::Int, 0, 0, 3, "", "camera pose of the scene (four per scene)"),
        make("samples", T::Int, 16, 1, kMaxSamples, "samples", "samples per pixel (n)"),
        make("rays", T::Int, 1024, 1024, 65536, "rays", "rays per pixel, stratified (a Fibonacci lattice)"),
        make("radius", T::Float, 0.5, 0, 100, "world units", "reach of the occlusion R: occluders farther away do not count",
             true),
        make("bias", T::Float, 0.01, 0, 1, "world units",
             "distance a sample must lie beyond the surface's tangent plane to occlude (hides G-buffer rounding, "
             "no self-shadowing)"),
        make("scale", T::Float, 1.5, 0, 10, "", "obscurance scale s in A = max(0, 1 - s S)^k"),
        make("contrast", T::Float, 1, 0.1, 10, "", "contrast exponent k: the AO (or visibility) is raised to the power k"),
        make("strength", T::Float, 1, 0, 100, "", "k: how hard a distance shortfall counts"),
        flag("ign_jitter", true, "rotate the 4x4 noise vector by interleaved gradient noise, hiding the tile's grid"),
        flag("range_check", true, "fade out occluders far from the surface in depth (smoothstep(0, 1, R / |dz|))"),
        flag("step_jitter", false, "move each direction's steps in by a random share of a step per pixel"),
        // Points tested along each ray, out to R: hemisphere_cosine's march
        // (cosineKernel) and SSDO's (include/ssdo.glsl), where 1 is seed 003's
        // one point at a random length; ssdo_marched marches 4.
        make("steps", T::Int, 4, 1, 16, "points",
             "points tested along each ray, marched out to R (1: one point at a random length in (0, R], as published SSDO)"),
        // The box blur pass after the hemisphere kernels: seed 004's plain 4x4
        // box, or blur_box_depth (kernels/passes/blur_box_depth), which keeps to
        // the centre's surface.
        flag("depth_aware_box", false,
             "box-blur only the texels of the centre's surface (blur_box_depth), not all 16 (as the published hemisphere SSAO)"),
        // Level 5 of the 256x128 panorama is 8x4 texels of 45 degrees, about
        // 0.5 sr each: the 0.4 sr that each of the default 16 samples stands
        // for (2 pi / n). At level 4 or lower the sun is a lobe that only a
        // sample or two per pixel hit, and the direct radiance shows the sample
        // pattern as rings on curved surfaces; at 6 the sky is 4x2 texels and
        // the sun's direction is mostly lost. Seed 003's "8 to 10" is the same
        // choice for a panorama 8-32 times wider. An integer level also keeps
        // the GPU's quantised mip blend out of the reference comparison.
        make("sky_lod", T::Float, 5, 0, 8, "mip level", "level of the sky panorama the SSDO samples read (0: 256x128, 8: 1x1)"),
        make("bounce_strength", T::Float, 1, 0, 100, "", "scale of the indirect bounce (published SSDO's strength)"),
        // R / 5 at the default R. With Alchemy's 0.1 R, senders almost
        // touching their receiver at a crease gave single-pixel sparks of
        // up to 2.6 on the corner and slats scenes (direct radiance is about
        // 1 there); R / 5 caps 1/d^2 at 25 / R^2, and the bounce still grows
        // smoothly towards the crease.
        make("distance_clamp", T::Float, 0.1, 0, 10, "world units",
             "lower bound of the sender-receiver distance in the form factor's 1/d^2", true),
        make("blur", T::Int, 4, 0, 32, "px", "blur radius r, sigma = r/2; 0 passes through"),
        // Above 1e-4: the weight divides by 2 sigma^2 in 32-bit floats, and a
        // tinier sigma overflows that to inf and the centre tap to 0 * inf = NaN.
        make("depth_sigma", T::Float, 0.1, 1e-4, 10, "world units",
             "sigma of the depth weight exp(-dd^2 / (2 sigma^2)) between a tap and the centre", true),
        make("upsample_depth_tolerance", T::Float, 0.01, 0, 1, "fraction of depth",
             "distance of a half texel from the pixel's tangent plane, relative to depth, at which its "
             "weight falls to exp(-1/2)",
             true),
    };
    for (auto& d : declareSwitches()) decls.push_back(std::move(d));
    decls.push_back(choice("ssdo_mode", {"visibility", "radiance"},
                           "visibility: SH sky ambient x visibility + bounce; radiance: direct sky radiance + bounce"));
    decls.push_back(flag("dither", true, "add +-0.5/255 of interleaved gradient noise against 8-bit banding"));
    return decls;
}

std::string number(double x) {
    // A whole number up to 2^53 in full (2147483647, not 2.14748e+09),
    // anything else in the shortest text that reads back as the same value
    // (a float's as a float): %g's six digits printed 3.4028236e38 as
    // 3.40282e+38, the bound it was refused against.
    if (std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 9007199254740992.0) return std::to_string((long long)x);
    char buf[64];
    const bool isFloat = std::isfinite(x) && std::fabs(x) <= double(std::numeric_limits<float>::max()) &&
                         double(float(x)) == x;
    const auto r = isFloat ? std::to_chars(buf, buf + sizeof buf, float(x)) : std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, r.ptr);
}


}  // namespace

namespace {

std::deque<ParamDecl>& storage() {
    static std::deque<ParamDecl> decls = [] {
        const auto built = declare();
        return std::deque<ParamDecl>(built.begin(), built.end());
    }();
    return decls;
}

}  // namespace

// True on the thread that is building the registry (registry.cpp).
bool& registryBuilding() {
    thread_local bool building = false;
    return building;
}

// The built-in packages declare parameters as the registry is built, so the
// list is complete only after it: anyone else asking builds it first.
const std::deque<ParamDecl>& paramDecls() {
    if (!registryBuilding()) (void)all();
    return storage();
}

void forgetParamsAfter(size_t count) {
    while (storage().size() > count) storage().pop_back();
}

const ParamDecl* declareParam(ParamDecl p) {
    storage().push_back(std::move(p));
    return &storage().back();
}

// The built-in declarations first, without building the registry: static
// initialisers ask for them (noise_tables.cpp's largest sample count)
// before the registry may be built. Only a name they lack waits for the
// packages' parameters.
const ParamDecl* findParam(const std::string& name) {
    for (const auto& p : storage())
        if (p.name == name) return &p;
    for (const auto& p : paramDecls())
        if (p.name == name) return &p;
    return nullptr;
}

KernelParam use(const std::string& name, std::string note) {
    const ParamDecl* p = findParam(name);
    if (!p) throw std::logic_error("kernel registry: parameter '" + name + "' is not declared in kernels/params.cpp");
    return {p, p->def, std::move(note)};
}

KernelParam use(const std::string& name, double def, std::string note) {
    KernelParam k = use(name, std::move(note));
    k.def = def;
    return k;
}

Status checkValue(const ParamDecl& p, double x) {
    const std::string flag = "--" + p.name + " " + number(x);
    if (p.type == ParamType::Enum) {
        if (x != std::floor(x) || x < 0 || x >= double(p.choices.size())) return badInput(flag + ": must be " + allowedValues(p));
        return {};
    }
    const bool integral = isIntegral(p.type);
    const bool lowOk = p.minExclusive ? x > p.min : x >= p.min;
    // The shader reads a float: a value below the smallest normal float
    // would arrive as 0 or a denormal (a radius of 1e-300 is a radius of 0).
    const bool floatOk = integral || x == 0 || std::fabs(x) >= std::numeric_limits<float>::min();
    if (!std::isfinite(x) || (integral && x != std::floor(x)) || !lowOk || x > p.max || !floatOk)
        return badInput(flag + ": must be " + allowedValues(p));
    return {};
}

Result<double> parseValue(const ParamDecl& p, const std::string& text) {
    if (p.type == ParamType::Enum) {
        for (size_t i = 0; i < p.choices.size(); ++i)
            if (p.choices[i] == text) return double(i);
        return badInput("--" + p.name + " " + text + ": must be " + allowedValues(p));
    }
    // strtod-like syntax without locale or hex floats: std::from_chars.
    double v = 0;
    const char* b = text.data();
    auto r = std::from_chars(b, b + text.size(), v);
    if (text.empty() || r.ec != std::errc() || r.ptr != b + text.size() || !std::isfinite(v))
        return badInput("--" + p.name + " '" + text + "': must be " + allowedValues(p));
    // An integer is written in digits: 16.0 and 1e1 would otherwise name the
    // configuration n16 and n10 while the command line said something else.
    if (isIntegral(p.type) && text.find_first_not_of("-0123456789") != std::string::npos)
        return badInput("--" + p.name + " '" + text + "': must be " + allowedValues(p) + ", written in digits");
    CAVITY_TRY(checkValue(p, v));
    return canonicalValue(p, v);
}

double canonicalValue(const ParamDecl& p, double v) {
    if (v == 0) return 0;
    if (p.type != ParamType::Float || !std::isfinite(v) || std::fabs(v) > double(std::numeric_limits<float>::max()))
        return v;
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, float(v));
    double canonical = v;
    std::from_chars(buf, r.ptr, canonical);
    return canonical;
}

std::string allowedValues(const ParamDecl& p) {
    const bool integral = isIntegral(p.type);
    std::string what = integral ? "an integer in " + number(p.min) + ".." + number(p.max)
                     : p.minExclusive ? "a number > " + number(p.min) + " and <= " + number(p.max)
                                      : "a number in " + number(p.min) + ".." + number(p.max);
    if (p.type == ParamType::Bool) what = "0 or 1";
    if (p.type == ParamType::Enum) {
        what = "one of ";
        for (size_t i = 0; i < p.choices.size(); ++i) what += (i ? ", " : "") + p.choices[i];
    }
    // Denormals are refused (a GPU may flush them): said only where the
    // range reaches them, and 0 offered only where the range holds it.
    const double least = std::numeric_limits<float>::min();
    if (p.type == ParamType::Float && p.min < least && p.max > -least) {
        const bool zero = p.min <= 0 && p.max >= 0 && !(p.minExclusive && p.min == 0);
        what += std::string(", and ") + (zero ? "0 or " : "") + "at least " + number(least) + " in magnitude (a 32-bit float)";
    }
    return what + (p.unit.empty() ? "" : " (" + p.unit + ")");
}

std::string valueText(const ParamDecl& p, double v) {
    if (p.type == ParamType::Enum) {
        const auto i = std::lround(v);
        if (i >= 0 && i < long(p.choices.size())) return p.choices[size_t(i)];
    }
    return number(v);
}

// Checked values of Int, Bool and Enum parameters are exact integers; the
// rounding only makes a value set in code without a check (a test's) land on
// the nearest integer rather than below it.
int asInt(double checkedValue) { return int(std::lround(checkedValue)); }

int intValue(const ParamValues& values, const std::string& name) { return asInt(values.at(name)); }

float floatValue(const ParamValues& values, const std::string& name) { return float(values.at(name)); }

bool readByHarness(const std::string& name) {
    static const std::set<std::string> names = {"exact", "interleave", "pyramid_per_level", "fused_tail", "depth_aware_box"};
    return names.count(name) > 0;
}

}  // namespace cavity::kernels
