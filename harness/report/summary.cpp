// summary.md: what a reviewer reads in the pull request, at most
// kSummaryLines lines whatever fails. Failures are grouped by kernel and
// check (an image metric with the images it fails, a pass's time, an
// error), worst group
// first, and a configuration that fails the same way on OpenGL and Vulkan
// is one configuration "(gl+vk)". Everything else is one link away, in
// index.html (report/gate_report.h).
#include "report/gate_report.h"

#include "report/verdict_text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace cavity::report {

namespace {

// "rmse 0.0123 > 0.005 at (3,4)" -> {"rmse 0.0123 at (3,4)", "≤ 0.005"}: the
// result and the tolerance. A line without a comparator is all result.
std::pair<std::string, std::string> splitFailure(const std::string& f) {
    for (const char* op : {" > ", " < "}) {
        const auto at = f.find(op);
        if (at == std::string::npos) continue;
        std::string result = f.substr(0, at), tolerance = f.substr(at + 3);
        if (const auto where = tolerance.find(" at ("); where != std::string::npos) {
            result += tolerance.substr(where);
            tolerance.resize(where);
        }
        return {result, (op[1] == '>' ? "≤ " : "≥ ") + tolerance};
    }
    return {f, ""};
}

double firstNumber(const std::string& s) {
    std::smatch m;
    static const std::regex number(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
    return std::regex_search(s, m, number) ? std::stod(m.str()) : std::numeric_limits<double>::quiet_NaN();
}

// The check a failure line is about, its numbers taken out: "max abs error",
// "pixels over threshold", "differing pixels", "baseline missing".
std::string checkName(const std::string& result) {
    std::string name = result.substr(0, result.find(':'));
    name = std::regex_replace(name, std::regex(R"( at \([^)]*\)|\([^)]*\)|[-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?%?)"), "");
    name = std::regex_replace(name, std::regex(R"(\s+)"), " ");
    name = std::regex_replace(name, std::regex(R"(^[ ,]+|[ ,]+$)"), "");
    if (name.find("differ by more than") != std::string::npos) return "differing pixels";
    if (name.rfind("of pixels over", 0) == 0) return "pixels over threshold";
    return name.empty() ? result : name;
}

// How far over its tolerance a failure is (1: at it); lines with no
// tolerance (a missing baseline, NaN) rank first.
double severity(const std::string& result, const std::string& tolerance) {
    const double value = firstNumber(result), limit = firstNumber(tolerance);
    if (tolerance.empty() || !std::isfinite(value) || !std::isfinite(limit)) return std::numeric_limits<double>::infinity();
    if (tolerance.rfind("≤", 0) == 0) return limit > 0 ? value / limit : std::numeric_limits<double>::infinity();
    return value > 0 ? limit / value : std::numeric_limits<double>::infinity();
}

// The id without its API: "corner/alchemy/n16/b4/full/160x90/compute".
std::string withoutApi(const std::string& id) {
    return std::regex_replace(id, std::regex("/(gl|vk)/(compute|fragment)$"), "/$2");
}

std::string apiOf(const std::string& id) {
    std::smatch m;
    return std::regex_search(id, m, std::regex("/(gl|vk)/(compute|fragment)$")) ? m[1].str() : "";
}

struct Group {
    std::string kernel, check;
    std::set<std::string> images;          // the images failing this check
    std::set<std::string> configs, apis;   // ids without the API; APIs seen
    double worst = -1;
    std::string worstResult, worstTolerance, worstId;
    // Each configuration's limit of this check: they differ where tolerances
    // are sized to each image's pixels ("sized_for_pixels").
    double leastLimit = std::numeric_limits<double>::infinity(), mostLimit = -leastLimit;
};

void add(std::map<std::pair<std::string, std::string>, Group>& groups, const ConfigResult& r, const std::string& check,
         const std::string& result, const std::string& tolerance, const std::string& image = "") {
    auto& g = groups[{r.config.kernel, check}];
    g.kernel = r.config.kernel;
    g.check = check;
    if (!image.empty()) g.images.insert(image);
    g.configs.insert(withoutApi(r.id));
    if (const auto api = apiOf(r.id); !api.empty()) g.apis.insert(api);
    if (const double limit = firstNumber(tolerance); !tolerance.empty() && std::isfinite(limit))
        g.leastLimit = std::min(g.leastLimit, limit), g.mostLimit = std::max(g.mostLimit, limit);
    const double s = severity(result, tolerance);
    if (s > g.worst) g.worst = s, g.worstResult = result, g.worstTolerance = tolerance, g.worstId = withoutApi(r.id);
}

std::vector<Group> failureGroups(const GateRun& run) {
    std::map<std::pair<std::string, std::string>, Group> groups;
    for (const auto& r : run.results) {
        if (!r.fatal()) continue;
        if (!r.error.empty()) add(groups, r, "run", r.error, "");
        if (r.verdict() == "unexpected-pass") add(groups, r, "expectation", "unexpected pass", r.expectedWhy);
        for (const auto& i : r.images)
            for (const auto& f : i.failures) {
                const auto [result, tolerance] = splitFailure(f);
                add(groups, r, checkName(result), result, tolerance, i.image);
            }
        for (const auto& t : r.timings)
            if (!t.passed())
                add(groups, r, "time " + t.pass,
                    num(t.medianMs) + " ms (+" + num(100 * (t.medianMs / *t.budgetMs - 1), 3) + "%)", "≤ " + num(*t.budgetMs) + " ms");
    }
    std::vector<Group> out;
    for (auto& [key, g] : groups) out.push_back(std::move(g));
    std::stable_sort(out.begin(), out.end(), [](const Group& a, const Group& b) { return a.worst > b.worst; });
    return out;
}

std::string cell(std::string s) {
    for (auto& c : s)
        if (c == '|' || c == '\n') c = c == '|' ? '/' : ' ';
    return s;
}

// The non-fatal verdicts, one line per kind: "- flaky: `id`, `id` and 3 more".
std::vector<std::string> notedLines(const GateRun& run) {
    std::map<std::string, std::vector<std::string>> byVerdict;
    for (const auto* r : ordered(run)) {
        if (r->fatal() || r->verdict() == "pass") continue;
        std::string label = r->label() + "`";
        // A change within tolerance: by how much, as its card says.
        const gate::ImageCheck* most = nullptr;
        for (const auto& i : r->images)
            if (i.changed() && (!most || i.metrics->maxAbs > most->metrics->maxAbs)) most = &i;
        if (most)
            label += " (" + most->image + " max |d| " + num(most->metrics->maxAbs, 3) + ", " +
                     num(100 * most->metrics->overThresholdShare, 3) + "% of pixels over " +
                     num(most->tolerance.pixelThreshold, 3) + ")";
        byVerdict[r->verdict()].push_back(label);
    }
    std::vector<std::string> lines;
    for (const auto& [verdict, labels] : byVerdict) {
        std::string line = "- " + verdict + ": ";
        for (size_t i = 0; i < labels.size() && i < 3; ++i) line += (i ? ", `" : "`") + labels[i];
        if (labels.size() > 3) line += " and " + std::to_string(labels.size() - 3) + " more";
        lines.push_back(line);
    }
    return lines;
}

// The lines under the table: what else a reviewer should know, short.
std::vector<std::string> noteLines(const GateRun& run) {
    int unbudgeted = 0, nondet = 0, repetitions = 1, advisory = 0;
    for (const auto& r : run.results) {
        repetitions = std::max(repetitions, r.repetition + 1);
        nondet += !r.deterministic;
        for (const auto& t : r.timings) {
            unbudgeted += !t.budgetMs;
            advisory += t.advisory && !t.withinBudget();
        }
    }
    std::vector<std::string> n = notedLines(run);
    std::map<std::string, int> routes;
    int ownClass = 0;   // judged by tolerance against an image approved for its own device class
    for (const auto& r : run.results)
        for (const auto& i : r.images) {
            ++routes[i.route];
            ownClass += i.route == "tolerance" && !i.reference.empty() && i.reference != "default";
        }
    if (routes.count("digest") || routes.count("negative") || ownClass) {
        std::string line = "- images decided";
        for (const auto& [route, count] : routes)
            line += std::string(line.back() == 'd' ? ": " : ", ") + std::to_string(count) + " by " +
                    (route == "negative" ? "a known-bad digest" : route == "digest" ? "approved digest" : "tolerance");
        if (ownClass) line += " (" + std::to_string(ownClass) + " against their device class's approved reference)";
        n.push_back(line);
    }
    for (const auto& e : run.backendErrors) n.push_back("- backend could not start: " + e);
    for (const auto& r : run.replaced)
        n.push_back("- kernel source replaced: `" + kernels::sourceLabel(r.name) + "` by `" + r.file + "` (" + r.digest + ")");
    if (repetitions > 1)
        n.push_back("- each configuration was rendered " + std::to_string(repetitions) + " times; every repetition is judged");
    if (nondet) n.push_back("- " + std::to_string(nondet) + " configurations were not bit-identical across two frames");
    if (advisory)
        n.push_back("- " + std::to_string(advisory) + " pass timings over budget on a software renderer (reported, not failed: "
                    "the host's load moves them; `--enforce-cpu-budgets` fails them)");
    if (unbudgeted) n.push_back("- " + std::to_string(unbudgeted) + " pass timings had no budget for this device (reported, not failed)");
    return n;
}

std::string headline(const GateRun& run, int failed, int noted) {
    const std::string total = std::to_string(run.results.size());
    return "## Cavity gate `" + run.matrix + "`" +
           (run.shardCount > 1 ? " (shard " + std::to_string(run.shardIndex) + "/" + std::to_string(run.shardCount) + ")" : "") +
           ": " +
           (failed ? "**" + std::to_string(failed) + " of " + total + " configurations failed**"
            : noted ? "no regression in " + total + " configurations, " + std::to_string(noted) + " reported"
            // An empty shard of a split larger than the matrix judged
            // nothing: `gate merge` of every shard is the verdict.
            : run.results.empty() && run.backendErrors.empty()
                ? std::string("no configuration of the matrix falls in this selection; nothing was judged")
                : "all " + total + " configurations passed") +
           (run.renderSeconds > 0 ? " (rendered in " + num(run.renderSeconds, 3) + " s, judged in " +
                                        num(run.seconds - run.renderSeconds, 3) + " s)"
                                  : " (" + num(run.seconds, 3) + " s)");
}

}  // namespace

std::string summaryMarkdown(const GateRun& run, const std::string& reportUrl) {
    int failed = 0, noted = 0;
    for (const auto& r : run.results) {
        failed += r.fatal();
        noted += !r.fatal() && r.verdict() != "pass";
    }
    std::vector<std::string> lines = {headline(run, failed, noted), "", countsText(run), ""};
    const auto groups = failureGroups(run);
    auto notes = noteLines(run);
    const size_t fixedLines = lines.size() + 2 /* table head */ + 1 /* blank */ + 1 /* link */;
    const size_t noteRoom = std::min(notes.size(), size_t(8));
    if (notes.size() > noteRoom) {
        notes.resize(noteRoom - 1);
        notes.push_back("- more notes in index.html");
    }
    if (!groups.empty()) {
        const size_t room = kSummaryLines - fixedLines - notes.size() - (notes.empty() ? 0 : 1);
        lines.push_back("| kernel | check | configurations | worst | tolerance |");
        lines.push_back("| --- | --- | --- | --- | --- |");
        const size_t shown = groups.size() <= room ? groups.size() : room - 1;
        for (size_t i = 0; i < shown; ++i) {
            const Group& g = groups[i];
            std::string apis;
            for (const auto& a : g.apis) apis += (apis.empty() ? "" : "+") + a;
            std::string images;
            for (const auto& i : g.images) images += (images.empty() ? " (" : ", ") + i;
            if (!images.empty()) images += ")";
            // The worst configuration's limit, and the range where the rows it
            // groups were held to different ones (images of several sizes).
            const std::string limits = g.leastLimit < g.mostLimit
                                           ? " (" + num(g.leastLimit) + " to " + num(g.mostLimit) + " across them)"
                                           : "";
            lines.push_back("| `" + g.kernel + "` | " + cell(g.check + images) + " | " + std::to_string(g.configs.size()) +
                            (apis.empty() ? "" : " (" + apis + ")") + " | " + cell(g.worstResult) + " at `" + g.worstId +
                            "` | " + cell(g.worstTolerance + limits) + " |");
        }
        if (shown < groups.size())
            lines.push_back("| … | " + std::to_string(groups.size() - shown) + " more groups | | in the full report | |");
        lines.push_back("");
    }
    lines.insert(lines.end(), notes.begin(), notes.end());
    if (!notes.empty()) lines.push_back("");
    // An image judged against its class's approved reference is accepted by
    // approving the new digest; a baseline file would not replace it.
    bool byFile = false, byApproval = false;
    for (const auto& r : run.results)
        for (const auto& i : r.images)
            if (!i.passed() || i.changed()) (i.baseline.rfind("store:", 0) == 0 ? byApproval : byFile) = true;
    std::string accept = "`cavity baselines update " + acceptArgs(run) + "`";
    if (byApproval)
        accept = std::string(byFile ? accept + " (images judged against the stored baselines) and " : "") +
                 "`cavity baselines approve " + acceptArgs(run) + " --why ...` (images judged against a device class's "
                 "approved references)";
    // Configurations that rendered no image (a kernel that does not compile)
    // have nothing to accept: the fix is in the source.
    std::string after = ". Accept intended changes with " + accept + ".";
    if (!byFile && !byApproval) after = ".";
    lines.push_back("[Full report](" + reportUrl + "): every configuration with its images and heat-maps" + after);
    std::ostringstream m;
    for (const auto& l : lines) m << l << "\n";
    return m.str();
}

}  // namespace cavity::report
