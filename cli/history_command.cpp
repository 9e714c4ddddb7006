// `cavity history`: every benchmark run kept in a results database (SQLite
// or PostgreSQL), read back as series over commits, change points found by
// E-divisive, and charts (docs/history.md).
#include "history_command.h"
#include "history/ingest.h"
#include "history/run_file.h"
#include "printable.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>

namespace cavity::cli {

namespace {

constexpr const char* kUsage =
    "usage: cavity history <subcommand> [flags]\n"
    "subcommands:\n"
    "  ingest   store run files (cavity_bench JSON, results.json, gate.json) for a commit\n"
    "  show     a table per (configuration, pass, device) over commits: median and its 95% interval\n"
    "  chart    one self-contained HTML page of charts over commits, change points marked (and a PNG)\n"
    "  alerts   the change points (E-divisive, Student's t test): commit, change, p\n"
    "`cavity history SUBCOMMAND --help` lists its flags. The database: --db FILE (SQLite) or\n"
    "--db postgresql://... (docs/history.md).\n"
    "\n"
    "Examples:\n"
    "  cavity history ingest --db history.sqlite --commit $(git rev-parse HEAD) bench.json\n"
    "  cavity history alerts --db history.sqlite --json alerts.json\n"
    "  cavity history chart --db history.sqlite --id '/alchemy/' --out history/\n";

const CommandSpec& ingestSpec() {
    static const CommandSpec spec{
        "cavity history ingest",
        "Stores run files in the results database for one commit: every repetition's time of every pass, the clock, "
        "the device and what made the file. All of a file goes in one transaction; the same file for the same commit "
        "is stored once.",
        {
            {"--db", "FILE|URL", "the database: an SQLite file (created when missing) or postgresql://USER@HOST/DB"},
            {"--commit", "SHA", "the commit the files measured (4..64 hex digits)"},
            {"--parent", "SHA", "its parent commit"},
            {"--date", "ISO8601", "the run's date (2026-11-30 or 2026-11-30T12:00:00Z; default: the file's, else now)"},
            {"--branch", "NAME", "the branch it was measured on"},
            {"--build-type", "TYPE", "the build type of the measured binary (Release, RelWithDebInfo, ...)"},
        },
        "FILE...",
        "cavity_bench JSON (--benchmark_out), results.json of cavity run, or gate.json; .gz files are read as they are",
        "\nExit codes: 0 stored (or already there), 2 bad input (nothing written), 5 the database server cannot be "
        "reached or refuses the connection.",
        {
            "cavity history ingest --db history.sqlite --commit 4415bc7 bench.json",
            "cavity history ingest --db postgresql://ci@db.example/cavity --commit $SHA --branch main out/results.json",
        },
    };
    return spec;
}

Result<std::string> commitValue(const std::string& flag, const std::string& v) {
    if (!history::isCommit(v)) return badInput(flag + " " + v + ": must be a commit of 4..64 hex digits");
    std::string out = v;
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

Result<std::pair<std::string, history::RunInfo>> ingestFlags(const ParsedFlags& parsed) {
    std::string db;
    history::RunInfo info;
    for (const auto& [flag, v] : parsed.values) {
        if (flag == "--db") db = v;
        else if (flag == "--commit") {
            CAVITY_ASSIGN(info.commit, commitValue(flag, v));
        } else if (flag == "--parent") {
            CAVITY_ASSIGN(info.parent, commitValue(flag, v));
        } else if (flag == "--date") {
            info.date = history::normalizeDate(v);
            if (info.date.empty())
                return badInput("--date " + v + ": must be an ISO 8601 date (2026-11-30, 2026-11-30T12:00:00Z, "
                                "2026-11-30T12:00:00+02:00)");
        } else if (flag == "--branch" || flag == "--build-type") {
            // Printed in every table and chart label: one line of text.
            if (hasControlChar(v) || v.size() > 200)
                return badInput(flag + " " + printable(v.substr(0, 60)) + ": must be one line of printable text, at most 200 "
                                "characters");
            (flag == "--branch" ? info.branch : info.buildType) = v;
        }
    }
    if (db.empty()) return badInput("--db: missing (an SQLite file or a postgresql:// URL)");
    if (info.commit.empty()) return badInput("--commit: missing (the commit the files measured, e.g. $(git rev-parse HEAD))");
    if (parsed.positionals.empty()) return badInput("no FILE given (cavity_bench JSON, results.json or gate.json)");
    return std::make_pair(db, info);
}

}  // namespace

int historyIngest(const std::vector<std::string>& argv) {
    const std::string program = "cavity history ingest";
    auto parsed = parseFlags(ingestSpec(), argv);
    if (!parsed) return fail(program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    auto flags = ingestFlags(*parsed);
    if (!flags) return fail(program, flags.error());
    const auto& [location, info] = *flags;
    // Every file read and checked before the database is touched: a bad
    // file among good ones writes nothing.
    std::vector<history::RunFile> files;
    for (const auto& path : parsed->positionals) {
        auto f = history::readRunFile(path);
        if (!f) return fail(program, f.error());
        files.push_back(std::move(*f));
    }
    auto db = history::openDatabase(location, true);
    if (!db) return fail(program, db.error());
    for (const auto& f : files) {
        auto done = history::ingest(**db, f, info);
        if (!done) return fail(program, done.error());
        if (done->alreadyThere)
            std::cout << f.path << ": already stored for commit " << done->commit << " (run " << done->runId << "); "
                      << (done->renamed ? "its short id now reads as this full id" : "nothing written") << "\n";
        else
            std::cout << f.path << ": run " << done->runId << " for commit " << done->commit << " (" << f.format << "): "
                      << done->passes << " series, " << done->samples << " samples\n";
    }
    return 0;
}

int historyCommand(const std::vector<std::string>& argv) {
    if (!argv.empty() && (argv[0] == "--help" || argv[0] == "-h")) {
        std::cout << kUsage;
        return 0;
    }
    const std::vector<std::string> rest(argv.empty() ? argv.end() : argv.begin() + 1, argv.end());
    const std::string sub = argv.empty() ? "" : argv[0];
    // The readers parse the numbers the database holds as Cavity wrote them;
    // a database edited by hand or damaged can hold text there, which
    // std::stod and std::stoll throw on: one line, not an abort. The
    // readers write nothing, and ingest's transaction rolls back.
    try {
        if (sub == "ingest") return historyIngest(rest);
        if (sub == "show") return historyShow(rest);
        if (sub == "chart") return historyChart(rest);
        if (sub == "alerts") return historyAlerts(rest);
    } catch (const std::logic_error& e) {
        const auto db = std::find(rest.begin(), rest.end(), "--db");
        std::cerr << "cavity history " << sub << ": --db " << (db != rest.end() && db + 1 != rest.end() ? *(db + 1) : "")
                  << ": holds a value that is not what Cavity stores there (" << e.what()
                  << " failed on it): the database is damaged or not a Cavity results database\n";
        return 2;
    }
    const std::string near = nearest(sub, {"ingest", "show", "chart", "alerts"});
    std::cerr << "cavity history: " << (sub.empty() ? "needs a subcommand" : "unknown subcommand '" + sub + "'")
              << (near.empty() || sub.empty() ? "" : " (did you mean " + near + "?)")
              << " (ingest, show, chart, alerts); see cavity history --help\n";
    return 2;
}

}  // namespace cavity::cli
