#include "rts/test_outputs.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

#include "pathing/file_read.h"
#include "rts/cli_support.h"
#include "rts/scenario_support.h"
#include "rts/svg_plot.h"

namespace warpath::tools {
namespace {

namespace fs = std::filesystem;

// A summary names each case once and holds no report: 256 MiB is far past a million cases.
constexpr FileLimit kSummaryFileLimit{256 * kMiB, "test summaries"};

std::string seconds(double s) {
  return fmt::format("{:.6f}", s);  // a small case takes under a millisecond
}

// The file part of a case name: "demo.yaml#5" -> "demo.yaml" (file names end in .yaml or .yml,
// so a '#' with digits after it at the end is a seed, even in "a#b.yaml#5").
std::string_view fileOf(std::string_view name) {
  const std::size_t hash = name.rfind('#');
  if (hash == std::string_view::npos || hash + 1 == name.size() ||
      name.find_first_not_of("0123456789", hash + 1) != std::string_view::npos)
    return name;
  return name.substr(0, hash);
}

// A JUnit class name without the dots that Jenkins reads as packages: "demo.yaml" -> "demo".
std::string className(std::string_view name) {
  std::string stem(fileOf(name));
  for (const std::string_view ext : {".yaml", ".yml"})
    if (stem.size() > ext.size() && stem.ends_with(ext)) stem.resize(stem.size() - ext.size());
  std::replace(stem.begin(), stem.end(), '.', '_');
  std::replace(stem.begin(), stem.end(), '/', '.');
  return stem;
}

struct Counts {
  int tests = 0, failures = 0, errors = 0, skipped = 0;
  double time = 0.0;
  void add(const CaseResult& r) {
    ++tests;
    failures += r.status == CaseStatus::Fail ? 1 : 0;
    errors += r.status == CaseStatus::Error ? 1 : 0;
    skipped += r.status == CaseStatus::NotRun ? 1 : 0;
    time += r.seconds;
  }
  std::string attributes() const {
    return fmt::format(R"(tests="{}" failures="{}" errors="{}" skipped="{}" time="{}")", tests,
                       failures, errors, skipped, seconds(time));
  }
};

void appendTestCase(std::string& xml, const CaseResult& r) {
  const std::string seed = r.seed ? std::to_string(*r.seed) : "the file's";
  xml += fmt::format(R"(    <testcase name="{}" classname="{}" file="{}" time="{}">)",
                     escapeXml(r.name), escapeXml(className(r.name)), escapeXml(r.file),
                     seconds(r.seconds));
  xml += '\n';
  if (r.status == CaseStatus::Fail) {
    std::string message;
    std::string body;
    int failed = 0;
    for (const engine::ExpectationResult& e : r.expectations) {
      if (e.pass) continue;
      const std::string line = failureLine(e);
      if (failed++ == 0) message = line;
      body += line + '\n';
    }
    if (failed > 1) message += fmt::format(" (and {} more)", failed - 1);
    xml += fmt::format(R"(      <failure type="expectation" message="{}">{}</failure>)",
                       escapeXml(message), escapeXml(body));
    xml += '\n';
  } else if (r.status == CaseStatus::Error) {
    xml += fmt::format(R"(      <error type="error" message="{}">{}</error>)", escapeXml(r.message),
                       escapeXml(r.message));
    xml += '\n';
  } else if (r.status == CaseStatus::NotRun) {
    xml += "      <skipped message=\"not run: the run was interrupted first\"/>\n";
  }
  if (!r.stateHash.empty()) {
    xml += fmt::format(
        "      <system-out>seed {}, {} units, {} ticks{}, state hash {}{}</system-out>\n", seed,
        r.units, r.ticks, r.winner.empty() ? "" : ", winner " + escapeXml(r.winner), r.stateHash,
        r.reportFile.empty() ? "" : ", report " + escapeXml(r.reportFile));
  }
  xml += "    </testcase>\n";
}

[[noreturn]] void badSummary(const std::string& file, const std::string& problem) {
  throw BadInput{file + ": " + problem};
}

}  // namespace

std::string junitXml(const std::vector<CaseResult>& results) {
  Counts total;
  for (const CaseResult& r : results)
    total.add(r);
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuites name=\"rts test\" {}>\n", total.attributes());
  // Cases come file by file: a suite per run of cases of one file.
  for (std::size_t begin = 0; begin < results.size();) {
    std::size_t end = begin;
    Counts suite;
    while (end < results.size() && fileOf(results[end].name) == fileOf(results[begin].name))
      suite.add(results[end++]);
    xml += fmt::format("  <testsuite name=\"{}\" {}>\n", escapeXml(fileOf(results[begin].name)),
                       suite.attributes());
    for (std::size_t i = begin; i < end; ++i)
      appendTestCase(xml, results[i]);
    xml += "  </testsuite>\n";
    begin = end;
  }
  xml += "</testsuites>\n";
  return xml;
}

