#include "report/gate_report.h"

#include "core/json_file.h"
#include "measure/results.h"

#include <filesystem>
#include <map>

namespace cavity::report {

namespace fs = std::filesystem;

nlohmann::json commitStatus(const GateRun& run, const std::string& reportUrl) {
    const int code = run.exitCode();
    int failed = 0, changed = 0;
    for (const auto& r : run.results) {
        failed += r.fatal();
        changed += !r.fatal() && r.changed();
    }
    const std::string total = std::to_string(run.results.size());
    std::string description = code == 0 && run.results.empty() ? std::string("nothing judged: no configuration in this selection")
                              : code == 0 ? "all " + total + " configurations passed" +
                                              (changed ? ", " + std::to_string(changed) + " changed within tolerance" : "")
                              : code == 1 && failed == 0 ? std::to_string(changed) + " of " + total + " configurations changed (--strict)"
                              : code == 1 ? std::to_string(failed) + " of " + total + " configurations failed"
                                          : "the gate could not judge every configuration (exit " + std::to_string(code) + ")";
    // A substituted kernel comes first, so that a cut description keeps it:
    // a pass with kernels/ replaced is not a pass of the tree.
    std::string replaced;
    for (const auto& r : run.replaced) replaced += (replaced.empty() ? "" : ", ") + r.name;
    description = "matrix " + run.matrix + (replaced.empty() ? "" : ", kernel source replaced (" + replaced + ")") + ": " + description;
    if (description.size() > kStatusDescriptionMax) description.resize(kStatusDescriptionMax);
    return {{"state", code == 0 ? "success" : code == 1 ? "failure" : "error"},
            {"description", description},
            {"target_url", reportUrl.empty() ? nlohmann::json(nullptr) : nlohmann::json(reportUrl)},
            {"context", "cavity/gate/" + run.matrix}};
}

// Every report is made before any is written, each is written whole under
// its own name, and gate.json (what update, approve and merge read) goes
// last: a kill between the writes leaves no new gate.json beside older
// pages, and never a new verdict that the pages beside it contradict.
Status writeReports(const GateRun& judged, const std::string& outDir, const std::string& reportUrl) {
    const fs::path out(outDir);
    // The accept commands the reports print name this folder.
    GateRun run = judged;
    run.out = outDir;
    std::error_code ec;
    fs::create_directories(out, ec);
    CAVITY_ASSIGN(const std::string html, reportHtml(run, (out / "charts").string()));
    const std::map<std::string, std::string> text = {
        {"index.html", html},
        {"summary.md", summaryMarkdown(run, reportUrl.empty() ? "index.html" : reportUrl)},
        {"junit.xml", junitXml(run)},
        {"status.json", core::jsonText(commitStatus(run, reportUrl), 2) + "\n"},
        {"gate.json", core::jsonText(toJson(run), 2) + "\n"}};
    for (const char* name : gate::kReportFiles) CAVITY_TRY(writeFileAtomically((out / name).string(), text.at(name)));
    return {};
}

}  // namespace cavity::report
