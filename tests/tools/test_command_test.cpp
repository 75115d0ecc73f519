// `rts test` at scale, end to end: seeds, worker processes, shards, JUnit, report folders and
// `rts test merge`.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/rts_process.h"
#include "support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using warpath::testing::rts;
using Result = warpath::testing::RtsResult;

const fs::path kSource = WARPATH_SOURCE_DIR;

// Shell-quoted, for the command lines below.
std::string q(const fs::path& p) {
  return "'" + p.string() + "'";
}

std::string readFile(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The console lines without the wall time of each case, which differs from run to run.
std::string withoutTimes(const std::string& out) {
  // ", 1.25 s)" -> ")". Not std::regex: GCC 12 warns inside it at -O1 (the sanitizer build).
  std::string result;
  std::size_t at = 0;
  for (std::size_t comma; (comma = out.find(", ", at)) != std::string::npos;) {
    std::size_t end = comma + 2;
    while (end < out.size() &&
           (std::isdigit(static_cast<unsigned char>(out[end])) || out[end] == '.'))
      ++end;
    const bool time = end > comma + 2 && out.compare(end, 3, " s)") == 0;
    result.append(out, at, time ? comma - at : end - at);
    at = time ? end + 2 : end;
  }
  return result + out.substr(at);
}

// name -> "status hash" of every case of a report folder's summary.
std::map<std::string, std::string> casesOf(const fs::path& dir) {
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  std::map<std::string, std::string> cases;
  for (const nlohmann::json& c : j["cases"]) {
    const std::string hash = c["state_hash"].is_null() ? "-" : c["state_hash"].get<std::string>();
    EXPECT_TRUE(cases.emplace(c["name"], c["status"].get<std::string>() + " " + hash).second)
        << c["name"];
  }
  return cases;
}

// xmllint (libxml2-utils): whether the file is well-formed XML, and XPath counts in it.
bool wellFormed(const fs::path& xml) {
  return std::system(("xmllint --noout " + q(xml) + " 2>/dev/null").c_str()) == 0;
}
std::string xpath(const fs::path& xml, const std::string& expression) {
  FILE* pipe = popen(("xmllint --xpath \"" + expression + "\" " + q(xml) + " 2>&1").c_str(), "r");
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr)
    out += buffer;
  pclose(pipe);
  while (!out.empty() && out.back() == '\n')
    out.pop_back();
  return out;
}

class TestCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = warpath::testing::freshTestDir("warpath_test_command_");
    scenarios_ = dir_ / "scenarios";
    fs::create_directories(scenarios_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A 20 s run of `count` riflemen across a small open map: about 20 ms.
  void write(const std::string& name, const std::string& expectations, int count = 3) {
    std::ofstream(scenarios_ / name)
        << "map: {rows: ['..........', '..........', '..........', '..........']}\n"
           "catalogue: "
        << (kSource / "assets/units.yaml").string()
        << "\nduration: 20\nseed: 7\nteams: [blue]\ngroups:\n"
           "  - {name: g, team: blue, type: infantry, count: "
        << count
        << ", spawn: {x: 0, y: 0, w: 3, h: 4}, goal: {x: 7, y: 0, w: 3, h: 4}}\n"
           "expectations:\n"
        << expectations;
  }
  // Three passing scenarios and one whose expectation fails at every seed.
  void writeSweep() {
    write("a.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 20}\n");
    write("b.yaml", "  - max_stuck: 0\n", 6);
    write("c.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 0.5, by: 20}\n", 9);
    write("d.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 1}\n");
  }

  fs::path dir_;
  fs::path scenarios_;
};

