#include "rts/test_cases.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "engine/fnv1a.h"
#include "pathing/random.h"
#include "rts/cli_support.h"
#include "rts/scenario_support.h"

namespace warpath::tools {
namespace {

namespace fs = std::filesystem;

std::optional<std::uint64_t> parseSeed(std::string_view text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

[[noreturn]] void badSeeds(std::string_view text, const std::string& problem) {
  throw BadInput{"--seeds: " + problem + " in '" + std::string(text) +
                 "' (expected a list such as 1,2,5 or a range such as 1..10)"};
}

void addCasesOf(const fs::path& file, const std::string& name,
                const std::vector<std::uint64_t>& seeds, std::vector<TestCase>& cases) {
  if (seeds.empty()) {
    cases.push_back({name, file.string(), std::nullopt});
    return;
  }
  for (const std::uint64_t seed : seeds)
    cases.push_back({name + "#" + std::to_string(seed), file.string(), seed});
}

// The scenario files of a folder, in name order; an unreadable folder is bad input.
std::vector<fs::path> scenariosIn(const std::string& folder) {
  std::error_code error;
  fs::directory_iterator entries(folder, error);
  if (error) throw BadInput{folder + ": cannot read: " + error.message()};
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : entries) {
    const fs::path& p = entry.path();
    std::error_code ignored;
    if (entry.is_regular_file(ignored) && (p.extension() == ".yaml" || p.extension() == ".yml"))
      files.push_back(p);
  }
  std::sort(files.begin(), files.end());
  return files;
}

const std::pair<CaseStatus, std::string_view> kStatusNames[] = {
    {CaseStatus::Pass, "pass"},
    {CaseStatus::Fail, "fail"},
    {CaseStatus::Error, "error"},
    {CaseStatus::NotRun, "not_run"},
};

}  // namespace

std::vector<std::uint64_t> parseSeeds(std::string_view text) {
  std::vector<std::uint64_t> seeds;
  std::set<std::uint64_t> seen;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string_view item = text.substr(begin, comma - begin);
    const std::size_t dots = item.find("..");
    const auto first = parseSeed(item.substr(0, dots));
    const auto last = dots == std::string_view::npos ? first : parseSeed(item.substr(dots + 2));
    if (!first || !last)
      badSeeds(text, "'" + std::string(item) + "' is not a whole number or a range A..B");
    if (*first > *last) badSeeds(text, "the range '" + std::string(item) + "' runs backwards");
    if (*last - *first >= kMaxCases - seeds.size())
      badSeeds(text, "more than " + std::to_string(kMaxCases) + " seeds");
    for (std::uint64_t seed = *first;; ++seed) {
      if (!seen.insert(seed).second)
        badSeeds(text, "the seed " + std::to_string(seed) + " is given twice");
      seeds.push_back(seed);
      if (seed == *last) break;
    }
    begin = comma + 1;
  }
  return seeds;
}

Shard parseShard(std::string_view text) {
  const std::size_t slash = text.find('/');
  const auto index =
      slash == std::string_view::npos ? std::nullopt : parseInt(text.substr(0, slash));
  const auto count =
      slash == std::string_view::npos ? std::nullopt : parseInt(text.substr(slash + 1));
  if (!index || !count) {
    throw BadInput{"--shard: expected K/N (shard K of N, K counting from 0), got '" +
                   std::string(text) + "'"};
  }
  if (*count < 1 || *count > kMaxShards) {
    throw BadInput{"--shard: the shard count must be between 1 and " + std::to_string(kMaxShards) +
                   ", got '" + std::string(text) + "'"};
  }
  if (*index < 0 || *index >= *count) {
    throw BadInput{"--shard: K must be between 0 and " + std::to_string(*count - 1) +
                   " (shards count from 0), got '" + std::string(text) + "'"};
  }
  return {*index, *count};
}

bool inShard(std::string_view name, const Shard& shard) {
  engine::Fnv1a hash;
  for (const char c : name)
    hash.add(static_cast<unsigned char>(c), 1);
  // FNV-1a's low bits follow the last characters (seeds 1..4 would deal round-robin): one
  // SplitMix64 step mixes every bit into every other before the shard is picked.
  return pathing::SplitMix64(hash.value()).below(static_cast<std::uint32_t>(shard.count)) ==
         static_cast<std::uint32_t>(shard.index);
}

