// Chart.js, as Debian packages it (libjs-chart.js), embedded in the binary at
// build time: the pages that chart inline it, so that they open from a file
// with no network.
#pragma once

#include <string>

namespace cavity::core {

// The library's minified text, ready to go inside a <script> element.
const std::string& chartLibrary();

// Inside <script>, "</" would end the element: JSON text may write it "<\/".
std::string scriptSafeJson(std::string jsonText);

}  // namespace cavity::core
