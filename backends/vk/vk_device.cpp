#include "vk_device.h"

#include "vk_util.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <utility>

namespace cavity::gpu::vk {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

Error startFailure(const std::string& what, VkResult r) {
    return unavailable("vk: could not start: " + what + ": " + vkResultName(r));
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT types,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    std::string m = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    m += (types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT)    ? " [validation]: "
         : (types & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) ? " [performance]: "
                                                                     : " [general]: ";
    m += data && data->pMessage ? data->pMessage : "(no message)";
    static_cast<Device*>(user)->addMessage(std::move(m));
    return VK_FALSE;   // never abort the call that triggered it
}

bool hasLayer(const char* name) {
    uint32_t n = 0;
    if (vkEnumerateInstanceLayerProperties(&n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(n);
    if (vkEnumerateInstanceLayerProperties(&n, layers.data()) != VK_SUCCESS) return false;
    return std::any_of(layers.begin(), layers.begin() + n,
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool layerHasExtension(const char* layer, const char* name) {
    uint32_t n = 0;
    if (vkEnumerateInstanceExtensionProperties(layer, &n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> exts(n);
    if (vkEnumerateInstanceExtensionProperties(layer, &n, exts.data()) != VK_SUCCESS) return false;
    return std::any_of(exts.begin(), exts.begin() + n,
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t n = 0;
    if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> exts(n);
    if (vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data()) != VK_SUCCESS) return false;
    return std::any_of(exts.begin(), exts.begin() + n,
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string vendorName(uint32_t id) {
    switch (id) {
    case 0x10DE: return "NVIDIA";
    case 0x1002: return "AMD";
    case 0x8086: return "Intel";
    case 0x13B5: return "ARM";
    case 0x5143: return "Qualcomm";
    case 0x106B: return "Apple";
    case 0x10005: return "Mesa";
    }
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X", id);
    return buf;
}

Result<VkPhysicalDevice> pickPhysicalDevice(VkInstance instance, const BackendOptions& o) {
    uint32_t n = 0;
    VkResult r = vkEnumeratePhysicalDevices(instance, &n, nullptr);
    if (r != VK_SUCCESS) return startFailure("vkEnumeratePhysicalDevices", r);
    if (n == 0) return unavailable("vk: could not start: no Vulkan physical device (is an ICD installed?)");
    std::vector<VkPhysicalDevice> devices(n);
    r = vkEnumeratePhysicalDevices(instance, &n, devices.data());
    if (r != VK_SUCCESS && r != VK_INCOMPLETE) return startFailure("vkEnumeratePhysicalDevices", r);
    devices.resize(n);

    std::vector<std::string> names;
    for (auto pd : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        names.push_back(p.deviceName);
    }
    std::string have;
    for (size_t i = 0; i < names.size(); ++i) have += (i ? ", " : "") + names[i];

    if (!o.deviceName.empty()) {
        for (size_t i = 0; i < names.size(); ++i)
            if (lower(names[i]).find(lower(o.deviceName)) != std::string::npos) return devices[i];
        return unavailable("vk: no physical device matches '" + o.deviceName + "' (have: " + have + ")");
    }
    if (o.deviceIndex < 0 || size_t(o.deviceIndex) >= devices.size())
        return unavailable("vk: --device " + std::to_string(o.deviceIndex) + ": no such physical device (have " +
                           std::to_string(devices.size()) + ": " + have + ")");
    return devices[size_t(o.deviceIndex)];
}

Status createInstance(Device& d, const BackendOptions& o, uint32_t apiVersion) {
    std::vector<const char*> layers, extensions;
    if (o.validation) {
        if (!hasLayer(kValidationLayer))
            return unavailable("vk: validation requested but VK_LAYER_KHRONOS_validation is not installed");
        // Synchronisation validation is what reports a missing or too narrow
        // barrier; without it the layer only checks API usage.
        if (!layerHasExtension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME))
            return unavailable("vk: validation requested but VK_LAYER_KHRONOS_validation lacks "
                               VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME " (synchronisation validation)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }
    auto app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "cavity";
    app.pEngineName = "cavity";
    app.apiVersion = apiVersion;

    // Every warning and error, of any type: tests fail on any of them.
    auto messenger =
        vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = onDebugMessage;
    messenger.pUserData = &d;

    const VkValidationFeatureEnableEXT enabled[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    auto features = vkStruct<VkValidationFeaturesEXT>(VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, &messenger);
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enabled;

    auto ci = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    // The messenger is chained here too, so that messages from
    // vkCreateInstance and vkDestroyInstance themselves are caught.
    ci.pNext = o.validation ? &features : nullptr;
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = uint32_t(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    VkResult r = vkCreateInstance(&ci, nullptr, &d.instance);
    if (r != VK_SUCCESS) return startFailure("vkCreateInstance", r);

    if (o.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d.instance, "vkCreateDebugUtilsMessengerEXT"));
        d.destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (!create || !d.destroyMessenger)
            return unavailable("vk: could not start: VK_EXT_debug_utils has no vkCreateDebugUtilsMessengerEXT");
        r = create(d.instance, &messenger, nullptr, &d.messenger);
        if (r != VK_SUCCESS) return startFailure("vkCreateDebugUtilsMessengerEXT", r);
    }
    return {};
}

void loadExecutableProperties(Device& d) {
    d.getExecutableProperties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
        vkGetDeviceProcAddr(d.device, "vkGetPipelineExecutablePropertiesKHR"));
    d.getExecutableStatistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
        vkGetDeviceProcAddr(d.device, "vkGetPipelineExecutableStatisticsKHR"));
}

// The first queue family with graphics, compute and timestamps.
Status pickQueueFamily(Device& d, const std::string& name) {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &n, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    auto family = std::find_if(families.begin(), families.end(), [&](const VkQueueFamilyProperties& f) {
        return (f.queueFlags & need) == need && f.timestampValidBits > 0 && f.queueCount > 0;
    });
    if (family == families.end())
        return unavailable("vk: '" + name + "' has no queue family with graphics, compute and timestamps");
    d.queueFamily = uint32_t(family - families.begin());
    d.timestampValidBits = family->timestampValidBits;
    return {};
}

Status createLogicalDevice(Device& d, uint32_t instanceVersion) {
    const std::string name = d.props.deviceName;
    if (d.props.apiVersion < VK_API_VERSION_1_2)
        return unavailable("vk: '" + name + "' supports Vulkan " + versionString(d.props.apiVersion) + ", need 1.2");
    // The version we may use is the lower of what we asked the instance for
    // and what the device offers.
    const bool core13 = std::min(instanceVersion, d.props.apiVersion) >= VK_API_VERSION_1_3;

    CAVITY_TRY(pickQueueFamily(d, name));
    std::vector<const char*> extensions;
    if (!core13) {
        if (!hasDeviceExtension(d.physical, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME))
            return unavailable("vk: '" + name + "' (Vulkan " + versionString(d.props.apiVersion) +
                               ") lacks " VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
        extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
    }
    // synchronization2 is queried (and so enabled) only on 1.3, where it is core.
    auto sync2 = vkStruct<VkPhysicalDeviceSynchronization2Features>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES);
    using DynamicRendering = VkPhysicalDeviceDynamicRenderingFeatures;
    auto dynamicRendering = vkStruct<DynamicRendering>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES,
                                                       core13 ? &sync2 : nullptr);
    // Half-float arithmetic (float16_t in a kernel), core in 1.2 as both the
    // device and the instance are; queried and so enabled where the device has it.
    auto float16 = vkStruct<VkPhysicalDeviceShaderFloat16Int8Features>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES, &dynamicRendering);
    // The compiled pipelines' statistics (registers on NVIDIA), for results.json.
    const bool executables = hasDeviceExtension(d.physical, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    auto executableInfo = vkStruct<VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR);
    if (executables) {
        extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
        executableInfo.pNext = float16.pNext;
        float16.pNext = &executableInfo;
    }
    auto have = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &float16);
    vkGetPhysicalDeviceFeatures2(d.physical, &have);
    float16.shaderInt8 = VK_FALSE;   // only what kernels may use
    if (!dynamicRendering.dynamicRendering)
        return unavailable("vk: '" + name + "' does not support dynamic rendering");

    // Only what kernels may use: r8/r16f/rg16f storage formats, image and
    // buffer stores from vertex and fragment kernels, and storage images
    // declared without a format. Each is enabled where the device has it.
    auto enable = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &float16);
    enable.features.shaderStorageImageExtendedFormats = have.features.shaderStorageImageExtendedFormats;
    enable.features.fragmentStoresAndAtomics = have.features.fragmentStoresAndAtomics;
    enable.features.vertexPipelineStoresAndAtomics = have.features.vertexPipelineStoresAndAtomics;
    enable.features.shaderStorageImageReadWithoutFormat = have.features.shaderStorageImageReadWithoutFormat;
    enable.features.shaderStorageImageWriteWithoutFormat = have.features.shaderStorageImageWriteWithoutFormat;
    dynamicRendering.dynamicRendering = VK_TRUE;

    const float priority = 1.0f;
    auto queue = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = d.queueFamily;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    auto ci = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable);
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &queue;
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    const VkResult r = vkCreateDevice(d.physical, &ci, nullptr, &d.device);
    if (r != VK_SUCCESS) return startFailure("vkCreateDevice on '" + name + "'", r);
    vkGetDeviceQueue(d.device, d.queueFamily, 0, &d.queue);

    d.cmdBeginRendering = reinterpret_cast<PFN_vkCmdBeginRendering>(
        vkGetDeviceProcAddr(d.device, core13 ? "vkCmdBeginRendering" : "vkCmdBeginRenderingKHR"));
    d.cmdEndRendering = reinterpret_cast<PFN_vkCmdEndRendering>(
        vkGetDeviceProcAddr(d.device, core13 ? "vkCmdEndRendering" : "vkCmdEndRenderingKHR"));
    if (!d.cmdBeginRendering || !d.cmdEndRendering)
        return unavailable("vk: '" + name + "' exposes no vkCmdBeginRendering entry point");
    if (executableInfo.pipelineExecutableInfo) loadExecutableProperties(d);
    if (sync2.synchronization2)
        d.cmdPipelineBarrier2 =
            reinterpret_cast<PFN_vkCmdPipelineBarrier2>(vkGetDeviceProcAddr(d.device, "vkCmdPipelineBarrier2"));
    return {};
}

void describe(Device& d) {
    // Chained only where the device has the extension, as the spec requires.
    auto sm = vkStruct<VkPhysicalDeviceShaderSMBuiltinsPropertiesNV>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SM_BUILTINS_PROPERTIES_NV);
    const bool hasSm = hasDeviceExtension(d.physical, VK_NV_SHADER_SM_BUILTINS_EXTENSION_NAME);
    auto id = vkStruct<VkPhysicalDeviceIDProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES,
                                                     hasSm ? &sm : nullptr);
    auto driver = vkStruct<VkPhysicalDeviceDriverProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &id);
    auto props = vkStruct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver);
    vkGetPhysicalDeviceProperties2(d.physical, &props);
    d.info.api = "vk";
    d.info.deviceName = d.props.deviceName;
    d.info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    d.info.apiVersion = versionString(d.props.apiVersion);
    d.info.vendor = vendorName(d.props.vendorID);
    d.info.softwareRenderer = d.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    unsigned char uuid[16];
    std::memcpy(uuid, id.deviceUUID, sizeof uuid);
    d.info.uuid = hexUuid(uuid);
    if (hasSm) d.info.smCount = int(sm.shaderSMCount);
}

}  // namespace