std::vector<TestCase> collectCases(const std::vector<std::string>& inputs,
                                   const std::vector<std::uint64_t>& seeds) {
  std::vector<TestCase> cases;
  std::map<std::string, std::string> fileOfName;  // to name both files of a clash
  for (const std::string& input : inputs) {
    std::error_code error;
    const fs::file_status status = fs::status(input, error);
    std::vector<std::pair<fs::path, std::string>> files;  // path, case name
    if (fs::is_directory(status)) {
      for (const fs::path& file : scenariosIn(input))
        files.emplace_back(file, file.lexically_relative(input).generic_string());
    } else if (fs::is_regular_file(status)) {
      files.emplace_back(input, fs::path(input).filename().string());
    } else if (status.type() == fs::file_type::not_found) {
      throw BadInput{input + ": no such file or folder"};
    } else if (error) {
      throw BadInput{input + ": cannot read: " + error.message()};
    } else {
      throw BadInput{"'" + input + "' is not a folder or a regular file"};
    }
    for (const auto& [file, name] : files) {
      const auto [it, fresh] = fileOfName.emplace(name, file.string());
      if (!fresh) {
        throw BadInput{"two scenario files would make cases named '" + name + "': " + it->second +
                       " and " + file.string() + " (cases are named by file name; run them apart)"};
      }
      addCasesOf(file, name, seeds, cases);
      if (cases.size() > kMaxCases)
        throw BadInput{"more than " + std::to_string(kMaxCases) + " cases"};
    }
  }
  return cases;
}

CaseResult notRun(const TestCase& testCase) {
  CaseResult r;
  r.name = testCase.name;
  r.file = testCase.file;
  r.seedGiven = testCase.seed.has_value();
  r.seed = testCase.seed;
  return r;
}

