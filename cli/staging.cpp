#include "staging.h"

#include <fstream>

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

namespace cavity::cli {

namespace {

bool processRuns(const std::string& pid) {
    // A zombie (state Z: killed, not yet reaped) has ended too.
    std::ifstream stat("/proc/" + pid + "/stat");
    std::string line;
    if (!std::getline(stat, line)) return false;
    const auto paren = line.rfind(')');
    return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] != 'Z' && line[paren + 2] != 'X';
}

}  // namespace

std::filesystem::path stagingDir(const std::string& out) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(out, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(".partial-", 0) == 0 && !processRuns(name.substr(9))) fs::remove_all(e.path(), ec);
    }
    return fs::path(out) / (".partial-" + std::to_string(::getpid()));
}

std::error_code replaceFolder(const std::filesystem::path& from, const std::filesystem::path& to) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(to, ec) && ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_EXCHANGE) == 0) {
        fs::remove_all(from, ec);
        return {};
    }
    fs::remove_all(to, ec);
    fs::create_directories(to.parent_path(), ec);
    ec.clear();
    fs::rename(from, to, ec);
    return ec;
}

}  // namespace cavity::cli
