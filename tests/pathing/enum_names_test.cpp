#include "pathing/enum_names.h"

#include <gtest/gtest.h>

namespace warpath {
namespace {

enum class Colour { Red, Green, Blue };
constexpr EnumNames<Colour, 4> kColours{{{
    {Colour::Red, "red"},
    {Colour::Green, "green"},
    {Colour::Green, "verdant"},  // alias
    {Colour::Blue, "blue"},
}}};

TEST(EnumNames, NamesAreTheFirstRowOfEachValue) {
  EXPECT_EQ(kColours.name(Colour::Red), "red");
  EXPECT_EQ(kColours.name(Colour::Green), "green");
  EXPECT_EQ(kColours.name(static_cast<Colour>(7)), "?");
}

TEST(EnumNames, ParseAcceptsEverySpellingAndNothingElse) {
  EXPECT_EQ(kColours.parse("blue"), Colour::Blue);
  EXPECT_EQ(kColours.parse("verdant"), Colour::Green);
  EXPECT_EQ(kColours.parse("Blue"), std::nullopt);
  EXPECT_EQ(kColours.parse(""), std::nullopt);
}

TEST(EnumNames, ListShowsCanonicalNamesOnly) {
  EXPECT_EQ(kColours.list(), "red, green, blue");
  EXPECT_EQ(kColours.list("|"), "red|green|blue");
}

TEST(EnumNames, WorksAtCompileTime) {
  static_assert(kColours.parse("red") == Colour::Red);
  static_assert(kColours.name(Colour::Blue) == "blue");
}

}  // namespace
}  // namespace warpath
