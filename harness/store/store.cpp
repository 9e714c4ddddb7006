#include "store/store.h"
#include "printable.h"

#include "core/digest.h"
#include "core/json_file.h"
#include "render/image_file.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace cavity::store {

namespace fs = std::filesystem;

namespace {

class FolderStore final : public ImageStore {
public:
    explicit FolderStore(std::string root) : root_(std::move(root)) {}
    std::string where() const override { return root_; }

    Result<std::string> getBytes(const std::string& digest) override {
        const fs::path p = fs::path(root_) / objectPath(digest);
        std::error_code ec;
        if (!fs::is_regular_file(p, ec))
            return unreachable("store " + root_ + ": no object " + digest + " (" + p.string() + ")");
        std::ifstream f(p, std::ios::binary);
        if (!f) return unreachable("store " + root_ + ": cannot read " + p.string());
        return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    }

    Result<bool> has(const std::string& digest) override {
        std::error_code ec;
        return fs::is_regular_file(fs::path(root_) / objectPath(digest), ec);
    }

    Status put(const std::string& digest, const std::string& bytes) override {
        const fs::path p = fs::path(root_) / objectPath(digest);
        std::error_code ec;
        fs::create_directories(p.parent_path(), ec);
        if (ec) return unreachable("store " + root_ + ": cannot create " + p.parent_path().string() + ": " + ec.message());
        return writeFileAtomically(p.string(), bytes);
    }

private:
    std::string root_;
};

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

}  // namespace

bool validDigest(const std::string& digest) { return core::isImageDigest(digest); }

std::string objectPath(const std::string& digest) {
    const size_t colon = digest.find(':');
    return digest.substr(0, colon) + "/" + digest.substr(colon + 1) + ".f32z";
}

std::string defaultLocation(const std::string& baselines) {
    const std::string fromEnv = env("CAVITY_STORE");
    return fromEnv.empty() ? (fs::path(baselines) / "store").string() : fromEnv;
}

std::unique_ptr<ImageStore> folderStore(const std::string& root) { return std::make_unique<FolderStore>(root); }

void fillDefault(StoreOptions& o, const std::string& baselines) {
    if (!o.location.empty()) return;
    o.location = defaultLocation(baselines);
    if (!env("CAVITY_STORE").empty()) o.source = "CAVITY_STORE";
}

Result<std::unique_ptr<ImageStore>> openStore(const StoreOptions& o) {
    const std::string& at = o.location;
    const std::string& flag = o.source;
    if (at.empty()) return badInput(flag + ": empty (a folder, or an http:// or https:// URL)");
    // " " would be a folder named by a space: a variable set by mistake.
    if (at.find_first_not_of(" \t") == std::string::npos || hasControlChar(at))
        return badInput(flag + " '" + printable(at) + "': blank or with a control character (a folder, or an http:// or "
                        "https:// URL)");
    if (at.rfind("http://", 0) == 0 || at.rfind("https://", 0) == 0) return httpStore(at, o.cache, flag);
    std::string root = at;
    if (root.rfind("file://", 0) == 0) {
        root = root.substr(7);
        if (root.rfind("localhost/", 0) == 0) root = root.substr(9);
        // file://HOST/path names another machine's file: only this one's.
        if (root.empty() || root[0] != '/')
            return badInput(flag + " " + at + ": a file:// URL takes an absolute path on this machine (file:///path)");
    }
    else if (root.find("://") != std::string::npos)
        return badInput(flag + " " + at + ": unknown scheme (a folder, file://, http:// or https://)");
    std::error_code ec;
    if (fs::exists(root, ec) && !fs::is_directory(root, ec))
        return badInput(flag + " " + root + ": not a folder (a store is a folder or a URL)");
    return folderStore(root);
}

Result<HostImage> getImage(ImageStore& s, const std::string& digest) {
    if (!validDigest(digest))
        return badInput("digest '" + digest + "': not sha256: and 64 hex digits (nor an older fnv1a64: and 16)");
    CAVITY_ASSIGN(const std::string bytes, s.getBytes(digest));
    return decodeObject(bytes, digest, s.where() + "/" + objectPath(digest));
}

Result<HostImage> decodeObject(const std::string& bytes, const std::string& digest, const std::string& label) {
    auto image = render::decodeImage(bytes, label);
    if (!image) return corrupt(image.error().message);
    if (const std::string actual = core::imageDigestLike(*image, digest); actual != digest)
        return corrupt(label + ": corrupt: its pixels have digest " + actual + ", not " + digest);
    return image;
}

Result<std::string> putImage(ImageStore& s, const HostImage& image) {
    const std::string digest = imageDigest(image);
    CAVITY_TRY(s.put(digest, render::encodeImage(image)));
    return digest;
}

bool isMissingObject(const Error& e) {
    return e.code == ErrorCode::Unreachable && e.message.find(": no object ") != std::string::npos;
}

}  // namespace cavity::store
