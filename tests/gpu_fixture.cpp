#include "gpu_fixture.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>

namespace cavity::test {

bool inCI() {
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

bool validationOn() {
    const char* v = std::getenv("CAVITY_TEST_VALIDATION");
    return !(v && std::string(v) == "0");
}

namespace {

struct Slot {
    std::unique_ptr<gpu::Backend> backend;
    std::string error;
    bool tried = false;
};

std::map<gpu::Api, Slot>& slots() {
    static std::map<gpu::Api, Slot> s;
    return s;
}

// Backends go before static destruction (drivers dislike late teardown).
class ReleaseBackends : public ::testing::Environment {
public:
    void TearDown() override { slots().clear(); }
};
const auto* const kRelease = ::testing::AddGlobalTestEnvironment(new ReleaseBackends);

}  // namespace

gpu::Backend* sharedBackend(gpu::Api api, std::string* whyNot) {
    Slot& s = slots()[api];
    if (!s.tried) {
        s.tried = true;
        gpu::BackendOptions o;
        o.validation = validationOn();
        auto r = gpu::createBackend(api, o);
        if (r) s.backend = std::move(*r);
        else s.error = r.error().message;
    }
    if (!s.backend && whyNot) *whyNot = s.error;
    return s.backend.get();
}

void GpuTest::SetUp() {
    std::string why;
    backend_ = sharedBackend(GetParam(), &why);
    if (!backend_) {
        if (inCI()) FAIL() << "CI=true requires both backends: " << why;
        GTEST_SKIP() << why;
    }
    backend_->takeDebugMessages();
}

void GpuTest::TearDown() {
    if (!backend_) return;
    const auto messages = backend_->takeDebugMessages();
    std::string all;
    for (const auto& m : messages) all += "\n  " + m;
    EXPECT_TRUE(messages.empty()) << "debug/validation messages:" << all;
}

Diff diff(const HostImage& a, const HostImage& b, double threshold, const std::function<bool(int, int)>& include) {
    Diff d;
    if (!a.sameShape(b)) {
        d.maxAbs = INFINITY;
        return d;
    }
    double sum = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (include && !include(x, y)) continue;
            double worst = 0;
            for (int c = 0; c < a.channels; ++c) {
                const double e = std::fabs(double(a.at(x, y, c)) - double(b.at(x, y, c)));
                worst = std::isnan(e) ? INFINITY : std::max(worst, e);
            }
            sum += worst;
            ++d.compared;
            if (worst > threshold) ++d.over;
            if (worst > d.maxAbs || d.worstX < 0) {
                if (worst > d.maxAbs) d.maxAbs = worst;
                if (worst >= d.maxAbs) { d.worstX = x; d.worstY = y; }
            }
        }
    d.meanAbs = d.compared ? sum / double(d.compared) : 0;
    return d;
}

}  // namespace cavity::test
