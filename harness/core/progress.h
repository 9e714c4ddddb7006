// Progress on stderr for the commands that measure (run, gate, quality), the
// one progress line of every command:
//     [3/12] corner/alchemy/n16/b4/full/320x180/vk/compute  elapsed E s  ETA R s
// (E the seconds since the start, R the seconds the ETA expects still), one
// line rewritten in place (\r) when stderr is a terminal, otherwise (a pipe,
// a CI log) a plain line for the first step, the last, and one a tenth of
// the way in between; --quiet gives a Progress that says nothing. The ETA
// is the mean time per finished step times the steps left.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace cavity::core {

// Held by whatever writes to stderr while other threads run, and by an image
// read (images/image_module.cpp), which points fd 2 at a file for the
// duration to fold OpenImageIO's and libpng's messages into its one error
// line: a progress line printed meanwhile would land in that file and be
// lost. Progress takes it for every line.
std::mutex& stderrLock();

class Progress {
public:
    // `prefix` starts every line ("gate: ").
    Progress(size_t total, bool quiet, std::string prefix = "");
    ~Progress();
    // Step `id` starts: the count shown is the steps begun so far.
    void start(const std::string& id);
    // A step has finished, its verdict in `label`: a line of its own with the
    // count finished so far (the gate's form). With show false the step
    // counts but prints nothing (an error, reported on its own line).
    void done(const std::string& label, bool show = true);
    // Ends the in-place line, so that a message can follow on a line of its own.
    void interrupt();
    size_t total() const { return total_; }

private:
    void print(size_t count, const std::string& label, size_t finished, bool inPlace);
    size_t total_, begun_ = 0, finished_ = 0;
    std::string prefix_;
    bool quiet_, terminal_, open_ = false;
    std::chrono::steady_clock::time_point t0_;
};

}  // namespace cavity::core