// index.html: the embedded page with the report's data inlined
// (report/gate_report.h).
#include "report/gate_report.h"

#include "report/verdict_text.h"
#include "core/digest.h"
#include "pipeline/config_id.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

namespace cavity::report {

namespace fs = std::filesystem;

// harness/report/'s files by name, embedded at build time (cmake/embed.cmake).
const std::map<std::string, std::string>& reportFiles();

namespace {

std::string base64File(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return "";
    return core::base64(std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>()));
}

std::string dataUri(const std::string& png) {
    const std::string b = png.empty() ? "" : base64File(png);
    return b.empty() ? "" : "data:image/png;base64," + b;
}

// The heat-map's colour scale as a CSS gradient, from the colours it is drawn with.
std::string heatScaleCss() {
    std::string g = "linear-gradient(to right";
    for (int k = -8; k <= 8; ++k) {
        const auto c = metrics::diffColor(k / 8.0);
        char b[48];
        std::snprintf(b, sizeof b, ",rgb(%d,%d,%d)", int(255 * c[0] + 0.5f), int(255 * c[1] + 0.5f), int(255 * c[2] + 0.5f));
        g += b;
    }
    return g + ")";
}

// The PNG files the page shows, by the path gate.json names them: a passing
// configuration's new images (thumbnails), a failing or changed one's
// baseline, new image and heat-map. Every image of every passing ci
// configuration embedded in full made 8.4 MB.
nlohmann::json shownImages(const GateRun& run) {
    nlohmann::json images = nlohmann::json::object();
    auto add = [&](const std::string& png) {
        if (png.empty() || images.contains(png)) return;
        if (const std::string uri = dataUri(png); !uri.empty()) images[png] = uri;
    };
    for (const auto& r : run.results)
        for (const auto& i : r.images) {
            add(i.newPng);
            if (r.passed() && !r.changed()) continue;
            add(i.baselinePng);
            add(i.diffPng);
        }
    return images;
}

// Charts from scripts/charts/charts.py, when a benchmark run left them (and their
// index.json) next to the report; by name.
nlohmann::json charts(const std::string& chartsDir) {
    nlohmann::json out = nlohmann::json::array();
    std::error_code ec;
    if (!fs::exists(fs::path(chartsDir) / "index.json", ec)) return out;
    std::vector<fs::path> pngs;
    for (const auto& entry : fs::directory_iterator(chartsDir, ec))
        if (entry.path().extension() == ".png") pngs.push_back(entry.path());
    std::sort(pngs.begin(), pngs.end());
    for (const auto& png : pngs) out.push_back({{"name", png.stem().string()}, {"src", dataUri(png.string())}});
    return out;
}

// JSON inside <script>: every '<', '>' and '&' (which JSON holds only inside
// strings) as a \u escape, so that no "</script>" or "<!--" in a message or
// a path can end the block or change how it is parsed.
std::string scriptSafe(const std::string& json) {
    std::string o;
    o.reserve(json.size());
    for (char ch : json) {
        switch (ch) {
        case '<': o += "\\u003c"; break;
        case '>': o += "\\u003e"; break;
        case '&': o += "\\u0026"; break;
        default: o += ch;
        }
    }
    return o;
}

// Replaces the one occurrence of `marker` in `page`.
Status fill(std::string& page, const std::string& marker, const std::string& text) {
    const auto at = page.find(marker);
    if (at == std::string::npos || page.find(marker, at + 1) != std::string::npos)
        return internal("harness/report/index.html: needs " + marker + " exactly once");
    page.replace(at, marker.size(), text);
    return {};
}

// Whether two measured values are the same within kSameShare of the larger:
// GL and Vulkan builds of one kernel round a few blurred or composited
// pixels differently, which moves a metric in its last printed digit.
constexpr double kSameShare = 0.01;
bool near(double a, double b) {
    if (a == b) return true;
    if (!std::isfinite(a) || !std::isfinite(b)) return false;
    return std::fabs(a - b) <= kSameShare * std::max(std::fabs(a), std::fabs(b));
}

// The same failure: every image failed the same checks with its metrics
// near() each other's, and every time has the same verdict.
bool sameFailure(const ConfigResult& a, const ConfigResult& b) {
    if (a.images.size() != b.images.size() || a.timings.size() != b.timings.size()) return false;
    for (size_t k = 0; k < a.images.size(); ++k) {
        const auto &i = a.images[k], &j = b.images[k];
        if (i.image != j.image || i.route != j.route || i.failures.size() != j.failures.size()) return false;
        if (i.metrics.has_value() != j.metrics.has_value()) return false;
        if (!i.metrics) {
            if (i.failures != j.failures) return false;
            continue;
        }
        const auto &m = *i.metrics, &n = *j.metrics;
        if (!(near(m.maxAbs, n.maxAbs) && near(m.meanAbs, n.meanAbs) && near(m.rmse, n.rmse) && near(m.psnr, n.psnr) &&
              near(m.overThresholdShare, n.overThresholdShare) && near(1 - m.ssim, 1 - n.ssim) &&
              near(m.differingShare, n.differingShare) && m.nonFinite == n.nonFinite))
            return false;
    }
    for (size_t k = 0; k < a.timings.size(); ++k)
        if (a.timings[k].passed() != b.timings[k].passed()) return false;
    return true;
}

// Failures that are the same on both APIs get one card: for each result
// shown inside another's card, the index of that card. Two results are the
// same when only their API differs and sameFailure holds.
std::map<size_t, size_t> sharedCards(const GateRun& run, const std::vector<const ConfigResult*>& order) {
    std::map<std::string, size_t> first;
    std::map<size_t, size_t> shown;
    for (const auto* r : order) {
        if (r->passed() || !r->error.empty()) continue;
        core::RunConfig other = r->config;
        other.api = gpu::Api::Vulkan;
        const std::string key = pipeline::configId(other) + "#" + std::to_string(r->repetition) + "#" + r->verdict();
        const size_t k = size_t(r - run.results.data());
        const auto [at, fresh] = first.emplace(key, k);
        if (!fresh && run.results[at->second].config.api != r->config.api && sameFailure(run.results[at->second], *r))
            shown[k] = at->second;
    }
    return shown;
}

}  // namespace

