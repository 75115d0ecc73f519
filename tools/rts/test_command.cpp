// `rts test`: run scenarios at seeds as cases in worker processes, judge their expectations,
// optionally one shard of them, and write JUnit and a report folder; `rts test merge` joins
// the report folders of shards into one.

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/html_report.h"
#include "rts/scenario_support.h"
#include "rts/test_cases.h"
#include "rts/test_outputs.h"
#include "rts/test_workers.h"

namespace warpath::tools {
namespace {

namespace fs = std::filesystem;

struct TestOptions {
  std::vector<std::string> inputs;
  int jobs = 1;
  std::string seeds;
  std::string shard;
  std::string junit;
  std::string reportDir;
  std::string html;
  double minPassRate = 1.0;
};

struct MergeOptions {
  std::vector<std::string> dirs;
  std::string junit;
  std::string reportDir;
  double minPassRate = 1.0;
};

// The JUnit file and the report folder's summary, rewritten as cases finish (at most every
// couple of seconds, and at the end) so that an interrupted or killed run leaves what it did.
class Outputs {
 public:
  Outputs(std::string junit, std::string reportDir, Shard shard, std::vector<std::string> all)
      : junit_(std::move(junit)), reportDir_(std::move(reportDir)) {
    summary_.shard = shard;
    summary_.allCases = std::move(all);
  }

  void write(const std::vector<CaseResult>& results, bool last) {
    const auto now = std::chrono::steady_clock::now();
    if (!last && now - written_ < std::chrono::seconds(2)) return;
    written_ = now;
    try {
      if (!junit_.empty()) writeWholeFile(junit_, junitXml(results));
      if (!reportDir_.empty()) {
        summary_.cases = results;
        writeWholeFile(
            (fs::path(reportDir_) / kSummaryFile).string(),
            summaryJson(summary_).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                '\n');
      }
    } catch (const BadInput& e) {
      if (last) throw;
      fmt::print(stderr, "rts: warning: {}\n", e.message);  // the last write tries again
    }
  }

