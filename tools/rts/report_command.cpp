// `rts report plot REPORT.json --png FILE`: the arrival curve of a saved report as a PNG.

#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <string>

#include "pathing/file_read.h"
#include "render/png_io.h"
#include "rts/chart.h"
#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/png_plot.h"

namespace warpath::tools {
namespace {

// Reports of the largest bundled runs (2,000 units, every arrival time) are under 1 MiB.
constexpr FileLimit kReportFileLimit{64 * kMiB, "reports"};

struct PlotOptions {
  std::string report;
  std::string png;
  int width = 900;
  int height = 500;
};

int runPlot(const PlotOptions& options) {
  Result<std::string> text = readFileCapped(options.report, kReportFileLimit);
  if (!text.ok()) throw BadInput{text.error().describe()};
  const nlohmann::json report = nlohmann::json::parse(text.value(), nullptr, false);
  if (report.is_discarded() || !report.is_object())
    throw BadInput{options.report + ": not a JSON report (rts run --report)"};
  LineChart chart;
  try {
    chart = arrivalChart(report);
  } catch (const BadInput& e) {
    throw BadInput{options.report + ": " + e.message};
  }
  if (report.contains("scenario") && report["scenario"].is_string())
    chart.title += ": " + report["scenario"].get<std::string>();
  const render::Image image = rasterLineChart(chart, options.width, options.height);
  if (Status s = render::writePng(options.png, image); !s)
    throw BadInput{"--png: " + s.error().describe()};
  fmt::print("{}: {} curves, {}x{}\n", options.png, chart.series.size(), image.width, image.height);
  return kExitOk;
}

}  // namespace

void registerReportCommand(CLI::App& app, CommandRunner& run) {
  CLI::App* report = app.add_subcommand("report", "Pictures of a saved report (rts run --report)");
  report->require_subcommand(1);
  auto [cmd, options] = addSubcommand<PlotOptions>(
      *report, run, "plot", "Draw the arrival curves of a report as a PNG", runPlot);
  cmd->add_option("report", options->report, "Report JSON file")->required();
  cmd->add_option("--png", options->png, "The PNG file to write")->required();
  cmd->add_option("--width", options->width, "Pixels wide (900)")->check(CLI::Range(200, 8192));
  cmd->add_option("--height", options->height, "Pixels high (500)")->check(CLI::Range(200, 8192));
}

}  // namespace warpath::tools
