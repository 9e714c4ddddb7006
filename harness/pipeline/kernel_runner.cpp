#include "pipeline/kernel_runner.h"

#include "core/camera.h"
#include "texels/texels.h"

#include <cmath>
#include <cstring>

namespace cavity::pipeline {

namespace {

gpu::Format floatFormat(int channels) {
    switch (channels) {
    case 1: return gpu::Format::R32F;
    case 2: return gpu::Format::RG16F;
    default: return gpu::Format::RGBA32F;
    }
}

}  // namespace

void quantize(HostImage& img, gpu::Format format) {
    for (auto& v : img.pixels) {
        switch (format) {
        case gpu::Format::R16F:
        case gpu::Format::RG16F:
        case gpu::Format::RGBA16F: v = gpu::texels::roundToHalf(v); break;
        case gpu::Format::R8:
        case gpu::Format::RGBA8: v = gpu::texels::roundToUnorm8(v); break;
        default: break;
        }
    }
}

Result<std::vector<HostImage>> runKernel(gpu::Backend& gpu, const KernelRun& run) {
    const auto& k = *run.kernel;
    if (run.inputs.size() != k.inputs.size()) return internal("runKernel " + k.name + ": wrong number of inputs");
    std::vector<gpu::Image> images;
    std::vector<gpu::Buffer> buffers;
    gpu::Pipeline pipeline;
    auto cleanup = [&] {
        for (auto i : images) gpu.destroy(i);
        for (auto b : buffers) gpu.destroy(b);
        if (pipeline) gpu.destroy(pipeline);
    };
    auto body = [&]() -> Result<std::vector<HostImage>> {
        const int srcW = run.srcWidth ? run.srcWidth : run.width, srcH = run.srcHeight ? run.srcHeight : run.height;
        const auto frame = frameUniforms(run.width, run.height, srcW, srcH);
        const auto params = kernels::packParams(k, run.params);
        CAVITY_ASSIGN(gpu::Buffer fb, gpu.createBuffer({sizeof frame, gpu::BufferUsage::Uniform, k.name + ".frame"}));
        buffers.push_back(fb);
        CAVITY_ASSIGN(gpu::Buffer pb, gpu.createBuffer({params.size(), gpu::BufferUsage::Uniform, k.name + ".params"}));
        buffers.push_back(pb);
        CAVITY_TRY(gpu.updateBuffer(fb, std::as_bytes(std::span(&frame, 1))));
        CAVITY_TRY(gpu.updateBuffer(pb, params));
        std::vector<gpu::Bind> binds{{kernels::kFrameBinding, {}, fb, {}}, {kernels::kParamsBinding, {}, pb, {}}};
        uint32_t b = kernels::firstInputBinding(k, run.stage);
        for (size_t i = 0; i < run.inputs.size(); ++i) {
            const HostImage& in = *run.inputs[i];
            const gpu::Format f = i < run.inputFormats.size() ? run.inputFormats[i] : floatFormat(in.channels);
            if (gpu::channelCount(f) != in.channels) return internal("runKernel: input " + k.inputs[i].name + " channel mismatch");
            CAVITY_ASSIGN(gpu::Image img, gpu.createImage({in.width, in.height, f, 1, k.inputs[i].name}));
            images.push_back(img);
            CAVITY_TRY(gpu.uploadImage(img, 0, in.pixels));
            binds.push_back({b++, img, {}, k.inputs[i].sampler});
        }
        std::vector<gpu::Image> outs;
        for (const auto& o : k.outputs) {
            CAVITY_ASSIGN(gpu::Image img, gpu.createImage({run.width, run.height, o.format, 1, o.name}));
            images.push_back(img);
            outs.push_back(img);
        }
        CAVITY_ASSIGN(auto src, kernels::assemble(k, run.stage, run.overrides, &run.params));
        const auto layout = kernels::bindingLayout(k, run.stage);
        if (run.stage == gpu::Stage::Compute) {
            b = kernels::kFirstImageBinding;
            for (auto o : outs) binds.push_back({b++, o, {}, {}});
            CAVITY_ASSIGN(const kernels::Workgroup wg, kernels::workgroupSize(k));
            CAVITY_ASSIGN(pipeline, gpu.createComputePipeline({std::move(src), layout, int(wg.x), int(wg.y), k.name}));
            gpu.beginFrame();
            gpu.dispatch(pipeline, binds, wg.groupsX(run.width), wg.groupsY(run.height));
        } else {
            gpu::GraphicsPipelineDesc d;
            d.vertex = kernels::fullscreenVertex();
            d.fragment = std::move(src);
            d.layout = layout;
            gpu::RenderTargets t;
            for (size_t o = 0; o < outs.size(); ++o) {
                d.colorFormats.push_back(k.outputs[o].format);
                t.colors.push_back(outs[o]);
            }
            d.label = k.name;
            CAVITY_ASSIGN(pipeline, gpu.createGraphicsPipeline(d));
            gpu.beginFrame();
            gpu.draw(pipeline, binds, t, 3);
        }
        CAVITY_TRY(gpu.endFrame());
        std::vector<HostImage> result;
        for (size_t o = 0; o < outs.size(); ++o) {
            CAVITY_ASSIGN(auto px, gpu.readImage(outs[o]));
            HostImage img(run.width, run.height, gpu::channelCount(k.outputs[o].format));
            img.pixels = std::move(px);
            result.push_back(std::move(img));
        }
        return result;
    };
    auto r = body();
    cleanup();
    return r;
}

}  // namespace cavity::pipeline