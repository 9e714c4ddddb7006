// The SQLite side of history/database.h: one file, one connection.
#include "history/database.h"

#include <sqlite3.h>

#include <cstdio>
#include <filesystem>

namespace cavity::history {

namespace {

namespace fs = std::filesystem;

class SqliteDatabase final : public Database {
public:
    SqliteDatabase(sqlite3* db, std::string path) : db_(db), where_("sqlite:" + std::move(path)) {}
    ~SqliteDatabase() override { sqlite3_close_v2(db_); }

    Dialect dialect() const override { return Dialect::SQLite; }
    const std::string& where() const override { return where_; }
    Status begin() override { return exec("BEGIN IMMEDIATE", {}); }

    Status exec(const std::string& sql, const std::vector<Param>& params) override {
        auto rows = run(sql, params, false);
        if (!rows) return rows.error();
        return {};
    }
    Result<std::vector<Row>> query(const std::string& sql, const std::vector<Param>& params) override {
        return run(sql, params, true);
    }
    Status forEach(const std::string& sql, const std::vector<Param>& params, const RowCallback& each) override {
        auto rows = run(sql, params, false, &each);
        if (!rows) return rows.error();
        return {};
    }

private:
    // What a failed call means to the user: a file that is no database (or a
    // damaged one) is their input; a lock held past the busy timeout is the
    // database being unavailable; anything else is ours.
    Error error(int rc, const std::string& sql) const {
        const std::string what = where_ + ": " + sqlite3_errmsg(db_);
        if (rc == SQLITE_NOTADB || rc == SQLITE_CORRUPT) return badInput(what + " (not an SQLite database, or a damaged one)");
        if (rc == SQLITE_READONLY || rc == SQLITE_CANTOPEN || rc == SQLITE_PERM)
            return badInput(what + " (the file or its folder cannot be written)");
        if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) return unreachable(what + " (another process holds the database)");
        if (rc == SQLITE_FULL || rc == SQLITE_IOERR) return internal(what);
        return internal(what + " in: " + sql.substr(0, 80));
    }

    Status bind(sqlite3_stmt* st, const std::vector<Param>& params) const {
        for (size_t i = 0; i < params.size(); ++i) {
            const int at = int(i) + 1;
            int rc = SQLITE_OK;
            if (std::holds_alternative<std::monostate>(params[i])) rc = sqlite3_bind_null(st, at);
            else if (const auto* n = std::get_if<int64_t>(&params[i])) rc = sqlite3_bind_int64(st, at, *n);
            else if (const auto* d = std::get_if<double>(&params[i])) rc = sqlite3_bind_double(st, at, *d);
            else {
                const auto& s = std::get<std::string>(params[i]);
                rc = sqlite3_bind_text(st, at, s.data(), int(s.size()), SQLITE_TRANSIENT);
            }
            if (rc != SQLITE_OK) return error(rc, "bind");
        }
        return {};
    }

    static std::optional<std::string> column(sqlite3_stmt* st, int c) {
        switch (sqlite3_column_type(st, c)) {
        case SQLITE_NULL: return std::nullopt;
        case SQLITE_INTEGER: return std::to_string(sqlite3_column_int64(st, c));
        case SQLITE_FLOAT: return exactText(sqlite3_column_double(st, c));
        default: {
            const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(st, c));
            return std::string(t ? t : "", size_t(sqlite3_column_bytes(st, c)));
        }
        }
    }

    Result<std::vector<Row>> run(const std::string& sql, const std::vector<Param>& params, bool collect,
                                 const RowCallback* each = nullptr) {
        sqlite3_stmt* st = nullptr;
        int rc = sqlite3_prepare_v2(db_, sql.c_str(), int(sql.size()), &st, nullptr);
        if (rc != SQLITE_OK) return error(rc, sql);
        std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> guard(st, sqlite3_finalize);
        CAVITY_TRY(bind(st, params));
        std::vector<Row> rows;
        Row row;
        while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
            if (!collect && !each) continue;
            row.clear();
            for (int c = 0; c < sqlite3_column_count(st); ++c) row.push_back(column(st, c));
            if (each) CAVITY_TRY((*each)(row));
            else rows.push_back(row);
        }
        if (rc != SQLITE_DONE) return error(rc, sql);
        return rows;
    }

    sqlite3* db_;
    std::string where_;
};

}  // namespace

std::string exactText(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

Result<std::unique_ptr<Database>> openSqlite(const std::string& path, bool create) {
    const std::string given = "--db " + path;
    if (path.empty()) return badInput("--db '': must be an SQLite file or a postgresql:// URL");
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (fs::is_directory(status)) return badInput(given + ": is a folder (an SQLite file or a postgresql:// URL is expected)");
    if (!fs::exists(status)) {
        if (!create) return badInput(given + ": no such database (cavity history ingest creates it)");
        const fs::path parent = fs::path(path).parent_path();
        if (!parent.empty() && !fs::is_directory(parent, ec))
            return badInput(given + ": " + parent.string() +
                            (fs::exists(parent, ec) ? " is a file, not a folder" : ": no such folder"));
    } else if (!fs::is_regular_file(status)) {
        return badInput(given + ": not a regular file (an SQLite file or a postgresql:// URL is expected)");
    } else if (!create && fs::file_size(path, ec) == 0 && !ec) {
        // SQLite would take an empty file for an empty database, and the
        // schema would be written into it by a command that only reads.
        return badInput(given + ": is empty, not a database (cavity history ingest creates one)");
    }
    sqlite3* db = nullptr;
    const int flags = SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0) | SQLITE_OPEN_NOMUTEX;
    const int rc = sqlite3_open_v2(path.c_str(), &db, flags, nullptr);
    if (rc != SQLITE_OK) {
        const std::string why = db ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
        sqlite3_close_v2(db);
        return badInput(given + ": cannot be opened (" + why + ")");
    }
    // Another writer (a second ingest) is waited for, not failed; foreign
    // keys are off in SQLite unless asked for.
    sqlite3_busy_timeout(db, 30000);
    auto out = std::make_unique<SqliteDatabase>(db, path);
    CAVITY_TRY(out->exec("PRAGMA foreign_keys = ON", {}));
    return std::unique_ptr<Database>(std::move(out));
}

}  // namespace cavity::history
