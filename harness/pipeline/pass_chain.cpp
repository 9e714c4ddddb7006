#include "package/package.h"
#include "pipeline/namespace.h"
#include "core/camera.h"
#include "pipeline/meshes.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace cavity::pipeline {

namespace {

// Each image asks for what the chain does with it (ImageDesc::usage): its writer's use, sampling
// when a later pass reads it, transfers for uploads and readbacks (read, findNonFinite, the tests).
uint32_t outputUsage(const std::vector<PassSpec>& specs, const std::string& image, uint32_t written) {
    uint32_t usage = written | gpu::ImageTransfer;
    for (const auto& spec : specs)
        if (std::find(spec.inputs.begin(), spec.inputs.end(), image) != spec.inputs.end()) usage |= gpu::ImageSampled;
    return usage;
}

constexpr uint32_t kUploaded = gpu::ImageSampled | gpu::ImageTransfer;

}  // namespace

struct PassChain::Pass {
    // A dispatch after the first of a pass that writes a mip chain
    // (kernels::OutputDecl::mipLevels): its level's frame and bindings.
    struct Level {
        gpu::Buffer frameUbo;
        std::vector<gpu::Bind> binds;
        int width = 0, height = 0;
    };
    const kernels::KernelDecl* kernel = nullptr;
    gpu::Stage stage = gpu::Stage::Compute;
    gpu::Pipeline pipeline;
    gpu::Buffer frameUbo, paramsUbo;
    std::vector<gpu::Bind> binds;
    gpu::RenderTargets targets;          // fragment stage, raster
    gpu::Buffer mesh;                    // raster
    gpu::Image depth;                    // raster
    int vertexCount = 3;
    int width = 0, height = 0;
    int layers = 1;   // interleaved layers per axis: dispatched over their atlas (recordPass)
    // The atlas of whole layers reaches the last pixels where k does not divide the size.
    int atlas(int size) const { return (size + layers - 1) / layers * layers; }
    kernels::Workgroup workgroup;        // compute stage
    std::vector<Level> levels;           // levels 1.. of a mip-chain pass
};

// The rasterised G-buffer: a graphics pass over the scene mesh with a depth
// target, writing the images gbuffer_sdf would (kernels/gbuffer_raster.glsl).
Status PassChain::createRaster(const PassSpec& spec, const RunConfig& c) {
    auto pass = std::make_unique<Pass>();
    pass->stage = gpu::Stage::Fragment;
    pass->width = c.width;
    pass->height = c.height;
    const auto mesh = sceneMesh(int(c.params.count("scene") ? c.params.at("scene") : 0),
                                int(c.params.count("view") ? c.params.at("view") : 0));
    if (mesh.empty()) return badInput("--gbuffer raster: scene " + c.scene() + " has no mesh");
    pass->vertexCount = int(mesh.size());
    CAVITY_ASSIGN(pass->mesh, gpu_.createBuffer({mesh.size() * sizeof(MeshVertex), gpu::BufferUsage::Storage, "mesh"}));
    CAVITY_TRY(gpu_.updateBuffer(pass->mesh, std::as_bytes(std::span(mesh))));
    const auto frame = frameUniforms(c.width, c.height, c.width, c.height);
    CAVITY_ASSIGN(pass->frameUbo, gpu_.createBuffer({sizeof(frame), gpu::BufferUsage::Uniform, "gbuffer.frame"}));
    CAVITY_TRY(gpu_.updateBuffer(pass->frameUbo, std::as_bytes(std::span(&frame, 1))));
    const gpu::Format formats[4] = {gpu::Format::RGBA32F, gpu::Format::RGBA16F, gpu::Format::RGBA8, gpu::Format::R32F};
    gpu::GraphicsPipelineDesc d;
    const std::string* text = kernels::sourceFile("gbuffer_raster.glsl");
    if (!text) return internal("kernels/gbuffer_raster.glsl is not embedded");
    d.vertex = {"gbuffer_raster", gpu::Stage::Vertex, "#version 450\n#define CAVITY_STAGE_VERTEX 1\n#line 1 1\n" + *text,
                {"<raster preamble>", "kernels/gbuffer_raster.glsl"}};
    d.fragment = {"gbuffer_raster", gpu::Stage::Fragment,
                  "#version 450\n#define CAVITY_STAGE_FRAGMENT 1\n#line 1 1\n" + *text,
                  {"<raster preamble>", "kernels/gbuffer_raster.glsl"}};
    d.layout = {{0, gpu::BindingKind::UniformBuffer, {}}, {1, gpu::BindingKind::StorageBuffer, {}}};
    d.colorFormats = {formats[0], formats[1], formats[2], formats[3]};
    d.depthFormat = gpu::Format::D32;
    d.depthTest = true;
    d.label = spec.name;
    CAVITY_ASSIGN(pass->pipeline, gpu_.createGraphicsPipeline(d));
    CAVITY_ASSIGN(pass->depth,
                  gpu_.createImage({c.width, c.height, gpu::Format::D32, 1, "hardware depth", gpu::ImageDepthTarget}));
    for (size_t o = 0; o < 4; ++o) {
        const uint32_t usage = outputUsage(specs_, spec.outputs[o], gpu::ImageColorTarget);
        CAVITY_ASSIGN(gpu::Image img, gpu_.createImage({c.width, c.height, formats[o], 1, spec.outputs[o], usage}));
        images_[spec.outputs[o]] = {img, c.width, c.height, formats[o]};
        pass->targets.colors.push_back(img);
    }
    pass->targets.depth = pass->depth;
    pass->binds = {{0, {}, pass->frameUbo, {}}, {1, {}, pass->mesh, {}}};
    passes_.push_back(std::move(pass));
    return {};
}

