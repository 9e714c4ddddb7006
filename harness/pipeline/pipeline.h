// A kernel pipeline: the passes one configuration runs, in order, wired by
// image name. pipelines.cpp builds the list for a RunConfig; PassChain
// creates the GPU resources and records the passes on any backend.
#pragma once

#include "pipeline/namespace.h"
#include "backend.h"
#include "core/config.h"
#include "core/image.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cavity::pipeline {

// Where a pass's input comes from: an image a pass wrote (or the uploaded
// G-buffer), or one the CPU makes (kernels::ConstantImageDecl: the noise
// tile, the sky panorama).
enum class ImageSource { Pass, Constant };

struct ImageRef {
    std::string name;
    ImageSource source = ImageSource::Pass;
    ImageRef(std::string n, ImageSource s = ImageSource::Pass) : name(std::move(n)), source(s) {}
    ImageRef(const char* n) : name(n) {}
};
// True for the image a pass wrote under that name (never a constant).
inline bool operator==(const ImageRef& r, const std::string& passImage) {
    return r.source == ImageSource::Pass && r.name == passImage;
}

struct PassSpec {
    std::string name;                  // timestamp scope and results key: "gbuffer", "ao", ...
    std::string kernel;                // a kernels::all() name
    std::vector<ImageRef> inputs;      // in the kernel's input order
    std::vector<std::string> outputs;  // image names, in the kernel's output order
    bool half = false;                 // runs at half the configuration's resolution
};

std::vector<PassSpec> buildPasses(const RunConfig& c);
// Whether some pass of c's pipeline declares the parameter `name`: a value
// no pass reads changes nothing that runs (cavity run and the matrices
// refuse one).
bool pipelineReads(const RunConfig& c, const std::string& name);
// Takes out of c.params each of `names` that no pass of c's pipeline reads,
// with it or at its default, so that a kernel's own parameter given for a
// mixed selection (--kernel alchemy,crease --shells 3) stays out of the
// other kernels' ids. A value that decides whether its reader runs at all
// (--blur 0) stays.
void dropUnreadParams(RunConfig& c, const std::vector<std::string>& names);
// Whether a kernel has a half-resolution pipeline (SSDO does not: its
// radiance would need an upsample of its own).
bool supportsHalf(const std::string& kernel);

// The interleaved layers per axis a configuration asks for (its `interleave`
// parameter; KernelDecl::interleaved): 1 for a plain dispatch.
int interleaveOf(const RunConfig& c);
// The stage kernel `k` runs on in configuration `c`: a mip chain and
// interleaved layers are compute work whatever the configuration's stage.
gpu::Stage passStage(const kernels::KernelDecl& k, const RunConfig& c);

// Validates the whole configuration against the pipeline it builds: kernel
// known and of role "ao", every parameter in range for every kernel of the
// pipeline, sizes; with an imported G-buffer, no pass that evaluates the
// analytic scene.
Status validate(const RunConfig& c);

// The images a user looks at, in the order they are written: name and what it is.
struct OutputSpec { std::string image; std::string description; };
std::vector<OutputSpec> userOutputs(const RunConfig& c);

// Replacement kernel sources by file name (planted-bug tests, --kernel-source).
using SourceOverrides = std::map<std::string, std::string>;

// Validates c, renders one frame of its pipeline and reads back the named
// images (tests, cavity quality: where the images matter, not the timing).
Result<std::map<std::string, HostImage>> renderImages(gpu::Backend& gpu, const RunConfig& c,
                                                      const std::vector<std::string>& images,
                                                      const SourceOverrides& overrides = {});
// A kernel source replaced from a file (--kernel-source NAME=FILE), as every
// report records it: which code a verdict judged.
struct ReplacedSource {
    std::string name;     // "ssao_alchemy.glsl", relative to kernels/
    std::string file;     // the file given
    std::string digest;   // digestText of its text
};
// Fails naming the first replaced source that no pass of `configs` compiles
// (with its #includes): a replacement that would change nothing is a mistake.
Status checkSourcesUsed(const std::vector<ReplacedSource>& replaced, const std::vector<RunConfig>& configs);
// A planted slowdown: dependent FMAs per pixel by pass name (kernels::assemble).
using PlantedSlowdown = std::map<std::string, int>;

