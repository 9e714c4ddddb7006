#include "history/ingest.h"
#include "measure/results.h"

#include <algorithm>
#include <filesystem>
#include <map>

namespace cavity::history {

namespace {

Result<int64_t> firstInt(const std::vector<Row>& rows, const std::string& what) {
    if (rows.empty() || rows[0].empty() || !rows[0][0]) return internal("no id returned for " + what);
    return std::stoll(*rows[0][0]);
}

Param textOrNull(const std::string& s) { return s.empty() ? Param{} : Param{s}; }
Param mhz(double v) { return v > 0 ? Param{v} : Param{}; }

Result<int64_t> configurationId(Database& db, const std::string& id, std::map<std::string, int64_t>& cache) {
    if (auto it = cache.find(id); it != cache.end()) return it->second;
    CAVITY_TRY(db.exec("INSERT INTO configurations (config_id) VALUES (?) ON CONFLICT (config_id) DO NOTHING", {id}));
    CAVITY_ASSIGN(const auto rows, db.query("SELECT id FROM configurations WHERE config_id = ?", {id}));
    CAVITY_ASSIGN(const int64_t out, firstInt(rows, "configuration " + id));
    cache[id] = out;
    return out;
}

// The samples of one pass, many rows a statement: a file of thousands of
// samples is a few dozen round trips to a server, not thousands.
Status insertSamples(Database& db, int64_t passId, const std::vector<Sample>& samples) {
    constexpr size_t kRowsPerStatement = 200;
    for (size_t at = 0; at < samples.size(); at += kRowsPerStatement) {
        std::string sql = "INSERT INTO samples (pass_id, repetition, ms, sm_mhz, mem_mhz) VALUES ";
        std::vector<Param> params;
        for (size_t i = at; i < std::min(samples.size(), at + kRowsPerStatement); ++i) {
            sql += i == at ? "(?, ?, ?, ?, ?)" : ", (?, ?, ?, ?, ?)";
            const Sample& s = samples[i];
            params.insert(params.end(), {passId, int64_t(s.repetition), s.ms, mhz(s.smMhz), mhz(s.memMhz)});
        }
        CAVITY_TRY(db.exec(sql, params));
    }
    return {};
}

// The run's id, or 0 when this content is already stored for this commit
// (ON CONFLICT: two jobs ingesting the same file at once store it once).
Result<int64_t> insertRun(Database& db, const RunFile& file, const RunInfo& info) {
    std::string date = info.date.empty() ? normalizeDate(file.date) : info.date;
    if (date.empty()) date = measure::utcTimestamp();
    CAVITY_ASSIGN(const auto rows,
                  db.query("INSERT INTO runs (file_digest, commit_sha, parent_sha, branch, run_date, device, driver, api, "
                           "build_type, cavity_version, format, file_name, ingested_utc, ingested_by) "
                           "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) "
                           "ON CONFLICT (file_digest, commit_sha) DO NOTHING RETURNING id",
                           {file.digest, info.commit, textOrNull(info.parent), textOrNull(info.branch), date,
                            textOrNull(file.device), textOrNull(file.driver), textOrNull(file.api),
                            textOrNull(info.buildType), textOrNull(file.cavityVersion), file.format,
                            std::filesystem::path(file.path).filename().string(), measure::utcTimestamp(),
                            measure::gitCommit()}));
    if (rows.empty()) return int64_t(0);
    return firstInt(rows, "run");
}

// A short id (under 40 digits) that begins exactly one longer commit the
// database holds is that commit: the same commit is never stored twice under
// two names. A prefix of several is refused. A full id whose short form was
// stored first takes that short form's place, in the runs and as a parent,
// so that the file stored under both names is stored once.
Result<std::string> storedForm(Database& db, const std::string& flag, const std::string& sha, bool& renamed) {
    if (sha.empty()) return sha;
    if (sha.size() >= 40) {
        CAVITY_ASSIGN(const auto shorter, db.query("SELECT DISTINCT commit_sha FROM runs WHERE length(commit_sha) < ? "
                                                   "AND substr(?, 1, length(commit_sha)) = commit_sha",
                                                   {int64_t(sha.size()), sha}));
        renamed |= !shorter.empty();
        for (const auto& r : shorter) {
            CAVITY_TRY(db.exec("UPDATE runs SET commit_sha = ? WHERE commit_sha = ?", {sha, *r[0]}));
            CAVITY_TRY(db.exec("UPDATE runs SET parent_sha = ? WHERE parent_sha = ?", {sha, *r[0]}));
        }
        return sha;
    }
    CAVITY_ASSIGN(const auto rows, db.query("SELECT DISTINCT commit_sha FROM runs WHERE commit_sha LIKE ? AND length(commit_sha) > ?",
                                            {sha + "%", int64_t(sha.size())}));
    if (rows.size() > 1)
        return badInput(flag + " " + sha + ": begins " + std::to_string(rows.size()) + " commits in " + db.where() +
                        " (give more digits, or the full id)");
    return rows.empty() ? sha : *rows[0][0];
}

// The history is ordered by its parents (--parent): a commit that is its
// own parent, or a parent that descends from the commit by the parents
// already stored, would make that order a cycle.
Status checkParent(Database& db, const RunInfo& info) {
    if (info.parent.empty()) return {};
    if (info.parent == info.commit) return badInput("--parent " + info.parent + ": is --commit itself (a commit is not its own parent)");
    // Every ancestor of the parent in one recursive query (UNION stops at a
    // commit seen before), not a query per commit: a long history over a
    // PostgreSQL server would take a round trip each.
    CAVITY_ASSIGN(const auto rows,
                  db.query("WITH RECURSIVE ancestors(sha) AS (SELECT CAST(? AS TEXT) UNION "
                           "SELECT r.parent_sha FROM runs r JOIN ancestors a ON r.commit_sha = a.sha "
                           "WHERE r.parent_sha IS NOT NULL) SELECT sha FROM ancestors WHERE sha = ?",
                           {info.parent, info.commit}));
    if (!rows.empty())
        return badInput("--parent " + info.parent + ": descends from --commit " + info.commit + " by the parents " +
                        db.where() + " holds (a commit cannot come after its own child)");
    return {};
}

}  // namespace

bool isCommit(const std::string& s) {
    return s.size() >= 4 && s.size() <= 64 &&
           s.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
}

// A commit has one parent here (a merge is stored with its first): another
// --parent for a commit stored with one would reorder the history under
// runs already judged, so it is refused, naming the one stored.
Status oneParent(Database& db, const RunInfo& info) {
    if (info.parent.empty()) return {};
    CAVITY_ASSIGN(const auto rows, db.query("SELECT DISTINCT parent_sha FROM runs WHERE commit_sha = ? AND parent_sha IS NOT NULL",
                                            {info.commit}));
    for (const auto& r : rows) {
        const std::string& stored = *r[0];
        const size_t n = std::min(stored.size(), info.parent.size());
        if (stored.compare(0, n, info.parent, 0, n) != 0)
            return badInput("--parent " + info.parent + ": commit " + info.commit + " is stored with parent " + stored +
                            " (one parent a commit; for a merge, its first parent)");
    }
    return {};
}

Result<Ingested> ingest(Database& db, const RunFile& file, const RunInfo& info) {
    Ingested out;
    Transaction t(db);
    CAVITY_TRY(t.begin());
    RunInfo resolved = info;
    bool renamed = false;
    CAVITY_ASSIGN(resolved.commit, storedForm(db, "--commit", info.commit, renamed));
    CAVITY_ASSIGN(resolved.parent, storedForm(db, "--parent", info.parent, renamed));
    CAVITY_TRY(checkParent(db, resolved));
    CAVITY_TRY(oneParent(db, resolved));
    out.commit = resolved.commit;
    CAVITY_ASSIGN(out.runId, insertRun(db, file, resolved));
    if (out.runId == 0) {
        CAVITY_ASSIGN(const auto seen, db.query("SELECT id FROM runs WHERE file_digest = ? AND commit_sha = ?",
                                                {file.digest, resolved.commit}));
        out.alreadyThere = true;
        CAVITY_ASSIGN(out.runId, firstInt(seen, "run"));
        // The file is there; a short id it was stored under now reads as
        // the full one given. Otherwise the transaction rolls back: it
        // wrote nothing.
        out.renamed = renamed;
        if (renamed) CAVITY_TRY(t.commit());
        return out;
    }
    std::map<std::string, int64_t> configs;
    for (const auto& s : file.series) {
        CAVITY_ASSIGN(const int64_t config, configurationId(db, s.configId, configs));
        CAVITY_ASSIGN(const auto rows,
                      db.query("INSERT INTO passes (run_id, configuration_id, pass, device, api, clock, timing_mode, "
                               "software_renderer) VALUES (?, ?, ?, ?, ?, ?, ?, ?) RETURNING id",
                               {out.runId, config, s.pass, s.device, textOrNull(s.api), s.clock,
                                textOrNull(s.timingMode), int64_t(s.softwareRenderer ? 1 : 0)}));
        CAVITY_ASSIGN(const int64_t passId, firstInt(rows, "pass"));
        CAVITY_TRY(insertSamples(db, passId, s.samples));
        ++out.passes;
        out.samples += s.samples.size();
    }
    CAVITY_TRY(t.commit());
    return out;
}

}  // namespace cavity::history
