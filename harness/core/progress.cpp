#include "core/progress.h"

#include <cstdio>

#include <unistd.h>

namespace cavity::core {

Progress::Progress(size_t total, bool quiet)
    : total_(total), quiet_(quiet), terminal_(::isatty(2) == 1), t0_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { interrupt(); }

void Progress::start(const std::string& id) {
    if (quiet_) return;
    ++begun_;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const size_t finished = begun_ - 1;
    char eta[48] = "ETA ?";
    if (finished > 0)
        std::snprintf(eta, sizeof eta, "ETA %.1f s", elapsed / double(finished) * double(total_ - finished));
    // \033[K clears what a longer previous line left behind.
    std::fprintf(stderr, "%s[%zu/%zu] %s  elapsed %.1f s  %s%s", terminal_ ? "\r" : "", begun_, total_, id.c_str(),
                 elapsed, eta, terminal_ ? "\033[K" : "\n");
    std::fflush(stderr);
    open_ = terminal_;
}

void Progress::interrupt() {
    if (!open_) return;
    std::fputc('\n', stderr);
    open_ = false;
}

}  // namespace cavity::core