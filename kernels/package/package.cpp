#include "package/package.h"

#include "package/declaration.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cavity::kernels {

const std::map<std::string, std::string>& embeddedSources();   // kernel_sources.cpp

namespace {

namespace fs = std::filesystem;

std::vector<PackageInfo>& loaded() {
    static std::vector<PackageInfo> list;
    return list;
}

std::map<std::string, PackageSource>& sources() {
    static std::map<std::string, PackageSource> map;
    return map;
}

// A package's files are its GLSL (with includes of its own) and kernel.toml;
// anything larger than this is not a shader.
constexpr std::uintmax_t kMaxFileBytes = 1 << 20;

Result<std::string> readText(const fs::path& p) {
    std::error_code ec;
    const auto size = fs::file_size(p, ec);
    if (ec) return badInput(p.string() + ": cannot read: " + ec.message());
    if (size > kMaxFileBytes) return badInput(p.string() + ": " + std::to_string(size) + " bytes; a package file is at most 1 MiB");
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) return badInput(p.string() + ": cannot read");
    std::string text = s.str();
    if (text.find('\0') != std::string::npos) return badInput(p.string() + ": a NUL byte; a package file is text");
    return text;
}

bool taken(const std::vector<KernelDecl>& registry, const std::string& name) {
    return std::any_of(registry.begin(), registry.end(), [&](const KernelDecl& k) { return k.name == name; });
}

// One package folder from disk: its declaration, then its GLSL under the
// keys "<name>/<path in the folder>", each labelled with its path on disk.
Status loadFolder(const fs::path& folder, std::vector<KernelDecl>& registry) {
    const fs::path decl = folder / "kernel.toml";
    std::error_code ec;
    if (!fs::is_regular_file(decl, ec))
        return badInput(decl.string() + ": " + (ec ? ec.message() : std::string("not a file")) +
                        " (a package folder holds its declaration, kernel.toml)");
    CAVITY_ASSIGN(const std::string text, readText(decl));
    std::map<std::string, std::string> glsl;   // path in the folder -> text
    const fs::path inside = fs::weakly_canonical(folder, ec);
    // A link in a circle or a folder that cannot be read is the package's
    // error, said in one line, not an exception.
    try {
        for (const auto& e : fs::recursive_directory_iterator(folder)) {
            // A package inside a package would be read as the outer one's
            // files and never loaded: said, not left unseen.
            if (e.path().filename() == "kernel.toml" && e.path().parent_path() != folder)
                return badInput(e.path().string() + ": a package inside the package " + folder.string() +
                                " is not loaded; put it beside it (a folder of packages is read one level deep)");
            if (e.path().extension() != ".glsl") continue;
            if (!e.is_regular_file(ec))
                return badInput(e.path().string() + ": " + (ec ? ec.message() : std::string("not a regular file")) +
                                " (a package's GLSL files are plain files)");
            // Named by its own path in the folder (a link too); a link
            // that leads out of the folder is not the package's file.
            const auto target = fs::weakly_canonical(e.path(), ec).lexically_relative(inside);
            if (target.empty() || *target.begin() == "..") continue;
            CAVITY_ASSIGN(std::string body, readText(e.path()));
            glsl[e.path().lexically_relative(folder).generic_string()] = std::move(body);
        }
    } catch (const fs::filesystem_error& e) {
        return badInput(e.path1().string() + ": cannot be read (" + e.code().message() + ")");
    }
    PackageInfo info;
    DeclarationInput in{text, decl.string(), "", [&](const std::string& f) { return glsl.count(f) > 0; },
                        [&](const std::string& n) { return taken(registry, n); }, false};
    CAVITY_ASSIGN(KernelDecl k, readDeclaration(in, info));
    // An output no code writes would stay as it was made, black, and a run
    // would time and judge that image: refused before anything runs.
    // (cavity kernels check says it again from the compiled shader.)
    std::string code = sourceFile(k.file) ? *sourceFile(k.file) : std::string();
    for (const auto& [path, body] : glsl) code += body;
    for (const auto& o : k.outputs)
        if (code.find("write_" + o.name) == std::string::npos)
            return badInput(decl.string() + ": outputs: '" + o.name + "' is declared, but the package's GLSL never calls write_" +
                            o.name + " (its image would stay black)");
    // Its files' keys start with its name, which no other kernel has.
    if (glsl.count(k.file)) k.file = k.name + "/" + k.file;
    info.folder = folder.string();
    for (auto& [path, body] : glsl) {
        const std::string key = k.name + "/" + path;
        sources()[key] = {std::move(body), (folder / path).string()};
        info.sourceKeys.push_back(key);
    }
    registry.push_back(std::move(k));
    loaded().push_back(std::move(info));
    return {};
}

}  // namespace

