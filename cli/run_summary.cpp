#include "run_summary.h"
#include "imports.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace cavity::cli {

namespace {

// A CV above this is flagged in the table: the timing was noisy enough that
// the median may move by more than a kernel change one wants to see.
constexpr double kNoisyCv = 0.10;
// The summary's kernel rows; the rest are counted (the summary stays one screen).
constexpr size_t kSummaryKernels = 9;

std::vector<std::string> split(const std::string& id) {
    std::vector<std::string> parts;
    for (size_t start = 0;;) {
        const size_t slash = id.find('/', start);
        parts.push_back(id.substr(start, slash - start));
        if (slash == std::string::npos) return parts;
        start = slash + 1;
    }
}

// A configuration named by the parts of its id that vary in this run, the
// kernel left out (its row names it).
struct ShortNames {
    std::set<size_t> varying;
    size_t parts = 0;
    explicit ShortNames(const std::vector<measure::RunRecord>& runs) {
        std::vector<std::vector<std::string>> ids;
        for (const auto& r : runs) ids.push_back(split(configId(r.config)));
        parts = ids.front().size();
        for (const auto& id : ids)
            if (id.size() != parts) parts = 0;
        for (size_t i = 0; i < parts; ++i)
            for (const auto& id : ids)
                if (i != 1 && id[i] != ids.front()[i]) varying.insert(i);
    }
    std::string of(const measure::RunRecord& r) const {
        const auto id = split(configId(r.config));
        if (id.size() != parts) return configId(r.config);
        std::string name;
        for (size_t i : varying) name += (name.empty() ? "" : " ") + id[i];
        return name.empty() ? "(one configuration)" : name;
    }
};

// The geometric mean of a/b over the pairs `twin` matches, on one clock.
// "-": no pair; otherwise the ratio, or why there is none.
std::string pairedRatio(const std::vector<const measure::RunRecord*>& runs, auto isA, auto twinKey) {
    std::map<std::string, const measure::RunRecord*> bByKey;
    for (const auto* r : runs)
        if (!isA(*r)) bByKey[twinKey(*r)] = r;
    double logSum = 0;
    int pairs = 0, otherClock = 0;
    for (const auto* a : runs) {
        if (!isA(*a)) continue;
        const auto it = bByKey.find(twinKey(*a));
        if (it == bByKey.end()) continue;
        const auto* b = it->second;
        if (measure::clockDescription(*a) != measure::clockDescription(*b)) {
            ++otherClock;
            continue;
        }
        const double ma = a->timing.pipeline.stats.median, mb = b->timing.pipeline.stats.median;
        if (!(ma > 0) || !(mb > 0)) continue;
        logSum += std::log(ma / mb);
        ++pairs;
    }
    if (pairs > 0) return fmt::format("{:.2f}x", std::exp(logSum / pairs));
    if (otherClock > 0) return "not comparable: clocks differ";
    return "-";
}

std::string timed(const measure::RunRecord& r, const ShortNames& names) {
    return fmt::format("{:.3f} {}", r.timing.pipeline.stats.median, names.of(r));
}

}  // namespace

