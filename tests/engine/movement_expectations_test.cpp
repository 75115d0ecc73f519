// The movement expectations (docs/scenarios.md): delay, max_wait and max_deadlocks read the
// report's movement section, and each fails when its bound is below what the run did.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "engine/scenario.h"
#include "engine/scenario_run.h"
#include "support/run_out.h"
#include "support/scenario_files.h"

namespace warpath::engine {
namespace {

const std::string kCorridorFile = testing::kScenariosDir + "chokepoints/corridor_tanks_4.yaml";

// Two tanks head on in a 4-wide corridor (one waits for the other): the file up to its
// expectations, which the tests write.
std::string corridorWithoutExpectations() {
  std::ifstream in(kCorridorFile);
  std::ostringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  yaml.resize(yaml.find("expectations:"));
  return yaml + "expectations:\n";
}

// The corridor with `expectations` (YAML list entries, one a line) instead of the file's own.
Scenario corridorExpecting(const std::string& expectations) {
  return testing::parsedScenario(corridorWithoutExpectations() + expectations, kCorridorFile);
}

const DelayStats& delayOf(const Report& r, const std::string& team) {
  for (const DelayStats& d : r.movement.delay) {
    if (d.team == team && d.type == "tank") return d;
  }
  ADD_FAILURE() << "no delay row for " << team;
  return r.movement.delay.front();
}

TEST(MovementExpectations, ParseIntoTheirKindsAndPrintTheirBounds) {
  const Scenario s = corridorExpecting(
      "  - delay: {team: blue, type: tank, percentile: 90, at_most: 1.5}\n"
      "  - delay: {percentile: 100, at_most: 2}\n"
      "  - max_wait: 12.5\n"
      "  - max_deadlocks: 0\n");
  ASSERT_EQ(s.expectations.size(), 4u);
  EXPECT_EQ(s.expectations[0].kind, ExpectationKind::Delay);
  EXPECT_EQ(s.expectations[0].text, "delay(blue, tank) p90 <= 1.5");
  EXPECT_EQ(s.expectations[1].text, "delay(*, *) p100 <= 2");
  EXPECT_EQ(s.expectations[2].kind, ExpectationKind::MaxWait);
  EXPECT_EQ(s.expectations[2].text, "max_wait <= 12.5s");
  EXPECT_EQ(s.expectations[3].kind, ExpectationKind::MaxDeadlocks);
  EXPECT_EQ(s.expectations[3].text, "max_deadlocks <= 0");
}

TEST(MovementExpectations, BadBoundsAreRefusedAtTheirLine) {
  const auto errorOf = [](const std::string& entry) {
    const std::string yaml = corridorWithoutExpectations();
    const int line = static_cast<int>(std::count(yaml.begin(), yaml.end(), '\n')) + 1;
    const Error e = testing::scenarioError(yaml + entry, kCorridorFile);
    EXPECT_EQ(e.line, line) << e.describe();
    return e.message;
  };
  EXPECT_NE(errorOf("  - delay: {percentile: 50}\n").find("at_most"), std::string::npos);
  EXPECT_NE(errorOf("  - delay: {percentile: 50, at_most: 2, by: 3}\n").find("by"),
            std::string::npos);
  EXPECT_NE(errorOf("  - delay: {percentile: 150, at_most: 2}\n").find("percentile"),
            std::string::npos);
  EXPECT_NE(errorOf("  - max_wait: -1\n").find("max_wait"), std::string::npos);
  EXPECT_NE(errorOf("  - max_deadlocks: 0.5\n").find("max_deadlocks"), std::string::npos);
}

// The actual values are the report's, and a bound just below them fails where the same bound
// just above passes.
TEST(MovementExpectations, HoldExactlyUpToWhatTheRunDid) {
  const std::string generous =
      "  - delay: {team: blue, type: tank, percentile: 50, at_most: 100}\n"
      "  - delay: {percentile: 100, at_most: 100}\n"
      "  - max_wait: 1000\n"
      "  - max_deadlocks: 1000\n";
  const Report r = testing::runToEnd(corridorExpecting(generous), 1);
  ASSERT_EQ(r.expectations.size(), 4u);
  for (const ExpectationResult& e : r.expectations) {
    EXPECT_TRUE(e.pass) << e.text << " (" << e.actual << ")";
    EXPECT_TRUE(e.units.empty()) << e.text;  // none beyond a bound it holds
  }
  const DelayStats& blue = delayOf(r, "blue");
  const DelayStats& red = delayOf(r, "red");
  ASSERT_EQ(blue.arrived, 1);
  ASSERT_EQ(red.arrived, 1);
  EXPECT_EQ(r.expectations[0].actual, blue.p50);
  EXPECT_EQ(r.expectations[1].actual, std::max(blue.max, red.max));
  EXPECT_EQ(r.expectations[2].actual, r.movement.maxWaitSeconds);
  EXPECT_EQ(r.expectations[3].actual, static_cast<double>(r.movement.counters.deadlocksBroken));
  // One tank waits for the other to clear the corridor: there is a wait to bound.
  ASSERT_GT(r.movement.maxWaitSeconds, 0.0);

  const auto bound = [](double v) {
    std::ostringstream out;
    out.precision(17);
    out << v;
    return out.str();
  };
  const auto below = [](double v) { return std::nextafter(v, 0.0); };
  const Report tight = testing::runToEnd(
      corridorExpecting(
          "  - delay: {team: blue, type: tank, percentile: 50, at_most: " + bound(below(blue.p50)) +
          "}\n  - delay: {percentile: 100, at_most: " + bound(below(std::max(blue.max, red.max))) +
          "}\n  - max_wait: " + bound(below(r.movement.maxWaitSeconds)) + "\n"),
      1);
  ASSERT_EQ(tight.expectations.size(), 3u);
  for (const ExpectationResult& e : tight.expectations)
    EXPECT_FALSE(e.pass) << e.text << " held (" << e.actual << ")";
  // Each delay bound counts against the one tank beyond it (the blue one; for the maximum, the
  // later one); a wait is no unit's in particular.
  EXPECT_EQ(tight.expectations[0].units.size(), 1u);
  EXPECT_EQ(tight.expectations[1].units.size(), 1u);
  EXPECT_TRUE(tight.expectations[2].units.empty());
  const Report exact = testing::runToEnd(
      corridorExpecting(
          "  - delay: {team: blue, type: tank, percentile: 50, at_most: " + bound(blue.p50) +
          "}\n  - max_wait: " + bound(r.movement.maxWaitSeconds) + "\n"),
      1);
  for (const ExpectationResult& e : exact.expectations)
    EXPECT_TRUE(e.pass) << e.text << " failed (" << e.actual << ")";
}

// A unit that never arrives is infinitely late: the run cut between the two tanks' arrivals
// leaves one late, so the slowest delay is infinite while the median is the arrived tank's
// (the report's delay row, arrived units only, is empty for the late one).
TEST(MovementExpectations, AUnitThatNeverArrivesIsInfinitelyLate) {
  Scenario s = corridorExpecting(
      "  - delay: {percentile: 100, at_most: 1000}\n"
      "  - delay: {percentile: 50, at_most: 1000}\n");
  const Report whole = testing::runToEnd(s, 1);
  ASSERT_EQ(whole.arrivals.size(), 2u);
  ASSERT_EQ(whole.arrivals[0].arrived, 1);
  ASSERT_EQ(whole.arrivals[1].arrived, 1);
  const double first = std::min(whole.arrivals[0].arrivedAt[0], whole.arrivals[1].arrivedAt[0]);
  const double last = std::max(whole.arrivals[0].arrivedAt[0], whole.arrivals[1].arrivedAt[0]);
  ASSERT_GT(last - first, 1.0);  // [Unit: s] one waited for the other
  s.duration = 0.5 * (first + last);
  const Report cut = testing::runToEnd(s, 1);
  ASSERT_EQ(cut.expectations.size(), 2u);
  EXPECT_FALSE(cut.expectations[0].pass);
  EXPECT_EQ(cut.expectations[0].actual, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(cut.expectations[1].pass) << cut.expectations[1].actual;
  const std::string late = cut.arrivals[0].arrived == 0 ? "blue" : "red";
  EXPECT_EQ(delayOf(cut, late).arrived, 0);
}

}  // namespace
}  // namespace warpath::engine
