// Kernel declarations: the one place that says what a kernel is called, which
// GLSL file holds its body, which parameters it takes (with default, range and
// unit), which images it reads and writes. The CLI, the config parser, the
// benchmark registration, the uniform-block layout and the error messages all
// read these declarations; adding a kernel touches no backend code.
//
// A kernel body (kernels/<file>) defines
//
//     void cavity_main(ivec2 pixel)
//
// and is wrapped by a generated preamble (assemble.cpp) that declares, for a
// kernel with inputs {position, normal} and outputs {ao} on the fragment
// stage (compute binds its output images from 0 and the inputs after them):
//
//     layout(std140, binding = 30) uniform Frame { ... } frame;   // FrameUniforms
//     layout(std140, binding = 31) uniform Params { <params>; <arrays> } P;
//     layout(binding = 0) uniform sampler2D in_position;
//     layout(binding = 1) uniform sampler2D in_normal;
//     void write_ao(ivec2 pixel, vec4 value);   // imageStore or a render target
//
// Int and enum parameters become GLSL int, Float become float, Bool become
// int (0/1). Arrays become vec4 NAME[N]. Which stage runs is visible as
// CAVITY_STAGE_COMPUTE or CAVITY_STAGE_FRAGMENT; the body must not depend on it.
#pragma once

#include "backend.h"
#include "params.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace cavity::kernels {

struct InputDecl {
    std::string name;                   // GLSL sampler in_<name>
    gpu::SamplerState sampler;          // default: nearest, clamp to edge
};

struct OutputDecl {
    std::string name;                   // GLSL write_<name>(pixel, value)
    gpu::Format format = gpu::Format::R16F;
    // More than 1: the image has a mip chain of that many levels, and the
    // pass runs once per level (level 0 first, a barrier between), each run
    // with frame.level and frame.size set to that level's. Such a pass runs
    // as compute whatever the configuration's stage: a fragment pass would
    // need a render target per level, which no kernel's speed depends on.
    int mipLevels = 1;
    // With mipLevels > 1: every level written by one dispatch over level 0,
    // through a storage binding per level and
    //     void write_<name>_level(int level, ivec2 pixel, vec4 value);
    // (CAVITY_LEVELS_<name> is the level count) instead of a dispatch per
    // level a barrier apart.
    bool oneDispatch = false;
    // An atlas of the kernel's `interleave` x `interleave` layers (docs/kernels.md,
    // "Interleaved layers"): the pass's size rounded up to a multiple of
    // k in each axis, layer l = pixel % k holding pixel p at
    // cavityLayerTexel(p) = l * layerSize + p / k. Written by the pass that
    // makes it (the depth pyramid's "zlayers"), read by an interleaved kernel.
    bool layered = false;
};

// The `interleave` value of a configuration's parameters: 1 when unset.
int interleaveValue(const ParamValues& values);
// One side of an output image of a pass `extent` pixels wide (or high): the
// extent itself, or for an atlas of layers (OutputDecl::layered) rounded up
// to whole layers of `interleave`.
inline int outputExtent(const OutputDecl& o, int extent, int interleave) {
    const int r = o.layered ? interleave : 1;
    return (extent + r - 1) / r * r;
}

struct ArrayDecl {
    std::string name;                   // GLSL P.<name>[i], a vec4 array
    int vec4Count = 1;
};

// What one output pixel of a kernel costs in memory traffic, for the
// benchmark's bytes/s counter and each pass's floor (harness/measure/roofline.h,
// docs/roofline.md). Fill all four: a cost with fetches but no fetch slots,
// or no DRAM bytes, gives its pass no floor rather than a floor of zero.
struct Cost {
    double fetchesPerPixel = 0;      // texel fetches
    double bytesPerPixel = 0;        // bytes read and written, every fetch counted
    double fetchSlotsPerPixel = 0;   // texture-unit slots of those fetches: sum of fetchSlots(texel bytes)
    // DRAM bytes with perfect cache reuse: each input image read once and
    // each output written once, per output pixel (a half-resolution input
    // read by a full-resolution pass counts a quarter of its texel).
    double dramBytesPerPixel = 0;
};

