#include "core/json_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <mutex>
#include <set>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace cavity::core {

namespace {

bool wordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; }

bool nonFiniteWord(std::string w) {
    std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return w == "nan" || w == "inf" || w == "infinity";
}

// nlohmann's what() reads "[json.exception.parse_error.101] parse error at
// line 3, column 7: syntax error ..."; the line comes from the byte offset,
// so keep only what it says after the position.
std::string reason(const nlohmann::json::exception& e) {
    const std::string what = e.what();
    const size_t column = what.find(", column ");
    const size_t colon = column == std::string::npos ? column : what.find(": ", column);
    return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

std::string nullNonFiniteTokens(const std::string& text) {
    std::string out;
    out.reserve(text.size() + 16);
    bool inString = false;
    for (size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (inString) {
            out += c;
            if (c == '\\' && i + 1 < text.size()) out += text[++i];   // an escaped quote does not end the string
            else if (c == '"') inString = false;
            ++i;
            continue;
        }
        if (c == '"') {
            inString = true;
            out += c;
            ++i;
            continue;
        }
        // A word that starts here (after an optional sign) and is not the tail
        // of a number or of another word: "1e5" or "nullx" are not ours to touch.
        const bool boundary = i == 0 || !wordChar(text[i - 1]);
        const size_t start = (c == '-' || c == '+') ? i + 1 : i;
        if (boundary && start < text.size() && std::isalpha(static_cast<unsigned char>(text[start]))) {
            size_t end = start;
            while (end < text.size() && wordChar(text[end])) ++end;
            if (nonFiniteWord(text.substr(start, end - start))) {
                out += "null";
                i = end;
                continue;
            }
        }
        out += c;
        ++i;
    }
    return out;
}

Result<nlohmann::json> readJsonFile(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status)) return badInput(path + ": cannot be read (no such file)");
    if (fs::is_directory(status)) return badInput(path + ": is a folder, not a JSON file");
    // A device (/dev/zero) never ends: a file or a pipe (a shell's <(...)) is read.
    if (fs::is_character_file(status) || fs::is_block_file(status) || fs::is_socket(status))
        return badInput(path + ": is a device or socket, not a JSON file");
    std::ifstream f(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << f.rdbuf();
    if (!f) return badInput(path + ": cannot be read");
    const std::string text = nullNonFiniteTokens(buffer.str());
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is 1-based and may point one past the end (a truncated file).
        const size_t upTo = std::min(e.byte > 0 ? e.byte - 1 : 0, text.size());
        const auto line = 1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(upTo), '\n');
        return badInput(path + ": does not parse: line " + std::to_string(line) + ": " + reason(e));
    } catch (const nlohmann::json::out_of_range& e) {
        // 406: "number overflow parsing '1e999'", a number no double holds.
        const std::string what = e.what();
        const size_t open = what.find('\''), close = what.rfind('\'');
        const std::string number = open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
        const size_t at = number.empty() ? std::string::npos : text.find(number);
        const auto line = at == std::string::npos ? 0 : 1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n');
        return badInput(path + ": does not parse: " + (line ? "line " + std::to_string(line) + ": " : "") + number +
                        " is not a finite number (every number must fit a double)");
    } catch (const nlohmann::json::exception& e) {
        return badInput(path + ": does not parse: " + reason(e));
    }
}

void removeStaleTemps(const std::string& dir) {
    static std::mutex lock;
    static std::set<std::string> done;
    namespace fs = std::filesystem;
    std::error_code ec;
    const std::string key = fs::absolute(dir.empty() ? "." : dir, ec).lexically_normal().string();
    {
        std::lock_guard<std::mutex> hold(lock);
        if (!done.insert(key).second) return;
    }
    for (fs::directory_iterator it(key, ec), last; !ec && it != last; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const size_t at = name.rfind(".tmp-");
        if (at == std::string::npos || at == 0) continue;
        size_t end = at + 5;
        while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
        if (end == at + 5 || end - at - 5 > 9 || (end < name.size() && name[end] != '.')) continue;
        const long pid = std::stol(name.substr(at + 5, end - at - 5));
        if (pid == long(::getpid()) || pid <= 0) continue;
        if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;   // alive, or not ours to judge
        std::error_code rm;
        if (it->is_regular_file(rm)) fs::remove(it->path(), rm);
    }
}

Status writeFileAtomically(const std::string& path, const std::string& text) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return badInput(path + ": is a folder (a file is written here)");
    removeStaleTemps(std::filesystem::path(path).parent_path().string());
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream f(tmp);
        if (!f) return badInput(path + ": cannot write");
        f << text;
        if (!f) {
            f.close();
            std::filesystem::remove(tmp, ec);
            return internal("write " + path + " failed (disk full?)");
        }
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(tmp, ec);   // nothing half-written left behind
        return internal("rename " + tmp + " -> " + path + ": " + why);
    }
    return {};
}

}  // namespace cavity::core
