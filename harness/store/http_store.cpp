// The HTTP store: objects at <URL>/sha256/<hex>.f32z, read with GET (after
// a look in the local cache), probed with HEAD, written with PUT. Plain HTTP
// rather than S3's signed requests: every WebDAV server (nginx's dav module,
// Apache's mod_dav), an S3 or GCS bucket behind an HTTP gateway, Artifactory
// or a static file server answers GET, HEAD and PUT with nothing more than a
// token or a password, and nginx from Debian is a real server the tests can
// start (docs/store.md).
#include "store/store.h"
#include "printable.h"

#include "core/json_file.h"

#include <curl/curl.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>

namespace cavity::store {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxObjectBytes = size_t(1) << 30;

std::string envText(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

std::string cacheFolder(const std::string& given) {
    if (!given.empty()) return given;
    if (const std::string c = envText("CAVITY_STORE_CACHE"); !c.empty()) return c;
    if (const std::string x = envText("XDG_CACHE_HOME"); !x.empty()) return (fs::path(x) / "cavity" / "store").string();
    const std::string home = envText("HOME");
    return (fs::path(home.empty() ? "." : home) / ".cache" / "cavity" / "store").string();
}

size_t onBody(char* data, size_t size, size_t n, void* user) {
    auto* out = static_cast<std::string*>(user);
    if (out->size() + size * n > kMaxObjectBytes) return 0;   // CURLE_WRITE_ERROR
    out->append(data, size * n);
    return size * n;
}

struct Upload {
    const std::string* bytes;
    size_t at = 0;
};

size_t onUpload(char* buffer, size_t size, size_t n, void* user) {
    auto* u = static_cast<Upload*>(user);
    const size_t left = u->bytes->size() - u->at, take = std::min(left, size * n);
    std::copy_n(u->bytes->data() + u->at, take, buffer);
    u->at += take;
    return take;
}

struct Response {
    long status = 0;
    std::string body;
};

class HttpStore final : public ImageStore {
public:
    HttpStore(std::string url, std::string cache) : url_(std::move(url)), cache_(std::move(cache)) {
        if (!url_.empty() && url_.back() == '/') url_.pop_back();
    }
    std::string where() const override { return url_; }

    Result<std::string> getBytes(const std::string& digest) override {
        const fs::path cached = fs::path(cache_) / objectPath(digest);
        std::error_code ec;
        if (fs::is_regular_file(cached, ec)) {
            std::ifstream f(cached, std::ios::binary);
            std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
            if (decodeObject(bytes, digest, cached.string()).ok()) return bytes;
            fs::remove(cached, ec);   // damaged in the cache: fetched again below
        }
        CAVITY_ASSIGN(Response r, request("GET", digest, nullptr));
        if (r.status == 404) return unreachable("store " + url_ + ": no object " + digest + " (HTTP 404)");
        if (r.status != 200) return refused("GET", digest, r.status);
        CAVITY_TRY(decodeObject(r.body, digest, url_ + "/" + objectPath(digest)));
        fs::create_directories(cached.parent_path(), ec);
        // The cache is a convenience: an object that cannot be kept there is
        // still returned, and one that is kept is whole (written, then renamed).
        if (!ec) (void)writeFileAtomically(cached.string(), r.body);
        return std::move(r.body);
    }

    Result<bool> has(const std::string& digest) override {
        CAVITY_ASSIGN(Response r, request("HEAD", digest, nullptr));
        if (r.status == 200) return true;
        if (r.status == 404) return false;
        return refused("HEAD", digest, r.status);
    }

    Status put(const std::string& digest, const std::string& bytes) override {
        CAVITY_ASSIGN(Response r, request("PUT", digest, &bytes));
        if (r.status == 200 || r.status == 201 || r.status == 204) return {};
        return refused("PUT", digest, r.status);
    }

private:
    Error refused(const std::string& method, const std::string& digest, long status) const {
        const std::string head = "store " + url_ + ": " + method + " " + objectPath(digest) + ": HTTP " + std::to_string(status);
        if (status == 401)
            return unreachable(head + (method == "PUT" ? ": credentials missing, refused, or without write access"
                                                            : ": credentials missing or refused") +
                                    " (CAVITY_STORE_TOKEN, CAVITY_STORE_USER and CAVITY_STORE_PASSWORD, or a netrc file)");
        if (status == 403 || status == 405)
            return unreachable(head + (method == "PUT" ? ": these credentials may not write to the store"
                                                             : ": these credentials may not read the store"));
        return unreachable(head);
    }

    Result<Response> request(const std::string& method, const std::string& digest, const std::string* upload);

    std::string url_, cache_;
};

void globalInit() {
    static std::once_flag once;
    std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

struct Limits {
    long total = 600;   // CAVITY_STORE_TIMEOUT: seconds a request may take
    long stall = 30;    // CAVITY_STORE_STALL: seconds a transfer may stay under 1 KiB/s
};

// The time limits from the environment, each whole seconds in its range, or
// bad input naming the variable.
Result<Limits> limits() {
    Limits out;
    const auto read = [](const char* name, long lo, long hi, long& into) -> Status {
        const std::string v = envText(name);
        if (v.empty()) return {};
        char* end = nullptr;
        errno = 0;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (errno || end == v.c_str() || *end || n < lo || n > hi)
            return badInput(std::string(name) + "=" + v + ": must be whole seconds, " + std::to_string(lo) + ".." + std::to_string(hi));
        into = n;
        return {};
    };
    CAVITY_TRY(read("CAVITY_STORE_TIMEOUT", 1, 86400, out.total));
    CAVITY_TRY(read("CAVITY_STORE_STALL", 1, 3600, out.stall));
    // Credentials go into a request header: a line break in one would start
    // a header of its own. Their values are never shown.
    for (const char* name : {"CAVITY_STORE_TOKEN", "CAVITY_STORE_USER", "CAVITY_STORE_PASSWORD"}) {
        if (hasControlChar(envText(name)))
            return badInput(std::string(name) + ": holds a control character (a line break?); its value is not shown");
    }
    if (!envText("CAVITY_STORE_USER").empty() && envText("CAVITY_STORE_TOKEN").empty() && envText("CAVITY_STORE_PASSWORD").empty())
        return badInput("CAVITY_STORE_USER is set without CAVITY_STORE_PASSWORD (basic authentication takes both)");
    for (const char* name : {"CAVITY_STORE_NETRC", "CAVITY_STORE_CA"}) {
        const std::string v = envText(name);
        std::error_code ec;
        if (!v.empty() && (!std::filesystem::is_regular_file(v, ec) || !std::ifstream(v)))
            return badInput(std::string(name) + "=" + v + ": not a readable file");
    }
    return out;
}

// Credentials, CA and time limits from the environment; nothing of them is
// ever put into a message.
void configure(CURL* h, curl_slist*& headers) {
    if (const std::string token = envText("CAVITY_STORE_TOKEN"); !token.empty()) {
        headers = curl_slist_append(headers, ("Authorization: Bearer " + token).c_str());
        curl_easy_setopt(h, CURLOPT_HTTPHEADER, headers);
    } else if (const std::string user = envText("CAVITY_STORE_USER"); !user.empty()) {
        curl_easy_setopt(h, CURLOPT_HTTPAUTH, long(CURLAUTH_BASIC));
        curl_easy_setopt(h, CURLOPT_USERNAME, user.c_str());
        curl_easy_setopt(h, CURLOPT_PASSWORD, envText("CAVITY_STORE_PASSWORD").c_str());
    } else {
        curl_easy_setopt(h, CURLOPT_NETRC, long(CURL_NETRC_OPTIONAL));
        if (const std::string netrc = envText("CAVITY_STORE_NETRC"); !netrc.empty())
            curl_easy_setopt(h, CURLOPT_NETRC_FILE, netrc.c_str());
    }
    if (const std::string ca = envText("CAVITY_STORE_CA"); !ca.empty()) curl_easy_setopt(h, CURLOPT_CAINFO, ca.c_str());
    // Checked when the store was opened (limits()).
    const Limits l = limits().value();
    curl_easy_setopt(h, CURLOPT_TIMEOUT, l.total);
    curl_easy_setopt(h, CURLOPT_CONNECTTIMEOUT, std::min(l.total, 20L));
    // A server that accepts and never answers, or a transfer that stops
    // halfway, is below 1 KiB/s from then on: cut off after `stall` seconds,
    // long before the whole request's limit.
    curl_easy_setopt(h, CURLOPT_LOW_SPEED_LIMIT, 1024L);
    curl_easy_setopt(h, CURLOPT_LOW_SPEED_TIME, l.stall);
    curl_easy_setopt(h, CURLOPT_NOSIGNAL, 1L);
    curl_easy_setopt(h, CURLOPT_PROTOCOLS_STR, "http,https");
    curl_easy_setopt(h, CURLOPT_FOLLOWLOCATION, 0L);   // credentials go to this host only
}

std::string failureText(CURLcode c, const char* detail) {
    std::string why = detail[0] ? detail : curl_easy_strerror(c);
    if (c == CURLE_PEER_FAILED_VERIFICATION || c == CURLE_SSL_CACERT_BADFILE || c == CURLE_SSL_CONNECT_ERROR)
        return "TLS: " + why + " (certificates are always verified; give the server's CA with CAVITY_STORE_CA)";
    if (c == CURLE_OPERATION_TIMEDOUT && why.find("too slow") != std::string::npos)
        return "stalled: " + why + " (CAVITY_STORE_STALL sets how long, in seconds)";
    if (c == CURLE_OPERATION_TIMEDOUT) return why + " (CAVITY_STORE_TIMEOUT sets the limit in seconds)";
    if (c == CURLE_PARTIAL_FILE || c == CURLE_RECV_ERROR) return "the transfer broke off: " + why;
    return why;
}

Result<Response> HttpStore::request(const std::string& method, const std::string& digest, const std::string* upload) {
    globalInit();
    CURL* h = curl_easy_init();
    if (!h) return internal("store " + url_ + ": curl_easy_init failed");
    curl_slist* headers = nullptr;
    char detail[CURL_ERROR_SIZE] = {0};
    Response r;
    Upload up{upload};
    const std::string object = url_ + "/" + objectPath(digest);
    curl_easy_setopt(h, CURLOPT_URL, object.c_str());
    curl_easy_setopt(h, CURLOPT_ERRORBUFFER, detail);
    curl_easy_setopt(h, CURLOPT_WRITEFUNCTION, onBody);
    curl_easy_setopt(h, CURLOPT_WRITEDATA, &r.body);
    configure(h, headers);
    if (method == "HEAD") curl_easy_setopt(h, CURLOPT_NOBODY, 1L);
    if (upload) {
        curl_easy_setopt(h, CURLOPT_UPLOAD, 1L);
        curl_easy_setopt(h, CURLOPT_READFUNCTION, onUpload);
        curl_easy_setopt(h, CURLOPT_READDATA, &up);
        curl_easy_setopt(h, CURLOPT_INFILESIZE_LARGE, curl_off_t(upload->size()));
    }
    const CURLcode c = curl_easy_perform(h);
    curl_easy_getinfo(h, CURLINFO_RESPONSE_CODE, &r.status);
    curl_slist_free_all(headers);
    curl_easy_cleanup(h);
    if (c == CURLE_WRITE_ERROR)
        return corrupt("store " + url_ + ": " + objectPath(digest) + ": larger than " +
                            std::to_string(kMaxObjectBytes >> 20) + " MiB, no image object");
    if (c != CURLE_OK) return unreachable("store " + url_ + ": " + method + " " + objectPath(digest) + ": " + failureText(c, detail));
    return r;
}

}  // namespace

Result<std::unique_ptr<ImageStore>> httpStore(const std::string& url, const std::string& cacheDir, const std::string& source) {
    const size_t host = url.find("://") + 3;
    const size_t slash = url.find('/', host);
    if (url.substr(host, slash == std::string::npos ? std::string::npos : slash - host).find('@') != std::string::npos)
        return badInput(source + ": credentials in the URL are refused (they would be printed with it); give them in "
                        "CAVITY_STORE_TOKEN, CAVITY_STORE_USER and CAVITY_STORE_PASSWORD, or a netrc file");
    if (host >= url.size() || url[host] == '/') return badInput(source + " " + url + ": no host in the URL");
    // What libcurl would refuse at the first request (a port past 65535, a
    // bracket left open) is the flag's value, not an outage.
    std::unique_ptr<CURLU, void (*)(CURLU*)> parsed(curl_url(), curl_url_cleanup);
    if (const CURLUcode c = curl_url_set(parsed.get(), CURLUPART_URL, url.c_str(), 0); c != CURLUE_OK)
        return badInput(source + " " + url + ": not a usable URL (" + curl_url_strerror(c) + ")");
    if (const auto l = limits(); !l) return l.error();
    // A cache named by the user that cannot hold a folder is their mistake
    // (the default one is a convenience, used where it can be).
    const std::string named = !cacheDir.empty() ? "--store-cache" : !envText("CAVITY_STORE_CACHE").empty() ? "CAVITY_STORE_CACHE" : "";
    std::error_code ec;
    if (const std::string cache = cacheFolder(cacheDir);
        !named.empty() && (cache.find_first_not_of(" \t") == std::string::npos || hasControlChar(cache)))
        return badInput(named + " '" + printable(cache) + "': blank or with a control character (a folder)");
    if (const std::string cache = cacheFolder(cacheDir);
        !named.empty() && fs::exists(cache, ec) && !fs::is_directory(cache, ec))
        return badInput(named + " " + cache + ": not a folder (where an HTTP store's objects are cached)");
    return std::unique_ptr<ImageStore>(std::make_unique<HttpStore>(url, cacheFolder(cacheDir)));
}

}  // namespace cavity::store
