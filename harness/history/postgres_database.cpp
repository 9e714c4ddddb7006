// The PostgreSQL side of history/database.h, through libpq. Parameters go
// as text and the server types them from their place in the statement;
// results come back as text (float8 in its shortest form that reads back
// exactly, PostgreSQL 12 and later).
#include "history/database.h"

#include <libpq-fe.h>

#include <cstdlib>
#include <set>
#include <sstream>

namespace cavity::history {

namespace {

std::string firstLine(const char* text) {
    std::string s = text ? text : "";
    if (const auto nl = s.find('\n'); nl != std::string::npos) s.erase(nl);
    return s;
}

// `?` placeholders numbered $1, $2, ... outside quoted literals.
std::string numbered(const std::string& sql) {
    std::string out;
    int n = 0;
    bool quoted = false;
    for (char c : sql) {
        if (c == '\'') quoted = !quoted;
        if (c == '?' && !quoted) {
            out.push_back('$');
            out.append(std::to_string(++n));
        } else {
            out.push_back(c);
        }
    }
    return out;
}

class PostgresDatabase final : public Database {
public:
    PostgresDatabase(PGconn* conn, std::string where) : conn_(conn), where_(std::move(where)) {}
    ~PostgresDatabase() override { PQfinish(conn_); }

    Dialect dialect() const override { return Dialect::PostgreSQL; }
    const std::string& where() const override { return where_; }
    Status begin() override { return exec("BEGIN", {}); }

    Status exec(const std::string& sql, const std::vector<Param>& params) override {
        auto rows = run(sql, params);
        if (!rows) return rows.error();
        return {};
    }
    Result<std::vector<Row>> query(const std::string& sql, const std::vector<Param>& params) override {
        return run(sql, params);
    }

    // libpq's single-row mode: the server's rows arrive one result at a time.
    Status forEach(const std::string& sql, const std::vector<Param>& params, const RowCallback& each) override {
        std::vector<std::string> text;
        const auto values = paramValues(params, text);
        if (!PQsendQueryParams(conn_, numbered(sql).c_str(), int(params.size()), nullptr, values.data(), nullptr, nullptr, 0))
            return failure(sql);
        PQsetSingleRowMode(conn_);
        Status out;
        bool failed = false;
        // Every result is read, even after an error: the connection is
        // ready for the next query only once the last one is.
        while (PGresult* res = PQgetResult(conn_)) {
            std::unique_ptr<PGresult, void (*)(PGresult*)> guard(res, PQclear);
            const auto status = PQresultStatus(res);
            if (status == PGRES_SINGLE_TUPLE) {
                if (!out) continue;
                Row row;
                for (int c = 0; c < PQnfields(res); ++c)
                    row.push_back(PQgetisnull(res, 0, c) ? std::nullopt : std::optional<std::string>(PQgetvalue(res, 0, c)));
                out = each(row);
            } else if (status != PGRES_TUPLES_OK && status != PGRES_COMMAND_OK && !failed) {
                failed = true;
                out = failure(sql);
            }
        }
        return out;
    }

private:
    static std::vector<const char*> paramValues(const std::vector<Param>& params, std::vector<std::string>& text) {
        text.assign(params.size(), "");
        std::vector<const char*> values(params.size(), nullptr);
        for (size_t i = 0; i < params.size(); ++i) {
            if (std::holds_alternative<std::monostate>(params[i])) continue;
            if (const auto* n = std::get_if<int64_t>(&params[i])) text[i] = std::to_string(*n);
            else if (const auto* d = std::get_if<double>(&params[i])) text[i] = exactText(*d);
            else text[i] = std::get<std::string>(params[i]);
            values[i] = text[i].c_str();
        }
        return values;
    }

    Error failure(const std::string& sql) const {
        const std::string what = where_ + ": " + firstLine(PQerrorMessage(conn_));
        // A server that went away mid-way is unavailable, not our bug.
        if (PQstatus(conn_) == CONNECTION_BAD) return unreachable(what);
        return internal(what + " in: " + sql.substr(0, 80));
    }

    Result<std::vector<Row>> run(const std::string& sql, const std::vector<Param>& params) {
        std::vector<std::string> text;
        const auto values = paramValues(params, text);
        PGresult* res = PQexecParams(conn_, numbered(sql).c_str(), int(params.size()), nullptr, values.data(), nullptr,
                                     nullptr, 0);
        std::unique_ptr<PGresult, void (*)(PGresult*)> guard(res, PQclear);
        const auto status = PQresultStatus(res);
        if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) return failure(sql);
        std::vector<Row> rows;
        for (int r = 0; r < PQntuples(res); ++r) {
            Row row;
            for (int c = 0; c < PQnfields(res); ++c)
                row.push_back(PQgetisnull(res, r, c) ? std::nullopt : std::optional<std::string>(PQgetvalue(res, r, c)));
            rows.push_back(std::move(row));
        }
        return rows;
    }