nlohmann::json reportData(const GateRun& run, const std::string& chartsDir) {
    nlohmann::json order = nlohmann::json::array(), results = nlohmann::json::array();
    const auto sorted = ordered(run);
    const auto shared = sharedCards(run, sorted);
    for (const auto* r : sorted)
        if (!shared.count(size_t(r - run.results.data()))) order.push_back(r - run.results.data());
    for (size_t k = 0; k < run.results.size(); ++k) {
        const auto& r = run.results[k];
        nlohmann::json v = {{"label", r.label()}, {"note", verdictNote(r, "", acceptArgs(run))}, {"card", k},
                            {"same", nlohmann::json::array()}};
        if (const auto at = shared.find(k); at != shared.end()) v["card"] = at->second;
        results.push_back(std::move(v));
    }
    for (const auto& [k, card] : shared) {
        results[card]["same"].push_back(run.results[k].label());
        // The card's commands accept both APIs' configurations.
        const auto& r = run.results[card];
        std::string both = r.id;
        const std::string api = std::string("/") + gpu::apiName(r.config.api) + "/";
        if (const auto at = both.find(api); at != std::string::npos) both.replace(at, api.size(), "/(gl|vk)/");
        results[card]["note"] = verdictNote(r, both, acceptArgs(run));
    }
    return {{"gate", toJson(run)},
            {"view",
             {{"counts", countsText(run)},
              {"order", order},
              {"results", results},
              {"images", shownImages(run)},
              {"heat_scale", heatScaleCss()},
              {"charts", charts(chartsDir)}}}};
}

Result<std::string> reportHtml(const GateRun& run, const std::string& chartsDir) {
    const auto& files = reportFiles();
    std::string page = files.at("index.html");
    // A message or a path that is not UTF-8 is written with U+FFFD rather
    // than failing the report.
    const std::string data = reportData(run, chartsDir).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    CAVITY_TRY(fill(page, "<script src=\"report.js\"></script>", "<script>\n" + files.at("report.js") + "</script>"));
    CAVITY_TRY(fill(page, "@GATE_DATA@", scriptSafe(data)));
    return page;
}

}  // namespace cavity::report
