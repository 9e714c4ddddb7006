// `cavity history` on SQLite files, as a user runs it: ingest (the same file
// twice is one run; every bad input one line, exit 2, nothing written),
// migrations and a database from a newer cavity, show, alerts (a planted
// step found at its commit) and the chart page. The PostgreSQL side:
// tests/test_history_postgres.py, against a real server.
#include "run_binary.h"
#include "history/database.h"
#include "history/ingest.h"
#include "history/schema.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using ::cavity::test::Outcome;
namespace history = ::cavity::history;

const std::string kId = "corner/alchemy/n16/b4/full/160x90/gl/compute";
const std::string kOther = "corner/alchemy/n16/b4/full/160x90/vk/compute";

Outcome cavity(const std::string& args) { return ::cavity::test::runBinary(CAVITY_EXE, args); }

std::string commitOf(int i) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%08x%032x", 0xabc00000u + unsigned(i), unsigned(i * 2654435761u));
    return buf;
}

// cavity_bench JSON of commit i: 5 repetitions of two configurations, the
// AO pass of kId a tenth slower from commit `stepAt` on, with deterministic noise far smaller.
json benchDoc(int i, int stepAt, int revertAt = 1 << 30) {
    json benchmarks = json::array();
    for (const auto& id : {kId, kOther})
        for (int r = 0; r < 5; ++r) {
            const double wobble = 1 + 0.005 * std::sin(double(i * 7 + r * 3 + (id == kId ? 0 : 11)));
            const double ao = 0.2 * wobble * (id == kId && i >= stepAt && i < revertAt ? 1.10 : 1.0), blur = 0.3 * wobble;
            benchmarks.push_back({{"name", id + "/iterations:20/manual_time"}, {"run_name", id + "/iterations:20/manual_time"},
                                  {"run_type", "iteration"}, {"repetitions", 5}, {"repetition_index", r},
                                  {"real_time", ao + blur}, {"time_unit", "ms"}, {"pass_ao_ms", ao}, {"pass_blur_ms", blur},
                                  {"sm_mhz_median", 1980.0}, {"mem_mhz_median", 3201.0}, {"label", "clock=gpu-timestamp"}});
        }
    char date[40];
    std::snprintf(date, sizeof date, "2026-11-%02dT12:00:00+00:00", 1 + i);
    return {{"context", {{"date", date}, {"cavity_device", "gl: NVIDIA H200/PCIe/SSE2; vk: NVIDIA H200"},
                         {"cavity_driver", "gl: 580; vk: 580"}, {"cavity_api_versions", "gl: 4.5; vk: 1.4"},
                         {"cavity_software_renderer", "false"}}},
            {"benchmarks", benchmarks}};
}

class History : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("cavity-history-" + std::to_string(::getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        db_ = (dir_ / "h.sqlite").string();
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) {
        const std::string path = (dir_ / name).string();
        std::ofstream(path) << text;
        return path;
    }
    std::string bench(int i, int stepAt = 8, int revertAt = 1 << 30) {
        return write("bench_" + std::to_string(i) + ".json", benchDoc(i, stepAt, revertAt).dump());
    }
    // Commits 0..n-1, one file each.
    void history(int n, int stepAt = 8) {
        for (int i = 0; i < n; ++i) {
            const Outcome o = cavity("history ingest --db " + db_ + " --commit " + commitOf(i) + " " + bench(i, stepAt));
            ASSERT_EQ(o.code, 0) << o.output;
        }
    }
    long long count(const std::string& table) {
        auto db = history::openSqlite(db_, false);
        EXPECT_TRUE(db.ok());
        if (!db) return -1;
        auto rows = (*db)->query("SELECT count(*) FROM " + table);
        return rows.ok() ? std::stoll(*(*rows)[0][0]) : -1;
    }
    // Exit 2, one line naming `needle`, and the database as it was.
    void refused(const std::string& args, const std::string& needle, int code = 2) {
        const bool existed = fs::exists(db_);
        const long long before = existed ? count("samples") : 0;
        const Outcome o = cavity(args);
        EXPECT_EQ(o.code, code) << args << "\n" << o.output;
        EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << args << "\n" << o.output;
        EXPECT_NE(o.output.find(needle), std::string::npos) << args << "\n" << o.output;
        EXPECT_EQ(fs::exists(db_), existed) << args;
        if (existed) {
            EXPECT_EQ(count("samples"), before) << args;
        }
    }

    fs::path dir_;
    std::string db_;
};