Result<std::unique_ptr<Device>> createDevice(const BackendOptions& o) {
    auto d = std::make_unique<Device>();
    // vkEnumerateInstanceVersion is missing from 1.0 loaders, hence the lookup.
    uint32_t loader = VK_API_VERSION_1_0;
    auto enumerateVersion = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
        vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
    if (enumerateVersion && enumerateVersion(&loader) != VK_SUCCESS) loader = VK_API_VERSION_1_0;
    if (loader < VK_API_VERSION_1_2)
        return unavailable("vk: could not start: the Vulkan loader offers " + versionString(loader) + ", need 1.2");
    const uint32_t instanceVersion = std::min(loader, VK_API_VERSION_1_3);

    d->fullBarriers = o.fullBarriers;
    d->noBarriers = o.noBarriers;
    CAVITY_TRY(createInstance(*d, o, instanceVersion));
    CAVITY_ASSIGN(d->physical, pickPhysicalDevice(d->instance, o));
    vkGetPhysicalDeviceProperties(d->physical, &d->props);
    vkGetPhysicalDeviceMemoryProperties(d->physical, &d->memory);
    CAVITY_TRY(createLogicalDevice(*d, instanceVersion));
    describe(*d);

    auto pool = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = d->queueFamily;
    CAVITY_VK(vkCreateCommandPool(d->device, &pool, nullptr, &d->oncePool), "vkCreateCommandPool (transfers)");
    auto cb = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    cb.commandPool = d->oncePool;
    cb.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cb.commandBufferCount = 1;
    CAVITY_VK(vkAllocateCommandBuffers(d->device, &cb, &d->onceCmd), "vkAllocateCommandBuffers (transfers)");
    auto fence = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    CAVITY_VK(vkCreateFence(d->device, &fence, nullptr, &d->onceFence), "vkCreateFence (transfers)");
    return d;
}

