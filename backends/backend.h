// The API-neutral GPU interface. Everything above backends/ talks to the GPU
// through this header only: opaque handles, description structs whose zero
// values mean "default", one function per operation (after Filament's
// DriverAPI and sokol_gfx). No GL name or Vk* type crosses this line.
//
// Conventions every backend honours, so that one kernel source gives the
// same pixels on every API:
//  * Image row 0 is the first row in memory and the top of a written PNG.
//    In compute and fragment kernels, ivec2(gl_FragCoord.xy) and
//    gl_GlobalInvocationID.xy both address (column, row) of that layout.
//  * Clip space: NDC y = -1 maps to row 0, depth range is [0, 1]
//    (the GL backend sets glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)).
//  * Between passes the caller issues barrier(): the commands recorded after
//    it see the writes of those before it, and their writes land after the
//    earlier reads. Without one, passes may overlap. A backend makes it no
//    wider than the commands on either side need (Vulkan: their stages and
//    accesses, recorded before the next command; GL: the glMemoryBarrier
//    bits for how later commands read earlier shader stores).
//  * Vulkan images live in VK_IMAGE_LAYOUT_GENERAL (vk_resources.cpp says why).
#pragma once

#include "result.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace cavity::gpu {

enum class Api { OpenGL, Vulkan };
const char* apiName(Api api);   // "gl", "vk"

enum class Format { R8, R16F, R32F, RG16F, RG32F, RGBA8, RGBA16F, RGBA32F, D32 };
int channelCount(Format f);     // 1, 1, 1, 2, 2, 4, 4, 4, 1
constexpr int bytesPerPixel(Format f) {
    switch (f) {
    case Format::R8: return 1;
    case Format::R16F: return 2;
    case Format::R32F: return 4;
    case Format::RG16F: return 4;
    case Format::RG32F: return 8;
    case Format::RGBA8: return 4;
    case Format::RGBA16F: return 8;
    case Format::RGBA32F: return 16;
    case Format::D32: return 4;
    }
    return 4;
}
const char* formatName(Format f);  // "R8", "RGBA16F", ... as in error messages

enum class Stage { Compute, Vertex, Fragment };

