#include "gate/baseline_update.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace cavity::gate {

namespace fs = std::filesystem;

namespace {

// Beside images/, on the same file system, so every move is a rename.
fs::path stagingDir(const fs::path& root) { return root / ".update-staging"; }
fs::path journalPath(const fs::path& root) { return root / ".update-journal"; }

struct Entry {
    std::string staged;   // file name in the staging folder
    fs::path target;      // relative to root
};

Result<std::vector<Entry>> readJournal(const fs::path& path) {
    std::ifstream f(path);
    if (!f) return internal(path.string() + ": cannot be read");
    std::vector<Entry> entries;
    for (std::string line; std::getline(f, line);) {
        const auto tab = line.find('\t');
        if (tab == std::string::npos) return internal(path.string() + ": malformed line '" + line + "'");
        entries.push_back({line.substr(0, tab), line.substr(tab + 1)});
    }
    return entries;
}

// Moves every staged file still there to its target; a move already done
// (a recovery that was itself interrupted) is skipped.
Status rollForward(const fs::path& root, const std::vector<Entry>& entries) {
    for (const auto& e : entries) {
        const fs::path from = stagingDir(root) / e.staged, to = root / e.target;
        std::error_code ec;
        if (!fs::exists(from, ec)) continue;
        fs::create_directories(to.parent_path(), ec);
        fs::rename(from, to, ec);
        if (ec) return internal("rename " + from.string() + " -> " + to.string() + ": " + ec.message());
    }
    std::error_code ec;
    fs::remove(journalPath(root), ec);
    fs::remove_all(stagingDir(root), ec);
    return {};
}

}  // namespace

Status recoverBaselineUpdate(const fs::path& root) {
    std::error_code ec;
    if (fs::exists(journalPath(root), ec)) {
        CAVITY_ASSIGN(const auto entries, readJournal(journalPath(root)));
        CAVITY_TRY(rollForward(root, entries));
    }
    fs::remove_all(stagingDir(root), ec);
    fs::remove(root / ".update-journal.tmp", ec);
    for (auto it = fs::recursive_directory_iterator(root / "images", ec); !ec && it != fs::recursive_directory_iterator();
         ++it)
        if (it->path().filename().string().rfind(".tmp-", 0) == 0) fs::remove(it->path(), ec);
    return {};
}

Status applyBaselineUpdate(const fs::path& root, const std::vector<BaselineWrite>& writes) {
    CAVITY_TRY(recoverBaselineUpdate(root));
    for (const auto& w : writes) {
        std::error_code ec;
        if (!fs::is_regular_file(w.source, ec) || !std::ifstream(w.source))
            return badInput(w.source.string() + ": missing or not a readable file (the gate output it names is "
                            "incomplete); no baseline was changed");
    }
    if (writes.empty()) return {};
    // 1. Stage: a kill here leaves the old set and a folder the next command drops.
    std::error_code ec;
    fs::create_directories(stagingDir(root), ec);
    if (ec) return internal("create " + stagingDir(root).string() + ": " + ec.message());
    std::ostringstream journal;
    for (size_t i = 0; i < writes.size(); ++i) {
        const std::string name = std::to_string(i);
        fs::copy_file(writes[i].source, stagingDir(root) / name, fs::copy_options::overwrite_existing, ec);
        if (ec) return internal("copy " + writes[i].source.string() + ": " + ec.message());
        journal << name << '\t' << writes[i].target.string() << '\n';
    }
    if (std::getenv("CAVITY_TEST_INTERRUPT_UPDATE"))   // tests: stop as a kill before the commit would
        return internal("interrupted before committing the update staged in " + stagingDir(root).string());
    // 2. Commit: the journal appears whole or not at all.
    const fs::path tmp = root / ".update-journal.tmp";
    {
        std::ofstream f(tmp, std::ios::trunc);
        f << journal.str();
        if (!f.flush()) return internal("write " + tmp.string() + " failed");
    }
    fs::rename(tmp, journalPath(root), ec);
    if (ec) return internal("rename " + tmp.string() + ": " + ec.message());
    // 3. Apply: a kill here leaves a committed update the next command finishes.
    CAVITY_ASSIGN(const auto entries, readJournal(journalPath(root)));
    return rollForward(root, entries);
}

}  // namespace cavity::gate