TEST_F(History, SameFileTwiceIsOneRun) {
    const std::string file = bench(0);
    const std::string args = "history ingest --db " + db_ + " --commit " + commitOf(0) + " " + file;
    const Outcome first = cavity(args);
    ASSERT_EQ(first.code, 0) << first.output;
    EXPECT_NE(first.output.find("6 series, 30 samples"), std::string::npos) << first.output;
    const Outcome again = cavity(args);
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_NE(again.output.find("already stored"), std::string::npos) << again.output;
    EXPECT_EQ(count("runs"), 1);
    EXPECT_EQ(count("samples"), 30);   // pipeline, ao and blur of two configurations, 5 repetitions each
    // The same content for another commit is another run.
    ASSERT_EQ(cavity("history ingest --db " + db_ + " --commit " + commitOf(1) + " " + file).code, 0);
    EXPECT_EQ(count("runs"), 2);
    EXPECT_EQ(count("configurations"), 2);
}

TEST_F(History, StoresClocksDevicesAndMetadata) {
    ASSERT_EQ(cavity("history ingest --db " + db_ + " --commit ABCDEF12 --parent 1234abcd --branch main --build-type Release "
                     "--date 2026-11-30T14:00:00+02:00 " + bench(0)).code, 0);
    auto db = history::openSqlite(db_, false);
    ASSERT_TRUE(db.ok());
    auto run = (*db)->query("SELECT commit_sha, parent_sha, branch, run_date, build_type, format FROM runs");
    ASSERT_TRUE(run.ok());
    EXPECT_EQ(*(*run)[0][0], "abcdef12");
    EXPECT_EQ(*(*run)[0][1], "1234abcd");
    EXPECT_EQ(*(*run)[0][2], "main");
    EXPECT_EQ(*(*run)[0][3], "2026-11-30T12:00:00Z");
    EXPECT_EQ(*(*run)[0][4], "Release");
    EXPECT_EQ(*(*run)[0][5], "google-benchmark");
    auto pass = (*db)->query("SELECT p.device, p.api, p.clock, s.sm_mhz, s.mem_mhz FROM passes p JOIN samples s ON "
                             "s.pass_id = p.id JOIN configurations c ON c.id = p.configuration_id WHERE c.config_id = ? "
                             "AND p.pass = 'ao'", {kOther});
    ASSERT_TRUE(pass.ok());
    ASSERT_EQ(pass->size(), 5u);
    EXPECT_EQ(*(*pass)[0][0], "NVIDIA H200");
    EXPECT_EQ(*(*pass)[0][1], "vk");
    EXPECT_EQ(*(*pass)[0][2], "gpu-timestamp");
    EXPECT_EQ(std::stod(*(*pass)[0][3]), 1980.0);
    EXPECT_EQ(std::stod(*(*pass)[0][4]), 3201.0);
}

TEST_F(History, MigratesAnOlderDatabaseAndRefusesANewerOne) {
    {
        auto db = history::openSqlite(db_, true);
        ASSERT_TRUE(db.ok());
        ASSERT_TRUE(history::migrate(**db, 1).ok());
        EXPECT_EQ(*history::schemaVersion(**db), 1);
    }
    history(1);
    {
        auto db = history::openSqlite(db_, false);
        EXPECT_EQ(*history::schemaVersion(**db), history::kSchemaVersion);
        auto idx = (*db)->query("SELECT count(*) FROM sqlite_master WHERE type = 'index' AND name = 'passes_series'");
        EXPECT_EQ(*(*idx)[0][0], "1");
        ASSERT_TRUE((*db)->exec("UPDATE schema_version SET version = 99").ok());
    }
    refused("history show --db " + db_, "schema version 99 is newer than this cavity's (2)");
    refused("history ingest --db " + db_ + " --commit " + commitOf(5) + " " + bench(5), "schema version 99");
}

