// The results database behind `cavity history`: one small interface, two
// implementations. SQLite (a file, for a laptop or one CI machine) and
// PostgreSQL through libpq (a server a team's CI jobs share). The SQL the
// callers write is portable: `?` placeholders (PostgreSQL's are numbered by
// its implementation), INSERT ... RETURNING, ON CONFLICT DO NOTHING, and
// DOUBLE PRECISION, BIGINT and TEXT columns, which both read the same way;
// where the two differ (an auto-numbered key, how to ask whether a table
// exists, how to serialise migrations) the Dialect says which to write.
#pragma once

#include "history/namespace.h"
#include "result.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace cavity::history {

enum class Dialect { SQLite, PostgreSQL };

// A bound parameter: NULL, an integer, a double (finite: the callers check)
// or text.
using Param = std::variant<std::monostate, int64_t, double, std::string>;
// A result row, every value as text (a double written so that it reads back
// to the same double), NULL as nullopt.
using Row = std::vector<std::optional<std::string>>;

class Database {
public:
    virtual ~Database() = default;
    virtual Dialect dialect() const = 0;
    // For messages: "sqlite:FILE", or the URL without its password.
    virtual const std::string& where() const = 0;
    virtual Status exec(const std::string& sql, const std::vector<Param>& params = {}) = 0;
    virtual Result<std::vector<Row>> query(const std::string& sql, const std::vector<Param>& params = {}) = 0;
    // The rows one at a time, none kept: a long history is read in bounded
    // memory. An error the callback returns stops the query and is returned.
    using RowCallback = std::function<Status(const Row&)>;
    virtual Status forEach(const std::string& sql, const std::vector<Param>& params, const RowCallback& each) = 0;
    // A transaction that writes: SQLite takes its write lock at once (BEGIN
    // IMMEDIATE), so two writers wait for each other instead of failing at commit.
    virtual Status begin() = 0;
    Status commit() { return exec("COMMIT"); }
    Status rollback() { return exec("ROLLBACK"); }
};

// Rolls back unless committed: an error or an early return in the middle
// of a file's rows leaves none of them.
class Transaction {
public:
    explicit Transaction(Database& db) : db_(db) {}
    ~Transaction() {
        if (open_) (void)db_.rollback();
    }
    Transaction(const Transaction&) = delete;
    Transaction& operator=(const Transaction&) = delete;
    Status begin() {
        CAVITY_TRY(db_.begin());
        open_ = true;
        return {};
    }
    Status commit() {
        open_ = false;
        return db_.commit();
    }

private:
    Database& db_;
    bool open_ = false;
};

// `--db` names a PostgreSQL database by URL (postgresql:// or postgres://;
// user, password, host, port and options as libpq reads them, PG* variables
// and ~/.pgpass filling what the URL leaves out), anything else an SQLite
// file. `create`: an SQLite file that does not exist is created (ingest);
// otherwise it is an error (the read commands have nothing to read).
// Errors: bad input (2) for a location that is no database; unavailable (5)
// for a server that is down, refuses the connection or the credentials.
// The schema is brought up to date (schema.h) before it is returned.
Result<std::unique_ptr<Database>> openDatabase(const std::string& location, bool create);

bool isPostgresUrl(const std::string& location);
// The URL with any password replaced by "***", for messages.
std::string redactUrl(const std::string& url);

// The two implementations, without the migration step (tests and schema.cpp).
Result<std::unique_ptr<Database>> openSqlite(const std::string& path, bool create);
Result<std::unique_ptr<Database>> openPostgres(const std::string& url);

// A double as text that reads back to the same double ("%.17g").
std::string exactText(double v);

}  // namespace cavity::history
