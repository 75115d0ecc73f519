#include "rts/chart.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "rts/cli_support.h"

namespace warpath::tools {
namespace {

using nlohmann::json;

// `object[key]`, or BadInput naming the key and what it should have been.
const json& field(const json& object, const std::string& key, json::value_t kind) {
  if (!object.is_object() || !object.contains(key))
    throw BadInput{"the report has no '" + key + "'"};
  const json& value = object[key];
  const bool ok = kind == json::value_t::number_float ? value.is_number() : value.type() == kind;
  if (!ok) throw BadInput{"the report's '" + key + "' has the wrong type"};
  return value;
}

double number(const json& object, const std::string& key) {
  return field(object, key, json::value_t::number_float).get<double>();
}

const json& array(const json& object, const std::string& key) {
  return field(object, key, json::value_t::array);
}

std::string text(const json& object, const std::string& key) {
  return field(object, key, json::value_t::string).get<std::string>();
}

std::string pairName(const json& entry) {
  return text(entry, "team") + " " + text(entry, "type");
}

std::vector<double> numbers(const json& object, const std::string& key) {
  std::vector<double> out;
  for (const json& v : array(object, key)) {
    if (!v.is_number()) throw BadInput{"the report's '" + key + "' holds a non-number"};
    out.push_back(v.get<double>());
  }
  return out;
}

}  // namespace

render::Rgba seriesColour(std::size_t index) {
  // Okabe and Ito's palette, without its black and yellow (too faint on white).
  constexpr std::array<render::Rgba, 6> kColours{
      {{0, 114, 178}, {213, 94, 0}, {0, 158, 115}, {204, 121, 167}, {86, 180, 233}, {230, 159, 0}}};
  return kColours[index % kColours.size()];
}

std::vector<double> niceTicks(double max, int wanted) {
  if (!(max > 0.0) || !std::isfinite(max)) max = 1.0;  // a bad report still draws axes
  const double rough = max / std::max(wanted, 1);
  const double power = std::pow(10.0, std::floor(std::log10(rough)));
  double step = power;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= rough) break;
  }
  std::vector<double> ticks;
  for (int i = 0; i <= 2 * wanted + 2; ++i) {  // the bound only guards against rounding
    const double v = step * i;
    ticks.push_back(v);
    if (v >= max * (1 - 1e-9)) break;
  }
  return ticks;
}

std::string tickLabel(double value, double step) {
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return fmt::format("{:.{}f}", value, std::clamp(decimals, 0, 6));
}

LineChart arrivalChart(const json& report) {
  LineChart chart;
  chart.title = "Arrivals over time";
  chart.xLabel = "simulated time (s)";
  chart.yLabel = "fraction arrived";
  chart.steps = true;
  chart.xMax = std::max(number(report, "sim_seconds"), 1e-3);
  if (report.contains("duration_seconds") && report["duration_seconds"].is_number())
    chart.xMax = std::max(chart.xMax, report["duration_seconds"].get<double>());
  std::string none;
  for (const json& entry : array(report, "arrivals")) {
    const double units = number(entry, "units");
    const std::vector<double> times = numbers(entry, "arrived_at");
    const std::string name = pairName(entry);
    if (times.empty() || units <= 0) {
      none += (none.empty() ? "" : ", ") + name + fmt::format(" ({:g})", units);
      continue;
    }
    Series s;
    s.name = fmt::format("{} ({}/{:g})", name, times.size(), units);
    s.xs.push_back(0.0);
    s.ys.push_back(0.0);
    for (std::size_t i = 0; i < times.size(); ++i) {
      s.xs.push_back(times[i]);
      s.ys.push_back(static_cast<double>(i + 1) / units);
    }
    s.xs.push_back(chart.xMax);  // flat to the end of the run
    s.ys.push_back(s.ys.back());
    chart.series.push_back(std::move(s));
  }
  if (!none.empty()) chart.note = "no arrivals: " + none;
  return chart;
}

std::vector<Histogram> delayHistograms(const json& report) {
  const json& movement = field(report, "movement", json::value_t::object);
  std::vector<std::pair<std::string, std::vector<double>>> pairs;
  double lo = 1.0;
  double hi = 1.0;
  for (const json& entry : array(movement, "delay")) {
    std::vector<double> delays = numbers(entry, "delays");
    if (delays.empty()) continue;
    lo = std::min(lo, *std::min_element(delays.begin(), delays.end()));
    hi = std::max(hi, *std::max_element(delays.begin(), delays.end()));
    pairs.emplace_back(pairName(entry), std::move(delays));
  }
  if (pairs.empty()) return {};
  // About 12 bins of a round width over the range of every pair.
  const double width = niceTicks(std::max(hi - lo, 0.1), 12)[1];
  const double first = std::floor(lo / width) * width;
  const auto bins = static_cast<std::size_t>(std::floor((hi - first) / width + 1e-9)) + 1;
  std::vector<Histogram> out;
  for (auto& [name, delays] : pairs) {
    Histogram h;
    h.title = fmt::format("{} ({} units)", name, delays.size());
    h.xLabel = "delay (time to arrive / planned time)";
    h.lo = first;
    h.width = width;
    h.counts.assign(bins, 0);
    for (const double d : delays) {
      const auto bin = static_cast<std::size_t>(std::max(0.0, std::floor((d - first) / width)));
      ++h.counts[std::min(bin, bins - 1)];
    }
    out.push_back(std::move(h));
  }
  return out;
}

BarChart battleChart(const json& report) {
  BarChart chart;
  chart.title = "Kills and losses";
  chart.yLabel = "units";
  Series kills{.name = "kills", .xs = {}, .ys = {}};
  Series losses{.name = "losses", .xs = {}, .ys = {}};
  for (const json& entry : array(report, "battle")) {
    if (number(entry, "kills") == 0 && number(entry, "losses") == 0 &&
        number(entry, "shots_fired") == 0)
      continue;
    chart.categories.push_back(pairName(entry));
    kills.ys.push_back(number(entry, "kills"));
    losses.ys.push_back(number(entry, "losses"));
  }
  chart.series = {std::move(kills), std::move(losses)};
  return chart;
}

BarChart timingChart(const json& report) {
  const json& timing = field(report, "timing", json::value_t::object);
  BarChart chart;
  chart.title = "Wall time per tick by phase";
  chart.yLabel = "ms per tick";
  Series s{.name = "ms per tick", .xs = {}, .ys = {}};
  for (const char* phase : {"pathing", "combat", "steering", "physics", "bookkeeping"}) {
    chart.categories.emplace_back(phase);
    s.ys.push_back(number(timing, std::string(phase) + "_ms"));
  }
  chart.series = {std::move(s)};
  return chart;
}

}  // namespace warpath::tools