// A schema_version edited by hand or damaged crashed every command (a
// negative version indexed the migrations; text threw from std::stoi), or
// re-ran the first migration over the tables: now one line and exit 2.
TEST_F(History, ADamagedSchemaVersionIsRefusedWithOneLine) {
    history(1);
    const std::vector<std::pair<std::string, std::string>> damages = {
        {"UPDATE schema_version SET version = -1", "holds '-1'"},
        {"UPDATE schema_version SET version = 'abc'", "holds 'abc'"},
        {"UPDATE schema_version SET version = 99999999999", "holds '99999999999'"},
        {"UPDATE schema_version SET version = 0", "holds '0'"},
        {"UPDATE schema_version SET version = 1.5", "holds '1.5'"},
        {"DELETE FROM schema_version", "holds 0 rows"}};
    for (const auto& [sql, said] : damages) {
        {
            auto db = history::openSqlite(db_, false);
            ASSERT_TRUE(db.ok());
            ASSERT_TRUE((*db)->exec("DELETE FROM schema_version").ok());
            ASSERT_TRUE((*db)->exec("INSERT INTO schema_version (version) VALUES (2)").ok());
            ASSERT_TRUE((*db)->exec(sql).ok()) << sql;
        }
        refused("history alerts --db " + db_, said);
    }
    // Text where a number is stored aborted in std::stod.
    for (const std::string sql : {"UPDATE samples SET ms = 'abc'"}) {
        const std::string copy = (dir_ / "damaged.sqlite").string();
        fs::copy_file(db_, copy, fs::copy_options::overwrite_existing);
        {
            auto db = history::openSqlite(copy, false);
            ASSERT_TRUE(db.ok());
            ASSERT_TRUE((*db)->exec("DELETE FROM schema_version").ok());
            ASSERT_TRUE((*db)->exec("INSERT INTO schema_version (version) VALUES (2)").ok());
            ASSERT_TRUE((*db)->exec(sql).ok()) << sql;
        }
        for (const char* cmd : {"alerts", "show"}) {
            const Outcome o = cavity(std::string("history ") + cmd + " --db " + copy);
            EXPECT_EQ(o.code, 2) << sql << "\n" << o.output;
            EXPECT_NE(o.output.find("the database is damaged"), std::string::npos) << o.output;
            EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
        }
    }
}

TEST_F(History, AFailureHalfwayLeavesNothing) {
    auto file = history::readRunFile(bench(0));
    ASSERT_TRUE(file.ok()) << file.error().message;
    file->series.push_back(file->series.front());   // the same (configuration, pass, device) twice: refused at its insert
    auto db = history::openDatabase(db_, true);
    ASSERT_TRUE(db.ok());
    auto done = history::ingest(**db, *file, {commitOf(0), "", "", "", ""});
    EXPECT_FALSE(done.ok());
    db->reset();
    EXPECT_EQ(count("runs"), 0);
    EXPECT_EQ(count("passes"), 0);
    EXPECT_EQ(count("samples"), 0);
}

