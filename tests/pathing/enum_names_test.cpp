#include "pathing/enum_names.h"

#include <gtest/gtest.h>

#include "pathing/cluster_abstraction.h"
#include "pathing/planner.h"
#include "pathing/search.h"
#include "pathing/terrain.h"
#include "support/enum_round_trip.h"

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
  EXPECT_EQ(kColours.list(", ", " or "), "red, green or blue");  // the alias is not last
}

TEST(EnumNames, WorksAtCompileTime) {
  static_assert(kColours.parse("red") == Colour::Red);
  static_assert(kColours.name(Colour::Blue) == "blue");
}

// Every enum of pathing names each of its values through its table, and the names parse back.
TEST(EnumNames, PathingTablesRoundTrip) {
  using namespace pathing;
  testing::expectRoundTrip(kTerrainNames, {Terrain::Ground, Terrain::Swamp, Terrain::Trees,
                                           Terrain::Water, Terrain::Blocked});
  testing::expectRoundTrip(
      kAlgorithmNames, {Algorithm::AStar, Algorithm::HaaHigh, Algorithm::HaaLow, Algorithm::Hybrid,
                        Algorithm::Jps, Algorithm::JpsPlus});
  testing::expectRoundTrip(kPathStatusNames, {PathStatus::Found, PathStatus::Unreachable,
                                              PathStatus::InvalidStart, PathStatus::InvalidGoal,
                                              PathStatus::BudgetExhausted, PathStatus::Pending});
  testing::expectRoundTrip(kAbstractionQualityNames,
                           {AbstractionQuality::High, AbstractionQuality::Low});
}

// The named functions are the tables.
TEST(EnumNames, PathingFunctionsReadTheTables) {
  using namespace pathing;
  for (const auto& row : kTerrainNames.rows()) {
    EXPECT_EQ(terrainName(row.value), row.name);
    EXPECT_EQ(terrainFromName(row.name), row.value);
  }
  EXPECT_EQ(terrainFromName("WaTeR"), Terrain::Water);  // terrain names ignore case
  EXPECT_FALSE(terrainFromName("lava"));
  EXPECT_EQ(terrainName(static_cast<Terrain>(9)), "?");
  EXPECT_EQ(traversableTerrainNames(), "ground, swamp, trees, water");
  for (const auto& row : kAlgorithmNames.rows()) {
    EXPECT_EQ(toString(row.value), row.name);
    EXPECT_EQ(algorithmFromName(row.name), row.value);
  }
  EXPECT_FALSE(algorithmFromName("HAA-HQ"));
  for (const auto& row : kPathStatusNames.rows())
    EXPECT_EQ(toString(row.value), row.name);
}

}  // namespace
}  // namespace warpath
