#include "plan/approvals.h"

#include "core/digest.h"
#include "core/json_file.h"
#include "core/json_input.h"

#include <cctype>
#include <filesystem>

namespace cavity::plan {

namespace fs = std::filesystem;
using nlohmann::json;

const Approval* Approvals::find(const std::string& key, const std::string& image, const std::string& digest,
                                const std::string& deviceClass) const {
    const Approval* positive = nullptr;
    for (const auto& a : entries) {
        if (a.key != key || a.image != image || a.digest != digest) continue;
        if (!a.positive) return &a;
        if (a.deviceClass == deviceClass) positive = &a;
    }
    return positive;
}

const Approval* Approvals::reference(const std::string& key, const std::string& image, const std::string& deviceClass,
                                     const std::string& api, const std::string& stage) const {
    const Approval* best = nullptr;
    int bestScore = -1;
    for (const auto& a : entries) {
        if (!a.positive || a.key != key || a.image != image || a.deviceClass != deviceClass) continue;
        const int score = 2 * (a.api == api) + (a.stage == stage);
        if (score > bestScore || (score == bestScore && a.when >= best->when)) {
            best = &a;
            bestScore = score;
        }
    }
    return best;
}

std::string deviceClass(const std::string& deviceName) {
    const std::string name = deviceName.substr(0, std::min(deviceName.find(" ("), deviceName.find('/')));
    std::string out;
    for (char c : name) {
        if (std::isalnum(static_cast<unsigned char>(c))) out += char(std::tolower(static_cast<unsigned char>(c)));
        else if (!out.empty() && out.back() != '-') out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    return out.empty() ? "unknown" : out;
}

Result<Approvals> loadApprovals(const std::string& path) {
    Approvals a;
    std::error_code ec;
    if (!fs::exists(path, ec)) return a;
    CAVITY_ASSIGN(const json doc, readJsonFile(path));
    CAVITY_ASSIGN(const JsonObject top, JsonObject::of(path, "", doc));
    CAVITY_TRY(top.onlyKeys({"schema", "approvals"}));
    CAVITY_ASSIGN(const std::string schema, top.str("schema"));
    if (schema != "cavity.approvals/1") return top.bad("schema", "must be cavity.approvals/1");
    CAVITY_ASSIGN(const auto list, top.objects("approvals"));
    for (const auto& e : list) {
        CAVITY_TRY(e.onlyKeys({"key", "image", "digest", "verdict", "device_class", "api", "stage", "driver", "by", "when", "why"}));
        Approval x;
        std::string verdict;
        for (auto [field, out] : {std::pair{"key", &x.key}, {"image", &x.image}, {"digest", &x.digest}, {"verdict", &verdict},
                                  {"device_class", &x.deviceClass}, {"api", &x.api}, {"stage", &x.stage},
                                  {"driver", &x.driver}, {"by", &x.by}, {"when", &x.when}, {"why", &x.why}}) {
            CAVITY_ASSIGN(*out, e.str(field));
        }
        if (verdict != "positive" && verdict != "negative") return e.bad("verdict", "must be positive or negative");
        if (!core::isImageDigest(x.digest))
            return e.bad("digest", "must be sha256: and 64 lower-case hex digits (or, approved before SHA-256, "
                                   "fnv1a64: and 16)");
        // Classes, APIs and stages that a render can produce, and no other:
        // an entry no render can match is a typo that approves nothing.
        if (x.deviceClass.empty() || x.deviceClass == "unknown" || deviceClass(x.deviceClass) != x.deviceClass)
            return e.bad("device_class", "must be a device class as cavity names one (lower case, words joined by '-', "
                                         "e.g. nvidia-h200, llvmpipe)");
        if (x.api != "gl" && x.api != "vk") return e.bad("api", "must be gl or vk");
        if (x.stage != "compute" && x.stage != "fragment") return e.bad("stage", "must be compute or fragment");
        if (x.key.empty()) return e.bad("key", "must name a baseline (e.g. corner/alchemy/n16/b4/full/160x90)");
        x.positive = verdict == "positive";
        a.legacy += core::isLegacyDigest(x.digest);
        a.entries.push_back(std::move(x));
    }
    return a;
}

Status saveApprovals(const std::string& path, const Approvals& a) {
    json list = json::array();
    for (const auto& x : a.entries)
        list.push_back({{"key", x.key}, {"image", x.image}, {"digest", x.digest},
                        {"verdict", x.positive ? "positive" : "negative"}, {"device_class", x.deviceClass}, {"api", x.api},
                        {"stage", x.stage}, {"driver", x.driver}, {"by", x.by}, {"when", x.when}, {"why", x.why}});
    // One approval a line: the file grows by a line per image a review
    // approves, and a diff shows which.
    std::string text = "{\n  \"schema\": \"cavity.approvals/1\",\n  \"approvals\": [";
    for (size_t i = 0; i < list.size(); ++i) text += (i ? ",\n    " : "\n    ") + core::jsonText(list[i]);
    text += list.empty() ? "]\n}\n" : "\n  ]\n}\n";
    return writeFileAtomically(path, text);
}

}  // namespace cavity::plan
