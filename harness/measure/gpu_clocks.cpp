#include "measure/gpu_clocks.h"

#include "stats/stats.h"

#include <algorithm>
#include <map>

#include <dlfcn.h>

namespace cavity::measure {

namespace {

// The few NVML entry points used, by their documented C signatures
// (nvml.h is not a Debian package; the ABI of these has been stable since
// NVML v2). Return value 0 is NVML_SUCCESS.
using nvmlDevice = struct nvmlDevice_st*;
using InitFn = int (*)();
using ShutdownFn = int (*)();
using CountFn = int (*)(unsigned*);
using ByIndexFn = int (*)(unsigned, nvmlDevice*);
using ByUuidFn = int (*)(const char*, nvmlDevice*);
using NameFn = int (*)(nvmlDevice, char*, unsigned);
using ClockFn = int (*)(nvmlDevice, int, unsigned*);
using ReasonsFn = int (*)(nvmlDevice, unsigned long long*);
constexpr int kClockSm = 1, kClockMem = 2;

class NvmlClocks final : public GpuClocks {
public:
    ~NvmlClocks() override {
        if (shutdown_) shutdown_();
        if (lib_) dlclose(lib_);
    }

    static std::unique_ptr<GpuClocks> open(const gpu::DeviceInfo& info) {
        void* lib = dlopen("libnvidia-ml.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!lib) return nullptr;
        std::unique_ptr<NvmlClocks> c(new NvmlClocks);
        c->lib_ = lib;
        auto sym = [&](const char* name) { return dlsym(lib, name); };
        auto init = reinterpret_cast<InitFn>(sym("nvmlInit_v2"));
        auto count = reinterpret_cast<CountFn>(sym("nvmlDeviceGetCount_v2"));
        auto byIndex = reinterpret_cast<ByIndexFn>(sym("nvmlDeviceGetHandleByIndex_v2"));
        auto byUuid = reinterpret_cast<ByUuidFn>(sym("nvmlDeviceGetHandleByUUID"));
        auto name = reinterpret_cast<NameFn>(sym("nvmlDeviceGetName"));
        c->clock_ = reinterpret_cast<ClockFn>(sym("nvmlDeviceGetClockInfo"));
        auto maxClock = reinterpret_cast<ClockFn>(sym("nvmlDeviceGetMaxClockInfo"));
        // Renamed "clocks event reasons" in newer drivers; the old name stays.
        c->reasons_ = reinterpret_cast<ReasonsFn>(sym("nvmlDeviceGetCurrentClocksThrottleReasons"));
        if (!init || !count || !byIndex || !c->clock_ || init() != 0) return nullptr;
        c->shutdown_ = reinterpret_cast<ShutdownFn>(sym("nvmlShutdown"));
        // NVML spells a UUID "GPU-xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx".
        bool found = false;
        if (byUuid && info.uuid.size() == 32) {
            const std::string& u = info.uuid;
            const std::string s = "GPU-" + u.substr(0, 8) + "-" + u.substr(8, 4) + "-" + u.substr(12, 4) + "-" +
                                  u.substr(16, 4) + "-" + u.substr(20);
            found = byUuid(s.c_str(), &c->device_) == 0;
        }
        unsigned n = 0;
        if (!found && count(&n) == 0 && n == 1) found = byIndex(0, &c->device_) == 0;
        if (!found) return nullptr;
        char buf[96] = {};
        if (name && name(c->device_, buf, sizeof buf) == 0) c->name_ = buf;
        if (unsigned mhz = 0; maxClock && maxClock(c->device_, kClockSm, &mhz) == 0 && mhz > 0) c->maxSmMhz_ = mhz;
        if (!c->sample()) return nullptr;
        return c;
    }

    std::optional<GpuClockSample> sample() override {
        unsigned sm = 0, mem = 0;
        if (clock_(device_, kClockSm, &sm) != 0 || clock_(device_, kClockMem, &mem) != 0) return std::nullopt;
        GpuClockSample s{double(sm), double(mem), 0};
        unsigned long long r = 0;
        if (reasons_ && reasons_(device_, &r) == 0) s.reasons = r;
        return s;
    }
    std::string source() const override { return "nvml"; }
    std::string device() const override { return name_; }
    std::optional<double> maxSmMhz() const override { return maxSmMhz_; }

private:
    NvmlClocks() = default;
    void* lib_ = nullptr;
    ShutdownFn shutdown_ = nullptr;
    ClockFn clock_ = nullptr;
    ReasonsFn reasons_ = nullptr;
    nvmlDevice device_ = nullptr;
    std::string name_;
    std::optional<double> maxSmMhz_;
};

}  // namespace

std::unique_ptr<GpuClocks> GpuClocks::open(const gpu::DeviceInfo& device) {
    if (device.softwareRenderer) return nullptr;
    return NvmlClocks::open(device);
}

GpuClocks* GpuClocks::forDevice(const gpu::DeviceInfo& device) {
    static std::map<std::string, std::unique_ptr<GpuClocks>> cache;
    const std::string key = device.api + "/" + device.deviceName + "/" + device.uuid;
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, open(device)).first;
    return it->second.get();
}

GpuClockSummary summarizeClocks(const std::vector<GpuClockSample>& samples, const std::string& source,
                                const std::string& device) {
    GpuClockSummary s;
    if (samples.empty()) return s;
    s.source = source;
    s.device = device;
    s.samples = int(samples.size());
    std::vector<double> sm, mem;
    for (const auto& x : samples) {
        sm.push_back(x.smMhz);
        mem.push_back(x.memMhz);
        s.reasons |= x.reasons;
    }
    const Stats a = summarize(sm), b = summarize(mem);
    s.smMin = a.min, s.smMedian = a.median, s.smMax = a.max;
    s.memMin = b.min, s.memMedian = b.median, s.memMax = b.max;
    return s;
}

std::vector<std::string> GpuClockSummary::reasonNames() const {
    // NVML's nvmlClocksEventReason bits.
    static const std::pair<uint64_t, const char*> names[] = {
        {0x1, "gpu_idle"},          {0x2, "applications_clocks_setting"}, {0x4, "sw_power_cap"},
        {0x8, "hw_slowdown"},       {0x10, "sync_boost"},                 {0x20, "sw_thermal_slowdown"},
        {0x40, "hw_thermal_slowdown"}, {0x80, "hw_power_brake_slowdown"}, {0x100, "display_clock_setting"}};
    std::vector<std::string> out;
    for (const auto& [bit, name] : names)
        if (reasons & bit) out.push_back(name);
    return out;
}

}  // namespace cavity::measure