TEST_F(TestCommand, SeedsMakeOneCasePerScenarioAndSeed) {
  writeSweep();
  const Result r = rts("test " + q(scenarios_) + " --seeds 1..3,10 --report-dir " + q(dir_ / "r"));
  EXPECT_EQ(r.status, 1) << r.out;  // d.yaml fails
  EXPECT_NE(r.out.find("PASS " + (scenarios_ / "a.yaml").string() + " seed 10 (3 units, 600 ticks"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("FAIL " + (scenarios_ / "d.yaml").string() + " seed 2 ("), std::string::npos)
      << r.out;
  EXPECT_TRUE(r.out.ends_with("12 passed, 4 failed\n")) << r.out;
  const std::map<std::string, std::string> cases = casesOf(dir_ / "r");
  ASSERT_EQ(cases.size(), 16u);
  EXPECT_TRUE(cases.contains("c.yaml#10"));
  // Each case's report is the JSON of `rts run --report` at that seed.
  const nlohmann::json report =
      nlohmann::json::parse(std::ifstream(dir_ / "r/cases/b.yaml.seed3.json"));
  EXPECT_EQ(report["seed"], 3);
  EXPECT_EQ(report["units"], 6);
  const Result run =
      rts("run " + q(scenarios_ / "b.yaml") + " --seed 3 --quiet --report " + q(dir_ / "run.json"));
  const nlohmann::json alone = nlohmann::json::parse(std::ifstream(dir_ / "run.json"));
  EXPECT_EQ(report["state_hash"], alone["state_hash"]);
  EXPECT_EQ(cases.at("b.yaml#3"), "pass " + alone["state_hash"].get<std::string>());

  // Without --seeds: the file's seed, named by the file alone.
  const Result own = rts("test " + q(scenarios_ / "a.yaml") + " --report-dir " + q(dir_ / "own"));
  EXPECT_EQ(own.status, 0) << own.out;
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir_ / "own/summary.json"));
  EXPECT_EQ(summary["cases"][0]["name"], "a.yaml");
  EXPECT_EQ(summary["cases"][0]["seed"], 7);
}

TEST_F(TestCommand, TwoJobsPrintAndFindWhatOneJobDoes) {
  writeSweep();
  const std::string args = "test " + q(scenarios_) + " " +
                           q(kSource / "scenarios/swamp_detour.yaml") +
                           " --seeds 1..5 --report-dir ";
  const Result one = rts(args + q(dir_ / "one") + " --jobs 1");
  const Result two = rts(args + q(dir_ / "two") + " --jobs 2");
  EXPECT_EQ(one.status, 1);
  EXPECT_EQ(two.status, one.status);
  EXPECT_EQ(withoutTimes(two.out), withoutTimes(one.out));
  EXPECT_TRUE(one.out.ends_with("20 passed, 5 failed\n")) << one.out;
  EXPECT_EQ(casesOf(dir_ / "two"), casesOf(dir_ / "one"));
  EXPECT_EQ(casesOf(dir_ / "one").size(), 25u);
}

TEST_F(TestCommand, ShardsCoverEveryCaseOnceAndMergeToTheLocalRun) {
  writeSweep();
  const std::string args = "test " + q(scenarios_) + " " +
                           q(kSource / "scenarios/swamp_detour.yaml") + " --seeds 1..8 --jobs 2";
  const Result local = rts(args + " --report-dir " + q(dir_ / "local"));
  const std::map<std::string, std::string> all = casesOf(dir_ / "local");
  ASSERT_EQ(all.size(), 40u);

  constexpr int kShards = 3;
  std::map<std::string, std::string> joined;
  std::string shardDirs;
  for (int k = 0; k < kShards; ++k) {
    const fs::path shard = dir_ / ("shard" + std::to_string(k));
    rts(args + " --shard " + std::to_string(k) + "/" + std::to_string(kShards) + " --report-dir " +
        q(shard));
    const std::map<std::string, std::string> cases = casesOf(shard);
    EXPECT_GT(cases.size(), 5u) << "shard " << k;  // the hash spreads them
    for (const auto& [name, result] : cases)
      EXPECT_TRUE(joined.emplace(name, result).second) << name << " is in two shards";
    shardDirs += " " + q(shard);
  }
  EXPECT_EQ(joined, all);  // every case once, with the local run's status and state hash

  const Result merged = rts("test merge" + shardDirs + " --report-dir " + q(dir_ / "merged") +
                            " --junit " + q(dir_ / "merged.xml"));
  EXPECT_EQ(merged.status, local.status) << merged.out;
  EXPECT_EQ(withoutTimes(merged.out), withoutTimes(local.out));
  EXPECT_EQ(casesOf(dir_ / "merged"), all);
  EXPECT_TRUE(fs::exists(dir_ / "merged/cases/swamp_detour.yaml.seed8.json"));
  EXPECT_TRUE(wellFormed(dir_ / "merged.xml"));
  EXPECT_EQ(xpath(dir_ / "merged.xml", "count(//testcase)"), "40");
}

