#include "vk_pipelines.h"

#include "compiler.h"
#include "vk_formats.h"
#include "vk_util.h"

#include <array>
#include <optional>
#include <set>

namespace cavity::gpu::vk {

namespace {

// Set layout and pipeline layout, shared by both kinds of pipeline.
Status initLayout(Device& d, PipelineRes& p) {
    std::set<uint32_t> seen;
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (const auto& s : p.slots) {
        if (!seen.insert(s.binding).second)
            return internal("pipeline '" + p.label + "': binding " + std::to_string(s.binding) +
                            " appears twice in its layout");
        bindings.push_back({s.binding, descriptorType(s.kind), 1, VK_SHADER_STAGE_ALL, nullptr});
    }
    auto sci = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    sci.bindingCount = uint32_t(bindings.size());
    sci.pBindings = bindings.data();
    CAVITY_VK(vkCreateDescriptorSetLayout(d.device, &sci, nullptr, &p.setLayout),
              "vkCreateDescriptorSetLayout '" + p.label + "'");
    auto lci = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    lci.setLayoutCount = 1;
    lci.pSetLayouts = &p.setLayout;
    CAVITY_VK(vkCreatePipelineLayout(d.device, &lci, nullptr, &p.layout), "vkCreatePipelineLayout '" + p.label + "'");
    return {};
}

// Owns a shader module for the length of pipeline creation.
struct Module {
    VkDevice device = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    ~Module() {
        if (module) vkDestroyShaderModule(device, module, nullptr);
    }
};

Status createModule(Device& d, const std::vector<uint32_t>& spirv, const std::string& what, Module& out) {
    auto ci = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    ci.codeSize = spirv.size() * sizeof(uint32_t);
    ci.pCode = spirv.data();
    out.device = d.device;
    CAVITY_VK(vkCreateShaderModule(d.device, &ci, nullptr, &out.module), "vkCreateShaderModule " + what);
    return {};
}

Status compileModule(Device& d, const ShaderSource& src, const std::string& label, Module& out) {
    CAVITY_ASSIGN(const std::vector<uint32_t> spirv, kernels::compileToSpirv(src, Api::Vulkan));
    return createModule(d, spirv, "'" + label + "' (" + src.name + ")", out);
}

// The work-group size from the module's OpExecutionMode LocalSize, if it
// states one as literals. The caller sizes dispatches by the description's
// localSizeX/Y, so a mismatch would silently leave pixels unwritten.
std::optional<std::array<uint32_t, 3>> localSize(const std::vector<uint32_t>& spirv) {
    constexpr uint32_t kOpExecutionMode = 16, kLocalSize = 17;
    for (size_t i = 5; i < spirv.size();) {   // after the 5-word header
        const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
        if (words == 0 || i + words > spirv.size()) break;
        if (op == kOpExecutionMode && words == 6 && spirv[i + 2] == kLocalSize)
            return std::array<uint32_t, 3>{spirv[i + 3], spirv[i + 4], spirv[i + 5]};
        i += words;
    }
    return std::nullopt;
}

VkPipelineShaderStageCreateInfo stageInfo(VkShaderStageFlagBits stage, VkShaderModule m) {
    auto s = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
    s.stage = stage;
    s.module = m;
    s.pName = "main";
    return s;
}

// Asks the driver to keep the statistics readStatistics() reads. The
// specification says the flag must not change the compiled pipeline (only,
// perhaps, how long creating it takes).
VkPipelineCreateFlags captureFlags(const Device& d) {
    return d.getExecutableStatistics ? VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR : 0;
}

Status initCompute(Device& d, PipelineRes& p, const ComputePipelineDesc& desc) {
    CAVITY_TRY(initLayout(d, p));
    CAVITY_ASSIGN(const std::vector<uint32_t> spirv, kernels::compileToSpirv(desc.shader, Api::Vulkan));
    if (const auto size = localSize(spirv);
        size && ((*size)[0] != uint32_t(desc.localSizeX) || (*size)[1] != uint32_t(desc.localSizeY)))
        return internal("pipeline '" + p.label + "': " + desc.shader.name + " declares local_size " +
                        std::to_string((*size)[0]) + "x" + std::to_string((*size)[1]) + ", the description " +
                        std::to_string(desc.localSizeX) + "x" + std::to_string(desc.localSizeY));
    const auto& limits = d.props.limits;
    if (uint32_t(desc.localSizeX) * uint32_t(desc.localSizeY) > limits.maxComputeWorkGroupInvocations ||
        uint32_t(desc.localSizeX) > limits.maxComputeWorkGroupSize[0] ||
        uint32_t(desc.localSizeY) > limits.maxComputeWorkGroupSize[1])
        return unavailable("vk: '" + std::string(d.props.deviceName) + "' runs workgroups of at most " +
                           std::to_string(limits.maxComputeWorkGroupInvocations) + " invocations, not " +
                           std::to_string(desc.localSizeX) + "x" + std::to_string(desc.localSizeY) +
                           ": set CAVITY_WORKGROUP=8x8 (docs/timing.md)");
    Module cs;
    CAVITY_TRY(createModule(d, spirv, "'" + p.label + "' (" + desc.shader.name + ")", cs));
    auto ci = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    ci.stage = stageInfo(VK_SHADER_STAGE_COMPUTE_BIT, cs.module);
    ci.layout = p.layout;
    ci.flags = captureFlags(d);
    CAVITY_VK(vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline),
              "vkCreateComputePipelines '" + p.label + "' (" + desc.shader.name + ")");
    return {};
}

Status initGraphics(Device& d, PipelineRes& p, const GraphicsPipelineDesc& desc) {
    for (Format f : desc.colorFormats)
        if (isDepth(f))
            return internal("pipeline '" + p.label + "': " + formatName(f) + " cannot be a color target");
    if (desc.depthTest && !isDepth(desc.depthFormat))
        return internal("pipeline '" + p.label + "': depth format " + formatName(desc.depthFormat) +
                        " is not a depth format");
    CAVITY_TRY(initLayout(d, p));
    Module vs, fs;
    CAVITY_TRY(compileModule(d, desc.vertex, p.label, vs));
    CAVITY_TRY(compileModule(d, desc.fragment, p.label, fs));
    const VkPipelineShaderStageCreateInfo stages[] = {stageInfo(VK_SHADER_STAGE_VERTEX_BIT, vs.module),
                                                      stageInfo(VK_SHADER_STAGE_FRAGMENT_BIT, fs.module)};

    auto vertexInput =
        vkStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    auto assembly =
        vkStruct<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    auto viewport = vkStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    viewport.viewportCount = viewport.scissorCount = 1;   // set per draw to the targets' size
    auto raster =
        vkStruct<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    auto multisample =
        vkStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    auto depth =
        vkStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    depth.depthTestEnable = depth.depthWriteEnable = desc.depthTest ? VK_TRUE : VK_FALSE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (auto& b : blends)
        b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    auto blend =
        vkStruct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    blend.attachmentCount = uint32_t(blends.size());
    blend.pAttachments = blends.data();
    const VkDynamicState dynamics[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    auto dynamic = vkStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamics;

    std::vector<VkFormat> colors;
    for (Format f : desc.colorFormats) colors.push_back(toVkFormat(f));
    // Only a depth-tested pipeline declares a depth attachment: newer
    // validation layers reject a declared format whose attachment is absent.
    auto rendering = vkStruct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
    rendering.colorAttachmentCount = uint32_t(colors.size());
    rendering.pColorAttachmentFormats = colors.data();
    rendering.depthAttachmentFormat = p.depth ? toVkFormat(desc.depthFormat) : VK_FORMAT_UNDEFINED;

    auto ci = vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering);
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vertexInput;
    ci.pInputAssemblyState = &assembly;
    ci.pViewportState = &viewport;
    ci.pRasterizationState = &raster;
    ci.pMultisampleState = &multisample;
    ci.pDepthStencilState = &depth;
    ci.pColorBlendState = &blend;
    ci.pDynamicState = &dynamic;
    ci.layout = p.layout;
    ci.flags = captureFlags(d);
    CAVITY_VK(vkCreateGraphicsPipelines(d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline),
              "vkCreateGraphicsPipelines '" + p.label + "' (" + desc.vertex.name + ", " + desc.fragment.name + ")");
    return {};
}

// Vulkan's two-call enumeration: the count, then the items.
template <class T, class Query>
Result<std::vector<T>> enumerate(VkStructureType type, const char* what, Query query) {
    uint32_t n = 0;
    CAVITY_VK(query(&n, nullptr), what);
    std::vector<T> items(n, vkStruct<T>(type));
    CAVITY_VK(query(&n, items.data()), what);
    items.resize(n);
    return items;
}

std::optional<double> statisticValue(const VkPipelineExecutableStatisticKHR& s) {
    switch (s.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: return s.value.b32 ? 1 : 0;
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: return double(s.value.i64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: return double(s.value.u64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: return s.value.f64;
    default: return std::nullopt;
    }
}

// Every statistic of every executable (compiled stage) of the pipeline.
Status readStatistics(Device& d, PipelineRes& p) {
    if (!d.getExecutableStatistics) {
        p.statsReason = "the device lacks " VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME;
        return {};
    }
    auto info = vkStruct<VkPipelineInfoKHR>(VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR);
    info.pipeline = p.pipeline;
    CAVITY_ASSIGN(const auto executables,
                  enumerate<VkPipelineExecutablePropertiesKHR>(
                      VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR, "vkGetPipelineExecutablePropertiesKHR",
                      [&](uint32_t* n, VkPipelineExecutablePropertiesKHR* out) {
                          return d.getExecutableProperties(d.device, &info, n, out);
                      }));
    for (uint32_t e = 0; e < executables.size(); ++e) {
        auto which = vkStruct<VkPipelineExecutableInfoKHR>(VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR);
        which.pipeline = p.pipeline;
        which.executableIndex = e;
        CAVITY_ASSIGN(const auto stats,
                      enumerate<VkPipelineExecutableStatisticKHR>(
                          VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR, "vkGetPipelineExecutableStatisticsKHR",
                          [&](uint32_t* n, VkPipelineExecutableStatisticKHR* out) {
                              return d.getExecutableStatistics(d.device, &which, n, out);
                          }));
        for (const auto& s : stats)
            if (const auto v = statisticValue(s)) p.stats.push_back({executables[e].name, s.name, *v});
    }
    if (p.stats.empty()) p.statsReason = "the driver reports no statistics for this pipeline";
    return {};
}

template <class Desc, class Init>
Result<PipelineRes> build(Device& d, PipelineRes p, const Desc& desc, Init init) {
    Status s = init(d, p, desc);
    if (s) s = readStatistics(d, p);
    if (!s) {
        destroyPipeline(d, p);
        return s.error();
    }
    return p;
}

}  // namespace

Result<PipelineRes> createComputePipeline(Device& d, const ComputePipelineDesc& desc) {
    PipelineRes p;
    p.label = desc.label.empty() ? desc.shader.name : desc.label;
    p.slots = desc.layout;
    return build(d, std::move(p), desc, initCompute);
}

Result<PipelineRes> createGraphicsPipeline(Device& d, const GraphicsPipelineDesc& desc) {
    PipelineRes p;
    p.label = desc.label.empty() ? desc.fragment.name : desc.label;
    p.graphics = true;
    p.slots = desc.layout;
    p.colorFormats = desc.colorFormats;
    p.depth = desc.depthTest;
    return build(d, std::move(p), desc, initGraphics);
}

void destroyPipeline(Device& d, PipelineRes& p) {
    if (p.pipeline) vkDestroyPipeline(d.device, p.pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(d.device, p.layout, nullptr);
    if (p.setLayout) vkDestroyDescriptorSetLayout(d.device, p.setLayout, nullptr);
    p = PipelineRes{};
}

VkDescriptorType descriptorType(BindingKind k) {
    switch (k) {
    case BindingKind::UniformBuffer: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingKind::StorageBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingKind::SampledImage: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case BindingKind::StorageImage: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    }
    return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

const char* bindingKindName(BindingKind k) {
    switch (k) {
    case BindingKind::UniformBuffer: return "uniform buffer";
    case BindingKind::StorageBuffer: return "storage buffer";
    case BindingKind::SampledImage: return "sampled image";
    case BindingKind::StorageImage: return "storage image";
    }
    return "?";
}

}  // namespace cavity::gpu::vk