TEST_F(History, BadInputsAreOneLineAndWriteNothing) {
    const std::string good = bench(0), ingest = "history ingest --db " + db_ + " ";
    const std::string commit = " --commit " + commitOf(0) + " ";
    refused(ingest + good, "--commit: missing");
    refused(ingest + "--commit xyz123 " + good, "--commit xyz123: must be a commit of 4..64 hex digits");
    refused(ingest + "--commit '' " + good, "--commit");
    refused(ingest + commit + "--parent 12 " + good, "--parent 12");
    refused(ingest + commit + "--date yesterday " + good, "--date yesterday: must be an ISO 8601 date");
    refused(ingest + commit + "--date 2026-02-30 " + good, "--date 2026-02-30");
    refused(ingest + commit + "--branch \"$(printf 'a\\nb')\" " + good, "--branch a\\x0ab: must be one line of printable text");
    refused(ingest + commit, "no FILE given");
    refused(ingest + commit + (dir_ / "missing.json").string(), "missing.json: cannot be read (no such file)");
    refused(ingest + commit + dir_.string(), "is a folder");
    refused(ingest + commit + write("empty.json", ""), "empty.json: is empty");
    refused(ingest + commit + write("other.json", "{\"a\": 1}"), "other.json: not a run file");
    json nan = benchDoc(0, 8);
    nan["benchmarks"][3]["real_time"] = nullptr;
    refused(ingest + commit + good + " " + write("nan.json", nan.dump()), "nan.json");
    refused(ingest + commit + write("broken.json", "{\"benchmarks\": [") , "broken.json: does not parse");
    json numberDate = benchDoc(0, 8);
    numberDate["context"]["date"] = 1764892800;
    refused(ingest + commit + write("numdate.json", numberDate.dump()), "numdate.json: context.date 1764892800: must be");
    json clock = benchDoc(0, 8);
    clock["benchmarks"][0]["sm_mhz_median"] = "fast";
    refused(ingest + commit + write("clock.json", clock.dump()), "clock.json: " + clock["benchmarks"][0]["name"].get<std::string>() +
                                                                 ": sm_mhz_median \"fast\": must be a clock in MHz");
    numberDate["context"]["date"] = "";
    refused(ingest + commit + write("emptydate.json", numberDate.dump()), "emptydate.json: context.date \"\": must be");

    refused("history ingest --db " + dir_.string() + commit + good, "is a folder");
    refused("history ingest --db " + (dir_ / "no/such/folder/h.sqlite").string() + commit + good, "no such folder");
    refused("history ingest --db " + good + "/h.sqlite" + commit + good, "is a file, not a folder");
    refused("history ingest --db ''" + commit + good, "--db");
    EXPECT_FALSE(fs::exists(db_));
    refused("history show --db " + db_, "no such database");
    const std::string empty = write("empty.sqlite", "");
    refused("history show --db " + empty, "is empty, not a database");
    EXPECT_EQ(fs::file_size(empty), 0u) << "no schema written into it";
    // A typo in a PostgreSQL URL is bad input, not a server that cannot be reached.
    refused("history show --db postgresql://localhost:abc/db", "port abc: must be a number");
    refused("history show --db 'postgresql://u:pw@[::1/db'", "matching \"]\"");
    refused("history show --db 'postgresql://localhost/db?sslmode=sure'", "sslmode=sure: must be");
    refused("history show --db 'postgresql://localhost/db?connect_timeout=x'", "connect_timeout=x");
    history(1);
    refused("history show --db " + db_ + " --json " + dir_.string(), "--json " + dir_.string() + ": is a folder");
    refused("history show --db " + db_ + " --json " + (dir_ / "no/such/x.json").string(), "does not exist");
    refused("history show --db " + db_ + " --id '('", "--id (: not a regular expression");
    refused("history show --db " + db_ + " --pass nosuch", "matches --pass nosuch");
    refused("history show --db " + db_ + " --since deadbeef", "--since deadbeef: no run of that commit");
    refused("history alerts --db " + db_ + " --since 2030-01-01", "--since 2030-01-01T00:00:00Z: no run of the series");
    refused("history show --db " + db_ + " --until 2026-13-01", "--until 2026-13-01: neither a date");
    refused("history alerts --db " + db_ + " --alpha nan", "--alpha 'nan': must be a number in (0, 0.5]");
    refused("history alerts --db " + db_ + " --alpha 0", "--alpha '0'");
    refused("history alerts --db " + db_ + " --min-change -1", "--min-change '-1'");
    refused("history chart --db " + db_, "--out: missing");
    refused("history chart --db " + db_ + " --out " + good, "is a file");
    refused("history nosuch", "unknown subcommand 'nosuch'");
    refused("history", "needs a subcommand");
    refused("history show", "--db: missing");
    EXPECT_EQ(count("runs"), 1);
}

