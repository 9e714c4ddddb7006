// `cavity history show`, `chart` and `alerts`: the database read back as
// series over commits, and their change points.
#include "history_command.h"
#include "history/chart.h"
#include "core/json_file.h"
#include "core/text_table.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>

namespace cavity::cli {

using nlohmann::json;

FlagSpec historyDbFlag() {
    return {"--db", "FILE|URL", "the database: an SQLite file or postgresql://USER@HOST/DB (docs/history.md)"};
}

std::vector<FlagSpec> historyFilterFlags(bool until) {
    std::vector<FlagSpec> out = {
        {"--id", "REGEX", "only configuration ids that match (searched)", "Filters"},
        {"--pass", "P", "only this pass (ao, blur, composite, frame, pipeline, ...)", "Filters"},
        {"--device", "D", "only devices whose name contains D (\"H200\", \"llvmpipe\")", "Filters"},
        {"--since", "DATE|SHA", "only runs from this date, or from this commit in the history's order, on", "Filters"},
    };
    if (until) out.push_back({"--until", "DATE|SHA", "only runs up to this date (a day: all of it), or up to this commit in the history's order", "Filters"});
    return out;
}

std::vector<FlagSpec> historyDetectorFlags() {
    return {
        {"--alpha", "A", "the adjusted p a change point must reach (default 0.001; (0, 0.5])", "Change points"},
        {"--min-change", "PCT", "the smallest change reported, in percent of the mean before (default 1; 0..1000)",
         "Change points"},
    };
}

Result<HistoryQuery> historyQuery(const ParsedFlags& parsed) {
    HistoryQuery q;
    std::string db, since, until;
    for (const auto& [flag, v] : parsed.values) {
        if (flag == "--db") db = v;
        else if (flag == "--id") {
            CAVITY_ASSIGN(q.filter.id, parseFilter(flag, v));
            q.filter.idText = v;
        } else if (flag == "--pass") q.filter.pass = v;
        else if (flag == "--device") q.filter.device = v;
        else if (flag == "--since") since = v;
        else if (flag == "--until") until = v;
        else if (flag == "--alpha") {
            CAVITY_ASSIGN(q.detector.alpha, parseNumber(flag, v, [](double a) { return a > 0 && a <= 0.5; }, "a number in (0, 0.5]"));
        } else if (flag == "--min-change") {
            CAVITY_ASSIGN(const double pct, parseNumber(flag, v, 0, 1000));
            q.detector.minChange = pct / 100;
        }
    }
    if (db.empty()) return badInput("--db: missing (an SQLite file or a postgresql:// URL)");
    // An output file that cannot be written is found before the database is
    // read or a table printed.
    for (const auto& [flag, v] : parsed.values)
        if (flag == "--json") CAVITY_TRY(checkWritableFile(flag, v));
    CAVITY_ASSIGN(q.db, history::openDatabase(db, false));
    if (!since.empty()) {
        CAVITY_ASSIGN(q.since, history::resolveBound(*q.db, "--since", since, true));
    }
    if (!until.empty()) {
        CAVITY_ASSIGN(const history::Bound b, history::resolveBound(*q.db, "--until", until, false));
        q.filter.until = b.date;
        q.filter.untilCommit = b.commit;
    }
    return q;
}

Result<std::vector<history::Series>> matchingSeries(HistoryQuery& q) {
    CAVITY_ASSIGN(auto series, history::loadSeries(*q.db, q.filter));
    if (series.empty()) {
        std::string f;
        if (!q.filter.idText.empty()) f += " --id " + q.filter.idText;
        if (!q.filter.pass.empty()) f += " --pass " + q.filter.pass;
        if (!q.filter.device.empty()) f += " --device " + q.filter.device;
        if (!q.filter.since.empty() || !q.filter.sinceCommit.empty()) f += " --since " + q.filter.since + q.filter.sinceCommit;
        if (!q.filter.until.empty() || !q.filter.untilCommit.empty()) f += " --until " + q.filter.until + q.filter.untilCommit;
        return badInput("no series in " + q.db->where() + " matches" + (f.empty() ? " (the database holds no run)" : f));
    }
    return series;
}

namespace {

std::string ms(double v) { return TextTable::number(v, v >= 10 ? 2 : v >= 1 ? 3 : 4); }

CommandSpec viewSpec(const std::string& name, const std::string& description, std::vector<FlagSpec> own, bool until,
                     bool detector, std::vector<std::string> examples) {
    CommandSpec spec;
    spec.program = "cavity history " + name;
    spec.description = description;
    spec.flags = {historyDbFlag()};
    for (auto& f : historyFilterFlags(until)) spec.flags.push_back(f);
    if (detector)
        for (auto& f : historyDetectorFlags()) spec.flags.push_back(f);
    for (auto& f : own) spec.flags.push_back(f);
    spec.footer = "\nExit codes: 0 done, 2 bad input (a flag, no such database, a filter that matches nothing, a database "
                  "from a newer cavity), 5 the database server cannot be reached or refuses the connection.";
    spec.examples = std::move(examples);
    return spec;
}

// Parses, answers --help, and opens the database: 0 and a query, or the exit code.
int prepare(const CommandSpec& spec, const std::vector<std::string>& argv, ParsedFlags& parsed, HistoryQuery& q) {
    auto p = parseFlags(spec, argv);
    if (!p) return fail(spec.program, p.error());
    parsed = std::move(*p);
    if (parsed.help) {
        std::cout << parsed.helpText;
        return -1;
    }
    auto query = historyQuery(parsed);
    if (!query) return fail(spec.program, query.error());
    q = std::move(*query);
    q.filter.since = q.since.date;
    q.filter.sinceCommit = q.since.commit;
    return 0;
}

std::string flagValue(const ParsedFlags& parsed, const std::string& flag) {
    for (const auto& [f, v] : parsed.values)
        if (f == flag) return v;
    return "";
}

}  // namespace

int historyShow(const std::vector<std::string>& argv) {
    static const CommandSpec spec = viewSpec(
        "show", "A table per (configuration, pass, device) over commits, oldest first: the commit, its date, the "
        "repetitions n, the median and its 95% interval (order statistics; min..max under 6 repetitions), min and max.",
        {{"--json", "FILE", "also write the tables as JSON (cavity.history.show/1)"}}, true, false,
        {"cavity history show --db history.sqlite --id '^corner/alchemy/' --pass ao --device H200"});
    ParsedFlags parsed;
    HistoryQuery q;
    if (int rc = prepare(spec, argv, parsed, q)) return rc < 0 ? 0 : rc;
    auto series = matchingSeries(q);
    if (!series) return fail(spec.program, series.error());
    json out = json::array();
    for (const auto& s : *series) {
        std::cout << s.configId << "  " << s.pass << "  " << s.device << "  (" << history::axisLabel(s) << ")\n";
        TextTable t({{"commit"}, {"date"}, {"n", TextTable::Align::Right}, {"median", TextTable::Align::Right},
                     {"95% interval", TextTable::Align::Right}, {"min", TextTable::Align::Right},
                     {"max", TextTable::Align::Right}});
        json points = json::array();
        for (const auto& p : s.points) {
            t.add({p.commit.substr(0, 12), p.date, std::to_string(p.ms.size()), ms(p.median), ms(p.lo) + ".." + ms(p.hi),
                   ms(p.min), ms(p.max)}, p.intervalCoversLess ? " (min..max)" : "");
            points.push_back({{"commit", p.commit}, {"date", p.date}, {"n", p.ms.size()}, {"runs", p.runs},
                              {"median_ms", p.median}, {"lo_ms", p.lo}, {"hi_ms", p.hi}, {"min_ms", p.min},
                              {"max_ms", p.max}, {"interval_below_95", p.intervalCoversLess}});
        }
        std::cout << t.str() << "\n";
        out.push_back({{"id", s.configId}, {"pass", s.pass}, {"device", s.device}, {"clock", s.clock}, {"points", points}});
    }
    if (const std::string path = flagValue(parsed, "--json"); !path.empty()) {
        const Status w = writeFileAtomically(path, core::jsonText(json{{"schema", "cavity.history.show/1"}, {"series", out}}, 2) + "\n");
        if (!w) return fail(spec.program, w.error());
    }
    return 0;
}

int historyChart(const std::vector<std::string>& argv) {
    static const CommandSpec spec = viewSpec(
        "chart", "Writes DIR/index.html: one self-contained page (Chart.js inlined; nothing fetched) with a chart per "
        "(configuration, pass, device) over commits: the median, its 95% interval as a band, change points marked, the "
        "commit on hover, zoom by wheel or drag. With chromium installed also DIR/index.png.",
        {{"--out", "DIR", "the folder for index.html and index.png (created when missing)"}}, true, true,
        {"cavity history chart --db history.sqlite --id '/alchemy/' --pass ao --out history/"});
    ParsedFlags parsed;
    HistoryQuery q;
    if (int rc = prepare(spec, argv, parsed, q)) return rc < 0 ? 0 : rc;
    const std::string dir = flagValue(parsed, "--out");
    if (dir.empty()) return fail(spec.program, badInput("--out: missing (the folder for index.html)"));
    auto series = matchingSeries(q);
    if (!series) return fail(spec.program, series.error());
    auto html = history::writeChartPage(dir, *series, {q.db->where(), q.detector});
    if (!html) return fail(spec.program, html.error());
    std::cout << *html << ": " << series->size() << " charts\n";
    std::string why;
    const std::string png = history::screenshot(*html, (std::filesystem::path(dir) / "index.png").string(), series->size(), why);
    std::cout << (png.empty() ? why : png + ": the page as headless chromium draws it") << "\n";
    return 0;
}

}  // namespace cavity::cli
