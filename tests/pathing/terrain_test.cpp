#include "pathing/terrain.h"

#include <gtest/gtest.h>

namespace warpath::pathing {
namespace {

TEST(CapabilityTest, ParsesNamesInAnyCaseAndOrder) {
  std::string error;
  const auto cap = parseCapability("Swamp, ground", &error);
  ASSERT_TRUE(cap) << error;
  EXPECT_EQ(*cap, Capability::of({Terrain::Ground, Terrain::Swamp}));
  EXPECT_EQ(cap->toString(), "ground,swamp");
}

TEST(CapabilityTest, RejectsUnknownEmptyAndBlockedNames) {
  std::string error;
  EXPECT_FALSE(parseCapability("ground,lava", &error));
  EXPECT_EQ(error, "'lava' is not a traversable terrain (ground, swamp, trees, water)");
  EXPECT_FALSE(parseCapability("ground,", &error));
  EXPECT_EQ(error, "empty terrain name in capability");
  EXPECT_FALSE(parseCapability("blocked", &error));
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
