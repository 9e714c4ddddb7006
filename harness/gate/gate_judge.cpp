#include "gate/gate_judge.h"

#include "core/digest.h"
#include "render/image_file.h"
#include "images/image_io.h"
#include "measure/runner.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

namespace cavity::gate {

namespace fs = std::filesystem;

namespace {

std::string fmt(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", x);
    return b;
}

std::vector<std::string> verdict(const metrics::Report& m, const Tolerance& t, bool perceptual) {
    std::vector<std::string> f;
    if (m.nonFinite > 0)
        f.push_back(std::to_string(m.nonFinite) + " non-finite pixels, first at (" + std::to_string(m.firstNonFiniteX) +
                    "," + std::to_string(m.firstNonFiniteY) + ")");
    if (m.maxAbs > t.maxAbs) f.push_back("max abs error " + fmt(m.maxAbs) + " > " + fmt(t.maxAbs) + " at (" +
                                         std::to_string(m.worstX) + "," + std::to_string(m.worstY) + ")");
    if (m.meanAbs > t.meanAbs) f.push_back("mean abs error " + fmt(m.meanAbs) + " > " + fmt(t.meanAbs));
    if (m.rmse > t.rmse) f.push_back("RMSE " + fmt(m.rmse) + " > " + fmt(t.rmse));
    if (m.psnr < t.psnrMin) f.push_back("PSNR " + fmt(m.psnr) + " dB < " + fmt(t.psnrMin) + " dB");
    if (m.overThresholdShare > t.overThresholdShare)
        f.push_back(fmt(100 * m.overThresholdShare) + "% of pixels over " + fmt(t.pixelThreshold) + " > " +
                    fmt(100 * t.overThresholdShare) + "%");
    if (m.ssim < t.ssimMin) f.push_back("SSIM " + fmt(m.ssim) + " < " + fmt(t.ssimMin));
    if (perceptual && m.flipMean > t.flipMeanMax) f.push_back("FLIP mean " + fmt(m.flipMean) + " > " + fmt(t.flipMeanMax));
    if (perceptual && m.differingShare > t.differingShareMax)
        f.push_back(fmt(100 * m.differingShare) + "% of pixels (" + std::to_string(m.differingPixels) + ") differ by more than " +
                    fmt(t.differingDelta) + " steps > " + fmt(100 * t.differingShareMax) + "%");
    return f;
}

// A baseline that exists must be readable and of the configuration's shape.
Status checkBaseline(const std::string& path, const RunConfig& c, const std::string& image) {
    if (!fs::exists(path)) return {};
    CAVITY_ASSIGN(HostImage b, readImage(path));
    const ImageShape need = checkedShape(c, image), have{b.width, b.height, b.channels};
    if (!(have == need))
        return badInput(path + ": baseline is " + shapeText(have) + ", configuration needs " + shapeText(need));
    return {};
}

}  // namespace

Result<HostImage> Judge::reference(const std::string& digest) const {
    std::lock_guard<std::mutex> hold(*fetchLock);
    if (const auto at = fetched->find(digest); at != fetched->end()) return at->second;
    if (!store) return internal("no image store to fetch " + digest + " from");
    if (*storeDown) return **storeDown;
    auto image = cavity::store::getImage(*store, digest);
    if (!image) {
        if (image.error().code == ErrorCode::Unreachable && !cavity::store::isMissingObject(image.error()))
            *storeDown = image.error();
        return image.error();
    }
    return fetched->emplace(digest, std::move(*image)).first->second;
}

Result<Judge> prepareJudge(const std::string& baselines, const std::vector<RunConfig>& configs, const std::string& out,
                           const store::StoreOptions& storeOptions, bool remote) {
    const fs::path root(baselines);
    Judge j;
    j.baselines = baselines;
    j.out = out;
    CAVITY_ASSIGN(j.manifest, loadManifest((root / "manifest.json").string()));
    CAVITY_ASSIGN(j.budgets, loadBudgets((root / "budgets.json").string()));
    CAVITY_ASSIGN(j.approvals, loadApprovals((root / "approvals.json").string()));
    // Said once, where an approval of this run's configurations is one.
    std::set<std::string> keys;
    for (const auto& c : configs) keys.insert(baselineKey(c));
    const auto legacy = std::count_if(j.approvals.entries.begin(), j.approvals.entries.end(), [&](const Approval& a) {
        return keys.count(a.key) && core::isLegacyDigest(a.digest);
    });
    if (legacy > 0) {
        std::lock_guard<std::mutex> hold(core::stderrLock());
        std::fprintf(stderr, "cavity: %s: %ld approvals of these configurations name their image by an FNV-1a digest, "
                             "which a forged image can be made to match; `cavity baselines migrate-digests --baselines %s` "
                             "makes them SHA-256\n",
                     (root / "approvals.json").c_str(), long(legacy), baselines.c_str());
    }
    j.remote = remote;
    for (const auto& c : configs)
        for (const auto& img : checkedImages())
            if (!remote) CAVITY_TRY(checkBaseline((root / "images" / baselineKey(c) / (img.name + img.extension)).string(), c, img.name));
    store::StoreOptions so = storeOptions;
    store::fillDefault(so, baselines);
    CAVITY_ASSIGN(std::unique_ptr<store::ImageStore> s, store::openStore(so));
    j.store = std::move(s);
    CAVITY_TRY(checkWritableDir("--out", out));
    return j;
}

namespace {

std::string approvalText(const Approval& a) {
    return std::string(a.positive ? "approved" : "approved as known bad") + " for " + a.deviceClass + " (" + a.api + ", " +
           a.stage + ") by " + a.by + " on " + a.when + ": " + a.why;
}

// The tolerance route: the metrics of the new image against the reference,
// the reference and a heat-map of the difference written beside it.
Status judgeAgainst(ImageCheck& check, const CheckedImage& ci, const HostImage& now, const HostImage& base,
                    const fs::path& dir, bool writeFiles = true) {
    const Tolerance& tol = check.tolerance;
    metrics::Options mo;
    mo.threshold = tol.pixelThreshold;
    mo.flip = ci.perceptual;
    mo.eightBit = ci.extension == ".png";
    mo.differingDelta = int(tol.differingDelta);
    CAVITY_ASSIGN(check.metrics, metrics::compare(base, now, mo));
    check.failures = verdict(*check.metrics, tol, ci.perceptual);
    // The report shows an unchanged image as a thumbnail of the new one
    // alone; the reference and the heat-map are for the images that failed
    // or changed within tolerance (which --strict fails after this).
    if ((check.passed() && !check.changed()) || !writeFiles) return {};
    check.baselinePng = (dir / (ci.name + ".baseline.png")).string();
    check.diffPng = (dir / (ci.name + ".diff.png")).string();
    CAVITY_TRY(writeImage(check.baselinePng, base, Encoding::Preview));
    CAVITY_TRY(writeImage(check.diffPng, metrics::heatmap(base, now, tol.pixelThreshold), Encoding::Preview));
    return {};
}

// Against the default class's reference, the stored baseline file.
Status judgeByTolerance(ImageCheck& check, const CheckedImage& ci, const HostImage& now, const fs::path& basePath,
                        const fs::path& dir, int& errorCode) {
    if (!fs::exists(basePath)) {
        // Never a silent pass: the configuration fails, the gate exits 2,
        // and the new image is there to accept.
        check.failures.push_back("baseline missing: " + basePath.string() +
                                 " (accept the new image with `cavity baselines update`)");
        errorCode = int(ErrorCode::BadInput);
        return {};
    }
    CAVITY_ASSIGN(HostImage base, readImage(basePath.string()));
    return judgeAgainst(check, ci, now, base, dir);
}

// The pixels of a checked image, which the tolerances are sized for.
long long pixelsOf(const ConfigResult& r, const std::string& image) {
    const ImageShape s = checkedShape(r.config, image);
    return (long long)s.width * s.height;
}

// The tolerances against the device's own class's reference, wherever it
// is judged: the defaults and the device entries of scope "all", sized for
// the image.
Tolerance classTolerance(const Judge& j, const ConfigResult& r, const std::string& image) {
    return sizedFor(j.manifest.forPipeline(r.config.kernel, r.device, true), pixelsOf(r, image));
}

// The nearest image approved for the device's own class (Approvals::reference).
const Approval* classReference(const Judge& j, const ConfigResult& r, const std::string& image) {
    const std::string stage = r.id.substr(r.id.rfind('/') + 1);
    return j.approvals.reference(r.key, image, deviceClass(r.device), gpu::apiName(r.config.api), stage);
}

// An image judged where it was rendered and found to pass (its file stayed
// there): its record, taken when it was judged with the tolerances this
// judge would use against the reference it would choose.
Result<ImageCheck> fromRemote(ImageCheck& check, const RemoteCheck& k, const ConfigResult& r, const Judge& j,
                              bool perceptual) {
    check.tolerance = classTolerance(j, r, check.image);
    const Approval* ref = classReference(j, r, check.image);
    if (!ref || ref->digest != k.referenceDigest)
        return badInput(r.label() + ": " + check.image + " was judged where it was rendered against " + k.referenceDigest +
                        ", and approvals.json here names " + (ref ? ref->digest : std::string("no reference")) +
                        " for it: render it again");
    if (k.tolerance != toleranceJson(check.tolerance))
        return badInput(r.label() + ": " + check.image + " was judged where it was rendered with other tolerances than "
                        "manifest.json's here (" + core::jsonText(k.tolerance) + "): render it again");
    CAVITY_ASSIGN(check.metrics, metricsFromJson(k.metrics, r.label() + " " + check.image));
    check.failures = verdict(*check.metrics, check.tolerance, perceptual);
    if (!check.failures.empty())
        return badInput(r.label() + ": " + check.image + " is recorded as passing where it was rendered, but its metrics "
                        "fail here (" + check.failures.front() + ")");
    check.reference = k.reference;
    check.approval = approvalText(*ref) + "; judged where it was rendered";
    check.baseline = "store:" + ref->digest;
    check.referenceDigest = ref->digest;
    return check;
}

// One checked image: a known-bad digest fails, an approved one of this
// device class passes with nothing computed, anything else is judged by
// tolerance. The new image is written where its pixels are held (`now`; a
// render folder holds none for an approved digest).
Result<ImageCheck> judgeImage(const CheckedImage& ci, const HostImage* now, const std::string& digest, const ConfigResult& r,
                              const Judge& j, const Tolerance& tol, const fs::path& dir, int& errorCode,
                              const std::map<std::string, RemoteCheck>& judged, bool software) {
    ImageCheck check;
    check.image = ci.name;
    check.digest = digest;
    check.tolerance = sizedFor(tol, pixelsOf(r, ci.name));
    const fs::path basePath = fs::path(j.baselines) / "images" / r.key / (ci.name + ci.extension);
    check.baseline = basePath.string();
    if (now && !j.remote) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        check.newExact = (dir / (ci.name + ".new" + ci.extension)).string();
        check.newPng = (dir / (ci.name + ".new.png")).string();
        // The very float bits, for `cavity baselines approve` to put into the
        // image store: an 8-bit PNG read back need not give the bits a
        // driver's readback gave (GL and Vulkan convert differently). First,
        // so that update and approve, which check them against gate.json's
        // digest, see any new image a killed run left.
        if (auto bits = render::writeImageFile((dir / (ci.name + ".new.f32z")).string(), *now, 1); !bits) return bits.error();
        CAVITY_TRY(writeImage(check.newExact, *now));
        if (ci.extension != ".png") CAVITY_TRY(writeImage(check.newPng, *now, Encoding::Preview));
    }
    const Approval* a = j.approvals.find(r.key, ci.name, digest, deviceClass(r.device));
    // An approval made before SHA-256 names the image by its FNV-1a digest.
    if (!a && now && j.approvals.legacy > 0)
        a = j.approvals.find(r.key, ci.name, core::legacyImageDigest(*now), deviceClass(r.device));
    if (a) {
        check.route = a->positive ? "digest" : "negative";
        check.approval = approvalText(*a);
        if (!a->positive) check.failures.push_back("digest " + digest + " is known bad: " + check.approval);
        return check;
    }
    if (!now) {
        if (const auto k = judged.find(ci.name); k != judged.end()) return fromRemote(check, k->second, r, j, ci.perceptual);
        return internal(r.label() + ": " + ci.name + " holds no pixels and its digest " + digest + " is not approved");
    }
    if (const Approval* ref = classReference(j, r, ci.name)) {
        // Its own class's reference: the default tolerances, and only the
        // device overrides of scope "all" (the others allow for another
        // device's rounding). A software renderer's approvals mark its
        // images unchanged by digest; where the image store does not hold
        // their pixels (a clone has none), a change is judged against the
        // stored baseline instead, which every clone has (docs/gate.md,
        // "Changed is a state of its own").
        auto base = j.reference(ref->digest);
        if (base || !software || !cavity::store::isMissingObject(base.error())) {
            check.tolerance = classTolerance(j, r, ci.name);
            check.reference = ref->deviceClass + " " + ref->api + "/" + ref->stage;
            check.referenceDigest = ref->digest;
            check.approval = approvalText(*ref);
            check.baseline = "store:" + ref->digest;
            CAVITY_ASSIGN(const HostImage image, std::move(base));
            CAVITY_TRY(judgeAgainst(check, ci, *now, image, dir, !j.remote));
            return check;
        }
    }
    if (j.remote) {
        check.route = "unjudged";
        return check;
    }
    check.reference = "default";
    CAVITY_TRY(judgeByTolerance(check, ci, *now, basePath, dir, errorCode));
    return check;
}

}  // namespace