TEST_F(History, ShowTablesAndJson) {
    history(3);
    const std::string out = (dir_ / "show.json").string();
    const Outcome o = cavity("history show --db " + db_ + " --id '/gl/' --pass ao --json " + out);
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_NE(o.output.find(kId + "  ao  NVIDIA H200/PCIe/SSE2  (GPU timestamps, ms)"), std::string::npos) << o.output;
    std::ifstream f(out);
    const json j = json::parse(f);
    ASSERT_EQ(j["series"].size(), 1u);
    const auto& points = j["series"][0]["points"];
    ASSERT_EQ(points.size(), 3u);
    EXPECT_EQ(points[0]["commit"], commitOf(0));
    EXPECT_EQ(points[0]["n"], 5);
    EXPECT_NEAR(points[0]["median_ms"].get<double>(), 0.2, 0.002);
    EXPECT_LE(points[0]["lo_ms"].get<double>(), points[0]["median_ms"].get<double>());
    // --since and --until by commit and by date.
    const Outcome since = cavity("history show --db " + db_ + " --id '/gl/' --pass ao --since " + commitOf(1).substr(0, 10) +
                                 " --until 2026-11-02");
    ASSERT_EQ(since.code, 0) << since.output;
    EXPECT_EQ(since.output.find(commitOf(0).substr(0, 12)), std::string::npos) << since.output;
    EXPECT_NE(since.output.find(commitOf(1).substr(0, 12)), std::string::npos) << since.output;
    EXPECT_EQ(since.output.find(commitOf(2).substr(0, 12)), std::string::npos) << since.output;
    // --device is a part of the name in any case.
    const Outcome device = cavity("history show --db " + db_ + " --id '/gl/' --pass ao --device h200/pcie");
    ASSERT_EQ(device.code, 0) << device.output;
    EXPECT_NE(device.output.find("NVIDIA H200/PCIe/SSE2"), std::string::npos) << device.output;
}

TEST_F(History, AlertsFindThePlantedStep) {
    history(14, 8);
    const std::string out = (dir_ / "alerts.json").string();
    const Outcome o = cavity("history alerts --db " + db_ + " --json " + out + " --bisect");
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(out);
    const json j = json::parse(f);
    // The AO pass of kId and, through it, its pipeline: nothing else moved.
    ASSERT_EQ(j["alerts"].size(), 2u) << j.dump(2);
    const auto& a = j["alerts"][0];
    EXPECT_EQ(a["id"], kId);
    EXPECT_EQ(a["pass"], "ao");
    EXPECT_EQ(a["device"], "NVIDIA H200/PCIe/SSE2");
    EXPECT_EQ(a["commit"], commitOf(8));
    EXPECT_EQ(a["previous_commit"], commitOf(7));
    EXPECT_EQ(a["direction"], "slower");
    EXPECT_NEAR(a["change_pct"].get<double>(), 10.0, 1.0);
    EXPECT_LT(a["p_value"].get<double>(), 0.001);
    EXPECT_EQ(j["alerts"][1]["pass"], "pipeline");
    EXPECT_NE(o.output.find("scripts/bisect.sh " + commitOf(7) + " " + commitOf(8) + " --id " + kId + " --pass ao"),
              std::string::npos) << o.output;
    // After the step: none; a threshold over the change: none.
    const Outcome later = cavity("history alerts --db " + db_ + " --since " + commitOf(9));
    EXPECT_NE(later.output.find("0 change points"), std::string::npos) << later.output;
    const Outcome big = cavity("history alerts --db " + db_ + " --min-change 15");
    EXPECT_NE(big.output.find("0 change points"), std::string::npos) << big.output;
    // A CI job's gate: exit 1 on the slowdown, 0 where none is left.
    EXPECT_EQ(cavity("history alerts --db " + db_ + " --fail-on-slower").code, 1);
    EXPECT_EQ(cavity("history alerts --db " + db_ + " --since " + commitOf(9) + " --fail-on-slower").code, 0);
}

