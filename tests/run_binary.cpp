#include "run_binary.h"

#include <array>
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

}  // namespace cavity::test
