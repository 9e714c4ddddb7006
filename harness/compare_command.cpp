// `cavity compare old.json new.json`: per configuration and pass, old and
// new median, the change, and a verdict from a two-sided Mann-Whitney U test
// on the per-frame samples, as Google Benchmark's compare.py does.
#include "cli.h"
#include "mann_whitney.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

namespace cavity::cli {

namespace {

using nlohmann::json;

struct PassSamples {
    double median = 0;
    std::vector<double> samples;
    std::string clock;
};

Result<std::map<std::string, PassSamples>> load(const std::string& path) {
    std::ifstream f(path);
    if (!f) return badInput(path + ": cannot be read");
    json doc;
    try {
        doc = json::parse(f);
    } catch (const json::exception& e) {
        return badInput(path + ": does not parse: " + e.what());
    }
    if (!doc.is_object() || doc.value("schema", "") != "cavity.results/1")
        return badInput(path + ": not a cavity results.json (schema cavity.results/1)");
    std::map<std::string, PassSamples> out;
    try {
        for (const auto& r : doc.at("runs")) {
            const std::string id = r.at("id");
            for (const auto& p : r.at("passes"))
                out[id + " " + p.at("name").get<std::string>()] = {p.at("stats").at("median_ms"),
                                                                    p.at("samples_ms").get<std::vector<double>>(),
                                                                    r.at("clock")};
            out[id + " frame"] = {r.at("frame").at("stats").at("median_ms"),
                                  r.at("frame").at("samples_ms").get<std::vector<double>>(), r.at("clock")};
        }
    } catch (const json::exception& e) {
        return badInput(path + ": malformed results: " + e.what());
    }
    return out;
}

}  // namespace

int compareCommand(const std::vector<std::string>& argv) {
    std::vector<std::string> files;
    double alpha = 0.05, minChange = 2.0;
    Args a(argv);
    while (!a.done()) {
        const std::string flag = a.next();
        if (flag == "--alpha" || flag == "--min-change") {
            auto v = a.value(flag);
            char* end = nullptr;
            const double x = v ? std::strtod(v->c_str(), &end) : NAN;
            const bool ok = v && end && *end == '\0' && std::isfinite(x) &&
                            (flag == "--alpha" ? (x > 0 && x < 1) : (x >= 0));
            if (!ok) {
                std::cerr << "cavity compare: " << flag << " " << (v ? *v : "") << ": must be "
                          << (flag == "--alpha" ? "a number in (0, 1)" : "a percentage >= 0") << "\n";
                return 2;
            }
            (flag == "--alpha" ? alpha : minChange) = x;
        } else if (flag.rfind("--", 0) == 0) {
            std::cerr << "cavity compare: " << flag << ": unknown flag\n";
            return 2;
        } else files.push_back(flag);
    }
    if (files.size() != 2) {
        std::cerr << "cavity compare: usage: cavity compare OLD.json NEW.json [--alpha 0.05] [--min-change 2]\n";
        return 2;
    }
    auto oldRuns = load(files[0]);
    if (!oldRuns) return std::cerr << "cavity compare: " << oldRuns.error().message << "\n", 2;
    auto newRuns = load(files[1]);
    if (!newRuns) return std::cerr << "cavity compare: " << newRuns.error().message << "\n", 2;
    std::printf("%-62s %10s %10s %8s %9s  %s\n", "configuration pass", "old ms", "new ms", "change", "U-test p",
                "verdict");
    int slower = 0;
    for (const auto& [key, o] : *oldRuns) {
        auto it = newRuns->find(key);
        if (it == newRuns->end()) continue;
        const auto& n = it->second;
        const double change = o.median > 0 ? 100.0 * (n.median - o.median) / o.median : 0.0;
        const auto u = stats::mannWhitneyU(o.samples, n.samples);
        const bool significant = u.p < alpha && std::fabs(change) >= minChange;
        const char* verdict = !significant ? "same" : change > 0 ? "SLOWER" : "faster";
        slower += significant && change > 0;
        std::printf("%-62s %10.4f %10.4f %+7.1f%% %9.4f  %s%s\n", key.c_str(), o.median, n.median, change, u.p, verdict,
                    o.clock != n.clock ? " (clocks differ)" : "");
    }
    for (const auto& [key, n] : *newRuns)
        if (!oldRuns->count(key)) std::printf("%-62s %10s %10.4f %8s %9s  new\n", key.c_str(), "-", n.median, "", "");
    std::printf("\n%d significantly slower (p < %g and change >= %g%%)\n", slower, alpha, minChange);
    return 0;
}

}  // namespace cavity::cli