// The imported G-buffer (harness/images/gbuffer_import.h): its three images and
// the linear depth (the position's w) in gbuffer_sdf's formats, read as a rendered one.
Status PassChain::uploadGBuffer(const RunConfig& c) {
    if (!c.gbufferImages) return internal("imported G-buffer " + c.gbufferFile + " was not loaded");
    const auto* decl = kernels::find("gbuffer_sdf");
    if (!decl || decl->outputs.size() != 4) return internal("no gbuffer_sdf declaration to take the G-buffer formats from");
    const HostImage& position = c.gbufferImages->position;
    HostImage linearDepth(position.width, position.height, 1);
    for (size_t i = 0; i < linearDepth.pixels.size() && i * 4 + 3 < position.pixels.size(); ++i)
        linearDepth.pixels[i] = position.pixels[i * 4 + 3];
    const HostImage* src[4] = {&position, &c.gbufferImages->normal, &c.gbufferImages->albedo, &linearDepth};
    for (size_t o = 0; o < 4; ++o) {
        const auto& out = decl->outputs[o];
        const HostImage& img = *src[o];
        if (img.width != c.width || img.height != c.height || img.channels != gpu::channelCount(out.format) ||
            img.pixels.size() != size_t(img.width) * img.height * img.channels)
            return badInput("--gbuffer-file " + c.gbufferFile + ": " + out.name + " is " + std::to_string(img.width) + "x" +
                            std::to_string(img.height) + "x" + std::to_string(img.channels) + ": must be " +
                            std::to_string(c.width) + "x" + std::to_string(c.height) + "x" + std::to_string(gpu::channelCount(out.format)));
        CAVITY_ASSIGN(gpu::Image image, gpu_.createImage({c.width, c.height, out.format, 1, out.name, kUploaded}));
        images_[out.name] = {image, c.width, c.height, out.format};
        CAVITY_TRY(gpu_.uploadImage(image, 0, img.pixels));
    }
    return {};
}

Result<std::unique_ptr<PassChain>> PassChain::create(gpu::Backend& gpu, const RunConfig& c,
                                                     const SourceOverrides& overrides, const PlantedSlowdown& plant) {
    std::unique_ptr<PassChain> chain(new PassChain(gpu));
    chain->specs_ = buildPasses(c);
    if (c.imported()) CAVITY_TRY(chain->uploadGBuffer(c));
    for (const auto& spec : chain->specs_) {
        if (spec.kernel == "gbuffer_raster") CAVITY_TRY(chain->createRaster(spec, c));
        else CAVITY_TRY(chain->createPass(spec, c, overrides, plant));
    }
    return chain;
}

