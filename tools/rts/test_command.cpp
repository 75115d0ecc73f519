// `rts test`: run every scenario of a folder and judge its expectations.

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/html_report.h"
#include "rts/scenario_support.h"

namespace warpath::tools {
namespace {

namespace fs = std::filesystem;

struct TestOptions {
  std::string folder;
  std::string html;
};

int runTest(const TestOptions& options) {
  std::error_code error;
  if (!fs::is_directory(options.folder, error))
    throw BadInput{"'" + options.folder + "' is not a folder"};
  std::vector<fs::path> files;
  // The error_code forms: an unreadable folder is bad input, not an uncaught exception.
  fs::directory_iterator entries(options.folder, error);
  if (error) throw BadInput{options.folder + ": cannot read: " + error.message()};
  for (const fs::directory_entry& entry : entries) {
    const fs::path& p = entry.path();
    std::error_code ignored;
    if (entry.is_regular_file(ignored) && (p.extension() == ".yaml" || p.extension() == ".yml"))
      files.push_back(p);
  }
  std::sort(files.begin(), files.end());
  installInterruptHandlers();

  int passed = 0;
  int failed = 0;
  std::vector<HtmlCase> page;  // --html: one section per case
  for (const fs::path& file : files) {
    if (interruptRequested()) break;
    Result<engine::Scenario> loaded = engine::loadScenario(file);
    if (!loaded.ok()) {
      fmt::print("FAIL {}: {}\n", file.string(), loaded.error().describe());
      page.push_back(HtmlCase::failed(file.string(), loaded.error().describe()));
      ++failed;
      continue;
    }
    engine::ScenarioRun run(loaded.value());
    const RunOutcome outcome = runToEnd(run, {});
    const bool ok = !outcome.interrupted && outcome.report.passed();
    fmt::print("{} {} ({} units, {} ticks{}, {:.2f} s)\n", ok ? "PASS" : "FAIL", file.string(),
               run.world().units().size(), outcome.report.ticks,
               outcome.report.winner.empty() ? "" : ", winner " + outcome.report.winner,
               outcome.wallSeconds);
    for (const engine::ExpectationResult& e : outcome.report.expectations) {
      if (!e.pass) fmt::print("  expectation \"{}\" failed: actual {:.4g}\n", e.text, e.actual);
    }
    (ok ? passed : failed) += 1;
    if (!options.html.empty())
      page.push_back(HtmlCase::ran(file.string(), reportJson(outcome, run)));
  }
  if (!options.html.empty()) writeHtmlReport(options.html, "warpath test: " + options.folder, page);
  fmt::print("{} passed, {} failed\n", passed, failed);
  return failed == 0 && !interruptRequested() ? kExitOk : kExitFailed;
}

}  // namespace

void registerTestCommand(CLI::App& app, CommandRunner& run) {
  auto [cmd, options] = addSubcommand<TestOptions>(
      app, run, "test", "Run every scenario (*.yaml) in a folder; ends with \"N passed, N failed\"",
      runTest);
  cmd->add_option("folder", options->folder, "Folder of scenario files")->required();
  cmd->add_option("--html", options->html, "Write one HTML page with every case's charts");
}

}  // namespace warpath::tools
