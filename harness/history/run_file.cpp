// Reading a run file: its bytes (through zlib, which reads plain files as
// they are), the digest it is stored under, its format, and its date.
#include "history/run_file.h"
#include "history/run_readers.h"
#include "core/digest.h"
#include "core/json_file.h"

#include <zlib.h>

#include "history/database.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace cavity::history {

namespace {

namespace fs = std::filesystem;

Result<std::string> readBytes(const std::string& path) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (path.empty()) return badInput("FILE '': an empty file name (give a results.json, cavity_bench JSON or gate.json)");
    if (!fs::exists(status)) return badInput(path + ": cannot be read (no such file)");
    if (fs::is_directory(status)) return badInput(path + ": is a folder, not a run file (results.json, cavity_bench JSON or gate.json)");
    gzFile f = gzopen(path.c_str(), "rb");
    if (!f) return badInput(path + ": cannot be read");
    std::string text;
    char buf[1 << 16];
    int n = 0;
    while ((n = gzread(f, buf, sizeof buf)) > 0) text.append(buf, size_t(n));
    int errnum = 0;
    const std::string why = n < 0 ? gzerror(f, &errnum) : "";
    // Z_BUF_ERROR from the close: the gzip stream ended before its trailer
    // (a truncated download), whose checksum was then never checked.
    const int closed = gzclose(f);
    if (n < 0) return badInput(path + ": cannot be read (" + why + ")");
    if (closed == Z_BUF_ERROR) return badInput(path + ": is cut short (its gzip stream ends before its end)");
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) return badInput(path + ": is empty (a JSON run file is expected)");
    return text;
}

Result<nlohmann::json> parse(const std::string& path, const std::string& text) {
    // A plain file through the reader every command uses (its messages give
    // the line); a compressed one parsed here.
    if (!(text.size() >= 2 && path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0))
        return readJsonFile(path);
    try {
        return nlohmann::json::parse(nullNonFiniteTokens(text));
    } catch (const nlohmann::json::exception& e) {
        return badInput(path + ": does not parse (gzip-compressed JSON): " + std::string(e.what()).substr(0, 160));
    }
}

bool digits(const std::string& s, size_t at, size_t n, int& out) {
    if (at + n > s.size()) return false;
    out = 0;
    for (size_t i = at; i < at + n; ++i) {
        if (s[i] < '0' || s[i] > '9') return false;
        out = out * 10 + (s[i] - '0');
    }
    return true;
}

// "+HH:MM", "-HHMM", "Z" or nothing (UTC) from `at` to the end: minutes east of UTC.
bool offsetMinutes(const std::string& s, size_t at, int& minutes) {
    minutes = 0;
    if (at == s.size() || (at + 1 == s.size() && (s[at] == 'Z' || s[at] == 'z'))) return true;
    if (s[at] != '+' && s[at] != '-') return false;
    int h = 0, m = 0;
    const size_t mAt = at + 3 + (s.size() > at + 3 && s[at + 3] == ':');
    if (!digits(s, at + 1, 2, h) || !digits(s, mAt, 2, m) || mAt + 2 != s.size() || h > 23 || m > 59) return false;
    minutes = (s[at] == '-' ? -1 : 1) * (h * 60 + m);
    return true;
}

}  // namespace

std::string normalizeDate(const std::string& text) {
    using namespace std::chrono;
    int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0, off = 0;
    if (!digits(text, 0, 4, y) || text.size() < 10 || text[4] != '-' || !digits(text, 5, 2, mo) || text[7] != '-' ||
        !digits(text, 8, 2, d))
        return "";
    size_t at = 10;
    if (at < text.size()) {
        if ((text[at] != 'T' && text[at] != ' ') || !digits(text, at + 1, 2, h) || text.size() < at + 9 ||
            text[at + 3] != ':' || !digits(text, at + 4, 2, mi) || text[at + 6] != ':' || !digits(text, at + 7, 2, sec))
            return "";
        at += 9;
        if (at < text.size() && text[at] == '.') {   // fractions of a second: dropped
            ++at;
            while (at < text.size() && text[at] >= '0' && text[at] <= '9') ++at;
        }
        if (!offsetMinutes(text, at, off)) return "";
    }
    const year_month_day ymd{year{y}, month{unsigned(mo)}, day{unsigned(d)}};
    if (!ymd.ok() || h > 23 || mi > 59 || sec > 60) return "";
    const auto t = sys_days{ymd} + hours{h} + minutes{mi} + seconds{std::min(sec, 59)} - minutes{off};
    const auto day0 = floor<days>(t);
    const year_month_day u{day0};
    const hh_mm_ss<seconds> tod{t - day0};
    char buf[32];
    std::snprintf(buf, sizeof buf, "%04d-%02u-%02uT%02d:%02d:%02dZ", int(u.year()), unsigned(u.month()), unsigned(u.day()),
                  int(tod.hours().count()), int(tod.minutes().count()), int(tod.seconds().count()));
    return buf;
}

Result<RunFile> readRunFile(const std::string& path) {
    CAVITY_ASSIGN(const std::string text, readBytes(path));
    CAVITY_ASSIGN(const nlohmann::json doc, parse(path, text));
    RunFile out;
    out.path = path;
    out.digest = digestText(fnv1a64(text.data(), text.size())) + "/" + std::to_string(text.size());
    if (doc.is_object() && doc.contains("schema") && doc["schema"] == "cavity.results/1") {
        CAVITY_TRY(readResults(doc, out));
    } else if (doc.is_object() && doc.contains("schema") && doc["schema"] == "cavity.gate/1") {
        CAVITY_TRY(readGate(doc, out));
    } else if (doc.is_object() && doc.contains("benchmarks") && doc["benchmarks"].is_array()) {
        CAVITY_TRY(readBenchmark(doc, out));
    } else {
        return badInput(path + ": not a run file: neither a cavity results.json (schema cavity.results/1), a gate.json "
                        "(schema cavity.gate/1) nor cavity_bench's Google Benchmark JSON (benchmarks[])");
    }
    if (out.series.empty()) return badInput(path + ": holds no time (no pass of any configuration was timed)");
    // A date the file gives must read as one: an unreadable one would be
    // replaced by the time of ingest, and the run ordered by that.
    if (!out.date.empty() && normalizeDate(out.date).empty())
        return badInput(path + ": its date '" + out.date.substr(0, 40) +
                        "' is not an ISO 8601 date (2026-11-30T12:00:00Z); the file is damaged");
    for (const auto& s : out.series)
        if (s.clock != "gpu-timestamp" && s.clock != "wall" && s.clock != "mixed" && s.clock != "unknown")
            return badInput(path + ": " + s.configId + " " + s.pass + ": clock '" + s.clock.substr(0, 40) +
                            "': must be gpu-timestamp or wall (the label's clock=)");
    for (const auto& s : out.series)
        for (const auto& x : s.samples)
            if (!std::isfinite(x.ms) || x.ms < 0)
                return badInput(path + ": " + s.configId + " " + s.pass + ": a time of " + exactText(x.ms) +
                                " ms (a finite time >= 0 is expected)");
    return out;
}

}  // namespace cavity::history