 private:
  std::string junit_;
  std::string reportDir_;
  Summary summary_;
  std::chrono::steady_clock::time_point written_{};
};

int runTest(const TestOptions& options) {
  if (options.inputs.empty())
    throw BadInput{"test: give scenario folders or files (or: rts test merge DIR...)"};
  const std::vector<std::uint64_t> seeds =
      options.seeds.empty() ? std::vector<std::uint64_t>{} : parseSeeds(options.seeds);
  const Shard shard = options.shard.empty() ? Shard{} : parseShard(options.shard);
  const std::vector<TestCase> all = collectCases(options.inputs, seeds);
  std::vector<TestCase> cases;
  std::vector<std::string> allNames;
  for (const TestCase& c : all) {
    allNames.push_back(c.name);
    if (inShard(c.name, shard)) cases.push_back(c);
  }
  if (!options.shard.empty()) {  // on stderr: stdout stays what a whole run prints
    fmt::print(stderr, "rts: shard {}/{}: {} of {} cases\n", shard.index, shard.count, cases.size(),
               all.size());
  }
  prepareOutputPath(options.junit, "--junit");
  prepareOutputPath(options.html, "--html");
  if (!options.reportDir.empty()) prepareReportDir(options.reportDir);
  Outputs outputs(options.junit, options.reportDir, shard, std::move(allNames));
  outputs.write({}, true);  // a summary from the start: merge tells a shard that never ran
  installInterruptHandlers();

  // Results are printed and written in case order, whatever order the workers finish in.
  std::vector<std::optional<CaseResult>> finished(cases.size());
  std::vector<CaseResult> inOrder;
  std::vector<std::optional<HtmlCase>> page(options.html.empty() ? 0 : cases.size());  // --html
  const std::size_t started =
      runInWorkers(cases, options.jobs, [&](std::size_t index, CaseResult result) {
        try {
          if (!options.reportDir.empty()) writeCaseReport(options.reportDir, result);
        } catch (const BadInput& e) {  // the run goes on; its workers must be waited for
          fmt::print(stderr, "rts: warning: {}\n", e.message);
          result.reportFile.clear();
        }
        if (!options.html.empty()) {
          const std::string name =
              result.file +
              (result.seedGiven && result.seed ? " seed " + std::to_string(*result.seed) : "");
          page[index] = result.report.is_null() ? HtmlCase::failed(name, result.message)
                                                : HtmlCase::ran(name, result.report);
        }
        result.report = nullptr;  // on disk now; a sweep need not hold every report
        finished[index] = std::move(result);
        while (inOrder.size() < cases.size() && finished[inOrder.size()]) {
          printCase(*finished[inOrder.size()]);
          inOrder.push_back(std::move(*finished[inOrder.size()]));
        }
        outputs.write(inOrder, false);
      });
  for (std::size_t i = inOrder.size(); i < cases.size(); ++i)
    inOrder.push_back(notRun(cases[i]));
  outputs.write(inOrder, true);
  if (!options.html.empty()) {
    std::vector<HtmlCase> ran;  // in case order; the cases never started are left out
    for (std::optional<HtmlCase>& c : page)
      if (c) ran.push_back(std::move(*c));
    std::string title = "warpath test:";
    for (const std::string& input : options.inputs)
      title += " " + input;
    writeHtmlReport(options.html, title, ran);
  }
  printTotals(inOrder);
  if (started < cases.size()) {
    fmt::print(stderr, "rts: interrupted; {} of {} cases not run\n", cases.size() - started,
               cases.size());
  }
  return passesAtRate(inOrder, options.minPassRate) ? kExitOk : kExitFailed;
}

// "a#1, b#2 and 3 more".
std::string listOf(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 20;
  std::string text;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i)
    text += (i == 0 ? "" : ", ") + names[i];
  if (names.size() > kShown) text += fmt::format(" and {} more", names.size() - kShown);
  return text;
}

int runMerge(const MergeOptions& options) {
  std::vector<Summary> summaries;
  std::vector<std::string> dirs;  // those of `summaries`
  std::vector<std::string> problems;
  for (const std::string& dir : options.dirs) {
    std::error_code error;
    if (!fs::exists(fs::path(dir) / kSummaryFile, error)) {  // a shard that never started
      problems.push_back(dir + ": no " + std::string(kSummaryFile) + "; its cases are missing");
      continue;
    }
    summaries.push_back(readSummary(dir));
    dirs.push_back(dir);
  }
  if (summaries.empty())
    throw BadInput{"no " + std::string(kSummaryFile) + " in " + listOf(options.dirs)};
  const Summary& first = summaries.front();
  for (std::size_t i = 1; i < summaries.size(); ++i) {
    if (summaries[i].allCases != first.allCases || summaries[i].shard.count != first.shard.count) {
      throw BadInput{dirs[i] + " and " + dirs[0] +
                     " are not shards of one run (their runs had other cases or shard counts)"};
    }
  }
  prepareOutputPath(options.junit, "--junit");
  if (!options.reportDir.empty()) prepareReportDir(options.reportDir);

  std::map<int, std::string> shardDirs;
  for (std::size_t i = 0; i < summaries.size(); ++i) {
    const auto [it, fresh] = shardDirs.emplace(summaries[i].shard.index, dirs[i]);
    if (!fresh) {
      problems.push_back(fmt::format("shard {}/{} is given twice: {} and {}",
                                     summaries[i].shard.index, first.shard.count, it->second,
                                     dirs[i]));
    }
  }
  for (int k = 0; k < first.shard.count && first.shard.count <= 1000; ++k)
    if (!shardDirs.contains(k))
      problems.push_back(fmt::format("shard {}/{} is not given", k, first.shard.count));
  // Each case from the folder that ran it; a second one is a duplicate.
  std::map<std::string, std::pair<CaseResult, std::size_t>> byName;
  std::vector<std::string> duplicated;
  for (std::size_t i = 0; i < summaries.size(); ++i) {
    for (CaseResult& r : summaries[i].cases) {
      const std::string name = r.name;
      const auto [it, fresh] = byName.try_emplace(name, std::move(r), i);
      if (!fresh)
        duplicated.push_back(name + " (" + dirs[it->second.second] + " and " + dirs[i] + ")");
    }
  }
  std::vector<CaseResult> results;
  std::vector<std::string> missing;
  std::vector<std::string> notRunNames;
  for (const std::string& name : first.allCases) {
    const auto it = byName.find(name);
    if (it == byName.end()) {
      missing.push_back(name);
      CaseResult r = notRun({name, name, std::nullopt});
      r.status = CaseStatus::Error;
      r.message = "missing: no shard's summary holds this case";
      results.push_back(std::move(r));
      continue;
    }
    auto& [result, from] = it->second;
    if (result.status == CaseStatus::NotRun) notRunNames.push_back(name);
    if (!options.reportDir.empty() && !result.reportFile.empty()) {
      const fs::path source = fs::path(dirs[from]) / result.reportFile;
      const fs::path target = fs::path(options.reportDir) / result.reportFile;
      std::error_code same;  // (no target yet is an error here, and not the same file)
      std::error_code error;
      if (!fs::equivalent(source, target, same))  // merging into a shard's own folder
        fs::copy_file(source, target, fs::copy_options::overwrite_existing, error);
      if (error) throw BadInput{"cannot copy " + source.string() + ": " + error.message()};
    }
    results.push_back(std::move(result));
    byName.erase(it);
  }
  for (const auto& [name, entry] : byName)
    problems.push_back("case " + name + " in " + dirs[entry.second] +
                       " is not one of the run's cases");
  if (!missing.empty())
    problems.push_back(fmt::format("{} cases missing: {}", missing.size(), listOf(missing)));
  if (!duplicated.empty())
    problems.push_back(
        fmt::format("{} cases duplicated: {}", duplicated.size(), listOf(duplicated)));
  if (!notRunNames.empty())
    problems.push_back(
        fmt::format("{} cases not run: {}", notRunNames.size(), listOf(notRunNames)));

  for (const CaseResult& r : results)
    if (r.status != CaseStatus::NotRun) printCase(r);
  Outputs outputs(options.junit, options.reportDir, Shard{}, first.allCases);
  outputs.write(results, true);
  printTotals(results);
  for (const std::string& problem : problems)
    fmt::print(stderr, "rts: {}\n", problem);
  const bool passed = passesAtRate(results, options.minPassRate);
  return passed && problems.empty() ? kExitOk : kExitFailed;
}

}  // namespace