std::string runSummary(const std::vector<measure::RunRecord>& runs, const std::vector<std::string>& files) {
    std::map<std::string, std::vector<const measure::RunRecord*>> byKernel;
    std::set<std::string> devices;
    int noisy = 0;
    for (const auto& r : runs) {
        byKernel[r.config.kernel].push_back(&r);
        devices.insert(std::string(gpu::apiName(r.config.api)) + " " + r.device.deviceName);
        noisy += r.timing.pipeline.stats.cv > kNoisyCv;
    }
    std::string deviceList;
    for (const auto& d : devices) deviceList += (deviceList.empty() ? "" : ", ") + d;
    std::string out = fmt::format("\n{} configuration{} on {}. AO pipeline ms (median; G-buffer left out):\n",
                                  runs.size(), runs.size() == 1 ? "" : "s", deviceList);
    const ShortNames names(runs);
    using A = TextTable::Align;
    TextTable table({{"kernel", A::Left}, {"clock", A::Left}, {"fastest", A::Left}, {"slowest", A::Left},
                     {"half/full", A::Right}, {"GL/Vulkan", A::Right}},
                    "  ");
    size_t shown = 0;
    for (const auto& [kernel, rs] : byKernel) {
        if (++shown > kSummaryKernels) break;
        std::set<std::string> clocks;
        for (const auto* r : rs) clocks.insert(measure::clockDescription(*r));
        std::string clock;
        for (const auto& c : clocks) clock += (clock.empty() ? "" : " + ") + c;
        auto by = [](const auto* a, const auto* b) { return a->timing.pipeline.stats.median < b->timing.pipeline.stats.median; };
        const auto* fastest = *std::min_element(rs.begin(), rs.end(), by);
        const auto* slowest = *std::max_element(rs.begin(), rs.end(), by);
        auto twinOf = [](const measure::RunRecord& r, auto change) {
            RunConfig c = r.config;
            change(c);
            return configId(c);
        };
        const std::string halfFull = pairedRatio(
            rs, [](const measure::RunRecord& r) { return r.config.half; },
            [&](const measure::RunRecord& r) { return twinOf(r, [](RunConfig& c) { c.half = false; }); });
        const std::string glVk = pairedRatio(
            rs, [](const measure::RunRecord& r) { return r.config.api == gpu::Api::OpenGL; },
            [&](const measure::RunRecord& r) { return twinOf(r, [](RunConfig& c) { c.api = gpu::Api::Vulkan; }); });
        table.add({kernel, clock, timed(*fastest, names), rs.size() > 1 ? timed(*slowest, names) : "-", halfFull, glVk});
    }
    out += table.str();
    if (byKernel.size() > kSummaryKernels)
        out += fmt::format("... and {} more kernels (table.txt)\n", byKernel.size() - kSummaryKernels);
    out += "Ratios are geometric means over configurations that differ only there, each pair on one clock.\n";
    if (noisy > 0)
        out += fmt::format("{} of {} configurations have a CV over {:.0f}%: their medians are uncertain (table.txt).\n",
                           noisy, runs.size(), 100 * kNoisyCv);
    for (const auto& f : files) out += f + "\n";
    return out;
}

std::string runTable(const std::vector<measure::RunRecord>& runs) {
    using A = TextTable::Align;
    TextTable table({{"configuration", A::Left}, {"pass", A::Left}, {"clock", A::Left}, {"median ms", A::Right},
                     {"min ms", A::Right}, {"p90 ms", A::Right}, {"CV", A::Right}},
                    "  ");
    int noisy = 0;
    for (const auto& r : runs) {
        // The id and the clock on the configuration's first row only.
        bool first = true;
        auto row = [&](const std::string& name, const Stats& st) {
            const bool flag = st.cv > kNoisyCv;
            const std::string clock = measure::clockDescription(r) + " (" + timingModeName(r.timing.mode) + ")";
            table.add({first ? configId(r.config) : "", name, first ? clock : "", TextTable::number(st.median, 3),
                       TextTable::number(st.min, 3), TextTable::number(st.p90, 3),
                       TextTable::number(100.0 * st.cv, 1) + "%"},
                      flag ? " !" : "");
            noisy += flag;
            first = false;
        };
        for (const auto& p : r.timing.passes) row(p.name, p.stats);
        row("pipeline", r.timing.pipeline.stats);
        row("frame", r.timing.frame.stats);
    }
    std::string out = "Every pass of every configuration: pipeline is the passes but the G-buffer, frame all of them.\n\n" +
                      table.str();
    if (noisy > 0)
        out += fmt::format("\nnote: ! marks a CV over {:.0f}%: the median is uncertain ({} rows; more --frames or a quieter "
                           "machine)\n", 100 * kNoisyCv, noisy);
    for (const auto& r : runs) {
        const auto& t = r.timing;
        const std::string id = configId(r.config);
        if (t.rejectedFrames)
            out += fmt::format("note: {}: {} frames failed the clock check and were left out ({})\n", id,
                               t.rejectedFrames, t.rejectedNote);
        if (t.steadyChecked && !t.steady)
            out += fmt::format("note: {}: the frame time was not steady after {:.1f} s of warm-up\n", id, t.warmupSeconds);
        if (!t.clocks.source.empty())
            out += fmt::format("clocks: {}: SM {:.0f} MHz ({:.0f}..{:.0f}), memory {:.0f} MHz{}\n", id, t.clocks.smMedian,
                               t.clocks.smMin, t.clocks.smMax, t.clocks.memMedian,
                               t.clocks.moved() ? ": the SM clock moved during the measurement" : "");
        if (!t.clockNote.empty())
            out += fmt::format("note: {}: {} {}: {}\n", id, gpu::apiName(r.config.api), r.device.deviceName, t.clockNote);
    }
    return out;
}

}  // namespace cavity::cli