void writeWholeFile(const std::string& file, const std::string& text) {
  const std::string temporary = file + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw BadInput{"cannot write '" + temporary + "'"};
  }
  std::error_code error;
  fs::rename(temporary, file, error);
  if (error) throw BadInput{"cannot write '" + file + "': " + error.message()};
}

void prepareReportDir(const std::string& dir) {
  std::error_code error;
  fs::create_directories(fs::path(dir) / "cases", error);
  if (error)
    throw BadInput{"--report-dir: cannot create the folder '" + dir + "': " + error.message()};
}

void writeCaseReport(const std::string& dir, CaseResult& result) {
  if (result.report.is_null()) return;
  std::string name = result.name;
  if (const std::size_t file = fileOf(name).size(); file < name.size())
    name.replace(file, 1, ".seed");
  result.reportFile = "cases/" + name + ".json";
  writeWholeFile(
      (fs::path(dir) / result.reportFile).string(),
      result.report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + '\n');
}

nlohmann::json summaryJson(const Summary& summary) {
  nlohmann::json cases = nlohmann::json::array();
  int passed = 0, failed = 0, errors = 0, notRun = 0;
  for (const CaseResult& r : summary.cases) {
    cases.push_back(caseJson(r, false));
    passed += r.status == CaseStatus::Pass ? 1 : 0;
    failed += r.status == CaseStatus::Fail ? 1 : 0;
    errors += r.status == CaseStatus::Error ? 1 : 0;
    notRun += r.status == CaseStatus::NotRun ? 1 : 0;
  }
  return {{"format", kSummaryFormat},
          {"shard", {{"index", summary.shard.index}, {"count", summary.shard.count}}},
          {"all_cases", summary.allCases},
          {"cases", cases},
          {"complete", notRun == 0},
          {"passed", passed},
          {"failed", failed},
          {"errors", errors},
          {"not_run", notRun}};
}

Summary readSummary(const std::string& dir) {
  const std::string file = (fs::path(dir) / kSummaryFile).string();
  Result<std::string> text = readFileCapped(file, kSummaryFileLimit);
  if (!text.ok()) throw BadInput{text.error().describe()};
  const nlohmann::json j = nlohmann::json::parse(text.value(), nullptr, false);
  if (j.is_discarded()) badSummary(file, "not JSON");
  if (!j.is_object() || j.value("format", "") != kSummaryFormat)
    badSummary(file, "not a summary written by rts test --report-dir (format " +
                         std::string(kSummaryFormat) + ")");
  Summary s;
  try {
    s.shard.index = j.at("shard").at("index").get<int>();
    s.shard.count = j.at("shard").at("count").get<int>();
    s.allCases = j.at("all_cases").get<std::vector<std::string>>();
    for (const nlohmann::json& c : j.at("cases"))
      s.cases.push_back(caseFromJson(c, file));
  } catch (const nlohmann::json::exception& e) {
    badSummary(file, std::string("not a summary: ") + e.what());
  }
  if (s.shard.count < 1 || s.shard.index < 0 || s.shard.index >= s.shard.count)
    badSummary(file, "shard " + std::to_string(s.shard.index) + "/" +
                         std::to_string(s.shard.count) + " is not a shard");
  return s;
}

void printTotals(const std::vector<CaseResult>& results) {
  int passed = 0, failed = 0;
  for (const CaseResult& r : results) {
    passed += r.status == CaseStatus::Pass ? 1 : 0;
    failed += r.status == CaseStatus::Fail || r.status == CaseStatus::Error ? 1 : 0;
  }
  fmt::print("{} passed, {} failed\n", passed, failed);
}

bool passesAtRate(const std::vector<CaseResult>& results, double minPassRate) {
  bool ok = true;
  std::map<std::string, std::pair<int, int>> byFile;  // file -> (passed, cases)
  for (const CaseResult& r : results) {
    // A case that could not run is a bug or a bad file, never a flaky seed.
    ok = ok && (r.status == CaseStatus::Pass || r.status == CaseStatus::Fail);
    auto& [passed, cases] = byFile[r.file];
    passed += r.status == CaseStatus::Pass ? 1 : 0;
    ++cases;
  }
  for (const auto& [file, count] : byFile) {
    const auto [passed, cases] = count;
    // (The tolerance keeps 0.95 of 40 at 38, whatever the rounding of 0.95 * 40.)
    if (passed >= minPassRate * cases - 1e-9) continue;
    ok = false;
    if (minPassRate < 1.0)  // (at 1 the FAIL lines say it all)
      fmt::print(stderr, "rts: {}: {} of {} cases passed ({:.1f} %), below --min-pass-rate {}\n",
                 file, passed, cases, 100.0 * passed / cases, minPassRate);
  }
  return ok;
}

}  // namespace warpath::tools
