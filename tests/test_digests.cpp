// Image digests are SHA-256, and an FNV-1a store and approvals.json migrate
// to them in one command: all or nothing under kill -9, every image still
// passing by digest afterwards.
#include "run_binary.h"
#include "core/digest.h"
#include "plan/approvals.h"
#include "render/image_file.h"
#include "store/store.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <unistd.h>

namespace cavity::test {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// One configuration of the ci matrix on both APIs: 6 approved images.
const std::string kFilter = "'^corner/alchemy/n16/b4/full/160x90/'";

class Digests : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("cavity-digests-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir);
    }

    // baselines/ with only this configuration's CPU approvals, made old: each
    // digest FNV-1a, each image filed under it in `store` (from a render).
    void makeOldBaselines(const fs::path& base, const fs::path& store) {
        fs::copy(fs::path(CAVITY_SOURCE_DIR) / "baselines", base, fs::copy_options::recursive);
        fs::remove_all(base / "store");
        auto approvals = plan::loadApprovals((base / "approvals.json").string());
        ASSERT_TRUE(approvals.ok());
        // Rendered with no approvals, so that every image is written whole.
        ASSERT_TRUE(plan::saveApprovals((base / "approvals.json").string(), {}).ok());
        const Outcome r = runBinary(CAVITY_RENDER_EXE, "--matrix ci --filter " + kFilter + " --baselines " + base.string() +
                                                           " --out " + (dir / "render").string());
        ASSERT_EQ(r.code, 0) << r.output;
        std::map<std::string, std::pair<std::string, std::string>> bySha;   // sha -> (fnv, object bytes)
        for (const auto& e : fs::recursive_directory_iterator(dir / "render"))
            if (e.path().extension() == ".f32z") {
                const std::string bytes = slurp(e.path());
                auto image = render::decodeImage(bytes, e.path().string());
                ASSERT_TRUE(image.ok()) << image.error().message;
                bySha[core::imageDigest(*image)] = {core::legacyImageDigest(*image), bytes};
            }
        plan::Approvals old;
        auto s = store::folderStore(store.string());
        for (auto a : approvals->entries) {
            if (a.deviceClass != "llvmpipe" || a.key != "corner/alchemy/n16/b4/full/160x90") continue;
            const auto it = bySha.find(a.digest);
            ASSERT_NE(it, bySha.end()) << a.key << " " << a.image << ": the render has no image of digest " << a.digest;
            a.digest = it->second.first;
            ASSERT_TRUE(s->put(a.digest, it->second.second).ok());
            old.entries.push_back(a);
        }
        ASSERT_EQ(old.entries.size(), 6u);
        ASSERT_TRUE(plan::saveApprovals((base / "approvals.json").string(), old).ok());
        fs::remove_all(dir / "render/images");   // the migration must find the pixels in the store
    }

    // The gate on this configuration: every image passed by digest.
    void expectPassByDigest(const fs::path& base, const fs::path& store, const std::string& name, bool warned) {
        const Outcome g = runBinary(CAVITY_EXE, "gate --matrix ci --filter " + kFilter + " --baselines " + base.string() +
                                                    " --store " + store.string() + " --quiet --out " + (dir / name).string());
        ASSERT_EQ(g.code, 0) << g.output;
        EXPECT_EQ(g.output.find("FNV-1a") != std::string::npos, warned) << g.output;
        const json doc = json::parse(slurp(dir / name / "gate.json"));
        int images = 0;
        for (const auto& r : doc["results"])
            for (const auto& i : r["images"]) {
                EXPECT_EQ(i["route"], "digest") << r["id"] << " " << i["image"];
                ++images;
            }
        EXPECT_EQ(images, 6);
    }

    fs::path dir;
};

}  // namespace

// The digest is SHA-256 of the pixels' float32 bytes, as coreutils' sha256sum computes it.
TEST(Digest, IsTheSha256OfThePixelBytes) {
    core::HostImage image{7, 3, 2};
    image.pixels.resize(7 * 3 * 2);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) * 0.37f - 2.0f;
    const fs::path raw = fs::temp_directory_path() / ("cavity-digest-" + std::to_string(::getpid()) + ".raw");
    std::ofstream(raw, std::ios::binary)
        .write(reinterpret_cast<const char*>(image.pixels.data()), std::streamsize(image.pixels.size() * sizeof(float)));
    const Outcome o = runBinary("sha256sum", raw.string(), "", "2>&1");
    fs::remove(raw);
    ASSERT_EQ(o.code, 0) << o.output;
    EXPECT_EQ(core::imageDigest(image), "sha256:" + o.output.substr(0, 64));
    EXPECT_TRUE(core::isImageDigest(core::imageDigest(image)));
    EXPECT_TRUE(core::isLegacyDigest(core::legacyImageDigest(image)));
    EXPECT_EQ(core::imageDigestLike(image, core::legacyImageDigest(image)), core::legacyImageDigest(image));
}

TEST_F(Digests, AnFnvStoreMigratesInOneCommandAndStillPassesByDigest) {
    const fs::path base = dir / "baselines", store = dir / "store";
    makeOldBaselines(base, store);
    if (HasFatalFailure()) return;
    expectPassByDigest(base, store, "before", true);

    const Outcome m = runBinary(CAVITY_EXE, "baselines migrate-digests --baselines " + base.string() + " --store " + store.string());
    ASSERT_EQ(m.code, 0) << m.output;
    EXPECT_NE(m.output.find("migrated 6 approvals"), std::string::npos) << m.output;
    auto after = plan::loadApprovals((base / "approvals.json").string());
    ASSERT_TRUE(after.ok());
    EXPECT_EQ(after->legacy, 0);
    auto s = store::folderStore(store.string());
    for (const auto& a : after->entries) {
        auto image = store::getImage(*s, a.digest);
        EXPECT_TRUE(image.ok()) << a.digest << ": " << (image.ok() ? "" : image.error().message);
    }
    expectPassByDigest(base, store, "after", false);
}

