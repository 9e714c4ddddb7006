// The image store: approved reference images kept under their digest,
// outside the git history. The repository keeps only the digests
// (baselines/approvals.json) and the tolerances; the pixels live here.
//
// An object is one image in the render-folder format (render/image_file.h,
// "cavity.f32z/1": the exact float32 pixels, zlib, readable with no
// OpenImageIO), named by the digest of its pixels:
//
//   <store>/sha256/<64 hex digits>.f32z
//
// (and <store>/fnv1a64/<16 hex digits>.f32z for images approved before
// SHA-256, read until they are migrated: core/digest.h).
//
// Every read decodes the object and checks that its pixels have the digest
// they are filed under, so a damaged or substituted object is never judged
// against. Stores:
//   a folder      (a path or file://...): the embedded default, no server;
//   HTTP(S)       (http://... or https://...): plain GET, HEAD and PUT, as a
//                 WebDAV server (nginx, Apache), an object store's HTTP
//                 gateway or any static file server answers them; read
//                 through a local cache folder (docs/store.md).
// Credentials come from the environment (CAVITY_STORE_TOKEN, or
// CAVITY_STORE_USER and CAVITY_STORE_PASSWORD) or a netrc file, never from
// the URL, and never appear in a message.
#pragma once

#include "store/namespace.h"
#include "core/image.h"
#include "result.h"

#include <memory>
#include <string>

namespace cavity::store {

// Is `digest` a digest objects can be filed under ("sha256:" and 64
// lower-case hex digits, or an older "fnv1a64:" and 16)? Anything else could
// name a path outside the store.
bool validDigest(const std::string& digest);
// "sha256/<64 hex digits>.f32z" (or "fnv1a64/<16 hex digits>.f32z")
std::string objectPath(const std::string& digest);

class ImageStore {
public:
    virtual ~ImageStore() = default;
    // The store as it may be printed: a folder, or a URL (which never holds
    // credentials).
    virtual std::string where() const = 0;
    // The object's bytes as stored. Not yet checked against the digest:
    // getImage() does that.
    virtual Result<std::string> getBytes(const std::string& digest) = 0;
    virtual Result<bool> has(const std::string& digest) = 0;
    // Stores `bytes` under `digest`; the object appears whole or not at all.
    virtual Status put(const std::string& digest, const std::string& bytes) = 0;
};

struct StoreOptions {
    std::string location;   // folder, file://, http:// or https:// URL
    // Where an HTTP store's objects are cached; empty: $CAVITY_STORE_CACHE,
    // else $XDG_CACHE_HOME/cavity/store, else ~/.cache/cavity/store.
    std::string cache;
    // What the location came from, for messages: the flag, or CAVITY_STORE.
    std::string source = "--store";
};

// The store of `--store`, checked for what can be checked without a
// request (the folder is a folder, the URL has no credentials in it).
// `flag` names the flag in messages.
Result<std::unique_ptr<ImageStore>> openStore(const StoreOptions& o);

// The default location: $CAVITY_STORE, else <baselines>/store.
std::string defaultLocation(const std::string& baselines);
// Fills an empty o.location from defaultLocation, naming CAVITY_STORE as its
// source when the variable gave it.
void fillDefault(StoreOptions& o, const std::string& baselines);

// Bytes of an object decoded and checked against the digest they are filed
// under (`label` names them in messages): anything else is
// ErrorCode::Corrupt.
Result<HostImage> decodeObject(const std::string& bytes, const std::string& digest, const std::string& label);
// The image filed under `digest`, decoded and checked (decodeObject).
Result<HostImage> getImage(ImageStore& s, const std::string& digest);
// Whether `e` says the store answered and holds no object of the digest (a
// folder without the file, HTTP 404), as against a store that could not be
// reached or sent a corrupt object.
bool isMissingObject(const Error& e);
// Encodes and stores `image` under its own digest; returns the digest.
Result<std::string> putImage(ImageStore& s, const HostImage& image);

// A folder store; `root` need not exist until the first put.
std::unique_ptr<ImageStore> folderStore(const std::string& root);
// An HTTP store read through a cache folder (http_store.cpp). Refuses a URL
// with credentials in it.
Result<std::unique_ptr<ImageStore>> httpStore(const std::string& url, const std::string& cacheDir,
                                              const std::string& source = "--store");

}  // namespace cavity::store