Result<ConfigResult> judgeRendering(const render::Rendering& rend, const Judge& j, const ConfigResult* first) {
    ConfigResult r;
    r.id = rend.id;
    r.key = rend.key;
    r.config = rend.config;
    r.repetition = rend.repetition;
    r.device = rend.device.deviceName;
    r.driver = rend.device.driver;
    if (!rend.error.empty()) {
        r.error = rend.error;
        r.errorCode = rend.errorCode;
        return r;
    }
    r.deterministic = rend.deterministic;
    const Tolerance tol = j.manifest.forPipeline(rend.config.kernel, r.device);
    fs::path dir = fs::path(j.out) / "images" / r.id;
    if (rend.repetition > 0) dir /= "rep" + std::to_string(rend.repetition);
    for (const auto& ci : checkedImages()) {
        const std::string& digest = rend.digests.at(ci.name);
        const auto pixels = rend.images.find(ci.name);
        if (pixels == rend.images.end()) {
            const ImageCheck* same = nullptr;
            if (first)
                for (const auto& i : first->images)
                    if (i.image == ci.name && i.digest == digest) same = &i;
            if (same) {
                r.images.push_back(*same);
                continue;
            }
        }
        const HostImage* now = pixels == rend.images.end() ? nullptr : &pixels->second;
        auto check = judgeImage(ci, now, digest, r, j, tol, dir, r.errorCode, rend.judged, rend.device.softwareRenderer);
        // The store failing (5) or holding a damaged object (6) is this
        // configuration's error, not the run's end: the report is written
        // whole and says so, and the run exits with the store's code.
        if (!check && (check.error().code == ErrorCode::Unreachable || check.error().code == ErrorCode::Corrupt)) {
            r.error = check.error().message;
            r.errorCode = int(check.error().code);
            return r;
        }
        if (!check) return check.error();
        r.images.push_back(std::move(*check));
    }
    for (const auto& p : rend.timings) {
        TimingCheck t;
        t.pass = p.pass;
        t.medianMs = p.medianMs;
        t.lowMs = p.lowMs;
        t.highMs = p.highMs;
        t.clock = p.clock;
        t.budgetMs = j.budgets.find(r.device, r.id, p.pass);
        t.advisory = rend.device.softwareRenderer && !j.enforceCpuBudgets;
        r.timings.push_back(t);
    }
    return r;
}

}  // namespace cavity::gate
