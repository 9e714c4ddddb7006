#include "run_binary.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <fstream>
#include <cstdio>
#include <sys/wait.h>

namespace cavity::test {

Outcome runBinary(const std::string& binary, const std::string& args, const std::string& env, const std::string& redirect) {
    const std::string cmd = env + " " + binary + " " + args + " " + redirect;
    Outcome o;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return o;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) o.output.append(buf.data(), n);
    const int status = pclose(p);
    o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return o;
}

void dropCpuApprovals(const std::string& baselines) {
    const std::string path = baselines + "/approvals.json";
    std::ifstream in(path);
    auto doc = nlohmann::json::parse(in);
    auto& list = doc["approvals"];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [](const nlohmann::json& a) { return a.value("device_class", "") == "llvmpipe"; }),
               list.end());
    std::ofstream(path, std::ios::trunc) << doc.dump(2) << "\n";
}

}  // namespace cavity::test
