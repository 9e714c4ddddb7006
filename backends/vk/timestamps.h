// Named GPU timestamp scopes of one frame: begin/end timestamp pairs in query
// pools, read back after the frame's fence and turned into milliseconds.
#pragma once

#include "backend.h"
#include "vk_device.h"

#include <string>
#include <vector>

namespace cavity::gpu::vk {

class Timestamps {
public:
    explicit Timestamps(Device& d) : d_(d) {}
    ~Timestamps();
    Timestamps(const Timestamps&) = delete;
    Timestamps& operator=(const Timestamps&) = delete;

    void beginFrame();   // forget the last frame's scopes; before recording
    Status beginScope(VkCommandBuffer cmd, const std::string& name);
    Status endScope(VkCommandBuffer cmd);
    Status checkClosed() const;   // every scope ended; before the frame is submitted
    Status resolve();             // after the frame's fence: fills times()
    const std::vector<ScopeTime>& times() const { return times_; }

private:
    Result<uint32_t> writeTimestamp(VkCommandBuffer cmd);

    struct Scope {
        std::string name;
        uint32_t begin = 0, end = 0;   // query numbers across pools_
    };
    Device& d_;
    std::vector<VkQueryPool> pools_;   // kPoolSize queries each; more are made mid-frame as needed
    uint32_t used_ = 0;                // queries written this frame
    std::vector<Scope> scopes_;        // begin order
    std::vector<size_t> open_;         // indices into scopes_, innermost last
    std::vector<ScopeTime> times_;
};

}  // namespace cavity::gpu::vk