    PGconn* conn_;
    std::string where_;
};

void quiet(void*, const char*) {}   // NOTICEs ("relation exists, skipping") are not the user's business

}  // namespace

bool isPostgresUrl(const std::string& location) {
    return location.rfind("postgresql://", 0) == 0 || location.rfind("postgres://", 0) == 0;
}

std::string redactUrl(const std::string& url) {
    const auto scheme = url.find("://");
    const auto at = url.find('@', scheme == std::string::npos ? 0 : scheme + 3);
    if (scheme == std::string::npos || at == std::string::npos) return url;
    const auto colon = url.find(':', scheme + 3);
    if (colon == std::string::npos || colon > at) return url;
    return url.substr(0, colon + 1) + "***" + url.substr(at);
}

namespace {

// The URL's syntax and the values libpq would only reject once connecting
// (a port, an sslmode, a time-out that is no number): a typo is bad input
// (2), never a server that "cannot be reached" (5), which a CI job would
// read as an outage.
Status checkUrl(const std::string& url, const std::string& where) {
    char* err = nullptr;
    PQconninfoOption* opts = PQconninfoParse(url.c_str(), &err);
    if (!opts) {
        std::string why = err ? firstLine(err) : "not a connection URL";
        PQfreemem(err);
        // libpq quotes the URL; the password stays out of the message.
        // Searching on past each replacement: `where` is the URL itself when
        // it holds no password.
        for (size_t at = 0; !url.empty() && (at = why.find(url, at)) != std::string::npos; at += where.size())
            why.replace(at, url.size(), where);
        return badInput("--db " + where + ": " + why);
    }
    std::unique_ptr<PQconninfoOption, void (*)(PQconninfoOption*)> guard(opts, PQconninfoFree);
    const auto whole = [](const std::string& v, long lo, long hi) {
        if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos) return false;
        const long n = std::stol(v);
        return n >= lo && n <= hi;
    };
    for (const PQconninfoOption* o = opts; o->keyword; ++o) {
        if (!o->val) continue;
        const std::string key = o->keyword, v = o->val;
        if (key == "port") {
            std::stringstream list(v);
            for (std::string p; std::getline(list, p, ',');)
                if (!p.empty() && !whole(p, 1, 65535))
                    return badInput("--db " + where + ": port " + p + ": must be a number, 1..65535");
        } else if (key == "sslmode") {
            static const std::set<std::string> modes = {"disable", "allow", "prefer", "require", "verify-ca", "verify-full"};
            if (!modes.count(v))
                return badInput("--db " + where + ": sslmode=" + v +
                                ": must be disable, allow, prefer, require, verify-ca or verify-full");
        } else if (key == "connect_timeout") {
            if (!whole(v, 0, 86400)) return badInput("--db " + where + ": connect_timeout=" + v + ": must be whole seconds, 0..86400");
        }
    }
    // libpq reads these when the URL does not say; a bad one is the user's
    // value, not a server that cannot be reached.
    if (const char* t = std::getenv("PGCONNECT_TIMEOUT"); t && *t && !whole(t, 0, 86400))
        return badInput(std::string("PGCONNECT_TIMEOUT=") + t + ": must be whole seconds, 0..86400");
    if (const char* p = std::getenv("PGPORT"); p && *p && !whole(p, 1, 65535))
        return badInput(std::string("PGPORT=") + p + ": must be a number, 1..65535");
    return {};
}

}  // namespace

Result<std::unique_ptr<Database>> openPostgres(const std::string& url) {
    const std::string where = redactUrl(url);
    CAVITY_TRY(checkUrl(url, where));
    // A server that does not answer fails after the connect_timeout below unless the
    // URL or PGCONNECT_TIMEOUT says otherwise (the URL's own setting wins: it is expanded after).
    const char* timeout = std::getenv("PGCONNECT_TIMEOUT");
    const char* keys[] = {"connect_timeout", "dbname", nullptr};
    const char* values[] = {timeout && *timeout ? timeout : "10", url.c_str(), nullptr};
    PGconn* conn = PQconnectdbParams(keys, values, 1);
    if (!conn) return internal(where + ": libpq could not allocate a connection");
    if (PQstatus(conn) != CONNECTION_OK) {
        const std::string why = firstLine(PQerrorMessage(conn));
        PQfinish(conn);
        // A URL libpq cannot parse is the user's; every other failure (down,
        // refused, wrong password, no such database) is the server's answer.
        if (why.rfind("invalid ", 0) == 0 || (why.find("invalid") != std::string::npos && why.find("URI") != std::string::npos))
            return badInput("--db " + where + ": " + why);
        return unreachable("--db " + where + ": cannot connect: " + why);
    }
    PQsetNoticeProcessor(conn, quiet, nullptr);
    return std::unique_ptr<Database>(std::make_unique<PostgresDatabase>(conn, where));
}

}  // namespace cavity::history
