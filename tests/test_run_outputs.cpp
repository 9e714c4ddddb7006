// What `cavity run` leaves a reader: the summary on stdout, read against the
// results.json it summarises, and index.html as headless Chromium shows it.
#include "chromium.h"
#include "run_binary.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace cavity::test {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

// A table row's cells: the columns are two spaces or more apart.
std::vector<std::string> cells(const std::string& row) {
    std::vector<std::string> out;
    const std::regex gap("  +");
    for (std::sregex_token_iterator it(row.begin(), row.end(), gap, -1), end; it != end; ++it)
        if (!it->str().empty()) out.push_back(*it);
    return out;
}

std::string clockOf(const json& run) {
    const bool host = run["device"]["software_renderer"].get<bool>();
    if (run["clock"] == "gpu-timestamp") return host ? "host timestamps" : "GPU timestamps";
    return (host ? "host " : "") + std::string("wall clock");
}

// half/full over one kernel's runs, from results.json as a reader would
// work it out: the geometric mean over same-clock pairs, else why not.
std::string halfOverFull(const std::vector<json>& runs) {
    std::map<std::string, const json*> full;
    for (const auto& r : runs)
        if (r["config"]["resolution"] == "full") full[r["id"].get<std::string>()] = &r;
    double logSum = 0;
    int pairs = 0, otherClock = 0;
    for (const auto& r : runs) {
        if (r["config"]["resolution"] != "half") continue;
        std::string id = r["id"];
        id.replace(id.find("/half/"), 6, "/full/");
        const json& f = *full.at(id);
        if (clockOf(r) != clockOf(f)) {
            ++otherClock;
            continue;
        }
        logSum += std::log(r["pipeline"]["stats"]["median_ms"].get<double>() / f["pipeline"]["stats"]["median_ms"].get<double>());
        ++pairs;
    }
    if (pairs == 0) return otherClock ? "not comparable: clocks differ" : "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.2fx", std::exp(logSum / pairs));
    return text;
}

}  // namespace

TEST(RunOutputs, SummaryReadsAsResultsJsonAndThePageShowsEveryConfiguration) {
    const fs::path dir = fs::temp_directory_path() / ("cavity_run_outputs_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const Outcome o = runBinary(CAVITY_EXE, "run --backend all --scene corner --kernel alchemy,hemisphere --radius 0.5,1 "
                                            "--resolution full,half --res 64x36 --frames 3 --warmup 1 --quiet --out " +
                                                dir.string(),
                                "", "2>/dev/null");
    ASSERT_EQ(o.code, 0) << o.output;

    // The summary: from its first line to the index.html path, at most 15 lines.
    const auto out = lines(o.output);
    size_t first = out.size(), last = out.size();
    for (size_t i = 0; i < out.size(); ++i) {
        if (out[i].rfind("16 configurations on", 0) == 0) first = i;
        if (out[i] == "open " + (dir / "index.html").string()) last = i;
    }
    ASSERT_LT(first, out.size()) << o.output;
    ASSERT_LT(last, out.size()) << o.output;
    EXPECT_LE(last - first + 1, 15u) << o.output;

    std::ifstream f(dir / "results.json");
    const json doc = json::parse(f);
    std::map<std::string, std::vector<json>> byKernel;
    for (const auto& r : doc["runs"]) byKernel[r["config"]["kernel"]].push_back(r);
    ASSERT_EQ(byKernel.size(), 2u);
    int rows = 0;
    for (size_t i = first; i <= last; ++i) {
        const auto c = cells(out[i]);
        if (c.size() != 6 || !byKernel.count(c[0])) continue;
        ++rows;
        const auto& runs = byKernel.at(c[0]);
        double fastest = 1e30;
        for (const auto& r : runs) fastest = std::min(fastest, r["pipeline"]["stats"]["median_ms"].get<double>());
        char text[32];
        std::snprintf(text, sizeof text, "%.3f ", fastest);
        EXPECT_EQ(c[2].rfind(text, 0), 0u) << c[0] << ": fastest " << c[2] << ", results.json " << fastest;
        EXPECT_EQ(c[4], halfOverFull(runs)) << c[0];
    }
    EXPECT_EQ(rows, 2) << o.output;

    // The page: one card per configuration, every image it links on disk,
    // one chart per kernel.
    REQUIRE_CHROMIUM();
    const std::string dom = renderedDom(dir / "index.html");
    std::set<std::string> cardIds;
    const std::regex card("class=\"card config\" data-id=\"([^\"]+)\"");
    for (std::sregex_iterator it(dom.begin(), dom.end(), card), end; it != end; ++it) cardIds.insert((*it)[1]);
    std::set<std::string> ids;
    for (const auto& r : doc["runs"]) ids.insert(r["id"].get<std::string>());
    EXPECT_EQ(cardIds, ids);
    // Each card's title names its configuration (the id without its
    // kernel, the section's heading): no two of a kernel alike, as no two
    // bars of its chart (their labels come from it).
    std::set<std::string> titles;
    const std::regex title("data-id=\"[^/\"]+/([^/\"]+)/[^\"]*\"><div class=\"title\">([^<]+)</div>");
    for (std::sregex_iterator it(dom.begin(), dom.end(), title), end; it != end; ++it)
        EXPECT_TRUE(titles.insert((*it)[1].str() + ": " + (*it)[2].str()).second) << "two cards titled " << (*it)[2];
    EXPECT_EQ(titles.size(), ids.size());
    int images = 0;
    const std::regex img("<img src=\"([^\"]+)\"");
    for (std::sregex_iterator it(dom.begin(), dom.end(), img), end; it != end; ++it, ++images)
        EXPECT_TRUE(fs::is_regular_file(dir / (*it)[1].str())) << (*it)[1];
    EXPECT_EQ(images, 16 * 4) << "ao, ao_blur, color and normal for each configuration";
    size_t canvases = 0;
    for (size_t at = 0; (at = dom.find("<canvas", at)) != std::string::npos; ++at) ++canvases;
    EXPECT_EQ(canvases, 2u);
    fs::remove_all(dir);
}

}  // namespace cavity::test
