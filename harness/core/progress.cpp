#include "core/progress.h"

#include <algorithm>
#include <cstdio>

#include <unistd.h>

namespace cavity::core {

std::mutex& stderrLock() {
    static std::mutex lock;
    return lock;
}

Progress::Progress(size_t total, bool quiet, std::string prefix)
    : total_(total), prefix_(std::move(prefix)), quiet_(quiet), terminal_(::isatty(2) == 1),
      t0_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { interrupt(); }

void Progress::print(size_t count, const std::string& label, size_t finished, bool inPlace) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    char eta[48] = "ETA ?";
    if (finished > 0)
        std::snprintf(eta, sizeof eta, "ETA %.1f s", elapsed / double(finished) * double(total_ - std::min(finished, total_)));
    // \033[K clears what a longer previous line left behind.
    std::lock_guard<std::mutex> hold(stderrLock());
    std::fprintf(stderr, "%s%s[%zu/%zu] %s  elapsed %.1f s  %s%s", inPlace ? "\r" : "", prefix_.c_str(), count, total_,
                 label.c_str(), elapsed, eta, inPlace ? "\033[K" : "\n");
    std::fflush(stderr);
}

void Progress::start(const std::string& id) {
    if (quiet_) return;
    ++begun_;
    // A log (no terminal) keeps a line per tenth of the steps, the first and
    // the last: a long run's log stays readable and still shows it moving.
    const bool tenth = begun_ == 1 || begun_ == total_ || begun_ * 10 / total_ != (begun_ - 1) * 10 / total_;
    if (!terminal_ && !tenth) return;
    print(begun_, id, begun_ - 1, terminal_);
    open_ = terminal_;
}

void Progress::done(const std::string& label, bool show) {
    ++finished_;
    if (quiet_ || !show) return;
    interrupt();
    print(finished_, label, finished_, false);
}

void Progress::interrupt() {
    if (!open_) return;
    std::lock_guard<std::mutex> hold(stderrLock());
    std::fputc('\n', stderr);
    open_ = false;
}

}  // namespace cavity::core