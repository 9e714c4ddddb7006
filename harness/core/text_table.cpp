#include "core/text_table.h"

#include <fmt/format.h>

#include <algorithm>

namespace cavity::core {

TextTable::TextTable(std::vector<Column> columns, std::string separator)
    : columns_(std::move(columns)), separator_(std::move(separator)) {}

void TextTable::add(std::vector<std::string> cells, std::string suffix) {
    cells.resize(columns_.size());
    rows_.emplace_back(std::move(cells), std::move(suffix));
}

std::string TextTable::number(double v, int decimals) { return fmt::format("{:.{}f}", v, decimals); }

std::string TextTable::str() const {
    std::vector<size_t> width(columns_.size(), 0);
    const bool header = std::any_of(columns_.begin(), columns_.end(), [](const Column& c) { return !c.header.empty(); });
    for (size_t i = 0; i < columns_.size(); ++i) {
        if (header) width[i] = columns_[i].header.size();
        for (const auto& [cells, _] : rows_) width[i] = std::max(width[i], cells[i].size());
    }
    std::string out;
    auto line = [&](auto cellOf, const std::string& suffix) {
        std::string l;
        for (size_t i = 0; i < columns_.size(); ++i) {
            if (i) l += separator_;
            const bool last = i + 1 == columns_.size();
            const std::string& cell = cellOf(i);
            if (columns_[i].align == Align::Right) l += fmt::format("{:>{}}", cell, width[i]);
            // A left-aligned last column is not padded: no trailing blanks.
            else l += last && suffix.empty() ? cell : fmt::format("{:<{}}", cell, width[i]);
        }
        out += l + suffix + "\n";
    };
    if (header) line([&](size_t i) -> const std::string& { return columns_[i].header; }, "");
    for (const auto& [cells, suffix] : rows_) line([&](size_t i) -> const std::string& { return cells[i]; }, suffix);
    return out;
}

void TextTable::print(std::FILE* out) const {
    const std::string s = str();
    std::fwrite(s.data(), 1, s.size(), out);
}

}  // namespace cavity::core