#pragma once
// Charts (chart.h) as inline SVG elements for the HTML report: text the page embeds as it is,
// so the page needs no script, no font and no network.

#include <string>
#include <string_view>

#include "rts/chart.h"

namespace warpath::tools {

// `text` with &, <, >, " and ' replaced by entities, and newline, tab and CR as character
// references: safe in element content and in quoted attributes of HTML, SVG and XML alike (the
// JUnit file of `rts test` too). Characters XML 1.0 forbids become '?', bytes that are not
// UTF-8 U+FFFD, so the text is always well-formed.
std::string escapeXml(std::string_view text);

// One <svg class="chart"> element each, with a <title>, axes, tick labels and a legend.
std::string svgLineChart(const LineChart& chart);
std::string svgBarChart(const BarChart& chart);
std::string svgHistogram(const Histogram& histogram);

}  // namespace warpath::tools
