#include "measure/roofline.h"

#include <cstdio>
#include <vector>

namespace cavity::measure {

namespace {

// Figures no driver reports (texture units, DRAM bandwidth) and the
// fallbacks for those it may not (SM count, maximum SM clock). Data-sheet
// figures, not measurements: a copy reaches less bandwidth (about 3.0 TB/s
// of the H100's 3.35, docs/roofline.md), so the DRAM floor is optimistic.
struct TableEntry {
    const char* name;           // VkPhysicalDeviceProperties::deviceName; GL_RENDERER up to its first '/'
    double smCount, textureUnitsPerSm, maxSmClockMhz, dramGBps;
    const char* source;
    // Measured, not from a data sheet: the study that fitted them, or none.
    std::optional<LaunchFigures> launchVk = std::nullopt, launchGl = std::nullopt;
    const char* launchSource = "";
};

const std::vector<TableEntry>& table() {
    static const std::vector<TableEntry> t = {
        {"NVIDIA H200", 132, 4, 1980, 4800,
         "NVIDIA H200 Tensor Core GPU data sheet (SXM: 4.8 TB/s HBM3e); NVIDIA H100 Tensor Core GPU "
         "Architecture whitepaper (GH100 SXM5, the H200's GPU: 132 SMs, 4 texture units per SM); 1980 MHz, "
         "the maximum SM clock NVML reports on the H200",
         LaunchFigures{3.65, 0.58}, LaunchFigures{6.05, 0.58},
         "study 2026-12-03_h200_batched: the empty dispatch at 2025, 8100 and 32400 workgroups, and GL's "
         "extra cost a pass (study 2026-12-03_h200_kernels2)"},
        {"NVIDIA H100 80GB HBM3", 132, 4, 1980, 3350,
         "NVIDIA H100 Tensor Core GPU data sheet (SXM: 3.35 TB/s HBM3) and Architecture whitepaper (GH100 "
         "SXM5: 132 SMs, 4 texture units per SM); 1980 MHz, the maximum SM clock NVML reports on the H100",
         LaunchFigures{1.94, 0.602}, LaunchFigures{5.07, 0.602},
         "study 2026-12-06_gpu_packed_texel: the empty dispatch at 135 to 32400 workgroups of 16x16, each API"},
    };
    return t;
}

// GL_RENDERER appends "/PCIe/SSE2" to the name Vulkan reports.
const TableEntry* findEntry(const std::string& deviceName) {
    const std::string name = deviceName.substr(0, deviceName.find('/'));
    for (const auto& e : table())
        if (name == e.name) return &e;
    return nullptr;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// "; launch vk <fixed> us + <per group> ns a workgroup, gl ...", or nothing.
std::string describeLaunch(const DeviceFigures& f) {
    std::string out;
    for (const auto& [api, l] : {std::pair{"vk", &f.launchVk}, std::pair{"gl", &f.launchGl}})
        if (*l) out += std::string(out.empty() ? "; launch " : ", ") + api + " " + number((*l)->fixedUs) + " us + " +
                       number((*l)->perWorkgroupNs) + " ns a workgroup";
    return out;
}

}  // namespace

DeviceFloor deviceFloor(const gpu::DeviceInfo& device, std::optional<double> maxSmMhz) {
    // A CPU renderer's time is the host's threads and caches: no GPU figure applies.
    if (device.softwareRenderer) return {std::nullopt, "software renderer (" + device.deviceName + "): no GPU floor"};
    const TableEntry* e = findEntry(device.deviceName);
    if (!e) return {std::nullopt, "device '" + device.deviceName + "' is not in the floor table (harness/measure/roofline.cpp)"};
    const std::string table = std::string("table:") + e->name;
    DeviceFigures f;
    f.name = e->name;
    f.tableSource = e->source;
    // The driver's count wins: it is the part this process runs on (a MIG
    // slice has fewer SMs than the whole GPU).
    f.smCount = device.smCount > 0 ? Figure{double(device.smCount), "driver"} : Figure{e->smCount, table};
    f.textureUnitsPerSm = {e->textureUnitsPerSm, table};
    f.smClockMhz = maxSmMhz && *maxSmMhz > 0 ? Figure{*maxSmMhz, "nvml"} : Figure{e->maxSmClockMhz, table};
    f.dramGBps = {e->dramGBps, table};
    f.launchVk = e->launchVk;
    f.launchGl = e->launchGl;
    f.launchSource = e->launchSource;
    return {f, ""};
}

std::string describe(const DeviceFloor& d) {
    if (!d.figures) return "no floor: " + d.reason;
    const DeviceFigures& f = *d.figures;
    return f.name + ": " + number(f.smCount.value) + " SMs (" + f.smCount.source + ") x " +
           number(f.textureUnitsPerSm.value) + " texture units/SM (" + f.textureUnitsPerSm.source + ") x " +
           number(f.smClockMhz.value) + " MHz (" + f.smClockMhz.source + "); DRAM " + number(f.dramGBps.value) +
           " GB/s (" + f.dramGBps.source + ")" + describeLaunch(f);
}

PassFloorResult passFloor(const DeviceFloor& device, const std::string& kernel, const kernels::ParamValues& params,
                          double pixels, const std::optional<kernels::PassShape>& shape, gpu::Api api) {
    const kernels::KernelDecl* k = kernels::find(kernel);
    if (!k || !k->cost) return {std::nullopt, "no cost declared"};
    const kernels::Cost cost = k->cost(kernels::withDefaults(*k, params), shape.value_or(kernels::PassShape{true, k->workgroup}));
    // The fields a declaration written before the floor leaves at 0.
    if ((cost.fetchesPerPixel > 0 && cost.fetchSlotsPerPixel <= 0) || cost.dramBytesPerPixel <= 0)
        return {std::nullopt, "cost declares no fetch slots or no DRAM bytes (kernels/kernel.h Cost)"};
    if (!device.figures) return {std::nullopt, device.reason};
    const DeviceFigures& f = *device.figures;
    PassFloor p;
    p.pixels = pixels;
    p.cost = cost;
    p.fetchMs = 1e3 * pixels * cost.fetchSlotsPerPixel / f.slotsPerSecond();
    p.dramMs = 1e3 * pixels * cost.dramBytesPerPixel / (f.dramGBps.value * 1e9);
    const auto& launch = api == gpu::Api::OpenGL ? f.launchGl : f.launchVk;
    if (!shape || !shape->compute)
        p.launchReason = shape ? "a fragment pass: the launch of its rasterized tiles is not modelled"
                               : "no dispatch given";
    else if (shape->dispatches <= 0)
        p.launchReason = "the pass's dispatches are unknown";
    else if (!launch)
        p.launchReason = "no launch figures measured for " + f.name + " on " + gpu::apiName(api);
    else
        p.launchMs = 1e-3 * shape->dispatches * launch->fixedUs + 1e-6 * double(shape->workgroups) * launch->perWorkgroupNs;
    return {p, ""};
}

}  // namespace cavity::measure