TEST_F(TestCommand, MergeNamesMissingAndDuplicatedCases) {
  writeSweep();
  const std::string args = "test " + q(scenarios_) + " --seeds 1..4 --jobs 2 --shard ";
  rts(args + "0/2 --report-dir " + q(dir_ / "s0"));
  rts(args + "1/2 --report-dir " + q(dir_ / "s1"));
  const std::size_t inFirst = casesOf(dir_ / "s0").size();

  const Result missing = rts("test merge " + q(dir_ / "s0") + " --junit " + q(dir_ / "m.xml"));
  EXPECT_EQ(missing.status, 1) << missing.out;
  EXPECT_NE(missing.out.find("rts: shard 1/2 is not given"), std::string::npos) << missing.out;
  EXPECT_NE(missing.out.find("rts: " + std::to_string(16 - inFirst) + " cases missing: "),
            std::string::npos)
      << missing.out;
  const std::string oneMissing = casesOf(dir_ / "s1").begin()->first;
  EXPECT_NE(missing.out.find(oneMissing), std::string::npos) << missing.out;
  // Missing cases are errors in the JUnit file, so CI shows them.
  EXPECT_EQ(xpath(dir_ / "m.xml", "count(//testcase)"), "16");
  EXPECT_NE(xpath(dir_ / "m.xml", "string(//testcase[@name='" + oneMissing + "']/error/@message)")
                .find("missing"),
            std::string::npos);

  const Result twice =
      rts("test merge " + q(dir_ / "s0") + " " + q(dir_ / "s1") + " " + q(dir_ / "s0"));
  EXPECT_EQ(twice.status, 1) << twice.out;
  EXPECT_NE(twice.out.find("rts: shard 0/2 is given twice"), std::string::npos) << twice.out;
  EXPECT_NE(twice.out.find("rts: " + std::to_string(inFirst) + " cases duplicated: "),
            std::string::npos)
      << twice.out;

  // Folders of different runs are not shards of one.
  rts("test " + q(scenarios_) + " --seeds 1..3 --shard 1/2 --report-dir " + q(dir_ / "other"));
  const Result foreign = rts("test merge " + q(dir_ / "s0") + " " + q(dir_ / "other"));
  EXPECT_EQ(foreign.status, 2) << foreign.out;
  EXPECT_NE(foreign.out.find("are not shards of one run"), std::string::npos) << foreign.out;
}

// --min-pass-rate: a sweep passes when each scenario file passes at that share of its cases;
// a file that does not load fails it whatever the rate.
TEST_F(TestCommand, AMinimumPassRateJudgesEachScenarioFileBySeeds) {
  // One rifleman from a random spawn cell: its arrival time (4.7-5.6 s) depends on the seed.
  write("mixed.yaml", "  - arrival_time: {team: blue, percentile: 100, at_most: 5}\n", 1);
  write("always.yaml", "  - max_stuck: 0\n");
  const std::string sweep = "test " + q(scenarios_) + " --seeds 1..10";
  const Result all = rts(sweep);
  EXPECT_EQ(all.status, 1) << all.out;
  // How many of mixed.yaml's ten pass (always.yaml's ten do); the rest is checked against it.
  int passed = 0;
  for (std::size_t at = 0; (at = all.out.find("PASS ", at)) != std::string::npos; ++at)
    passed += all.out.compare(at, 5 + (scenarios_ / "mixed").string().size(),
                              "PASS " + (scenarios_ / "mixed").string()) == 0
                  ? 1
                  : 0;
  ASSERT_GT(passed, 0) << all.out;
  ASSERT_LT(passed, 10) << all.out;
  EXPECT_TRUE(all.out.ends_with(std::to_string(10 + passed) + " passed, " +
                                std::to_string(10 - passed) + " failed\n"))
      << all.out;

  const auto tenths = [](int n) { return n == 10 ? std::string("1") : "0." + std::to_string(n); };
  const std::string enough = tenths(passed);
  const Result atRate = rts(sweep + " --min-pass-rate " + enough);
  EXPECT_EQ(atRate.status, 0) << atRate.out;
  const std::string tooMuch = tenths(passed + 1);
  const Result aboveRate =
      rts(sweep + " --min-pass-rate " + tooMuch + " --report-dir " + q(dir_ / "r") + " --jobs 2");
  EXPECT_EQ(aboveRate.status, 1) << aboveRate.out;
  EXPECT_NE(aboveRate.out.find((scenarios_ / "mixed.yaml").string() + ": " +
                               std::to_string(passed) + " of 10 cases passed"),
            std::string::npos)
      << aboveRate.out;
  EXPECT_EQ(aboveRate.out.find("always.yaml: "), std::string::npos) << aboveRate.out;
  // merge judges the joined cases by the same rule.
  EXPECT_EQ(rts("test merge " + q(dir_ / "r") + " --min-pass-rate " + enough).status, 0);
  EXPECT_EQ(rts("test merge " + q(dir_ / "r") + " --min-pass-rate " + tooMuch).status, 1);

  // A file that does not load is an error, never tolerated.
  std::ofstream(scenarios_ / "broken.yaml") << "map: [\n";
  const Result broken = rts(sweep + " --min-pass-rate 0");
  EXPECT_EQ(broken.status, 1) << broken.out;
  EXPECT_EQ(rts("test " + q(scenarios_ / "mixed.yaml") + " --min-pass-rate 1.5").status, 2);
}