// Texture-unit slots one fetch of a texel takes: 1 up to 32 bits (R16F,
// R32F, RGBA8), 2 for 64-bit (RGBA16F), 4 for 128-bit (RGBA32F). An
// assumption from NVIDIA's texture units filtering 32 bits per slot, not a
// measurement (docs/roofline.md); a bilinear fetch is one fetch, a
// trilinear one two.
constexpr double fetchSlots(double texelBytes) { return texelBytes <= 4 ? 1 : texelBytes / 4; }

// Fills derived uniform arrays (e.g. Gaussian weights for the blur radius)
// from the parameter values: arrays[name] gets 4 * vec4Count floats.
using DeriveFn = std::function<void(const ParamValues&, std::map<std::string, std::vector<float>>& arrays)>;

// What the harness may use a kernel for.
enum class Role {
    GBuffer,      // writes the G-buffer (or a view of it: hardware depth)
    Ao,           // an AO estimator: selectable with --kernel, in "every AO kernel" sweeps
    Reference,    // the ground truth: selectable with --kernel, never in a sweep (slow by design)
    Pyramid,      // the linear-depth mip pyramid of the fast kernels
    Downsample,   // the half-resolution G-buffer
    Upsample,     // half-resolution AO back to full
    Blur,         // filters AO (or SSDO's visibility and radiance)
    Indirect,     // SSDO's one-bounce indirect light
    Composite,    // the lit 8-bit image
};

// A compute pass's workgroup shape. Each invocation shades its own pixel
// whatever the shape, so the images do not change with it; the time does. A
// full-resolution pass cannot be faster than launching its workgroups, and
// on the H200 an empty 1920x1080 dispatch launches much faster in 16x16
// workgroups than in 8x8. That made the pyramid and the composite faster
// and moved neither the AO nor the blur passes; the passes between the two
// resolutions became slower in 16x16 and declare 8x8 (docs/timing.md;
// studies 2026-12-03_h200_batched and 2026-12-03_h200_kernels3). 256
// invocations is over Vulkan's guaranteed minimum of 128: a device with
// fewer needs CAVITY_WORKGROUP=8x8.
struct Workgroup {
    uint32_t x = 16, y = 16;

    // Workgroups across and down an image `w` x `h` pixels.
    int groupsX(int w) const { return (w + int(x) - 1) / int(x); }
    int groupsY(int h) const { return (h + int(y) - 1) / int(y); }
};

// How a pass runs, for its cost: a compute pass's workgroup may load a tile
// of its inputs into shared memory once (include/blur_separable.glsl,
// include/upsample.glsl), so that its pixels fetch fewer texels than their
// taps read. The fragment stage has no workgroup and fetches every tap.
// For its floor's launch term, what the pass dispatched: its dispatches (a
// per-level mip chain makes one a level) and their workgroups together; 0
// where unknown (a cost alone, or a fragment pass).
struct PassShape {
    bool compute = true;
    Workgroup workgroup;
    int dispatches = 0;
    long long workgroups = 0;
};

// A code path of a kernel that a parameter selects without being an option
// of its own (a loop's remainder, a table past a size, the smallest levels),
// as its package's [[paths]] declares it: the gate's coverage check asks
// that some stored matrix compiles and judges a configuration where `when`
// holds (harness/plan/coverage.h).
struct PathDecl {
    std::string name;       // "remainder"
    std::string whenText;   // the condition as written: "gt(mod(samples, steps), 0)"
    std::string note;       // what runs there
    // Of the kernel's parameter values and "compute" (1 on the compute
    // stage), "width", "height" (the pass's output) and "half" (1 when the
    // configuration runs at half resolution).
    std::function<bool(const ParamValues&)> when;
};