const std::vector<PackageInfo>& packages() { return loaded(); }

const PackageInfo* findPackage(const std::string& kernel) {
    for (const auto& p : loaded())
        if (p.name == kernel) return &p;
    return nullptr;
}

const PackageSource* packageSource(const std::string& key) {
    const auto it = sources().find(key);
    return it == sources().end() ? nullptr : &it->second;
}

std::string packageKeyOfFile(const std::string& path) {
    if (path.find('/') == std::string::npos) return "";
    std::error_code ec;
    const fs::path given = fs::weakly_canonical(path, ec);
    for (const auto& p : loaded())
        for (const auto& key : p.sourceKeys)
            if (const PackageSource* src = packageSource(key);
                src && !ec && key.ends_with(".glsl") && fs::weakly_canonical(src->label, ec) == given)
                return key;
    return "";
}

Status loadPackages(const std::string& dir) {
    std::error_code ec;
    if (fs::is_regular_file(dir, ec))
        return badInput(dir + ": is a file; give the package's folder (the one holding kernel.toml) or a folder of them");
    if (!fs::is_directory(dir, ec)) return badInput(dir + ": no such folder");
    // A folder named twice (CAVITY_KERNELS, which --kernels passes on to the
    // programs a command starts, and the same --kernels again) loads once.
    static std::set<std::string> done;
    const std::string canonical = fs::weakly_canonical(dir, ec).string();
    if (done.count(canonical)) return {};
    // "pkgs/mine/" (as shell completion writes it) is the folder "pkgs/mine":
    // its kernel.toml's parent is compared with it below.
    fs::path base = fs::path(dir).lexically_normal();
    if (base.filename().empty() && base.has_relative_path()) base = base.parent_path();
    std::vector<fs::path> folders;
    if (fs::exists(fs::symlink_status(base / "kernel.toml", ec))) {
        folders.push_back(base);
    } else {
        const auto at = [&](const fs::directory_entry& e) {
            std::error_code e2;
            return fs::exists(fs::symlink_status(e.path() / "kernel.toml", e2));
        };
        for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
            if (std::error_code e2; it->is_directory(e2) && at(*it)) folders.push_back(it->path());
        if (ec) return badInput(dir + ": cannot be read (" + ec.message() + ")");
        if (folders.empty()) return badInput(dir + ": no kernel.toml in it or in any folder directly under it");
        std::sort(folders.begin(), folders.end());
    }
    // All or nothing: a copy of the registry takes the folder's packages, and
    // replaces the real one only when every one of them loaded.
    std::vector<KernelDecl> registry = all();
    const size_t before = loaded().size(), params = paramDecls().size();
    // A package loaded already through another path (--kernels pkgs and
    // --kernels pkgs/mine) is the same package, not a second of its name.
    std::erase_if(folders, [&](const fs::path& f) {
        return std::any_of(loaded().begin(), loaded().end(), [&](const PackageInfo& p) {
            std::error_code e;
            return !p.builtIn && fs::weakly_canonical(p.folder, e) == fs::weakly_canonical(f, e);
        });
    });
    for (const auto& f : folders) {
        if (Status s = loadFolder(f, registry); !s) {
            for (size_t i = before; i < loaded().size(); ++i)
                for (const auto& key : loaded()[i].sourceKeys) sources().erase(key);
            loaded().resize(before);
            forgetParamsAfter(params);
            return s;
        }
    }
    registryForTests() = std::move(registry);
    done.insert(canonical);
    return {};
}