CaseResult runCase(const TestCase& testCase) {
  CaseResult r = notRun(testCase);
  const auto began = std::chrono::steady_clock::now();
  try {
    Result<engine::Scenario> loaded = engine::loadScenario(testCase.file);
    if (!loaded.ok()) {
      r.status = CaseStatus::Error;
      r.message = loaded.error().describe();
      return r;
    }
    engine::ScenarioRun run(loaded.value(), testCase.seed);
    const RunOutcome outcome = runToEnd(run, {});
    r.report = reportJson(outcome, run);
    r.seed = outcome.report.seed;
    r.units = run.world().units().size();
    r.ticks = outcome.report.ticks;
    r.winner = outcome.report.winner;
    r.stateHash = r.report["state_hash"].get<std::string>();
    r.expectations = outcome.report.expectations;
    if (outcome.interrupted) {
      r.status = CaseStatus::Error;
      r.message = "interrupted at tick " + std::to_string(outcome.report.ticks);
    } else {
      r.status = outcome.report.passed() ? CaseStatus::Pass : CaseStatus::Fail;
    }
  } catch (const std::exception& e) {
    r.status = CaseStatus::Error;
    r.message = std::string("internal error: ") + e.what();
  } catch (const BadInput& e) {
    r.status = CaseStatus::Error;
    r.message = e.message;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return r;
}

std::string_view toString(CaseStatus status) {
  for (const auto& [s, name] : kStatusNames)
    if (s == status) return name;
  return "error";
}

nlohmann::json caseJson(const CaseResult& r, bool withReport) {
  using nlohmann::json;
  json j = {{"name", r.name},
            {"file", r.file},
            {"seed_given", r.seedGiven},
            {"seed", r.seed ? json(*r.seed) : json(nullptr)},
            {"status", toString(r.status)},
            {"message", r.message},
            {"seconds", r.seconds},
            {"units", r.units},
            {"ticks", r.ticks},
            {"winner", r.winner.empty() ? json(nullptr) : json(r.winner)},
            {"state_hash", r.stateHash.empty() ? json(nullptr) : json(r.stateHash)},
            {"expectations", expectationsJson(r.expectations)}};
  if (withReport)
    j["report"] = r.report;
  else
    j["report"] = r.reportFile.empty() ? json(nullptr) : json(r.reportFile);
  return j;
}

CaseResult caseFromJson(const nlohmann::json& j, const std::string& where) {
  CaseResult r;
  try {
    r.name = j.at("name").get<std::string>();
    r.file = j.at("file").get<std::string>();
    r.seedGiven = j.at("seed_given").get<bool>();
    if (!j.at("seed").is_null()) r.seed = j.at("seed").get<std::uint64_t>();
    const std::string status = j.at("status").get<std::string>();
    const auto* named = std::find_if(std::begin(kStatusNames), std::end(kStatusNames),
                                     [&](const auto& s) { return s.second == status; });
    if (named == std::end(kStatusNames))
      throw BadInput{where + ": unknown status '" + status + "'"};
    r.status = named->first;
    r.message = j.at("message").get<std::string>();
    r.seconds = j.at("seconds").get<double>();
    r.units = j.at("units").get<std::size_t>();
    r.ticks = j.at("ticks").get<std::int64_t>();
    if (!j.at("winner").is_null()) r.winner = j.at("winner").get<std::string>();
    if (!j.at("state_hash").is_null()) r.stateHash = j.at("state_hash").get<std::string>();
    for (const nlohmann::json& e : j.at("expectations")) {
      const nlohmann::json& actual = e.at("actual");
      // (Results written before expectations named their units have no "units".)
      r.expectations.push_back(
          {e.at("text").get<std::string>(),
           actual.is_null() ? std::numeric_limits<double>::infinity() : actual.get<double>(),
           e.at("pass").get<bool>(), e.value("units", std::vector<std::uint32_t>{})});
    }
    const nlohmann::json& report = j.at("report");
    if (report.is_string())
      r.reportFile = report.get<std::string>();
    else
      r.report = report;
  } catch (const nlohmann::json::exception& e) {
    throw BadInput{where + ": not a test case result: " + e.what()};
  }
  return r;
}

namespace {

// The command that traces, tick by tick, the units a failed case's expectations count against
// (at most kUnitsNamed, lowest first); empty when they name none.
std::string traceHint(const CaseResult& r) {
  std::set<std::uint32_t> named;
  for (const engine::ExpectationResult& e : r.expectations) {
    if (!e.pass) named.insert(e.units.begin(), e.units.end());
  }
  if (named.empty()) return {};
  std::vector<std::uint32_t> units(named.begin(), named.end());
  if (units.size() > kUnitsNamed) units.resize(kUnitsNamed);
  // A path the shell would split or expand goes in single quotes (a quote in it as '\'').
  std::string file = r.file;
  if (file.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                             "_-./+,:@%=") != std::string::npos) {
    for (std::size_t at = file.find('\''); at != std::string::npos; at = file.find('\'', at + 4))
      file.replace(at, 1, "'\\''");
    file = "'" + file + "'";
  }
  const std::string seed = r.seedGiven && r.seed ? " --seed " + std::to_string(*r.seed) : "";
  return fmt::format("trace: rts run {}{} --quiet --trace trace.csv --trace-units {}", file, seed,
                     fmt::join(units.begin(), units.end(), ","));
}

}  // namespace

void printCase(const CaseResult& r) {
  const std::string seed = r.seedGiven && r.seed ? " seed " + std::to_string(*r.seed) : "";
  if (r.stateHash.empty()) {  // it never ran: a bad file or a crash
    fmt::print("FAIL {}{}: {}\n", r.file, seed, r.message);
    return;
  }
  fmt::print("{} {}{} ({} units, {} ticks{}, {:.2f} s)\n",
             r.status == CaseStatus::Pass ? "PASS" : "FAIL", r.file, seed, r.units, r.ticks,
             r.winner.empty() ? "" : ", winner " + r.winner, r.seconds);
  for (const engine::ExpectationResult& e : r.expectations) {
    if (!e.pass) fmt::print("  {}\n", failureLine(e));
  }
  if (!r.message.empty()) fmt::print("  {}\n", r.message);
  if (const std::string hint = traceHint(r); !hint.empty()) fmt::print("  {}\n", hint);
}

}  // namespace warpath::tools