// Dates against the graph (each commit dated a day before its parent, as a
// rebase can leave them): --since and --until by commit bound by the
// commits' places in the history, not their dates.
TEST_F(History, BoundsByCommitFollowTheHistorysOrder) {
    for (int i = 0; i < 16; ++i) {
        char date[40];
        std::snprintf(date, sizeof date, "2026-11-%02dT10:00:00Z", 28 - i);
        std::string args = "history ingest --db " + db_ + " --commit " + commitOf(i) + " --date " + date;
        if (i > 0) args += " --parent " + commitOf(i - 1);
        const Outcome o = cavity(args + " " + bench(i, 8));
        ASSERT_EQ(o.code, 0) << o.output;
    }
    const std::string out = (dir_ / "show.json").string();
    const Outcome o = cavity("history show --db " + db_ + " --id '" + kId + "' --pass ao --since " + commitOf(8) +
                             " --until " + commitOf(11) + " --json " + out);
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(out);
    const json j = json::parse(f);
    const auto& points = j["series"][0]["points"];
    ASSERT_EQ(points.size(), 4u) << j.dump(1);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(points[i]["commit"], commitOf(8 + i));
    // The step is at commit 8: from commit 9 on there is none to report.
    const Outcome all = cavity("history alerts --db " + db_ + " --pass ao");
    EXPECT_NE(all.output.find("1 change points"), std::string::npos) << all.output;
    const Outcome later = cavity("history alerts --db " + db_ + " --pass ao --since " + commitOf(9));
    EXPECT_EQ(later.code, 0) << later.output;
    EXPECT_NE(later.output.find("0 change points"), std::string::npos) << later.output;
}

// Every run on one date, ingested in a shuffled order: the parents put the
// commits in order, and the step is named at its commit.
TEST_F(History, CommitsAreOrderedByTheirParents) {
    const int n = 16;
    std::vector<int> shuffled;
    for (int i = 0; i < n; ++i) shuffled.push_back((i * 7) % n);
    for (int i : shuffled) {
        std::string args = "history ingest --db " + db_ + " --commit " + commitOf(i) + " --date 2026-11-20T10:00:00Z";
        if (i > 0) args += " --parent " + commitOf(i - 1);
        const Outcome o = cavity(args + " " + bench(i, 8));
        ASSERT_EQ(o.code, 0) << o.output;
    }
    const std::string out = (dir_ / "alerts.json").string();
    ASSERT_EQ(cavity("history alerts --db " + db_ + " --pass ao --json " + out).code, 0);
    std::ifstream f(out);
    const json j = json::parse(f);
    ASSERT_EQ(j["alerts"].size(), 1u) << j.dump(2);
    EXPECT_EQ(j["alerts"][0]["commit"], commitOf(8));
    EXPECT_EQ(j["alerts"][0]["previous_commit"], commitOf(7));
}

// A branch off commit 5 whose run falls between commits 7 and 8: the order
// places it before the step, yet the step's previous commit (the bisect
// range's good end) is 7, its parent, not the other branch's tip, which is
// not its ancestor (scripts/bisect.sh refused that range).
TEST_F(History, ThePreviousCommitIsAnAncestor) {
    for (int i = 0; i < 16; ++i) {
        std::string args = "history ingest --db " + db_ + " --commit " + commitOf(i);
        if (i > 0) args += " --parent " + commitOf(i - 1);
        const Outcome o = cavity(args + " " + bench(i, 8));
        ASSERT_EQ(o.code, 0) << o.output;
    }
    const Outcome side = cavity("history ingest --db " + db_ + " --commit " + commitOf(40) + " --parent " + commitOf(5) +
                                " --date 2026-11-08T18:00:00Z " + write("side.json", benchDoc(4, 8).dump()));
    ASSERT_EQ(side.code, 0) << side.output;
    const std::string out = (dir_ / "alerts.json").string();
    ASSERT_EQ(cavity("history alerts --db " + db_ + " --pass ao --json " + out).code, 0);
    std::ifstream f(out);
    const json j = json::parse(f);
    ASSERT_EQ(j["alerts"].size(), 1u) << j.dump(2);
    EXPECT_EQ(j["alerts"][0]["commit"], commitOf(8));
    EXPECT_EQ(j["alerts"][0]["previous_commit"], commitOf(7));
    const Outcome bisect = cavity("history alerts --db " + db_ + " --pass ao --bisect");
    EXPECT_NE(bisect.output.find("scripts/bisect.sh " + commitOf(7) + " " + commitOf(8)), std::string::npos) << bisect.output;
    // One parent a commit: another one for a stored commit would reorder
    // the runs judged under it.
    refused("history ingest --db " + db_ + " --commit " + commitOf(8) + " --parent " + commitOf(3) + " " +
                write("again.json", benchDoc(9, 8).dump()),
            "is stored with parent " + commitOf(7));
}