struct Image    { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct Buffer   { uint32_t id = 0; explicit operator bool() const { return id != 0; } };
struct Pipeline { uint32_t id = 0; explicit operator bool() const { return id != 0; } };

// What an image is used for; ImageDesc::usage is a mask of these. Vulkan
// creates the image with just these usages (a driver may lay out or compress
// an image by them); a use its description left out is an error at the call
// that needs it, on every backend.
enum ImageUsage : uint32_t {
    ImageSampled = 1u << 0,       // SampledImage bindings
    ImageStorage = 1u << 1,       // StorageImage bindings
    ImageColorTarget = 1u << 2,   // RenderTargets::colors
    ImageDepthTarget = 1u << 3,   // RenderTargets::depth
    ImageTransfer = 1u << 4,      // uploadImage, readImage
};

struct ImageDesc {
    int width = 0;
    int height = 0;
    Format format = Format::RGBA8;
    int mipLevels = 1;          // 0 or 1: a single level
    std::string label;          // shows up in error messages
    uint32_t usage = 0;         // ImageUsage bits; 0: every use the format allows
};

// Empty when `desc` allows `use`; otherwise why not, for an error message:
// "'ao' was created without ImageStorage".
std::string missingUsage(const ImageDesc& desc, ImageUsage use);

enum class BufferUsage { Uniform, Storage };
struct BufferDesc {
    size_t size = 0;
    BufferUsage usage = BufferUsage::Uniform;
    std::string label;
};

enum class Filter { Nearest, Linear };
enum class Address { ClampToEdge, Repeat };
struct SamplerState {
    Filter filter = Filter::Nearest;
    Address address = Address::ClampToEdge;
    bool mipmaps = false;       // trilinear between levels when true; level 0 otherwise
};

// One resource at one binding number. Binding numbers are unique across all
// kinds within a pipeline (Vulkan puts them all in descriptor set 0; GL uses
// the same number as the UBO / texture unit / image unit / SSBO index).
enum class BindingKind { UniformBuffer, StorageBuffer, SampledImage, StorageImage };
struct BindingSlot {
    uint32_t binding = 0;
    BindingKind kind = BindingKind::SampledImage;
    Format format = Format::RGBA8;   // StorageImage only
};
struct Bind {
    uint32_t binding = 0;
    Image image;                // SampledImage, StorageImage
    Buffer buffer;              // UniformBuffer, StorageBuffer
    SamplerState sampler;       // SampledImage
    // StorageImage: the one level imageStore / imageLoad address. A
    // SampledImage binding samples every level, so a pass may texelFetch
    // level k-1 of an image while it writes level k (a depth pyramid).
    int mipLevel = 0;
};

// A shader handed to a backend: one fully expanded GLSL 4.50 translation
// unit (no #include left) plus a name table for its #line source numbers,
// so that a compile error names the kernel file and line. The backend
// compiles it with glslang for its own API (backends/compiler/compiler.h).
struct ShaderSource {
    std::string name;           // kernel id, e.g. "alchemy"
    Stage stage = Stage::Compute;
    std::string glsl;
    std::vector<std::string> files;   // files[k] is "#line N k"'s source k
    // A kernel of a package from disk: whatever it includes, a source that
    // does not compile is the user's input (exit 2), not our bug.
    bool fromUser = false;
};

struct ComputePipelineDesc {
    ShaderSource shader;
    std::vector<BindingSlot> layout;
    int localSizeX = 8, localSizeY = 8;   // must match the shader's
    std::string label;
};

struct GraphicsPipelineDesc {
    ShaderSource vertex;
    ShaderSource fragment;
    std::vector<BindingSlot> layout;      // shared by both stages
    std::vector<Format> colorFormats;     // one per render target, location order
    Format depthFormat = Format::D32;
    bool depthTest = false;               // less, with depth writes; needs a depth target
    std::string label;
};

// How a pipeline's shader reached the driver: the shared SPIR-V, or (GL only)
// the GLSL text because the driver's SPIR-V path failed for this kernel.
enum class ShaderPath { Spirv, GlslFallback };
// One statistic the driver reports of a compiled pipeline
// (VK_KHR_pipeline_executable_properties), as the driver words it: NVIDIA's
// "Register Count", Mesa's instruction counts. A bool reads 0 or 1.
struct ShaderStat {
    std::string executable;   // the compiled stage it belongs to, as the driver names it (NVIDIA: "CS")
    std::string name;
    double value = 0;
};

struct PipelineInfo {
    ShaderPath path = ShaderPath::Spirv;
    std::string fallbackReason;   // the driver's message when path is GlslFallback
    std::vector<ShaderStat> stats;
    std::string statsReason;      // why `stats` is empty, where it is
};

// The registers a thread of the pipeline takes, where the driver reports
// them (a statistic named "...register..." or AMD's "VGPRs"), the most over
// its compiled stages; -1 where it does not. How many warps an SM holds, and
// so how much memory latency it can hide, follows from it.
double registerCount(const std::vector<ShaderStat>& stats);

struct RenderTargets {
    std::vector<Image> colors;
    Image depth;                  // optional
    bool clear = true;
    float clearColor[4] = {0, 0, 0, 0};
    float clearDepth = 1.0f;
};

struct DeviceInfo {
    std::string api;            // "gl" / "vk"
    std::string deviceName;     // GL_RENDERER / VkPhysicalDeviceProperties::deviceName
    std::string driver;         // GL_VERSION string / driverName + driverInfo
    std::string apiVersion;     // "4.5" / "1.3.238"
    std::string vendor;
    bool softwareRenderer = false;   // llvmpipe, lavapipe, swiftshader
    // The device's UUID as 32 hex digits (VkPhysicalDeviceIDProperties,
    // GL_EXT_memory_object's GL_DEVICE_UUID_EXT); empty where not reported.
    // NVIDIA's equals the NVML / CUDA UUID, which is how the clocks of the
    // device that ran are found (harness/gpu_clocks.h).
    std::string uuid;
    // Streaming multiprocessors as the driver reports them
    // (VK_NV_shader_sm_builtins shaderSMCount, GL_NV_shader_thread_group
    // GL_SM_COUNT_NV), for the floor (harness/roofline.h); 0: not reported.
    int smCount = 0;
};

// 16 bytes as 32 lower-case hex digits.
std::string hexUuid(const unsigned char (&bytes)[16]);

struct ScopeTime {
    std::string name;
    double gpuMs = 0;           // from the timestamp pair
};

struct BackendOptions {
    int deviceIndex = 0;        // EGL device / physical device index
    std::string deviceName;     // Vulkan: physical-device name substring; wins over index
    bool validation = false;    // Vulkan: Khronos validation layer with synchronisation validation; GL: KHR_debug output
    // Every barrier() the widest there is (Vulkan: all commands' memory
    // writes before all commands' reads and writes; GL: GL_ALL_BARRIER_BITS)
    // instead of as narrow as the passes around it need. A diagnostic: an
    // image that changes with it points at a missing barrier, and timing
    // with and without it measures what the narrowing buys. Also set by the
    // environment variable CAVITY_FULL_BARRIERS=1 (createBackend).
    bool fullBarriers = false;
    // No barrier() at all: nothing orders one pass's stores before the next
    // pass's reads. A timing diagnostic only, for what the barriers cost on
    // a chain whose passes do not read each other (docs/timing.md); on a
    // real pipeline the images are then undefined. Also set by
    // CAVITY_NO_BARRIERS=1. Not with fullBarriers.
    bool noBarriers = false;
};

class Backend {
public:
    virtual ~Backend() = default;

