// `cavity history alerts`: the change points of every series that matches,
// as a table, as JSON for a bot, and as the bisect command for each slowdown.
#include "history_command.h"
#include "core/json_file.h"
#include "core/text_table.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <memory>
#include <map>
#include <functional>
#include <cstdio>
#include <iostream>

namespace cavity::cli {

using nlohmann::json;

namespace {

const CommandSpec& alertsSpec() {
    static const CommandSpec spec = [] {
        CommandSpec s;
        s.program = "cavity history alerts";
        s.description =
            "Lists the change points of every (configuration, pass, device) series: E-divisive means over each "
            "commit's median, each step kept when the t test between the segments either side (the series' own noise, "
            "p adjusted for the splits tried) gives p < --alpha and the change reaches --min-change. Each with the first "
            "commit after the step, the last before it, the commits either side and how sure it is; one with fewer than "
            "3 commits after it is provisional and held to alpha / 10.";
        s.flags = {historyDbFlag()};
        for (auto& f : historyFilterFlags(false)) s.flags.push_back(f);
        for (auto& f : historyDetectorFlags()) s.flags.push_back(f);
        s.flags.push_back({"--json", "FILE", "also write the alerts as JSON (cavity.history.alerts/1)"});
        s.flags.push_back({"--bisect", "", "print the scripts/bisect.sh command of each slowdown's commit range"});
        s.flags.push_back({"--fail-on-slower", "",
                           "exit 1 when a series' newest change point is a slowdown: slower now (a CI job's gate)"});
        s.footer = "\n--since keeps the change points from that date or commit on; the series before it are still "
                   "read to find them.\nExit codes: 0 listed (alerts or none), 1 a slowdown with --fail-on-slower, 2 bad input (a flag, no such database, a "
                   "filter that matches nothing, a database from a newer cavity), 5 the database server cannot be "
                   "reached or refuses the connection.";
        s.examples = {"cavity history alerts --db history.sqlite --since 4415bc7 --json alerts.json",
                      "cavity history alerts --db history.sqlite --pass ao --min-change 5 --bisect"};
        return s;
    }();
    return spec;
}

std::string pText(double p) {
    char buf[32];
    std::snprintf(buf, sizeof buf, p < 1e-4 ? "%.1e" : "%.4f", p);
    return buf;
}

// How sure: the adjusted p as odds a reader can weigh, and why an alert
// may still move (its last commits).
std::string sureText(const history::Alert& a) {
    std::string out = a.pValue < 1e-6 ? "certain" : a.pValue < 1e-4 ? "very likely" : "likely";
    if (a.provisional)
        out += ", provisional: " + std::to_string(a.commitsAfter) + " commit" + (a.commitsAfter == 1 ? "" : "s") + " after it";
    return out;
}

json alertJson(const history::Alert& a) {
    return {{"id", a.configId}, {"pass", a.pass}, {"device", a.device}, {"clock", a.clock}, {"commit", a.commit},
            {"previous_commit", a.previousCommit}, {"date", a.date}, {"change_pct", a.changePct}, {"p_value", a.pValue},
            {"direction", a.slower() ? "slower" : "faster"}, {"before_ms", a.before}, {"after_ms", a.after},
            {"commits_before", a.commitsBefore}, {"commits_after", a.commitsAfter}, {"provisional", a.provisional},
            {"newest", a.newest}, {"host_clock", a.hostClock}, {"sure", sureText(a)}};
}

// scripts/bisect.sh's --pass mode judges with `cavity compare` on the
// results.json that each commit's `cavity run` writes; that of a commit older
// than results.json's "pipeline" series has only "frame", which every commit has.
std::string bisectLine(const history::Alert& a) {
    const std::string pass = a.pass == "pipeline" ? "frame" : a.pass;
    std::string line = "scripts/bisect.sh " + a.previousCommit + " " + a.commit + " --id " + a.configId + " --pass " + pass;
    if (a.pass == "pipeline") line += "   # cavity_bench's pipeline: bisected on the whole frame";
    return line;
}

// Whether a point or an alert is at or after --since: a date by its
// commit's first run, a commit by its place in the history's order (a
// commit after its parent may carry an older date).
using AtOrAfter = std::function<bool(const std::string& commit, const std::string& date)>;
Result<AtOrAfter> sinceTest(HistoryQuery& q) {
    if (q.since.commit.empty()) {
        const std::string date = q.since.date;
        return AtOrAfter([date](const std::string&, const std::string& d) { return date.empty() || d >= date; });
    }
    CAVITY_ASSIGN(const auto order, history::commitOrder(*q.db));
    auto rank = std::make_shared<std::map<std::string, size_t>>();
    for (size_t i = 0; i < order.size(); ++i) (*rank)[order[i]] = i;
    // The stored id may be the short form of the full id the order names.
    const std::string& since = q.since.commit;
    const auto at = std::find_if(order.begin(), order.end(), [&](const std::string& c) { return c.rfind(since, 0) == 0; });
    const size_t first = size_t(at - order.begin());
    return AtOrAfter([rank, first](const std::string& commit, const std::string&) {
        const auto it = rank->find(commit);
        return it != rank->end() && it->second >= first;
    });
}

}  // namespace

int historyAlerts(const std::vector<std::string>& argv) {
    const auto& spec = alertsSpec();
    auto parsed = parseFlags(spec, argv);
    if (!parsed) return fail(spec.program, parsed.error());
    if (parsed->help) {
        std::cout << parsed->helpText;
        return 0;
    }
    auto q = historyQuery(*parsed);
    if (!q) return fail(spec.program, q.error());
    auto series = matchingSeries(*q);
    if (!series) return fail(spec.program, series.error());
    auto atOrAfter = sinceTest(*q);
    if (!atOrAfter) return fail(spec.program, atOrAfter.error());
    // --since past every run judges nothing: "0 change points" would read
    // as a clean history.
    if (std::none_of(series->begin(), series->end(), [&](const history::Series& s) {
            return std::any_of(s.points.begin(), s.points.end(), [&](const history::Point& p) { return (*atOrAfter)(p.commit, p.date); });
        }))
        return fail(spec.program, badInput("--since " + q->since.date + q->since.commit + ": no run of the series matched in " +
                                           q->db->where() + " is from then on (nothing to judge)"));
    auto parents = history::commitParents(*q->db);
    if (!parents) return fail(spec.program, parents.error());
    auto alerts = history::findAlerts(*series, q->detector, &*parents);
    std::erase_if(alerts, [&](const history::Alert& a) { return !(*atOrAfter)(a.commit, a.date); });
    TextTable t({{"configuration"}, {"pass"}, {"device"}, {"commit"}, {"previous"}, {"change", TextTable::Align::Right},
                 {"p", TextTable::Align::Right}, {"before ms", TextTable::Align::Right}, {"after ms", TextTable::Align::Right},
                 {"commits", TextTable::Align::Right}, {"sure"}});
    json out = json::array();
    for (const auto& a : alerts) {
        char change[32];
        std::snprintf(change, sizeof change, "%+.1f%%", a.changePct);
        t.add({a.configId, a.pass, a.device, a.commit.substr(0, 12), a.previousCommit.substr(0, 12), change, pText(a.pValue),
               TextTable::number(a.before, 4), TextTable::number(a.after, 4),
               std::to_string(a.commitsBefore) + "|" + std::to_string(a.commitsAfter), sureText(a)},
              a.slower() ? " slower" : " faster");
        out.push_back(alertJson(a));
    }
    if (!alerts.empty()) std::cout << t.str();
    if (const auto host = std::count_if(alerts.begin(), alerts.end(), [](const auto& a) { return a.hostClock; }); host > 0)
        std::cout << host << " of these change points are a software renderer's: its times are the host CPU's wall "
                     "clock, which every other process on the machine shares; read them as leads, not as a GPU's "
                     "regressions\n";
    std::cout << alerts.size() << " change points in " << series->size() << " series (alpha " << q->detector.alpha
              << ", min change " << q->detector.minChange * 100 << "%)\n";
    if (parsed->has("--bisect"))
        for (const auto& a : alerts)
            if (a.slower()) std::cout << bisectLine(a) << "\n";
    for (const auto& [flag, path] : parsed->values) {
        if (flag != "--json") continue;
        const json doc = {{"schema", "cavity.history.alerts/1"}, {"alpha", q->detector.alpha},
                          {"min_change_pct", q->detector.minChange * 100}, {"alerts", out}};
        const Status w = writeFileAtomically(path, core::jsonText(doc, 2) + "\n");
        if (!w) return fail(spec.program, w.error());
    }
    return parsed->has("--fail-on-slower") && history::slowerNow(alerts) ? 1 : 0;
}

}  // namespace cavity::cli
