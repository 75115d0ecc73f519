#include "rts/svg_plot.h"

#include <fmt/core.h>

#include <algorithm>

namespace warpath::tools {
namespace {

// A chart's size and margins. [Unit: pixels]
struct Layout {
  double width = 720;
  double height = 340;
  double left = 60;    // room for the y tick labels and the y axis label
  double right = 210;  // room for the legend
  double top = 30;     // the title
  double bottom = 50;  // the x tick labels and the x axis label
};

// Histograms come several to a case, side by side, and have no legend.
constexpr Layout kSmall{
    .width = 440, .height = 240, .left = 50, .right = 20, .top = 30, .bottom = 50};

std::string colourText(render::Rgba c) {
  return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
}

// The plot area and the mapping of data to pixels, y up.
struct Area {
  Layout l;
  double xMax = 1.0;
  double yMax = 1.0;
  double x(double v) const { return l.left + v / xMax * (l.width - l.left - l.right); }
  double y(double v) const {
    return l.height - l.bottom - v / yMax * (l.height - l.top - l.bottom);
  }
};

std::string open(const Layout& l, const std::string& title) {
  return fmt::format(
      "<svg class=\"chart\" role=\"img\" width=\"{0}\" "
      "height=\"{1}\" viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"11\">"
      "<title>{2}</title><rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>"
      "<text x=\"{3}\" y=\"18\" font-size=\"13\" font-weight=\"bold\">{2}</text>",
      l.width, l.height, escapeXml(title), l.left);
}

// The y axis with grid lines at `ticks` (yMax is the last), and its label.
std::string yAxis(const Area& a, const std::vector<double>& ticks, const std::string& label) {
  std::string out;
  const double step = ticks.size() > 1 ? ticks[1] : 1.0;
  for (const double t : ticks) {
    out += fmt::format(
        "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>",
        a.l.left, a.l.width - a.l.right, a.y(t), a.l.left - 6, a.y(t) + 4, tickLabel(t, step));
  }
  out += fmt::format(
      "<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#333\"/>"
      "<text transform=\"translate(14 {3}) rotate(-90)\" text-anchor=\"middle\">{4}</text>",
      a.l.left, a.l.top, a.l.height - a.l.bottom, (a.l.top + a.l.height - a.l.bottom) / 2,
      escapeXml(label));
  return out;
}

// The x axis line.
std::string xLine(const Area& a) {
  return fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#333\"/>",
                     a.l.left, a.l.width - a.l.right, a.l.height - a.l.bottom);
}

// A label under the x axis at `x` (in data units).
std::string xTickLabel(const Area& a, double x, const std::string& label) {
  return fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>", a.x(x),
                     a.l.height - a.l.bottom + 16, escapeXml(label));
}

// The x axis's label, centred under it.
std::string xLabel(const Area& a, const std::string& label) {
  return fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                     (a.l.left + a.l.width - a.l.right) / 2, a.l.height - 10, escapeXml(label));
}

// The x axis line, numeric ticks and label.
std::string xAxis(const Area& a, const std::vector<double>& ticks, double step,
                  const std::string& label) {
  std::string out = xLine(a);
  for (const double t : ticks) {
    out +=
        fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#333\"/>",
                    a.x(t), a.l.height - a.l.bottom, a.l.height - a.l.bottom + 4);
    out += xTickLabel(a, t, tickLabel(t, step));
  }
  return out + xLabel(a, label);
}

std::string legend(const Layout& l, const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const double y = l.top + 8 + 18 * static_cast<double>(i);
    out += fmt::format(
        "<rect class=\"swatch\" x=\"{0}\" y=\"{1}\" width=\"12\" height=\"12\" fill=\"{2}\"/>"
        "<text x=\"{3}\" y=\"{4}\">{5}</text>",
        l.width - l.right + 14, y, colourText(seriesColour(i)), l.width - l.right + 32, y + 10,
        escapeXml(names[i]));
  }
  return out;
}

// The length of the UTF-8 sequence starting `text` at `i`, or 0 when it is not one.
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  if (lead >= 0xC2 && lead <= 0xDF)
    length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF)
    length = 3;
  else if (lead >= 0xF0 && lead <= 0xF4)
    length = 4;
  if (length == 0 || i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  // Overlong forms and surrogates (the second byte's range after E0, ED, F0 and F4).
  if ((lead == 0xE0 && byte(i + 1) < 0xA0) || (lead == 0xED && byte(i + 1) > 0x9F) ||
      (lead == 0xF0 && byte(i + 1) < 0x90) || (lead == 0xF4 && byte(i + 1) > 0x8F))
    return 0;
  return length;
}

}  // namespace

std::string escapeXml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      const std::size_t length = utf8Length(text, i);
      if (length == 0) {
        out += "\xEF\xBF\xBD";  // U+FFFD
        ++i;
      } else {
        out.append(text.substr(i, length));
        i += length;
      }
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      case '\n':  // a reference, so that attribute values keep it too
        out += "&#10;";
        break;
      case '\t':
        out += "&#9;";
        break;
      case '\r':
        out += "&#13;";
        break;
      default:
        out += c < 0x20 ? '?' : static_cast<char>(c);
    }
    ++i;
  }
  return out;
}