// Non-finite values a pass wrote into one of its images.
struct NonFinite {
    std::string pass, image;
    long long count = 0;        // pixels with a NaN or infinite channel
    int x = -1, y = -1;         // the first pixel, in row order
    std::string message() const;
};

class PassChain {
public:
    // With an imported G-buffer (c.imported()), c.gbufferImages must be set:
    // its images are uploaded as "position", "normal" and "albedo".
    static Result<std::unique_ptr<PassChain>> create(gpu::Backend& gpu, const RunConfig& c,
                                                     const SourceOverrides& overrides = {},
                                                     const PlantedSlowdown& plant = {});
    ~PassChain();
    PassChain(const PassChain&) = delete;
    PassChain& operator=(const PassChain&) = delete;

    // Records every pass, each in a timestamp scope named after it, with a
    // barrier between passes. The caller owns beginFrame/endFrame.
    void record();
    // Records pass i alone (the wall-clock fallback times passes one by one).
    // `scoped` false: no timestamp scope of its own (recordInOneScope).
    void recordPass(size_t i, bool scoped = true);
    // As record(), but the passes after the G-buffer share one scope named
    // "pipeline" (the G-buffer keeps its own): the pipeline's time without a
    // timestamp pair around each pass, which costs each API differently
    // (pass_chain_scopes.cpp).
    void recordInOneScope();
    size_t passCount() const { return passes_.size(); }
    const std::vector<PassSpec>& passes() const { return specs_; }

    // An image's pixels; `level` > 0 for a level of a mip-chain output.
    Result<HostImage> read(const std::string& image, int level = 0) const;
    // Every image a pass of this chain wrote in a float format (positions,
    // normals, depth, raw and blurred AO, radiance...), read back and
    // scanned: one finding per image that holds a NaN or an infinity. An
    // 8-bit image cannot hold one; its inputs are all scanned here.
    Result<std::vector<NonFinite>> findNonFinite() const;
    // How each pass's shader reached the driver (SPIR-V or GL's GLSL
    // fallback), and what the driver says it compiled (its statistics).
    std::map<std::string, gpu::PipelineInfo> pipelineInfos() const;
    // Pixels each pass writes (for throughput counters).
    long long passPixels(size_t i) const;
    // How pass i runs (its stage and compute workgroup), for its floor.
    kernels::PassShape passShape(size_t i) const;

private:
    explicit PassChain(gpu::Backend& gpu);
    // record() (each pass its own scope) or recordInOneScope().
    void recordFrame(bool oneScope);
    Status createConstant(const std::string& name, const kernels::ParamValues& params);
    Status createRaster(const PassSpec& spec, const RunConfig& c);
    Status uploadGBuffer(const RunConfig& c);
    struct Pass;
    // One pass of create(): its outputs, uniform blocks, bindings and pipeline.
    Status createPass(const PassSpec& spec, const RunConfig& c, const SourceOverrides& overrides,
                      const PlantedSlowdown& plant);
    Status createOutputs(Pass& pass, const PassSpec& spec, const RunConfig& c);
    Status createUniforms(Pass& pass, const PassSpec& spec, const RunConfig& c);
    Status bindInputs(Pass& pass, const PassSpec& spec, const RunConfig& c);
    Status createComputeLevels(Pass& pass, const PassSpec& spec, const RunConfig& c, int mipLevels);
    struct Target { gpu::Image image; int width, height; gpu::Format format; };
    gpu::Backend& gpu_;
    std::vector<PassSpec> specs_;
    std::vector<std::unique_ptr<Pass>> passes_;
    std::map<std::string, Target> images_;      // by name: what passes wrote, the uploaded G-buffer
    std::map<std::string, Target> constants_;   // by name: CPU-made images
};

}  // namespace cavity::pipeline