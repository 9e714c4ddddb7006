// Headless Chromium, as the page tests look at our HTML: the report and run
// pages are built by their scripts from inlined data, so what a reader sees
// is the document Chromium holds once the script has run.
#pragma once

#include "gpu_fixture.h"
#include "run_binary.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace cavity::test {

// Not installed: a failure in CI (scripts/setup.sh installs it), a skip elsewhere.
#define REQUIRE_CHROMIUM()                                                                          \
    if (::cavity::test::runBinary("command", "-v chromium", "", ">/dev/null 2>&1").code != 0) {    \
        if (::cavity::test::inCI()) FAIL() << "chromium is not installed (scripts/setup.sh installs it)"; \
        GTEST_SKIP() << "chromium is not installed";                                               \
    }

inline const std::string kChromium =
    "120 chromium --headless=new --no-sandbox --disable-gpu --hide-scrollbars --window-size=1400,1000 ";

// The document of the page at `html` once its script has run, as Chromium serialises it.
inline std::string renderedDom(const std::filesystem::path& html) {
    const Outcome o = runBinary("timeout", kChromium + "--dump-dom file://" + html.string(), "", "2>/dev/null");
    EXPECT_EQ(o.code, 0) << html;
    return o.output;
}

}  // namespace cavity::test