struct KernelDecl {
    std::string name;                   // "alchemy"
    std::string file;                   // "ssao_alchemy.glsl", relative to kernels/
    std::string summary;                // one line for --help
    // The published sources the kernel follows, for --help ("McGuire et al.,
    // HPG 2011"; docs/kernels.md, "Sources", says what each gives). Empty: our own.
    std::vector<std::string> sources;
    std::vector<KernelParam> params;   // uniform-block order
    std::vector<InputDecl> inputs;
    std::vector<OutputDecl> outputs;
    std::vector<ArrayDecl> arrays;
    DeriveFn derive;                    // may be empty
    Role role = Role::Ao;
    std::function<Cost(const ParamValues&, const PassShape&)> cost;   // may be empty
    // Parameters whose value is compiled into the shader as well as passed
    // in the uniform block: assemble() defines CAVITY_CONST_<name> when it
    // is given the values. For a value that selects whole code paths (the
    // scene): CPU renderers (llvmpipe's GL) otherwise run every path of a
    // branch on a uniform, and the ray march got 2.2x slower with six scenes.
    // And for a loop's count (the fast kernels' samples), so that the loop
    // can unroll (CAVITY_UNROLL); each value is then a pipeline of its own.
    std::vector<std::string> compileTime;
    Workgroup workgroup;   // compute stage
    // Runs as k x k interleaved layers when its `interleave` parameter k is
    // over 1: one compute dispatch over the layers side by side, invocation
    // (layer l, texel q) shading pixel q * k + l, so that a workgroup's
    // pixels are every k-th one and share l's sample phase; the result is
    // stored straight back at its pixel. An input named "zlayers" reads the
    // linear depth split into those layers (the pyramid's atlas); with k = 1
    // it is the pyramid itself, and the pass one plain dispatch.
    bool interleaved = false;
    // cavity_main runs for every invocation of each workgroup, those past
    // the image's edge included, so that a workgroup can share memory and
    // meet at barrier() (the separable blur's tile); the kernel must then
    // write nothing for a pixel outside frame.size. Compute stage only.
    bool wholeWorkgroups = false;
    // What the analytic tests hold this kernel to where it differs from the
    // family's bands (a package's [expectations], docs/packages.md): keys
    // "open_worst", "open_mean", "crease" (numbers as text), "narrow_gap"
    // ("layer" or "seed"). Empty for the C++ declarations, which
    // tests/test_analytic.cpp names itself.
    std::map<std::string, std::string> expectations;
    // The CPU reference that mirrors this kernel (harness/reference/), by the
    // name it is registered under there: its package's `reference` line.
    // Kernels that run one shader with other defaults share one
    // (hemisphere_cosine runs hemisphere's). Empty: none, and its images are
    // gated by approvals alone.
    std::string reference;
    std::vector<PathDecl> paths;        // its package's [[paths]]
};

// The fixed uniform block every kernel sees at binding 0 (std140).
// View space is right-handed, the camera looks down -Z; "linear depth" is -z.
struct FrameUniforms {
    float proj[16];        // view -> clip, column-major (GLSL mat4)
    float invProj[16];
    float camera[4];       // tan(fovY/2) * aspect, tan(fovY/2), near, far
    int size[2];           // this pass's output size in pixels
    int srcSize[2];        // size of the pass's first input (the G-buffer's, for sources)
    float invSize[2];      // 1 / size
    int level;             // the mip level a pass writes (OutputDecl::mipLevels); 0 for most
    int pad;
};
static_assert(sizeof(FrameUniforms) == 176);

// An image the harness makes on the CPU rather than a pass: the 4x4 rotation
// noise tile, the sky panorama with its mip chain. A kernel input of that name
// reads it (harness/pipeline/pipeline.h ImageSource::Constant); the InputDecl gives the sampler.
struct ConstantImageDecl {
    std::string name;
    gpu::Format format = gpu::Format::RGBA32F;
    // Level 0 first; each level is width x height x channelCount(format) floats.
    struct Level { int width, height; std::vector<float> pixels; };
    std::function<std::vector<Level>(const ParamValues&)> make;
};
const std::vector<ConstantImageDecl>& constantImages();
const ConstantImageDecl* findConstant(const std::string& name);

// The registry: every kernel the harness knows, in declaration order.
const std::vector<KernelDecl>& all();
const KernelDecl* find(const std::string& name);
// The same list, mutable: only the planted-bug tests use it, to swap a
// declaration's derive function for a broken one and put it back.
std::vector<KernelDecl>& registryForTests();

