#pragma once
// What `rts test` and `rts test merge` write besides the console: JUnit XML, and a report
// folder holding each case's report (the JSON of `rts run --report`) and a summary that
// `rts test merge` reads:
//   DIR/summary.json            {"format", "shard": {"index", "count"}, "all_cases": [names of
//                               every case of the run before sharding], "cases": [results],
//                               "complete", "passed", "failed", "errors", "not_run"}
//   DIR/cases/NAME.json         one case's report; NAME is the case name with "#" as ".seed"

#include <string>
#include <string_view>
#include <vector>

#include "rts/test_cases.h"

namespace warpath::tools {

inline constexpr std::string_view kSummaryFormat = "warpath-test-summary/1";
inline constexpr std::string_view kSummaryFile = "summary.json";

// JUnit XML of `results` (in case order): a <testsuite> per scenario file, a <testcase> per
// case with its time; a failed expectation is a <failure> with the expectation and its actual
// value, a case that did not run to its end an <error>, one never started <skipped/>.
std::string junitXml(const std::vector<CaseResult>& results);

// Writes `text` to `file` through a temporary file renamed over it, so a reader (or an
// interrupted run) finds the old or the new file whole. Throws BadInput naming the file.
void writeWholeFile(const std::string& file, const std::string& text);

// Creates the report folder and its cases/ folder; throws BadInput naming --report-dir.
void prepareReportDir(const std::string& dir);
// Writes the report of `result` (when it ran) into `dir` and records where in reportFile.
void writeCaseReport(const std::string& dir, CaseResult& result);

struct Summary {
  Shard shard;
  std::vector<std::string> allCases;  // every case of the run, before sharding, in order
  std::vector<CaseResult> cases;      // this shard's, in order; without the reports
};

nlohmann::json summaryJson(const Summary& summary);
// Reads DIR/summary.json; throws BadInput naming the file and the problem.
Summary readSummary(const std::string& dir);

// "N passed, N failed": errors count as failures, cases never started as neither.
void printTotals(const std::vector<CaseResult>& results);

// Whether a run of `results` passes: every case ran to its end (no error, none left unrun),
// and of each scenario file's cases at least `minPassRate` held every expectation (1: all of
// them; --min-pass-rate). Below 1, prints each file under the rate, with its count, to stderr.
bool passesAtRate(const std::vector<CaseResult>& results, double minPassRate);

}  // namespace warpath::tools
