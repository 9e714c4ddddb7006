// One test body, every backend (as Filament's backend tests and CTS do):
// derive from GpuTest, write TEST_P, and CAVITY_ALL_BACKENDS(Suite) makes
// a gl and a vk instance of each test. Vulkan runs with the Khronos
// validation layer, synchronisation validation included (a missing or too
// narrow barrier is a message), and GL with KHR_debug; any message fails
// the test.
// With CI=true a backend that cannot start fails the test instead of skipping.
// CAVITY_TEST_VALIDATION=0 runs without them (a GPU machine without the
// Vulkan validation layer); the tests that need them then skip.
#pragma once

#include "harness_names.h"
#include "backend.h"
#include "core/image.h"

#include <functional>

#include <gtest/gtest.h>

#include <string>

namespace cavity::gpu {
// Test names read ".../gl" and "... GetParam() = gl" rather than raw bytes.
inline void PrintTo(Api api, std::ostream* os) { *os << apiName(api); }
}  // namespace cavity::gpu

namespace cavity::test {

using namespace cavity::harness;

// Created once per API per process (backend start-up dominates small tests).
gpu::Backend* sharedBackend(gpu::Api api, std::string* whyNot);
bool inCI();
bool validationOn();   // not CAVITY_TEST_VALIDATION=0

class GpuTest : public ::testing::TestWithParam<gpu::Api> {
protected:
    void SetUp() override;
    void TearDown() override;
    gpu::Backend& gpu() { return *backend_; }
    gpu::Api api() const { return GetParam(); }

private:
    gpu::Backend* backend_ = nullptr;
};

// Max |a - b| over all channels; the position of the worst pixel in *where.
struct Diff {
    double maxAbs = 0, meanAbs = 0;
    int worstX = -1, worstY = -1;
    long long over = 0;    // pixels with any channel over the threshold
    long long compared = 0;
};
// Compares two images of the same shape; `include(x, y)` limits the pixels.
Diff diff(const HostImage& a, const HostImage& b, double threshold = 0,
          const std::function<bool(int, int)>& include = {});

}  // namespace cavity::test

#define CAVITY_ALL_BACKENDS(Suite)                                                                \
    INSTANTIATE_TEST_SUITE_P(Backends, Suite,                                                     \
                             ::testing::Values(::cavity::gpu::Api::OpenGL, ::cavity::gpu::Api::Vulkan), \
                             [](const auto& info) { return std::string(::cavity::gpu::apiName(info.param)); })
