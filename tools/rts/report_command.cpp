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

// A report holds two numbers per unit (arrival time, delay) besides a few KB of figures: the
// 2,000-unit run's is about 100 KB. 4 MiB of numbers parse in about a second within 200 MB.
constexpr FileLimit kReportFileLimit{4 * kMiB, "reports"};
// Reports nest four levels deep; a file nested deeper is no report (and a million levels of
// '[' would cost the parser hundreds of MB).
constexpr int kMaxReportNesting = 32;

// Whether `text`'s arrays and objects nest at most `limit` deep (brackets in strings skipped).
bool nestsWithin(const std::string& text, int limit) {
  int depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return false;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return true;
}

struct PlotOptions {
  std::string report;
  std::string png;
  int width = 900;
  int height = 500;
};

int runPlot(const PlotOptions& options) {
  Result<std::string> text = readFileCapped(options.report, kReportFileLimit);
  if (!text.ok()) throw BadInput{text.error().describe()};
  if (!nestsWithin(text.value(), kMaxReportNesting)) {
    throw BadInput{options.report + ": nested deeper than " + std::to_string(kMaxReportNesting) +
                   " levels: not a JSON report (rts run --report)"};
  }
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
