#pragma once
// A line chart (chart.h) rasterised into an image, without GL or a font file: lines, axes, grid,
// tick labels and legend in the renderer's 5x7 bitmap font. What `rts report plot --png` writes.

#include "render/image.h"
#include "rts/chart.h"

namespace warpath::tools {

// [Limit: width, height in 200..8192]
render::Image rasterLineChart(const LineChart& chart, int width, int height);

}  // namespace warpath::tools