Status PassChain::createPass(const PassSpec& spec, const RunConfig& c, const SourceOverrides& overrides,
                             const PlantedSlowdown& plant) {
    auto pass = std::make_unique<Pass>();
    pass->kernel = kernels::find(spec.kernel);
    if (!pass->kernel) return internal("pipeline names an unknown kernel '" + spec.kernel + "'");
    const auto& k = *pass->kernel;
    if (k.inputs.size() != spec.inputs.size() || k.outputs.size() != spec.outputs.size())
        return internal("pass '" + spec.name + "' wires the wrong number of images for kernel " + k.name);
    // A pass writes at most one mip chain (the pyramid), in one dispatch or a
    // dispatch a level.
    int mipLevels = 1;
    bool oneDispatch = false;
    for (const auto& o : k.outputs) {
        mipLevels = std::max(mipLevels, o.mipLevels);
        oneDispatch |= o.oneDispatch;
    }
    pass->stage = passStage(k, c);
    pass->width = spec.half ? (c.width + 1) / 2 : c.width;
    pass->height = spec.half ? (c.height + 1) / 2 : c.height;
    pass->layers = k.interleaved ? interleaveOf(c) : 1;
    CAVITY_TRY(createOutputs(*pass, spec, c));
    CAVITY_TRY(createUniforms(*pass, spec, c));
    CAVITY_TRY(bindInputs(*pass, spec, c));
    const auto planted = plant.find(spec.name);
    CAVITY_ASSIGN(auto body, kernels::assemble(k, pass->stage, overrides, &c.params,
                                               planted == plant.end() ? 0 : planted->second));
    const auto layout = kernels::bindingLayout(k, pass->stage);
    if (pass->stage == gpu::Stage::Compute) {
        auto b = kernels::kFirstImageBinding;
        for (size_t o = 0; o < spec.outputs.size(); ++o) {
            const auto& decl = k.outputs[o];
            // A one-dispatch mip chain binds its image once per level.
            for (int l = 0; l < (decl.oneDispatch ? decl.mipLevels : 1); ++l)
                pass->binds.push_back({b++, images_[spec.outputs[o]].image, {}, {}, l});
        }
        CAVITY_ASSIGN(pass->workgroup, kernels::workgroupSize(k));
        gpu::ComputePipelineDesc d{std::move(body), layout, int(pass->workgroup.x), int(pass->workgroup.y), spec.name};
        CAVITY_ASSIGN(pass->pipeline, gpu_.createComputePipeline(d));
        if (!oneDispatch) CAVITY_TRY(createComputeLevels(*pass, spec, c, mipLevels));
    } else {
        gpu::GraphicsPipelineDesc d;
        d.vertex = kernels::fullscreenVertex();
        d.fragment = std::move(body);
        d.layout = layout;
        for (size_t o = 0; o < spec.outputs.size(); ++o) {
            d.colorFormats.push_back(k.outputs[o].format);
            pass->targets.colors.push_back(images_[spec.outputs[o]].image);
        }
        d.label = spec.name;
        CAVITY_ASSIGN(pass->pipeline, gpu_.createGraphicsPipeline(d));
    }
    passes_.push_back(std::move(pass));
    return {};
}

// Outputs are created by the pass that writes them; an atlas of interleaved
// layers (OutputDecl::layered) is the pass's size rounded up to whole layers.
Status PassChain::createOutputs(Pass& pass, const PassSpec& spec, const RunConfig& c) {
    const auto& k = *pass.kernel;
    const int layers = interleaveOf(c);
    for (size_t o = 0; o < spec.outputs.size(); ++o) {
        const uint32_t written = pass.stage == gpu::Stage::Compute ? gpu::ImageStorage : gpu::ImageColorTarget;
        gpu::ImageDesc d{kernels::outputExtent(k.outputs[o], pass.width, layers),
                         kernels::outputExtent(k.outputs[o], pass.height, layers), k.outputs[o].format, k.outputs[o].mipLevels, spec.outputs[o],
                         outputUsage(specs_, spec.outputs[o], written)};
        CAVITY_ASSIGN(gpu::Image img, gpu_.createImage(d));
        images_[spec.outputs[o]] = {img, d.width, d.height, d.format};
    }
    return {};
}

// The frame block (sizes) and the kernel's parameter block, bound first.
Status PassChain::createUniforms(Pass& pass, const PassSpec& spec, const RunConfig& c) {
    const auto frame = frameUniforms(pass.width, pass.height, c.width, c.height);
    CAVITY_ASSIGN(pass.frameUbo, gpu_.createBuffer({sizeof(frame), gpu::BufferUsage::Uniform, spec.name + ".frame"}));
    CAVITY_TRY(gpu_.updateBuffer(pass.frameUbo, std::as_bytes(std::span(&frame, 1))));
    const auto params = kernels::packParams(*pass.kernel, c.params);
    CAVITY_ASSIGN(pass.paramsUbo, gpu_.createBuffer({params.size(), gpu::BufferUsage::Uniform, spec.name + ".params"}));
    CAVITY_TRY(gpu_.updateBuffer(pass.paramsUbo, params));
    pass.binds.push_back({kernels::kFrameBinding, {}, pass.frameUbo, {}});
    pass.binds.push_back({kernels::kParamsBinding, {}, pass.paramsUbo, {}});
    return {};
}