void registerTestCommand(CLI::App& app, CommandRunner& run) {
  auto options = std::make_shared<TestOptions>();
  CLI::App* cmd = app.add_subcommand(
      "test",
      "Run scenarios (folders of *.yaml, or files) at seeds as cases; ends with \"N passed, N "
      "failed\"; exits 1 when a case failed (see --min-pass-rate)");
  auto [merge, mergeOptions] = addSubcommand<MergeOptions>(
      *cmd, run, "merge",
      "Join the --report-dir folders of shards into one; exit 1 when a case failed, is missing "
      "or is duplicated",
      runMerge);
  // Set after the merge callback (CLI11 runs a subcommand's callback before its parent's).
  cmd->callback([&run, options, merge = merge] {
    if (!merge->parsed()) run = [options] { return runTest(*options); };
  });
  cmd->add_option("inputs", options->inputs, "Scenario folders (their *.yaml) or files");
  cmd->add_option("--jobs,-j", options->jobs, "Run cases in N worker processes (default 1)")
      ->check(wholeNumberIn(1, kMaxJobs));
  cmd->add_option("--seeds", options->seeds,
                  "Run each scenario at these seeds: 1,2,5 or 1..10 (default: the file's seed)");
  cmd->add_option("--shard", options->shard,
                  "Run shard K of N (K counts from 0), picked by a stable hash of each case name");
  cmd->add_option("--junit", options->junit, "Write JUnit XML to this file");
  cmd->add_option("--report-dir", options->reportDir,
                  "Write each case's report and summary.json (for rts test merge) here");
  cmd->add_option("--html", options->html, "Write one HTML page with every case's charts");
  const std::string rateHelp =
      "Pass when at least this share of each scenario file's cases pass (default 1: all); a case "
      "that could not run always fails the run";
  cmd->add_option("--min-pass-rate", options->minPassRate, rateHelp)->check(CLI::Range(0.0, 1.0));
  merge->add_option("dirs", mergeOptions->dirs, "Report folders of the shards")->required();
  merge->add_option("--junit", mergeOptions->junit, "Write the joined JUnit XML to this file");
  merge->add_option("--report-dir", mergeOptions->reportDir, "Write the joined report folder here");
  merge->add_option("--min-pass-rate", mergeOptions->minPassRate, rateHelp)
      ->check(CLI::Range(0.0, 1.0));
}

}  // namespace warpath::tools
