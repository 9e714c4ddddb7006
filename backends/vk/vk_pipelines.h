// Compute and graphics pipelines from the interface's descriptions: glslang
// SPIR-V, one descriptor set layout (set 0) and dynamic rendering.
#pragma once

#include "backend.h"
#include "vk_device.h"

#include <string>
#include <vector>

namespace cavity::gpu::vk {

struct PipelineRes {
    std::string label;
    bool graphics = false;
    std::vector<BindingSlot> slots;
    std::vector<Format> colorFormats;   // graphics: what draw() must be given
    bool depth = false;                 // graphics: has a D32 depth attachment
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::vector<ShaderStat> stats;   // the driver's, where Device::getExecutableStatistics
    std::string statsReason;         // why stats is empty, where it is
};

Result<PipelineRes> createComputePipeline(Device& d, const ComputePipelineDesc& desc);
Result<PipelineRes> createGraphicsPipeline(Device& d, const GraphicsPipelineDesc& desc);
void destroyPipeline(Device& d, PipelineRes& p);

VkDescriptorType descriptorType(BindingKind k);
const char* bindingKindName(BindingKind k);   // "uniform buffer", ...

}  // namespace cavity::gpu::vk