TEST_F(TestCommand, JUnitHasFailuresErrorsAndTimes) {
  write("pass.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 20}\n");
  write("slow.yaml", "  - arrival_rate: {team: blue, type: infantry, at_least: 1, by: 1}\n");
  // A file that does not load: an unknown team, on line 9.
  write("bad.yaml", "  - arrival_rate: {team: green, type: infantry, at_least: 1, by: 1}\n");
  // One whose error quotes markup, a control character and bytes that are not UTF-8.
  write("odd.yaml",
        "  - arrival_rate: {team: \"g\\x01<&>\xff\", type: infantry, at_least: 1, by: 1}\n");
  const fs::path xml = dir_ / "out/junit.xml";
  const Result r = rts("test " + q(scenarios_) + " --jobs 2 --junit " + q(xml));
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(r.out.ends_with("1 passed, 3 failed\n")) << r.out;
  ASSERT_TRUE(wellFormed(xml)) << readFile(xml);
  EXPECT_EQ(xpath(xml, "string(/testsuites/@tests)"), "4");
  EXPECT_EQ(xpath(xml, "count(/testsuites/testsuite)"), "4");
  EXPECT_EQ(xpath(xml, "string(/testsuites/@failures)"), "1");
  EXPECT_EQ(xpath(xml, "string(/testsuites/@errors)"), "2");
  EXPECT_NE(xpath(xml, "string(//testcase[@name='odd.yaml']/error/@message)")
                .find("unknown team 'g?<&>\xEF\xBF\xBD'"),
            std::string::npos)
      << readFile(xml);
  EXPECT_EQ(xpath(xml, "string(//testcase[@name='slow.yaml']/failure/@message)"),
            "expectation \"arrival_rate(blue, infantry) >= 1 by 1s\" failed: actual 0 (units 0, "
            "1, 2)");
  const std::string error = xpath(xml, "string(//testcase[@name='bad.yaml']/error/@message)");
  EXPECT_NE(error.find("bad.yaml:9:26: unknown team"), std::string::npos) << error;
  EXPECT_NE(error.find("unknown team 'green'"), std::string::npos) << error;
  EXPECT_EQ(xpath(xml, "count(//testcase[@name='pass.yaml']/*[self::failure or self::error])"),
            "0");
  const double time = std::stod(xpath(xml, "string(//testcase[@name='pass.yaml']/@time)"));
  EXPECT_GT(time, 0.0);
  EXPECT_LT(time, 30.0);
  EXPECT_EQ(xpath(xml, "string(//testcase[@name='pass.yaml']/@classname)"), "pass");
}

