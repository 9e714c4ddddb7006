#include "history/schema.h"

#include "printable.h"

#include <algorithm>
#include <functional>

namespace cavity::history {

namespace {

// The one place the two dialects' DDL differs: an auto-numbered key.
std::string idColumn(const Database& db) {
    return db.dialect() == Dialect::SQLite ? "id INTEGER PRIMARY KEY" : "id BIGSERIAL PRIMARY KEY";
}

Status execAll(Database& db, const std::vector<std::string>& statements) {
    for (const auto& s : statements) CAVITY_TRY(db.exec(s));
    return {};
}

// 0 -> 1: the tables.
Status createTables(Database& db) {
    const std::string id = idColumn(db);
    return execAll(db, {
        "CREATE TABLE schema_version (version INTEGER NOT NULL)",
        "INSERT INTO schema_version (version) VALUES (0)",
        "CREATE TABLE runs (" + id + ", file_digest TEXT NOT NULL, commit_sha TEXT NOT NULL, parent_sha TEXT, "
        "branch TEXT, run_date TEXT NOT NULL, device TEXT, driver TEXT, api TEXT, build_type TEXT, "
        "cavity_version TEXT, format TEXT NOT NULL, file_name TEXT NOT NULL, ingested_utc TEXT NOT NULL, "
        "ingested_by TEXT NOT NULL, UNIQUE (file_digest, commit_sha))",
        "CREATE TABLE configurations (" + id + ", config_id TEXT NOT NULL UNIQUE)",
        "CREATE TABLE passes (" + id + ", run_id BIGINT NOT NULL REFERENCES runs (id) ON DELETE CASCADE, "
        "configuration_id BIGINT NOT NULL REFERENCES configurations (id), pass TEXT NOT NULL, device TEXT NOT NULL, "
        "api TEXT, clock TEXT NOT NULL, timing_mode TEXT, software_renderer INTEGER NOT NULL DEFAULT 0, "
        "UNIQUE (run_id, configuration_id, pass, device))",
        "CREATE TABLE samples (pass_id BIGINT NOT NULL REFERENCES passes (id) ON DELETE CASCADE, "
        "repetition INTEGER NOT NULL, ms DOUBLE PRECISION NOT NULL, sm_mhz DOUBLE PRECISION, mem_mhz DOUBLE PRECISION, "
        "PRIMARY KEY (pass_id, repetition))",
    });
}

// 1 -> 2: the indexes `show`, `chart` and `alerts` read through: a series by
// (configuration, pass, device), runs by commit and date.
Status addIndexes(Database& db) {
    return execAll(db, {
        "CREATE INDEX passes_series ON passes (configuration_id, pass, device)",
        "CREATE INDEX runs_commit ON runs (commit_sha)",
        "CREATE INDEX runs_date ON runs (run_date)",
    });
}

// migrations[N] takes the schema from N to N + 1.
const std::vector<std::function<Status(Database&)>>& migrations() {
    static const std::vector<std::function<Status(Database&)>> all = {createTables, addIndexes};
    static_assert(kSchemaVersion == 2, "a migration per version");
    return all;
}

Result<bool> hasVersionTable(Database& db) {
    const std::string sql = db.dialect() == Dialect::SQLite
        ? "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'schema_version'"
        : "SELECT count(*) FROM pg_catalog.pg_tables WHERE tablename = 'schema_version' AND schemaname = current_schema()";
    CAVITY_ASSIGN(const auto rows, db.query(sql));
    return !rows.empty() && rows[0][0] && *rows[0][0] != "0";
}

Error tooNew(const Database& db, int version) {
    return badInput("--db " + db.where() + ": schema version " + std::to_string(version) +
                    " is newer than this cavity's (" + std::to_string(kSchemaVersion) +
                    "); use the cavity that wrote it, or a newer one");
}

}  // namespace

Result<int> schemaVersion(Database& db) {
    CAVITY_ASSIGN(const bool exists, hasVersionTable(db));
    if (!exists) return 0;
    // A committed database holds one row of 1 or more (the first migration
    // writes the table and its version in one transaction): anything else
    // was written by hand or damaged, and no migration can be trusted on it.
    CAVITY_ASSIGN(const auto rows, db.query("SELECT version FROM schema_version"));
    const std::string text = rows.size() == 1 && rows[0][0] ? *rows[0][0] : "";
    const bool digits = !text.empty() && text.size() <= 6 &&
                        std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    if (!digits || std::stoi(text) < 1) {
        std::string held = "NULL";
        if (rows.size() != 1) {
            held = std::to_string(rows.size());
            held += " rows";
        } else if (rows[0][0]) {
            held = "'";
            held += printable(text);
            held += "'";
        }
        return badInput("--db " + db.where() + ": table schema_version holds " + held +
                        ", not one version of 1 or more: the database is damaged or not a Cavity results database");
    }
    return std::stoi(text);
}

Status migrate(Database& db, int target) {
    CAVITY_ASSIGN(int version, schemaVersion(db));
    if (version > kSchemaVersion) return tooNew(db, version);
    if (version >= target) return {};
    Transaction t(db);
    CAVITY_TRY(t.begin());
    // Two CI jobs that open a new database at once: the second waits here,
    // then reads the version the first left.
    if (db.dialect() == Dialect::PostgreSQL) CAVITY_TRY(db.exec("SELECT pg_advisory_xact_lock(7283401)"));
    CAVITY_ASSIGN(version, schemaVersion(db));
    if (version > kSchemaVersion) return tooNew(db, version);
    for (; version < target; ++version) {
        CAVITY_TRY(migrations()[size_t(version)](db));
        CAVITY_TRY(db.exec("UPDATE schema_version SET version = ?", {int64_t(version + 1)}));
    }
    return t.commit();
}

Result<std::unique_ptr<Database>> openDatabase(const std::string& location, bool create) {
    std::unique_ptr<Database> db;
    if (isPostgresUrl(location)) {
        CAVITY_ASSIGN(db, openPostgres(location));
    } else if (const auto scheme = location.find("://"); scheme != std::string::npos && scheme > 0 &&
               location.find('/') > scheme) {
        return badInput("--db " + location.substr(0, scheme + 3) + "...: unknown scheme (an SQLite file, or a "
                        "postgresql:// URL)");
    } else {
        CAVITY_ASSIGN(db, openSqlite(location, create));
    }
    CAVITY_TRY(migrate(*db));
    return db;
}

}  // namespace cavity::history