// Whether the kernel takes the parameter `name`.
bool declares(const KernelDecl& k, const std::string& name);
// True for a kernel that evaluates the analytic scene itself (it declares
// --scene) outside the G-buffer passes: the SDF AO family and the ground
// truth. They cannot run on an imported G-buffer.
bool evaluatesScene(const KernelDecl& k);

// Default values for every parameter of a kernel, overridden by `given`.
ParamValues withDefaults(const KernelDecl& k, const ParamValues& given = {});

// Checks every value the kernel reads against its declaration (checkValue).
Status validate(const KernelDecl& k, const ParamValues& values);

// The std140 bytes of the Params block (binding 1) for these values.
std::vector<std::byte> packParams(const KernelDecl& k, const ParamValues& values);

// The full translation unit for one stage: preamble + includes + body + entry.
// `overrides` maps a kernel file name to replacement text (planted-bug tests).
// With `values`, the kernel's compileTime parameters are also #defined, and a
// kernel that declares `exact` run with it 0 gets EXACT defined empty and
// CAVITY_INEXACT (include/common.glsl); otherwise EXACT is `precise`.
// `plantedFmas` > 0 plants a slowdown (the timing-verdict check,
// scripts/gpu_verdict.sh): that many dependent FMAs per pixel after the body,
// whose result is never written, so the images stay bit-identical.
Result<gpu::ShaderSource> assemble(const KernelDecl& k, gpu::Stage stage,
                                   const std::map<std::string, std::string>& overrides = {},
                                   const ParamValues* values = nullptr, int plantedFmas = 0);

// The workgroup shape k's compute pass runs in: k.workgroup, or for every
// kernel what CAVITY_WORKGROUP=WxH in the environment says (W and H powers of
// two, W x H from 32 to 1024). An error names the variable and its value.
Result<Workgroup> workgroupSize(const KernelDecl& k);

// The full-screen-triangle vertex shader used by fragment-stage passes.
gpu::ShaderSource fullscreenVertex();

// Binding layout of a kernel's pipeline for a stage: Frame UBO, Params UBO,
// inputs as sampled images, and (compute only) outputs as storage images.
std::vector<gpu::BindingSlot> bindingLayout(const KernelDecl& k, gpu::Stage stage);
// A compute pass binds its storage images first, from 0, and its sampled
// inputs after them; the two uniform blocks take the last two bindings a
// kernel may use. GL numbers image units apart from texture units and
// uniform-buffer bindings, and the NVIDIA driver has 8 image units
// (GL_MAX_IMAGE_UNITS): a binding number is a unit there, so images from 0
// can use all 8 (the half-resolution downsample that builds the pyramid
// writes 7), where after the uniform blocks they had 6, and a pass with many
// inputs before its outputs overran them. Vulkan needs each number once per
// set; assemble() refuses a kernel whose images and inputs reach the blocks.
constexpr uint32_t kFirstImageBinding = 0;
constexpr uint32_t kFrameBinding = 30;
constexpr uint32_t kParamsBinding = 31;
uint32_t storageBindingCount(const KernelDecl& k, gpu::Stage stage);
inline uint32_t firstInputBinding(const KernelDecl& k, gpu::Stage stage) {
    return kFirstImageBinding + storageBindingCount(k, stage);
}

// The text of an embedded kernel file (kernels/*.glsl, kernels/include/*.glsl).
const std::string* sourceFile(const std::string& name);
// The key of the kernel source `name` names (--kernel-source NAME=FILE): a
// .glsl key itself ("ao/alchemy/ssao_alchemy.glsl", "include/common.glsl"),
// or a file name that one source alone has ("ssao_alchemy.glsl"), so that a
// command written before the kernels became packages still names its file.
Result<std::string> sourceKey(const std::string& name);
// How diagnostics and assemble()'s file list name the source `key`: its path
// in the repository ("kernels/include/common.glsl"), or for a file a package
// brought from disk, its path there.
std::string sourceLabel(const std::string& key);
// The first line of a replacement source read from a file, naming that file
// ("//!cavity-replaced-from: my_alchemy.glsl"): assemble() labels the
// replacement's diagnostics with it, and drops the line.
inline constexpr const char* kReplacedFrom = "//!cavity-replaced-from: ";

}  // namespace cavity::kernels
