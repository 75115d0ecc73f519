#include "rts/png_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string_view>

#include "render/bitmap_font.h"

namespace warpath::tools {
namespace {

using render::Rgba;

constexpr Rgba kInk{40, 40, 40};
constexpr Rgba kGrid{221, 221, 221};

class Canvas {
 public:
  Canvas(int w, int h, int scale) : image(w, h, Rgba{255, 255, 255}), scale_(scale) {}

  void dot(int x, int y, Rgba c) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                           static_cast<std::size_t>(x)) *
                          4;
    image.pixels[i] = c.r;
    image.pixels[i + 1] = c.g;
    image.pixels[i + 2] = c.b;
  }

  void fill(int x0, int y0, int x1, int y1, Rgba c) {
    for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
      for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x)
        dot(x, y, c);
  }

  // Bresenham, with a square brush `thick` pixels wide.
  void line(int x0, int y0, int x1, int y1, Rgba c, int thick) {
    const int dx = std::abs(x1 - x0);
    const int dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1;
    const int sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    for (;;) {
      fill(x0, y0, x0 + thick - 1, y0 + thick - 1, c);
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * err;
      if (e2 >= dy) {
        err += dy;
        x0 += sx;
      }
      if (e2 <= dx) {
        err += dx;
        y0 += sy;
      }
    }
  }

  int textWidth(std::string_view text) const {
    return static_cast<int>(text.size()) * render::kGlyphAdvance * scale_;
  }
  int textHeight() const { return render::kGlyphHeight * scale_; }

  // `text` with its top-left at (x, y).
  void text(int x, int y, std::string_view text, Rgba c) {
    for (const char ch : text) {
      const auto rows = render::glyphRows(ch);
      for (int r = 0; r < render::kGlyphHeight; ++r) {
        for (int col = 0; col < render::kGlyphWidth; ++col) {
          if ((rows[static_cast<std::size_t>(r)] >> (render::kGlyphWidth - 1 - col) & 1) == 0)
            continue;
          fill(x + col * scale_, y + r * scale_, x + (col + 1) * scale_ - 1,
               y + (r + 1) * scale_ - 1, c);
        }
      }
      x += render::kGlyphAdvance * scale_;
    }
  }

  render::Image image;

 private:
  int scale_;
};

}  // namespace

render::Image rasterLineChart(const LineChart& chart, int width, int height) {
  width = std::clamp(width, 200, 8192);
  height = std::clamp(height, 200, 8192);
  const int scale = std::max(1, std::min(width, height) / 300);
  Canvas canvas(width, height, scale);
  const int th = canvas.textHeight();
  std::size_t longest = 0;
  for (const Series& s : chart.series)
    longest = std::max(longest, s.name.size());
  const int legendWidth =
      std::min(width / 3, static_cast<int>(longest) * render::kGlyphAdvance * scale + 4 * th);
  const int left = canvas.textWidth("0.00") + 3 * th;
  const int right = width - legendWidth - th;
  const int top = 5 * th;  // the title and, under it, the y axis label
  const int bottom = height - 4 * th;

  const std::vector<double> yTicks = niceTicks(chart.yMax, 5);
  const std::vector<double> xTicks = niceTicks(chart.xMax, 8);
  const double xMax = xTicks.back();
  const double yMax = yTicks.back();
  const auto px = [&](double v) {
    return left + static_cast<int>(std::lround(v / xMax * (right - left)));
  };
  const auto py = [&](double v) {
    return bottom - static_cast<int>(std::lround(v / yMax * (bottom - top)));
  };

  canvas.text(left, th, chart.title, kInk);
  for (const double t : yTicks) {
    canvas.line(left, py(t), right, py(t), kGrid, 1);
    const std::string label = tickLabel(t, yTicks[1]);
    canvas.text(left - th / 2 - canvas.textWidth(label), py(t) - th / 2, label, kInk);
  }
  for (const double t : xTicks) {
    canvas.line(px(t), bottom, px(t), bottom + th / 2, kInk, 1);
    const std::string label = tickLabel(t, xTicks[1]);
    canvas.text(px(t) - canvas.textWidth(label) / 2, bottom + th, label, kInk);
  }
  canvas.line(left, top, left, bottom, kInk, 1);
  canvas.line(left, bottom, right, bottom, kInk, 1);
  canvas.text((left + right - canvas.textWidth(chart.xLabel)) / 2, height - th * 3 / 2,
              chart.xLabel, kInk);
  canvas.text(th / 2, th * 3, chart.yLabel, kInk);

  const int thick = std::max(2, scale);
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const Series& s = chart.series[i];
    const Rgba colour = seriesColour(i);
    for (std::size_t k = 1; k < s.xs.size() && k < s.ys.size(); ++k) {
      const double cornerY = chart.steps ? s.ys[k - 1] : s.ys[k];
      canvas.line(px(s.xs[k - 1]), py(s.ys[k - 1]), px(s.xs[k]), py(cornerY), colour, thick);
      if (chart.steps)
        canvas.line(px(s.xs[k]), py(cornerY), px(s.xs[k]), py(s.ys[k]), colour, thick);
    }
    const int y = top + static_cast<int>(i) * th * 2;
    canvas.fill(right + th, y, right + 2 * th, y + th, colour);
    canvas.text(right + 3 * th, y, s.name, kInk);
  }
  return std::move(canvas.image);
}

}  // namespace warpath::tools