// A 12-digit id is the commit whose full id it begins; a prefix of two is refused.
TEST_F(History, AShortIdIsTheSameCommit) {
    history(10, 20);
    const std::string shortId = commitOf(4).substr(0, 12);
    const Outcome o = cavity("history ingest --db " + db_ + " --commit " + shortId + " " +
                             write("again.json", benchDoc(4, 20).dump(1)));
    ASSERT_EQ(o.code, 0) << o.output;
    const std::string out = (dir_ / "show.json").string();
    ASSERT_EQ(cavity("history show --db " + db_ + " --id '" + kId + "' --pass ao --json " + out).code, 0);
    std::ifstream f(out);
    const json j = json::parse(f);
    const auto& points = j["series"][0]["points"];
    ASSERT_EQ(points.size(), 10u) << "the short id is not a commit of its own";
    EXPECT_EQ(points[4]["commit"], commitOf(4));
    EXPECT_EQ(points[4]["runs"], 2);
    // commitOf(i) all begin "abc000": a prefix of ten commits.
    refused("history ingest --db " + db_ + " --commit abc000 " + bench(11), "--commit abc000: begins 10 commits");
}

// A short id stored first, then its full id: the full id takes the short
// one's place, so the same file under the full id is already stored, and
// a new file of it is a second run of one commit.
TEST_F(History, AFullIdAfterItsShortIdIsTheSameCommit) {
    history(4, 20);
    const std::string full = commitOf(4);
    const std::string first = write("first.json", benchDoc(4, 20).dump(1));
    ASSERT_EQ(cavity("history ingest --db " + db_ + " --commit " + full.substr(0, 12) + " --parent " +
                     commitOf(3) + " " + first).code, 0);
    const long long samples = count("samples");
    const Outcome again = cavity("history ingest --db " + db_ + " --commit " + full + " " + first);
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_NE(again.output.find("already stored"), std::string::npos) << again.output;
    EXPECT_NE(again.output.find("its short id now reads as this full id"), std::string::npos) << again.output;
    EXPECT_EQ(count("samples"), samples);
    {
        auto db = history::openSqlite(db_, false);
        ASSERT_TRUE(db.ok());
        auto rows = (*db)->query("SELECT count(*) FROM runs WHERE commit_sha = ?", {full});
        ASSERT_TRUE(rows.ok());
        EXPECT_EQ(*(*rows)[0][0], "1") << "the short id was not replaced by the full one";
    }
    ASSERT_EQ(cavity("history ingest --db " + db_ + " --commit " + full + " " +
                     write("second.json", benchDoc(4, 20).dump(2))).code, 0);
    const std::string out = (dir_ / "show.json").string();
    ASSERT_EQ(cavity("history show --db " + db_ + " --id '" + kId + "' --pass ao --json " + out).code, 0);
    std::ifstream f(out);
    const json j = json::parse(f);
    const auto& points = j["series"][0]["points"];
    ASSERT_EQ(points.size(), 5u) << j.dump(1);
    EXPECT_EQ(points[4]["commit"], full);
    EXPECT_EQ(points[4]["runs"], 2);
}