    virtual Api api() const = 0;
    virtual const DeviceInfo& info() const = 0;

    // Resources. Images are usable as sampled, storage, color/depth attachment,
    // upload and readback target, or as few of these as ImageDesc::usage says.
    virtual Result<Image> createImage(const ImageDesc&) = 0;
    virtual Result<Buffer> createBuffer(const BufferDesc&) = 0;
    virtual void destroy(Image) = 0;
    virtual void destroy(Buffer) = 0;
    virtual void destroy(Pipeline) = 0;

    // Data in and out. Pixel data is channelCount(format) floats per pixel,
    // rows top to bottom; the backend converts to and from the image format
    // (unorm for R8/RGBA8, half for *16F). These wait for the GPU.
    virtual Status uploadImage(Image, int mipLevel, std::span<const float> pixels) = 0;
    virtual Result<std::vector<float>> readImage(Image, int mipLevel = 0) = 0;
    virtual Status updateBuffer(Buffer, std::span<const std::byte> data, size_t offset = 0) = 0;

    virtual Result<Pipeline> createComputePipeline(const ComputePipelineDesc&) = 0;
    virtual Result<Pipeline> createGraphicsPipeline(const GraphicsPipelineDesc&) = 0;
    virtual PipelineInfo pipelineInfo(Pipeline) const = 0;

    // Frame recording. Errors while recording are sticky and come back from
    // endFrame (as a command buffer's would). endFrame submits and waits.
    virtual void beginFrame() = 0;
    virtual void dispatch(Pipeline, std::span<const Bind>, int groupsX, int groupsY) = 0;
    // One render pass over the targets: a draw of vertexCount vertices with no
    // vertex buffers (vertex shaders pull from gl_VertexIndex / storage buffers).
    virtual void draw(Pipeline, std::span<const Bind>, const RenderTargets&, int vertexCount) = 0;
    virtual void barrier() = 0;
    // Named timestamp scopes; may nest. Scope names need not be unique.
    virtual void beginScope(const std::string& name) = 0;
    virtual void endScope() = 0;
    virtual Status endFrame() = 0;
    // The scopes of the last completed frame, in begin order.
    virtual std::vector<ScopeTime> scopeTimes() const = 0;
    // Drain the queue: every submitted command has completed on return.
    virtual Status finish() = 0;

    // Validation-layer (Vulkan) or KHR_debug error/warning (GL) messages
    // since the last call. Tests fail on any; the harness prints them.
    virtual std::vector<std::string> takeDebugMessages() = 0;
};

// `options` with what the environment adds: CAVITY_FULL_BARRIERS=1 and
// CAVITY_NO_BARRIERS=1, each 0 or 1 (unset: 0) and not both; anything else
// fails with ErrorCode::BadInput naming the variable, as does a bad
// CAVITY_WORKGROUP. A command checks it before it writes anything;
// createBackend applies it.
Result<BackendOptions> withEnvironment(const BackendOptions& options);

// Backends, by name ("gl", "vk"). Fails with ErrorCode::BackendUnavailable
// naming the backend and what was tried, or as withEnvironment.
Result<std::unique_ptr<Backend>> createBackend(Api api, const BackendOptions& options);

}  // namespace cavity::gpu
