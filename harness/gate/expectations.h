// Expected failures and known flakes per device class, after Mesa's
// deqp-runner `*-fails.txt` / `*-flakes.txt`: a driver with a known bug
// keeps the gate green on everything else, and the day the bug is fixed the
// entry says so (an unexpected pass fails the gate until it is removed).
//
// One file per device class, <baselines>/expectations/<class>.txt:
//
//     # comment
//     device llvmpipe                       regex on the device name; first line, once
//     fail   ^corner/ssdo/.*/gl/fragment$   reason, free text (required)
//     flake  ^slats/.*/vk/compute$          reason
//
// The id regex is searched in the configuration id (as --filter is). Every
// file of the folder applies to the devices its `device` line finds; for a
// configuration the first matching line of the first such file (files in
// name order) is its expectation. Loading is strict: an unknown word, a
// regex that does not compile, a missing reason or device line is a
// BadInput error naming FILE:LINE.
#pragma once

#include "gate/namespace.h"
#include "gate/gate.h"

#include <regex>
#include <string>
#include <vector>

namespace cavity::gate {

struct Expectation {
    std::string kind;       // "fail" or "flake"
    std::string pattern;    // the id regex as written
    std::regex re;
    std::string reason;
    std::string where;      // FILE:LINE
};

struct ExpectationFile {
    std::string path, devicePattern;
    std::regex device;
    std::vector<Expectation> entries;
};

struct Expectations {
    std::vector<ExpectationFile> files;
    const Expectation* find(const std::string& device, const std::string& id) const;
};

// Every *.txt in `dir`; a folder that does not exist holds none.
Result<Expectations> loadExpectations(const std::string& dir);
Result<ExpectationFile> parseExpectationFile(const std::string& path, const std::string& text);

// Sets expected/expectedWhy of each result its device's files list.
void applyExpectations(GateRun& run, const Expectations& e);

}  // namespace cavity::gate
