#include "report/gate_report.h"

#include "measure/results.h"

#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace cavity::report {

namespace fs = std::filesystem;

namespace {

Status writeText(const fs::path& path, const std::string& text) {
    const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream f(tmp);
        if (!f) return badInput(path.string() + ": cannot write");
        f << text;
        if (!f) return internal("write " + path.string() + " failed");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) return internal("rename " + tmp.string() + ": " + ec.message());
    return {};
}

}  // namespace

Status writeReports(const GateRun& run, const std::string& outDir) {
    const fs::path out(outDir);
    std::error_code ec;
    fs::create_directories(out, ec);
    CAVITY_TRY(writeJson((out / "gate.json").string(), toJson(run)));
    CAVITY_TRY(writeText(out / "junit.xml", junitXml(run)));
    CAVITY_TRY(writeText(out / "summary.md", summaryMarkdown(run)));
    CAVITY_ASSIGN(const std::string html, reportHtml(run, (out / "charts").string()));
    CAVITY_TRY(writeText(out / "index.html", html));
    return {};
}

}  // namespace cavity::report
