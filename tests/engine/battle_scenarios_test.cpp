// The three bundled battles: their expectations hold, each run is deterministic, and each has
// a variant in which an expectation fails, so the expectations are not vacuous.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "support/sanitized.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

std::string readScenario(const std::string& name) {
  std::ifstream in(testing::kScenariosDir + name + ".yaml");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// `text` with the first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

Report play(const std::string& text, const std::string& name) {
  Result<Scenario> s = parseScenario(text, testing::kScenariosDir + name + ".yaml");
  EXPECT_TRUE(s.ok()) << s.error().describe();
  if (!s.ok()) return {};
  ScenarioRun run(s.value());
  while (!run.done())
    run.step();
  return run.report();
}

const ExpectationResult* find(const Report& report, const std::string& text) {
  for (const ExpectationResult& e : report.expectations)
    if (e.text == text) return &e;
  ADD_FAILURE() << "no expectation '" << text << "'";
  return nullptr;
}

class BundledBattle : public ::testing::TestWithParam<const char*> {};

TEST_P(BundledBattle, HoldsItsExpectationsAndReplaysIdentically) {
  const std::string text = readScenario(GetParam());
  const Report first = play(text, GetParam());
  for (const ExpectationResult& e : first.expectations)
    EXPECT_TRUE(e.pass) << e.text << " (actual " << e.actual << ")";
  EXPECT_EQ(first.winner, "blue");
  EXPECT_GE(first.endTick, 0);  // decided before the time ran out
  int redLosses = 0;
  for (const BattleStats& b : first.battle)
    redLosses += b.team == "red" ? b.losses : 0;
  EXPECT_GT(redLosses, 0);
  const Report second = play(text, GetParam());
  EXPECT_EQ(first.stateHash, second.stateHash);
  EXPECT_EQ(first, second);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, BundledBattle,
                         ::testing::Values("river_ambush", "forest_battle", "amphibious_landing"));

// Without the tanks' guns the convoy bleeds riflemen in the ambush and never gets 20 units out.
TEST(BattleVariants, AmbushWithoutTankGunsFails) {
  const std::string text =
      replaced(readScenario("river_ambush"), "catalogue: ../assets/units.yaml\n",
               "catalogue: ../assets/units.yaml\n"
               "unit_types: {tank: {weapon: none}}\n");
  const Report r = play(text, "river_ambush");
  const ExpectationResult* winner = find(r, "winner == blue");
  const ExpectationResult* losses = find(r, "losses(blue, infantry) <= 6");
  ASSERT_TRUE(winner && losses);
  EXPECT_FALSE(winner->pass);
  EXPECT_FALSE(losses->pass);
}

// Unarmed tanks cannot clear the woods: the rocket teams destroy at least two more of them
// than of armed ones (3 against 1 at the file's seed). The file's bound of 3 caught the unarmed
// run (4 lost) until vehicles meeting head on veered right (replay format 21).
TEST(BattleVariants, ForestWithoutTankGunsLosesMoreTanks) {
  const std::string armedText = readScenario("forest_battle");
  const std::string unarmedText =
      replaced(armedText, "  rocket_team:\n", "  tank: {weapon: none}\n  rocket_team:\n");
  const Report armed = play(armedText, "forest_battle");
  const Report unarmed = play(unarmedText, "forest_battle");
  const ExpectationResult* armedLosses = find(armed, "losses(blue, tank) <= 3");
  const ExpectationResult* unarmedLosses = find(unarmed, "losses(blue, tank) <= 3");
  ASSERT_TRUE(armedLosses && unarmedLosses);
  EXPECT_TRUE(armedLosses->pass);
  EXPECT_GE(unarmedLosses->actual, armedLosses->actual + 2);
}

// The second wave decides the landing: with it blue wins at every seed of 1-30, without it the
// first wave alone is sunk on the beach at some (red wins: 7 of the 30 at replay format 28).
// Counted over seeds, not at the file's one alone: the first wave alone wins at 23 of those
// seeds, so a movement rule that changes the run at the file's seed could flip a one-seed test
// without changing the balance. Seeds 1-10 under the sanitizers (red wins at 3 and 9).
TEST(BattleVariants, LandingWithoutTheSecondWaveFailsAtSomeSeeds) {
  const std::string withWave = readScenario("amphibious_landing");
  const std::string without = replaced(withWave, "      - {reinforce: wave2}\n", "");
  const int seeds = testing::fullOrSanitized(30, 10);
  int blueWins[2] = {0, 0};  // without the second wave, with it
  int redWins = 0;           // without it
  for (int seed = 1; seed <= seeds; ++seed) {
    for (const bool wave : {false, true}) {
      const std::string text = replaced(wave ? withWave : without, "seed: 1944\n",
                                        "seed: " + std::to_string(seed) + "\n");
      const Report r = play(text, "amphibious_landing");
      const ExpectationResult* winner = find(r, "winner == blue");
      ASSERT_TRUE(winner);
      blueWins[wave ? 1 : 0] += winner->pass ? 1 : 0;
      if (!wave) redWins += r.winner == "red" ? 1 : 0;
    }
  }
  EXPECT_EQ(blueWins[1], seeds);
  EXPECT_LT(blueWins[0], blueWins[1]);
  EXPECT_GE(redWins, 1);
}

}  // namespace
}  // namespace warpath::engine