std::string svgLineChart(const LineChart& chart) {
  const std::vector<double> yTicks = niceTicks(chart.yMax, 5);
  const std::vector<double> xTicks = niceTicks(chart.xMax, 8);
  const Area a{.l = {}, .xMax = xTicks.back(), .yMax = yTicks.back()};
  std::string out = open(a.l, chart.title) + yAxis(a, yTicks, chart.yLabel) +
                    xAxis(a, xTicks, xTicks[1], chart.xLabel);
  std::vector<std::string> names;
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const Series& s = chart.series[i];
    names.push_back(s.name);
    std::string points;
    for (std::size_t k = 0; k < s.xs.size() && k < s.ys.size(); ++k) {
      if (chart.steps && k > 0)  // along at the old value, then up
        points += fmt::format("{:.1f},{:.1f} ", a.x(s.xs[k]), a.y(s.ys[k - 1]));
      points += fmt::format("{:.1f},{:.1f} ", a.x(s.xs[k]), a.y(s.ys[k]));
    }
    out += fmt::format(
        "<polyline class=\"series\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\" "
        "points=\"{}\"><title>{}</title></polyline>",
        colourText(seriesColour(i)), points, escapeXml(s.name));
  }
  return out + legend(a.l, names) + "</svg>";
}

std::string svgBarChart(const BarChart& chart) {
  double top = 0.0;
  for (const Series& s : chart.series)
    for (const double v : s.ys)
      top = std::max(top, v);
  const std::vector<double> yTicks = niceTicks(top, 5);
  const double groups = static_cast<double>(std::max<std::size_t>(chart.categories.size(), 1));
  // Categories are drawn at 0..groups on the x axis, one unit each.
  const Area a{.l = {}, .xMax = groups, .yMax = yTicks.back()};
  std::string out = open(a.l, chart.title) + yAxis(a, yTicks, chart.yLabel) + xLine(a);
  const double groupWidth = a.x(1) - a.x(0);
  const double bars = static_cast<double>(std::max<std::size_t>(chart.series.size(), 1));
  const double barWidth = groupWidth * 0.8 / bars;
  for (std::size_t c = 0; c < chart.categories.size(); ++c) {
    const double x0 = a.x(static_cast<double>(c)) + groupWidth * 0.1;
    for (std::size_t i = 0; i < chart.series.size(); ++i) {
      const double v = c < chart.series[i].ys.size() ? chart.series[i].ys[c] : 0.0;
      out += fmt::format(
          "<rect class=\"bar\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" "
          "fill=\"{}\"><title>{}: {} {:g}</title></rect>",
          x0 + barWidth * static_cast<double>(i), a.y(v), barWidth, a.y(0) - a.y(v),
          colourText(seriesColour(i)), escapeXml(chart.categories[c]),
          escapeXml(chart.series[i].name), v);
    }
    out += xTickLabel(a, static_cast<double>(c) + 0.5, chart.categories[c]);
  }
  std::vector<std::string> names;
  for (const Series& s : chart.series)
    names.push_back(s.name);
  return out + legend(a.l, names) + "</svg>";
}

std::string svgHistogram(const Histogram& h) {
  const int top =
      h.counts.empty() ? 1 : std::max(1, *std::max_element(h.counts.begin(), h.counts.end()));
  const std::vector<double> yTicks = niceTicks(top, std::min(top, 5));  // whole units
  const double span = h.width * static_cast<double>(std::max<std::size_t>(h.counts.size(), 1));
  // Bins are drawn from 0 at the left edge; the tick labels add lo back.
  const Area a{.l = kSmall, .xMax = span, .yMax = yTicks.back()};
  std::string out = open(a.l, h.title) + yAxis(a, yTicks, "units") + xLine(a);
  const std::size_t labelEvery = std::max<std::size_t>(1, h.counts.size() / 8);
  for (std::size_t i = 0; i <= h.counts.size(); ++i) {
    const double edge = h.width * static_cast<double>(i);
    if (i % labelEvery == 0) out += xTickLabel(a, edge, tickLabel(h.lo + edge, h.width));
    if (i == h.counts.size()) break;
    const double v = h.counts[i];
    out += fmt::format(
        "<rect class=\"bar\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" "
        "fill=\"{}\" stroke=\"#fff\"><title>{}..{}: {}</title></rect>",
        a.x(edge), a.y(v), a.x(edge + h.width) - a.x(edge), a.y(0) - a.y(v),
        colourText(seriesColour(0)), tickLabel(h.lo + edge, h.width / 10),
        tickLabel(h.lo + edge + h.width, h.width / 10), h.counts[i]);
  }
  return out + xLabel(a, h.xLabel) + "</svg>";
}

}  // namespace warpath::tools
