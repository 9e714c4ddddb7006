// Each pass's floor: the least time its memory traffic allows on the device
// that ran it, from the kernel's declared cost (kernels/kernel.h Cost) and
// the device's figures. docs/roofline.md explains the model and the H200's
// numbers; results.json and the benchmark JSON carry them.
//
//   fetch floor = pixels x fetch slots per pixel / (SMs x texture units per SM x SM clock)
//   DRAM floor  = pixels x DRAM bytes per pixel / DRAM bandwidth
//   launch      = dispatches x fixed cost + workgroups x cost a workgroup (the API's)
//   floor       = the larger of the two, plus the launch ("bound" names
//                 which of the three is largest)
//
// A figure comes from the driver where it reports it (the SM count:
// VK_NV_shader_sm_builtins, GL_NV_shader_thread_group), from NVML (the
// maximum SM clock), or else from a table keyed by device name whose entry
// names its source. A software renderer or a device the table lacks gets no
// floor: a reason instead, never a made-up number.
#pragma once

#include "measure/namespace.h"
#include "backend.h"
#include "kernel.h"

#include <optional>
#include <string>

namespace cavity::measure {

// A device figure and where it came from: "driver", "nvml" or "table:<name>".
struct Figure {
    double value = 0;
    std::string source;
};

// What starting a compute dispatch costs on one API: a fixed part (the
// dispatch, the barrier before it, its scope's timestamps) and a part a
// workgroup, fitted to the empty dispatch at several sizes
// (bench/overhead_probes.h, timer/empty_chain).
struct LaunchFigures {
    double fixedUs = 0, perWorkgroupNs = 0;
};

struct DeviceFigures {
    std::string name;           // the table entry's device name
    std::string tableSource;    // the document the table entry's figures are from
    Figure smCount, textureUnitsPerSm, smClockMhz, dramGBps;
    // Measured per API, where a study has (launchSource names it).
    std::optional<LaunchFigures> launchVk, launchGl;
    std::string launchSource;
    // 32-bit texels (fetch slots) per second.
    double slotsPerSecond() const { return smCount.value * textureUnitsPerSm.value * smClockMhz.value * 1e6; }
};

// The figures of one device, or why there are none.
struct DeviceFloor {
    std::optional<DeviceFigures> figures;
    std::string reason;         // empty when figures is set
};

// `maxSmMhz`: NVML's maximum SM clock of the device, when it could be read.
DeviceFloor deviceFloor(const gpu::DeviceInfo& device, std::optional<double> maxSmMhz);

// One line for logs and the benchmark context: "NVIDIA H200: 132 SMs (driver) x 4 ...", or the reason.
std::string describe(const DeviceFloor& d);

struct PassFloor {
    double pixels = 0;
    kernels::Cost cost;         // per pixel, at the configuration's parameter values
    double fetchMs = 0, dramMs = 0;
    // The launch term; 0 with launchReason set where the model has none
    // (a fragment pass, a shape of unknown dispatches, a device with no
    // measured launch figures).
    double launchMs = 0;
    std::string launchReason;
    double memoryMs() const { return fetchMs > dramMs ? fetchMs : dramMs; }
    double ms() const { return memoryMs() + launchMs; }
    const char* bound() const {
        if (launchMs > memoryMs()) return "launch";
        return fetchMs >= dramMs ? "fetch" : "dram";
    }
};

struct PassFloorResult {
    std::optional<PassFloor> floor;
    std::string reason;         // empty when floor is set
};

// The floor of a pass of `kernel` over `pixels` output pixels, with the
// configuration's parameters (the kernel's defaults fill the rest), run as
// `shape` says (PassChain::passShape); unset, a compute pass in the
// kernel's declared workgroup, with no launch term. `api`: whose launch
// figures count.
PassFloorResult passFloor(const DeviceFloor& device, const std::string& kernel, const kernels::ParamValues& params,
                          double pixels, const std::optional<kernels::PassShape>& shape = std::nullopt,
                          gpu::Api api = gpu::Api::Vulkan);

}  // namespace cavity::measure