void appendBuiltInPackages(std::vector<KernelDecl>& registry) {
    const auto& files = embeddedSources();
    for (const auto& [key, text] : files) {
        // "ao/<name>/kernel.toml" or "passes/<name>/kernel.toml"
        if ((key.rfind("ao/", 0) != 0 && key.rfind("passes/", 0) != 0) || key.size() < 16 ||
            key.compare(key.size() - 12, 12, "/kernel.toml") != 0)
            continue;
        const std::string folder = key.substr(0, key.size() - 12);
        PackageInfo info;
        DeclarationInput in{text, "kernels/" + key, folder + "/",
                            [&](const std::string& f) { return files.count(folder + "/" + f) > 0; },
                            [&](const std::string& n) { return taken(registry, n); }, true, false};
        auto k = readDeclaration(in, info);
        if (!k) throw std::logic_error("built-in kernel package: " + k.error().message);
        info.folder = "kernels/" + folder;
        info.builtIn = true;
        for (const auto& [other, body] : files)
            if (other.rfind(folder + "/", 0) == 0 && other != key) info.sourceKeys.push_back(other);
        registry.push_back(std::move(*k));
        loaded().push_back(std::move(info));
    }
}

Status loadPackagesFromCommandLine(std::vector<std::string>& args) {
    if (const char* env = std::getenv("CAVITY_KERNELS"); env && *env) {
        std::string list = env;
        for (size_t start = 0; start <= list.size();) {
            const size_t end = std::min(list.find(':', start), list.size());
            const std::string dir = list.substr(start, end - start);
            if (!dir.empty())
                if (Status s = loadPackages(dir); !s) return badInput("CAVITY_KERNELS=" + list + ": " + s.error().message);
            start = end + 1;
        }
    }
    std::string flagged;   // ":DIR" for each --kernels folder loaded
    for (size_t i = 0; i < args.size();) {
        std::string dir;
        size_t take = 0;
        if (args[i] == "--kernels") {
            if (i + 1 >= args.size() || args[i + 1].empty() || args[i + 1].rfind("--", 0) == 0)
                return badInput("--kernels: a folder is required (a kernel package, or a folder of them)");
            dir = args[i + 1], take = 2;
        } else if (args[i].rfind("--kernels=", 0) == 0) {
            dir = args[i].substr(10), take = 1;
            if (dir.empty()) return badInput("--kernels: a folder is required (a kernel package, or a folder of them)");
        } else {
            ++i;
            continue;
        }
        if (Status s = loadPackages(dir); !s) return badInput("--kernels " + dir + ": " + s.error().message);
        std::error_code ec;
        flagged.push_back(':');
        flagged.append(fs::absolute(dir, ec).string());
        args.erase(args.begin() + long(i), args.begin() + long(i + take));
    }
    // The programs a command starts (cavity ab's two builds) load what it
    // loaded: through CAVITY_KERNELS, in absolute paths.
    if (!flagged.empty()) {
        std::string list(std::getenv("CAVITY_KERNELS") ? std::getenv("CAVITY_KERNELS") : "");
        list.append(flagged, list.empty() ? 1 : 0, std::string::npos);
        ::setenv("CAVITY_KERNELS", list.c_str(), 1);
    }
    return {};
}

Status loadPackagesFromCommandLine(int& argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    CAVITY_TRY(loadPackagesFromCommandLine(args));
    // Keep argv's own strings: copy the survivors back in order.
    int out = 1;
    for (int i = 1; i < argc && out <= int(args.size()); ++i)
        if (args[size_t(out - 1)] == argv[i]) argv[out++] = argv[i];
    argc = out;
    return {};
}

}  // namespace cavity::kernels