Device::~Device() {
    if (device) {
        vkDeviceWaitIdle(device);
        if (onceFence) vkDestroyFence(device, onceFence, nullptr);
        if (oncePool) vkDestroyCommandPool(device, oncePool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger) destroyMessenger(instance, messenger, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
}

void fullBarrier(VkCommandBuffer cmd) {
    auto b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &b,
                         0, nullptr, 0, nullptr);
}

Status Device::submitOnce(const std::string& what, const std::function<void(VkCommandBuffer)>& record) {
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    CAVITY_VK(vkBeginCommandBuffer(onceCmd, &begin), "vkBeginCommandBuffer for " + what);
    fullBarrier(onceCmd);
    record(onceCmd);
    // A fence wait makes device writes available but not visible to the host:
    // readbacks need this barrier's HOST_READ.
    auto after = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    after.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    after.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT | VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(onceCmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0,
                         nullptr, 0, nullptr);
    CAVITY_VK(vkEndCommandBuffer(onceCmd), "vkEndCommandBuffer for " + what);
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &onceCmd;
    CAVITY_VK(vkQueueSubmit(queue, 1, &submit, onceFence), "vkQueueSubmit for " + what);
    CAVITY_VK(vkWaitForFences(device, 1, &onceFence, VK_TRUE, UINT64_MAX), "vkWaitForFences for " + what);
    CAVITY_VK(vkResetFences(device, 1, &onceFence), "vkResetFences for " + what);
    return {};
}

void Device::addMessage(std::string m) {
    std::lock_guard lock(messagesMutex_);
    messages_.push_back(std::move(m));
}

std::vector<std::string> Device::takeMessages() {
    std::lock_guard lock(messagesMutex_);
    return std::exchange(messages_, {});
}

}  // namespace cavity::gpu::vk