// The inputs in the kernel's order: images earlier passes wrote, and the
// CPU-made constants, created on first use.
Status PassChain::bindInputs(Pass& pass, const PassSpec& spec, const RunConfig& c) {
    uint32_t b = kernels::firstInputBinding(*pass.kernel, pass.stage);
    for (size_t i = 0; i < spec.inputs.size(); ++i) {
        const ImageRef& in = spec.inputs[i];
        const bool constant = in.source == ImageSource::Constant;
        if (constant && !constants_.count(in.name)) CAVITY_TRY(createConstant(in.name, c.params));
        auto& table = constant ? constants_ : images_;
        auto it = table.find(in.name);
        if (it == table.end()) {
            // A package from disk that reads what this pipeline does not make
            // (zlayers outside the layered build) is the user's declaration.
            const std::string what = "pass '" + spec.name + "' (" + spec.kernel + ") reads image '" + in.name +
                                     "' before any pass writes it";
            const kernels::PackageInfo* package = kernels::findPackage(spec.kernel);
            if (package && !package->builtIn)
                return badInput(package->declaration + ": " + what + " (the inputs this pipeline provides: cavity "
                                "kernels check)");
            return internal(what);
        }
        pass.binds.push_back({b++, it->second.image, {}, pass.kernel->inputs[i].sampler});
    }
    return {};
}

// Levels 1..: the same pipeline, each with its level's size in the frame
// block and its first output bound at that level.
Status PassChain::createComputeLevels(Pass& pass, const PassSpec& spec, const RunConfig& c, int mipLevels) {
    for (int l = 1; l < mipLevels; ++l) {
        Pass::Level level;
        level.width = std::max(1, pass.width >> l);
        level.height = std::max(1, pass.height >> l);
        auto lf = frameUniforms(level.width, level.height, c.width, c.height);
        lf.level = l;
        CAVITY_ASSIGN(level.frameUbo, gpu_.createBuffer({sizeof(lf), gpu::BufferUsage::Uniform,
                                                         spec.name + ".frame" + std::to_string(l)}));
        CAVITY_TRY(gpu_.updateBuffer(level.frameUbo, std::as_bytes(std::span(&lf, 1))));
        level.binds = pass.binds;
        level.binds[0].buffer = level.frameUbo;
        level.binds[level.binds.size() - spec.outputs.size()].mipLevel = l;
        pass.levels.push_back(std::move(level));
    }
    return {};
}

PassChain::PassChain(gpu::Backend& gpu) : gpu_(gpu) {}

Status PassChain::createConstant(const std::string& name, const kernels::ParamValues& params) {
    const auto* decl = kernels::findConstant(name);
    if (!decl) return internal("no constant image '" + name + "' (kernels/constants.cpp)");
    const auto levels = decl->make(params);
    if (levels.empty()) return internal("constant image '" + name + "' has no levels");
    gpu::ImageDesc d{levels[0].width, levels[0].height, decl->format, int(levels.size()), "constant " + name, kUploaded};
    CAVITY_ASSIGN(gpu::Image img, gpu_.createImage(d));
    constants_[name] = {img, d.width, d.height, d.format};
    for (size_t l = 0; l < levels.size(); ++l) CAVITY_TRY(gpu_.uploadImage(img, int(l), levels[l].pixels));
    return {};
}

PassChain::~PassChain() {
    for (auto& p : passes_) {
        if (p->pipeline) gpu_.destroy(p->pipeline);
        if (p->frameUbo) gpu_.destroy(p->frameUbo);
        if (p->paramsUbo) gpu_.destroy(p->paramsUbo);
        if (p->mesh) gpu_.destroy(p->mesh);
        if (p->depth) gpu_.destroy(p->depth);
        for (auto& l : p->levels) gpu_.destroy(l.frameUbo);
    }
    for (auto& [name, t] : images_) gpu_.destroy(t.image);
    for (auto& [name, t] : constants_) gpu_.destroy(t.image);
}

void PassChain::recordPass(size_t i, bool scoped) {
    auto& p = *passes_[i];
    if (scoped) gpu_.beginScope(specs_[i].name);
    if (p.stage == gpu::Stage::Compute) {
        gpu_.dispatch(p.pipeline, p.binds, p.workgroup.groupsX(p.atlas(p.width)), p.workgroup.groupsY(p.atlas(p.height)));
        // A mip chain's level l reads level l - 1: one scope, a barrier apart.
        for (const auto& l : p.levels) {
            gpu_.barrier();
            gpu_.dispatch(p.pipeline, l.binds, p.workgroup.groupsX(l.width), p.workgroup.groupsY(l.height));
        }
    } else
        gpu_.draw(p.pipeline, p.binds, p.targets, p.vertexCount);
    if (scoped) gpu_.endScope();
}

