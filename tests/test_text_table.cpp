// The text tables of run, quality and --help (harness/core/text_table.h): columns
// as wide as their widest cell, whatever the cells are.
#include "harness_names.h"
#include "core/text_table.h"

#include <gtest/gtest.h>

using namespace cavity::harness;

namespace {

using cavity::core::TextTable;
using A = TextTable::Align;

TEST(TextTable, ColumnsFitTheirWidestCell) {
    TextTable t({{"id", A::Left}, {"ms", A::Right}}, "  ");
    t.add({"short", TextTable::number(1.5, 3)});
    t.add({"a/much/longer/configuration/id/than/the/header", TextTable::number(12.25, 3)}, " !");
    EXPECT_EQ(t.str(),
              "id                                                  ms\n"
              "short                                            1.500\n"
              "a/much/longer/configuration/id/than/the/header  12.250 !\n");
}

TEST(TextTable, NoHeaderLineWithoutHeadersAndNoTrailingBlanks) {
    TextTable t({{"", A::Left}, {"", A::Left}});
    t.add({"alchemy", "one"});
    t.add({"ground_truth", "two"});
    EXPECT_EQ(t.str(), "alchemy      one\nground_truth two\n");
}

}  // namespace