// A digest whose pixels are nowhere: exit 5, and neither approvals.json nor
// the store changes.
TEST_F(Digests, MigrationRefusesWholeWhenAnImageIsMissing) {
    const fs::path base = dir / "baselines", store = dir / "store";
    makeOldBaselines(base, store);
    if (HasFatalFailure()) return;
    auto old = plan::loadApprovals((base / "approvals.json").string());
    ASSERT_TRUE(old.ok());
    fs::remove(store / store::objectPath(old->entries.front().digest));
    fs::remove_all(base / "images");   // nor a baseline file to find it in
    const std::string before = slurp(base / "approvals.json");
    const Outcome m = runBinary(CAVITY_EXE, "baselines migrate-digests --baselines " + base.string() + " --store " + store.string());
    EXPECT_EQ(m.code, 5) << m.output;
    EXPECT_NE(m.output.find("nothing written"), std::string::npos) << m.output;
    EXPECT_EQ(slurp(base / "approvals.json"), before);
    EXPECT_FALSE(fs::exists(store / "sha256"));
}

// An older approval of a slot whose image no render makes any more, beside
// the slot's current one: --drop-superseded drops it, and only it; without
// the flag the migration refuses as above.
TEST_F(Digests, SupersededApprovalsWhosePixelsAreGoneAreDropped) {
    const fs::path base = dir / "baselines", store = dir / "store";
    makeOldBaselines(base, store);
    if (HasFatalFailure()) return;
    auto approvals = plan::loadApprovals((base / "approvals.json").string());
    ASSERT_TRUE(approvals.ok());
    plan::Approval stale = approvals->entries.front();
    stale.digest = "fnv1a64:0123456789abcdef";   // pixels nowhere
    stale.when = "2026-01-01T00:00:00Z";
    plan::Approval orphan = stale;               // a slot with no other approval
    orphan.key = "corner/alchemy/n8/b4/full/160x90";
    orphan.digest = "fnv1a64:fedcba9876543210";
    approvals->entries.push_back(stale);
    approvals->entries.push_back(orphan);
    ASSERT_TRUE(plan::saveApprovals((base / "approvals.json").string(), *approvals).ok());
    const std::string flags = " --baselines " + base.string() + " --store " + store.string();
    EXPECT_EQ(runBinary(CAVITY_EXE, "baselines migrate-digests" + flags).code, 5);
    // The orphan is no one's older image: it still refuses, and writes nothing.
    const std::string before = slurp(base / "approvals.json");
    EXPECT_EQ(runBinary(CAVITY_EXE, "baselines migrate-digests --drop-superseded" + flags).code, 5);
    EXPECT_EQ(slurp(base / "approvals.json"), before);
    approvals->entries.pop_back();
    ASSERT_TRUE(plan::saveApprovals((base / "approvals.json").string(), *approvals).ok());
    const Outcome m = runBinary(CAVITY_EXE, "baselines migrate-digests --drop-superseded" + flags);
    ASSERT_EQ(m.code, 0) << m.output;
    EXPECT_NE(m.output.find("migrated 6 approvals"), std::string::npos) << m.output;
    EXPECT_NE(m.output.find("dropped 1 FNV-1a approvals"), std::string::npos) << m.output;
    auto after = plan::loadApprovals((base / "approvals.json").string());
    ASSERT_TRUE(after.ok());
    EXPECT_EQ(after->entries.size(), 6u);
    EXPECT_EQ(after->legacy, 0);
}

// Killed at any moment, the migration leaves approvals.json old or new,
// never between, and the gate passes either by digest.
TEST_F(Digests, MigrationKilledAnywhereLeavesAllOrNothing) {
    const fs::path base = dir / "baselines", store = dir / "store";
    makeOldBaselines(base, store);
    if (HasFatalFailure()) return;
    std::set<int> seen;
    for (const std::string after : {"0.01", "0.05", "0.1", "0.2", "0.4"}) {
        const fs::path b = dir / "b" / after, s = dir / "s" / after;
        fs::create_directories(b.parent_path());
        fs::create_directories(s.parent_path());
        fs::copy(base, b, fs::copy_options::recursive);
        fs::copy(store, s, fs::copy_options::recursive);
        runBinary("timeout", "-s KILL " + after + " " + CAVITY_EXE + " baselines migrate-digests --baselines " + b.string() +
                                 " --store " + s.string());
        auto a = plan::loadApprovals((b / "approvals.json").string());
        ASSERT_TRUE(a.ok()) << after << ": " << a.error().message;
        EXPECT_TRUE(a->legacy == 0 || a->legacy == 6) << after << ": " << a->legacy << " of 6 still FNV-1a";
        seen.insert(a->legacy);
        for (const auto& e : fs::recursive_directory_iterator(b))
            EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
        expectPassByDigest(b, s, "gate/" + after, a->legacy > 0);
    }
    EXPECT_TRUE(seen.count(6)) << "some kill must land before the rewrite";
}

}  // namespace cavity::test