// --fail-on-slower asks whether a series is slower now: a slowdown that was
// reverted is listed, with its revert, and does not fail the job.
TEST_F(History, ARevertedSlowdownIsFoundAndDoesNotFailTheJob) {
    for (int i = 0; i < 20; ++i) {
        const Outcome o = cavity("history ingest --db " + db_ + " --commit " + commitOf(i) + " " + bench(i, 6, 9));
        ASSERT_EQ(o.code, 0) << o.output;
    }
    const std::string out = (dir_ / "alerts.json").string();
    const Outcome o = cavity("history alerts --db " + db_ + " --pass ao --fail-on-slower --json " + out);
    EXPECT_EQ(o.code, 0) << o.output;
    std::ifstream f(out);
    const json j = json::parse(f);
    ASSERT_EQ(j["alerts"].size(), 2u) << j.dump(2);
    EXPECT_EQ(j["alerts"][0]["commit"], commitOf(6));
    EXPECT_EQ(j["alerts"][0]["direction"], "slower");
    EXPECT_EQ(j["alerts"][0]["commits_after"], 3);
    EXPECT_EQ(j["alerts"][1]["commit"], commitOf(9));
    EXPECT_EQ(j["alerts"][1]["direction"], "faster");
    EXPECT_TRUE(j["alerts"][1]["newest"].get<bool>());
    // Before the revert was measured, the same job fails.
    const std::string early = (dir_ / "early.sqlite").string();
    for (int i = 0; i < 9; ++i) {
        const Outcome in = cavity("history ingest --db " + early + " --commit " + commitOf(i) + " " + bench(i, 6, 9));
        ASSERT_EQ(in.code, 0) << in.output;
    }
    const Outcome now = cavity("history alerts --db " + early + " --pass ao --fail-on-slower");
    EXPECT_EQ(now.code, 1) << now.output;
    EXPECT_NE(now.output.find(" slower"), std::string::npos) << now.output;
}

// A software renderer's series is the host's wall clock: its alerts say so.
TEST_F(History, ACpuRenderersAlertsSayTheClockIsTheHosts) {
    for (int i = 0; i < 14; ++i) {
        json doc = benchDoc(i, 8);
        doc["context"]["cavity_software_renderer"] = "true";
        doc["context"]["cavity_device"] = "gl: llvmpipe (LLVM 15.0.6, 256 bits); vk: llvmpipe (LLVM 15.0.6, 256 bits)";
        // Which clock a CPU run trusts changes from run to run: every
        // third run here took the wall clock. It is one series.
        if (i % 3 == 0)
            for (auto& b : doc["benchmarks"]) b["label"] = "clock=wall";
        const Outcome o = cavity("history ingest --db " + db_ + " --commit " + commitOf(i) + " " +
                                 write("cpu_" + std::to_string(i) + ".json", doc.dump()));
        ASSERT_EQ(o.code, 0) << o.output;
    }
    const std::string shown = (dir_ / "show.json").string();
    ASSERT_EQ(cavity("history show --db " + db_ + " --id '" + kId + "' --pass ao --json " + shown).code, 0);
    std::ifstream s(shown);
    const json series = json::parse(s)["series"];
    ASSERT_EQ(series.size(), 1u) << series.dump(1);
    EXPECT_EQ(series[0]["points"].size(), 14u);
    const std::string out = (dir_ / "alerts.json").string();
    const Outcome o = cavity("history alerts --db " + db_ + " --pass ao --json " + out);
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_NE(o.output.find("host CPU's wall clock"), std::string::npos) << o.output;
    std::ifstream f(out);
    const json j = json::parse(f);
    ASSERT_FALSE(j["alerts"].empty());
    EXPECT_TRUE(j["alerts"][0]["host_clock"].get<bool>());
}

TEST_F(History, ChartPageIsSelfContained) {
    history(10, 6);
    const Outcome o = cavity("history chart --db " + db_ + " --pass ao --out " + (dir_ / "chart").string());
    ASSERT_EQ(o.code, 0) << o.output;
    std::ifstream f(dir_ / "chart" / "index.html");
    const std::string page((std::istreambuf_iterator<char>(f)), {});
    EXPECT_NE(page.find("Chart.js v3"), std::string::npos) << "Chart.js inlined";
    EXPECT_EQ(page.find("<script src"), std::string::npos) << "nothing fetched";
    EXPECT_NE(page.find("GPU timestamps, ms"), std::string::npos);
    EXPECT_NE(page.find(commitOf(6)), std::string::npos);
    EXPECT_NE(page.find("\"change_points\":[{"), std::string::npos) << "the step is marked";
    EXPECT_TRUE(o.output.find("index.png") != std::string::npos || o.output.find("chromium is not installed") != std::string::npos)
        << o.output;
}

}  // namespace
