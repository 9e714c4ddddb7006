// A plain-text table for stdout: every column as wide as its widest cell,
// text left-aligned and numbers right-aligned, formatted by fmt (GCC 12 has no
// std::format). The run, quality and --help kernel tables use it.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace cavity::core {

class TextTable {
public:
    enum class Align { Left, Right };
    struct Column {
        std::string header;   // empty for every column: no header line
        Align align = Align::Left;
    };

    explicit TextTable(std::vector<Column> columns, std::string separator = " ");
    // One cell per column; the last may be followed by a suffix that takes no
    // width (a flag such as " !").
    void add(std::vector<std::string> cells, std::string suffix = "");
    std::string str() const;
    void print(std::FILE* out = stdout) const;

    // "0.123": a number with `decimals` after the point.
    static std::string number(double v, int decimals);

private:
    std::vector<Column> columns_;
    std::string separator_;
    std::vector<std::pair<std::vector<std::string>, std::string>> rows_;
};

}  // namespace cavity::core