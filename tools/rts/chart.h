#pragma once
// Charts of a run's report (the JSON object of `rts run --report`), as plain data that the SVG
// writer (svg_plot.h, for the HTML page) and the PNG rasteriser (png_plot.h, `rts report plot`)
// both draw, so that both show the same curves from the same numbers.

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/image.h"

namespace warpath::tools {

// Series colours, in order (a colour-blind-safe qualitative palette); repeats past the end.
render::Rgba seriesColour(std::size_t index);

struct Series {
  std::string name;
  std::vector<double> xs;  // as many as ys
  std::vector<double> ys;
};

// Lines through each series' points; `steps` draws them as a staircase (a count that jumps at
// each x), as the arrival curve is.
struct LineChart {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  double xMax = 1.0;  // the axes run from 0 to xMax and 0 to yMax
  double yMax = 1.0;
  bool steps = false;
  std::vector<Series> series;
  std::string note;  // a line to print under the chart (what was left out); empty: none
};

// Grouped bars: one group per category, one bar per series in each.
struct BarChart {
  std::string title;
  std::string yLabel;
  std::vector<std::string> categories;
  std::vector<Series> series;  // ys: one value per category (xs unused)
};

// Counts of values in equal bins from `lo` in steps of `width`.
struct Histogram {
  std::string title;
  std::string xLabel;
  double lo = 0.0;
  double width = 1.0;       // [Limit: > 0]
  std::vector<int> counts;  // one per bin
};

// Up to about `wanted` round tick values (1, 2 or 5 times a power of ten apart) from 0 to at
// least `max`; [Limit: max > 0, wanted >= 1].
std::vector<double> niceTicks(double max, int wanted);

// A tick label: as few decimals as the step needs.
std::string tickLabel(double value, double step);

// Arrivals by simulated time per (team, type), as the fraction of the pair's units that have
// arrived; pairs none of whose units arrived are named in the note. Throws BadInput naming the
// key when the report lacks what it needs (reports written before arrival times were recorded
// included).
LineChart arrivalChart(const nlohmann::json& report);

// The delays (time to arrive / planned time) of the units of one (team, type) pair, in bins
// shared by every pair of the report. Empty when no unit has a delay.
std::vector<Histogram> delayHistograms(const nlohmann::json& report);

// Kills and losses per (team, type); empty categories when the report has no battle.
BarChart battleChart(const nlohmann::json& report);

// Mean wall time per tick by phase.
BarChart timingChart(const nlohmann::json& report);

}  // namespace warpath::tools
