// The GPU's own clocks, read while a measurement runs, so that every number
// carries the SM and memory clock it was taken at (a GPU that sets its own
// clock can halve a pass's time between two runs; docs/gpu.md).
//
// NVIDIA: NVML from the driver (libnvidia-ml.so.1), loaded at run time so
// nothing links against it and machines without it simply have no clocks.
// The device is matched by UUID (DeviceInfo::uuid), or taken as the only one.
#pragma once

#include "measure/namespace.h"
#include "backend.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cavity::measure {

struct GpuClockSample {
    double smMhz = 0, memMhz = 0;
    uint64_t reasons = 0;   // NVML clock event ("throttle") reasons, a bit mask
};

struct GpuClockSummary {
    std::string source;     // "nvml"; empty: no clock could be read
    std::string device;     // the NVML device name
    int samples = 0;
    double smMin = 0, smMedian = 0, smMax = 0;
    double memMin = 0, memMedian = 0, memMax = 0;
    uint64_t reasons = 0;   // every reason seen, OR-ed
    // The SM clock moved during the measurement: its range exceeds the share
    // of its median tested below (NVML reports whole MHz in steps of 15 on
    // Hopper).
    bool moved() const { return samples > 1 && smMax - smMin > 0.01 * smMedian; }
    std::vector<std::string> reasonNames() const;
};

GpuClockSummary summarizeClocks(const std::vector<GpuClockSample>& samples, const std::string& source,
                                const std::string& device);

class GpuClocks {
public:
    // Null where the driver has no NVML or no NVML device matches.
    static std::unique_ptr<GpuClocks> open(const gpu::DeviceInfo& device);
    // The same, opened once per device for the life of the process.
    static GpuClocks* forDevice(const gpu::DeviceInfo& device);
    virtual ~GpuClocks() = default;
    virtual std::optional<GpuClockSample> sample() = 0;
    // The highest SM clock the device can run at (the floor's clock,
    // harness/measure/roofline.h); empty where not reported.
    virtual std::optional<double> maxSmMhz() const = 0;
    virtual std::string source() const = 0;
    virtual std::string device() const = 0;
};

}  // namespace cavity::measure