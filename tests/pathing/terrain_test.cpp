#include "pathing/terrain.h"

#include <gtest/gtest.h>

namespace warpath::pathing {
namespace {

TEST(CapabilityTest, ParsesNamesInAnyCaseAndOrder) {
  const auto cap = parseCapability("Swamp, ground");
  ASSERT_TRUE(cap) << cap.error().describe();
  EXPECT_EQ(cap.value(), Capability::of({Terrain::Ground, Terrain::Swamp}));
  EXPECT_EQ(cap.value().toString(), "ground,swamp");
}

TEST(CapabilityTest, RejectsUnknownEmptyAndBlockedNames) {
  const auto lava = parseCapability("ground,lava");
  ASSERT_FALSE(lava);
  EXPECT_EQ(lava.error().describe(),
            "'lava' is not a traversable terrain (ground, swamp, trees, water)");
  const auto empty = parseCapability("ground,");
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().describe(), "empty terrain name in capability");
  EXPECT_FALSE(parseCapability("blocked"));
}

TEST(CapabilityTest, SubsetAndMembership) {
  const Capability ground = Capability::of({Terrain::Ground});
  const Capability amphibious = Capability::of({Terrain::Ground, Terrain::Swamp, Terrain::Water});
  EXPECT_TRUE(ground.isSubsetOf(amphibious));
  EXPECT_FALSE(amphibious.isSubsetOf(ground));
  EXPECT_TRUE(amphibious.allows(Terrain::Water));
  EXPECT_FALSE(amphibious.allows(Terrain::Trees));
  EXPECT_FALSE(amphibious.allows(Terrain::Blocked));
  EXPECT_EQ(Capability{}.toString(), "none");
}

TEST(CapabilityTest, MovingAiClasses) {
  EXPECT_EQ(movingAiClassOf(Terrain::Ground), movingAiClassOf(Terrain::Swamp));
  EXPECT_EQ(movingAiClassOf(Terrain::Water), Capability::of({Terrain::Water}));
  EXPECT_EQ(movingAiClassOf(Terrain::Trees), Capability::of({Terrain::Trees}));
  EXPECT_TRUE(movingAiClassOf(Terrain::Blocked).empty());
}

}  // namespace
}  // namespace warpath::pathing
