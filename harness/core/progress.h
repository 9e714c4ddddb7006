// Progress on stderr for the commands that measure (run, gate, quality):
//     [3/12] corner/alchemy/n16/b4/full/320x180/vk/compute  elapsed 4.1 s  ETA 12.3 s
// one line rewritten in place (\r) when stderr is a terminal, a plain line
// per step otherwise (a pipe, a CI log); --quiet gives a Progress that says
// nothing. The ETA is the mean time per finished step times the steps left.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace cavity::core {

class Progress {
public:
    Progress(size_t total, bool quiet);
    ~Progress();
    // Step `id` starts: the count shown is the steps begun so far.
    void start(const std::string& id);
    // Ends the in-place line, so that a message can follow on a line of its own.
    void interrupt();
    size_t total() const { return total_; }

private:
    size_t total_, begun_ = 0;
    bool quiet_, terminal_, open_ = false;
    std::chrono::steady_clock::time_point t0_;
};

}  // namespace cavity::core