// A worker that crashes is its case's error; the cases after it still run. An interrupted run
// keeps what it wrote: the case it was in is an error, the ones it never started are skipped.
TEST_F(TestCommand, CrashesAndInterruptsAreErrorsAndKeepTheOutputs) {
  // The 2,000-unit scenario runs for 30 s; the other one is quick.
  const std::string stress = (kSource / "scenarios/stress_2000.yaml").string();
  write("b.yaml", "  - max_stuck: 0\n");
  const fs::path xml = dir_ / "crash.xml";
  // Kills the worker (a child of the rts process) once it is running: SIGKILL, as the OOM killer
  // would, since sanitizers turn a SIGSEGV into an abort of their own.
  const std::string crash = "sh -c '" + std::string(RTS_BINARY) + " test " + stress + " " +
                            scenarios_.string() + " --junit " + xml.string() + " >" +
                            (dir_ / "crash.out").string() +
                            " & p=$!; sleep 2; pkill -KILL -P $p; wait $p'";
  const int crashStatus = std::system(crash.c_str());
  EXPECT_TRUE(WIFEXITED(crashStatus) && WEXITSTATUS(crashStatus) == 1) << crashStatus;
  const std::string out = readFile(dir_ / "crash.out");
  EXPECT_NE(out.find("stress_2000.yaml: crashed: signal 9 (Killed)"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS " + (scenarios_ / "b.yaml").string()), std::string::npos) << out;
  ASSERT_TRUE(wellFormed(xml));
  EXPECT_NE(xpath(xml, "string(//testcase[@name='stress_2000.yaml']/error/@message)")
                .find("crashed: signal 9"),
            std::string::npos);

  // SIGINT to rts alone: it stops its worker, which reports where it was.
  const fs::path reports = dir_ / "interrupted";
  const std::string interrupt =
      "sh -c '" + std::string(RTS_BINARY) + " test " + stress + " " + scenarios_.string() +
      " --report-dir " + reports.string() + " --junit " + (reports / "junit.xml").string() + " >" +
      (dir_ / "int.out").string() + " 2>&1 & p=$!; sleep 2; kill -INT $p; wait $p'";
  const int interruptStatus = std::system(interrupt.c_str());
  EXPECT_TRUE(WIFEXITED(interruptStatus) && WEXITSTATUS(interruptStatus) == 1);
  EXPECT_NE(readFile(dir_ / "int.out").find("rts: interrupted; 1 of 2 cases not run"),
            std::string::npos)
      << readFile(dir_ / "int.out");
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(reports / "summary.json"));
  EXPECT_EQ(summary["complete"], false);
  ASSERT_EQ(summary["cases"].size(), 2u);
  EXPECT_EQ(summary["cases"][0]["status"], "error");
  EXPECT_TRUE(summary["cases"][0]["message"].get<std::string>().starts_with("interrupted at tick"));
  EXPECT_EQ(summary["cases"][1]["status"], "not_run");
  const nlohmann::json report =
      nlohmann::json::parse(std::ifstream(reports / "cases/stress_2000.yaml.json"));
  EXPECT_EQ(report["interrupted"], true);  // the partial report, as rts run writes it
  ASSERT_TRUE(wellFormed(reports / "junit.xml"));
  EXPECT_EQ(xpath(reports / "junit.xml", "count(//testcase[@name='b.yaml']/skipped)"), "1");
  EXPECT_EQ(xpath(reports / "junit.xml", "count(//testcase[@name='stress_2000.yaml']/error)"), "1");
}

TEST_F(TestCommand, BadInputIsRefusedNamingTheProblem) {
  write("a.yaml", "  - max_stuck: 0\n");
  const std::string s = q(scenarios_);
  std::ofstream(dir_ / "plain") << "x";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"test " + s + " --shard 5/4",
       "--shard: K must be between 0 and 3 (shards count from 0), got '5/4'"},
      {"test " + s + " --shard 4/4", "--shard: K must be between 0 and 3"},
      {"test " + s + " --shard 2", "--shard: expected K/N (shard K of N, K counting from 0)"},
      {"test " + s + " --shard 0/0", "--shard: the shard count must be between 1 and 100000"},
      {"test " + s + " --seeds 5..1", "--seeds: the range '5..1' runs backwards"},
      {"test " + s + " --seeds 1,x", "--seeds: 'x' is not a whole number or a range A..B"},
      {"test " + s + " --seeds 1,,2", "--seeds: '' is not a whole number"},
      {"test " + s + " --seeds 1..3,2", "--seeds: the seed 2 is given twice"},
      {"test " + s + " --seeds 0..99999999999", "--seeds: more than 1000000 seeds"},
      {"test " + s + " --jobs 0", "--jobs: must be a whole number between 1 and 256, got '0'"},
      {"test " + s + " --frobnicate", "--frobnicate"},
      {"test " + q(dir_ / "nowhere"), (dir_ / "nowhere").string() + ": no such file or folder"},
      {"test /dev/null", "'/dev/null' is not a folder or a regular file"},
      {"test", "test: give scenario folders or files"},
      {"test " + q(scenarios_ / "a.yaml") + " " + s,
       "two scenario files would make cases named 'a.yaml'"},
      {"test " + s + " --report-dir " + q(dir_ / "plain/r"),
       "--report-dir: cannot create the folder"},
      {"test " + s + " --junit " + q(dir_ / "plain/j.xml"), "--junit: cannot create the folder"},
      {"test merge " + q(dir_), "no summary.json in " + dir_.string()},
      {"test merge " + q(dir_ / "plain"), "no summary.json in " + (dir_ / "plain").string()},
  };
  for (const auto& [args, message] : cases) {
    const Result r = rts(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << args << "\n" << r.out;
    EXPECT_EQ(r.out.find("PASS"), std::string::npos) << "it ran: " << args;
  }
  std::ofstream(dir_ / "summary.json") << "{\"format\": \"something else\"}";
  const Result foreign = rts("test merge " + q(dir_));
  EXPECT_EQ(foreign.status, 2);
  EXPECT_NE(foreign.out.find("not a summary written by rts test --report-dir"), std::string::npos)
      << foreign.out;
}

}  // namespace