Result<HostImage> PassChain::read(const std::string& image, int level) const {
    auto it = images_.find(image);
    if (it == images_.end()) return internal("no image '" + image + "' in this pipeline");
    const auto& t = it->second;
    CAVITY_ASSIGN(auto px, gpu_.readImage(t.image, level));
    HostImage img(std::max(1, t.width >> level), std::max(1, t.height >> level), gpu::channelCount(t.format));
    if (px.size() != img.pixels.size()) return internal("readback of '" + image + "' returned the wrong size");
    img.pixels = std::move(px);
    return img;
}

std::string NonFinite::message() const {
    return "pass " + pass + " wrote " + std::to_string(count) + " pixel" + (count == 1 ? "" : "s") +
           " of NaN or infinity to " + image + " (first at pixel " + std::to_string(x) + "," + std::to_string(y) + ")";
}

Result<std::vector<NonFinite>> PassChain::findNonFinite() const {
    std::vector<NonFinite> found;
    for (const auto& spec : specs_)
        for (const auto& name : spec.outputs) {
            auto it = images_.find(name);
            if (it == images_.end()) continue;
            const gpu::Format f = it->second.format;
            if (f == gpu::Format::R8 || f == gpu::Format::RGBA8) continue;
            CAVITY_ASSIGN(const HostImage img, read(name));
            NonFinite n{spec.name, name};
            const size_t channels = size_t(img.channels);
            for (size_t pixel = 0; pixel * channels < img.pixels.size(); ++pixel) {
                bool finite = true;
                for (size_t c = 0; c < channels; ++c) finite &= std::isfinite(img.pixels[pixel * channels + c]);
                if (finite) continue;
                if (n.count++ == 0) n.x = int(pixel % size_t(img.width)), n.y = int(pixel / size_t(img.width));
            }
            if (n.count) found.push_back(std::move(n));
        }
    return found;
}

std::map<std::string, gpu::PipelineInfo> PassChain::pipelineInfos() const {
    std::map<std::string, gpu::PipelineInfo> m;
    for (size_t i = 0; i < passes_.size(); ++i) m[specs_[i].name] = gpu_.pipelineInfo(passes_[i]->pipeline);
    return m;
}

long long PassChain::passPixels(size_t i) const { return (long long)passes_[i]->width * passes_[i]->height; }

kernels::PassShape PassChain::passShape(size_t i) const {
    const auto& p = *passes_[i];
    if (p.stage != gpu::Stage::Compute) return {false, p.workgroup};
    // What recordPass dispatches: the atlas, then each further mip level.
    long long groups = (long long)p.workgroup.groupsX(p.atlas(p.width)) * p.workgroup.groupsY(p.atlas(p.height));
    for (const auto& l : p.levels) groups += (long long)p.workgroup.groupsX(l.width) * p.workgroup.groupsY(l.height);
    return {true, p.workgroup, 1 + int(p.levels.size()), groups};
}

Result<std::map<std::string, HostImage>> renderImages(gpu::Backend& gpu, const RunConfig& c,
                                                      const std::vector<std::string>& images,
                                                      const SourceOverrides& overrides) {
    CAVITY_TRY(validate(c));
    CAVITY_ASSIGN(auto chain, PassChain::create(gpu, c, overrides));
    gpu.beginFrame();
    chain->record();
    CAVITY_TRY(gpu.endFrame());
    std::map<std::string, HostImage> out;
    for (const auto& name : images) {
        CAVITY_ASSIGN(out[name], chain->read(name));
    }
    return out;
}

Status checkSourcesUsed(const std::vector<ReplacedSource>& replaced, const std::vector<RunConfig>& configs) {
    if (replaced.empty()) return {};
    // Every file a pass compiles, as assemble() labels them: a repository
    // path for the embedded sources, a path on disk for a package's own.
    std::set<std::string> used, assembled;   // source labels; kernel and stage pairs done
    for (const auto& c : configs)
        for (const auto& spec : buildPasses(c)) {
            const auto* k = kernels::find(spec.kernel);
            if (!k || !assembled.insert(spec.kernel + (c.stage == gpu::Stage::Compute ? "/c" : "/f")).second) continue;
            auto src = kernels::assemble(*k, c.stage, {}, nullptr, 0);
            if (!src) continue;
            used.insert(src->files.begin(), src->files.end());
        }
    for (const auto& r : replaced)
        if (const std::string label = kernels::sourceLabel(r.name); !used.count(label))
            return badInput("--kernel-source " + r.name + "=" + r.file + ": no configuration of the selection compiles " +
                            label + " (the replacement would change nothing)");
    return {};
}

}  // namespace cavity::pipeline
