// The HTML report and its charts (tools/rts/html_report.h, svg_plot.h, chart.h, png_plot.h):
// self-contained pages, the charts present, names escaped, malformed reports refused; and
// `rts run --html`, `rts test --html` and `rts report plot` end to end.

#include "rts/html_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "render/png_io.h"
#include "rts/chart.h"
#include "rts/cli_support.h"
#include "rts/png_plot.h"
#include "rts/svg_plot.h"
#include "support/rts_process.h"
#include "support/scratch_dir.h"
#include "support/walk_scenario.h"

namespace warpath::tools {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

// A report as reportJson writes it, cut down to what the page reads.
json sampleReport() {
  return json::parse(R"({
    "scenario": "<script>alert('x')</script> & co", "seed": 7, "ticks": 300,
    "sim_seconds": 10.0, "duration_seconds": 12.0, "wall_seconds": 0.5, "units": 5,
    "state_hash": "00000000deadbeef", "complete": true, "passed": false,
    "arrivals": [
      {"team": "blue", "type": "tank", "units": 4, "arrived": 3, "rate": 0.75, "dead": 0,
       "time_to_arrive": {"p50": 4.0, "p90": 6.0, "max": 6.0}, "arrived_at": [2.0, 4.0, 6.0]},
      {"team": "red", "type": "jeep", "units": 1, "arrived": 0, "rate": 0.0, "dead": 1,
       "time_to_arrive": {"p50": null, "p90": null, "max": null}, "arrived_at": []}],
    "movement": {"cooperative": false, "window": 16, "waits": 0, "give_ways": 0,
                 "deadlocks_broken": 0, "max_wait_s": 0.0,
                 "delay": [{"team": "blue", "type": "tank", "arrived": 3, "p50": 1.1,
                            "p90": 1.4, "max": 1.4, "delays": [1.0, 1.1, 1.4]},
                           {"team": "red", "type": "jeep", "arrived": 0, "p50": null,
                            "p90": null, "max": null, "delays": []}]},
    "battle": [{"team": "blue", "type": "tank", "units": 4, "alive": 4, "losses": 0,
                "kills": 1, "shots_fired": 5, "hits": 3, "damage_dealt": 90,
                "damage_taken": 0},
               {"team": "red", "type": "jeep", "units": 1, "alive": 0, "losses": 1,
                "kills": 0, "shots_fired": 2, "hits": 0, "damage_dealt": 0,
                "damage_taken": 90}],
    "winner": "blue", "victory": "eliminate", "end_tick": 290,
    "pathing": {"algo": "hybrid", "requests": 4, "cache_hits": 0, "searches": 4, "found": 4,
                "failed": 0, "expanded": 100, "max_queue": 2, "search_us": 50,
                "preprocess_ms": 1.5},
    "repaths": 0, "no_path_units": 0, "stuck_units": {"count": 0, "ids": []},
    "timing": {"ms_per_tick": 0.2, "pathing_ms": 0.05, "combat_ms": 0.01, "steering_ms": 0.02,
               "physics_ms": 0.1, "bookkeeping_ms": 0.02, "slowest_tick_ms": 1.0,
               "static_boxes": 3},
    "expectations": [{"text": "arrival_rate(blue, tank) >= 0.5 by 10s", "actual": 0.75,
                      "pass": true},
                     {"text": "losses(red, jeep) <= 0", "actual": 1, "pass": false}]
  })");
}

TEST(Charts, NiceTicksAreRoundAndReachTheMaximum) {
  EXPECT_EQ(niceTicks(120, 8), (std::vector<double>{0, 20, 40, 60, 80, 100, 120}));
  const std::vector<double> unit = niceTicks(1.0, 5);
  ASSERT_EQ(unit.size(), 6u);
  EXPECT_DOUBLE_EQ(unit[1], 0.2);
  EXPECT_GE(niceTicks(7.3, 5).back(), 7.3);
  EXPECT_EQ(niceTicks(-1, 5).back(), 1.0);  // nonsense draws [0, 1]
  EXPECT_EQ(tickLabel(0.4, 0.2), "0.4");
  EXPECT_EQ(tickLabel(40, 20), "40");
}

TEST(Charts, ArrivalCurveStepsByEachArrival) {
  const LineChart chart = arrivalChart(sampleReport());
  EXPECT_DOUBLE_EQ(chart.xMax, 12.0);  // the scenario's duration
  ASSERT_EQ(chart.series.size(), 1u);  // red jeep never arrived: in the note
  const Series& s = chart.series[0];
  EXPECT_EQ(s.name, "blue tank (3/4)");
  EXPECT_EQ(s.xs, (std::vector<double>{0, 2, 4, 6, 12}));
  EXPECT_EQ(s.ys, (std::vector<double>{0, 0.25, 0.5, 0.75, 0.75}));
  EXPECT_EQ(chart.note, "no arrivals: red jeep (1)");
}

TEST(Charts, DelayHistogramsShareBins) {
  const std::vector<Histogram> hs = delayHistograms(sampleReport());
  ASSERT_EQ(hs.size(), 1u);
  int total = 0;
  for (const int c : hs[0].counts)
    total += c;
  EXPECT_EQ(total, 3);
  EXPECT_LE(hs[0].lo, 1.0);
  EXPECT_GT(hs[0].lo + hs[0].width * static_cast<double>(hs[0].counts.size()), 1.4);
}

TEST(Charts, MalformedReportsAreRefusedNamingTheKey) {
  json r = sampleReport();
  r.erase("arrivals");
  try {
    arrivalChart(r);
    FAIL() << "accepted a report without arrivals";
  } catch (const BadInput& e) {
    EXPECT_EQ(e.message, "the report has no 'arrivals'");
  }
  r = sampleReport();
  r["arrivals"][0]["arrived_at"] = "soon";
  EXPECT_THROW(arrivalChart(r), BadInput);
  r = sampleReport();
  r["movement"]["delay"][0]["delays"][1] = "x";
  EXPECT_THROW(delayHistograms(r), BadInput);
}

TEST(Svg, EscapesMarkup) {
  EXPECT_EQ(escapeXml("<a href=\"x\">'&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
  LineChart chart;
  chart.title = "<b>";
  chart.series.push_back({.name = "a&b", .xs = {0, 1}, .ys = {0, 1}});
  const std::string svg = svgLineChart(chart);
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
  EXPECT_NE(svg.find("&lt;b&gt;"), std::string::npos);
  EXPECT_NE(svg.find("a&amp;b"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 1);
}

TEST(HtmlPage, IsSelfContainedAndHasEveryChart) {
  const fs::path dir = warpath::testing::freshTestDir("warpath_html_");
  std::ofstream(dir / "run.gif", std::ios::binary) << "GIF89a";
  HtmlCase c = HtmlCase::ran("a <case>", sampleReport());
  c.gif = (dir / "run.gif").string();
  const std::string page = htmlReport("title <1>", {c}, dir.string());
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  // Nothing to fetch: no address of any scheme, no script.
  EXPECT_EQ(page.find("http:"), std::string::npos);
  EXPECT_EQ(page.find("https:"), std::string::npos);
  EXPECT_EQ(page.find("//"), std::string::npos);
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  // The scenario's name (with markup in it) is text.
  EXPECT_NE(page.find("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; co"),
            std::string::npos);
  EXPECT_NE(page.find("title &lt;1&gt;"), std::string::npos);
  EXPECT_NE(page.find("a &lt;case&gt;"), std::string::npos);
  // Arrivals, one delay histogram, battle and timing.
  EXPECT_EQ(count(page, "<svg class=\"chart\""), 4);
  EXPECT_EQ(count(page, "<polyline class=\"series\""), 1);
  // The expectations with their results and values.
  EXPECT_NE(page.find("losses(red, jeep) &lt;= 0</td><td><span class=\"fail\">FAIL</span></td>"
                      "<td>1</td>"),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"pass\">PASS</span></td><td>0.75</td>"), std::string::npos);
  EXPECT_NE(page.find("src=\"data:image/gif;base64,R0lGODlh\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(HtmlPage, ListsCasesAndFailedLoads) {
  const std::string page = htmlReport("suite",
                                      {HtmlCase::ran("one.yaml", sampleReport()),
                                       HtmlCase::failed("two.yaml", "two.yaml:3:1: bad")},
                                      ".");
  EXPECT_NE(page.find("0 passed, 2 failed"), std::string::npos);
  EXPECT_NE(page.find("<a href=\"#case-1\">two.yaml</a>"), std::string::npos);
  EXPECT_NE(page.find("two.yaml:3:1: bad"), std::string::npos);
  json broken = sampleReport();
  broken["timing"] = 3;
  try {
    htmlReport("suite", {HtmlCase::ran("three.yaml", broken)}, ".");
    FAIL() << "accepted a report with a bad timing section";
  } catch (const BadInput& e) {
    EXPECT_EQ(e.message.rfind("three.yaml: ", 0), 0u) << e.message;
  }
}

TEST(PngPlot, DrawsTheCurvesOnWhite) {
  const render::Image image = rasterLineChart(arrivalChart(sampleReport()), 400, 300);
  ASSERT_EQ(image.width, 400);
  ASSERT_EQ(image.height, 300);
  const render::Rgba colour = seriesColour(0);
  int curve = 0;
  int white = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const render::Rgba p = image.at(x, y);
      curve += p == colour ? 1 : 0;
      white += p == render::Rgba{255, 255, 255, 255} ? 1 : 0;
    }
  }
  EXPECT_GT(curve, 300);  // the staircase, two pixels thick, and the legend's swatch
  EXPECT_GT(white, image.width * image.height / 2);
}

// End to end through the `rts` binary.
class HtmlCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = warpath::testing::freshTestDir("warpath_html_cli_");
    fs::create_directories(dir_ / "suite");
    // Its name, with markup in it, shows escaped.
    scenario_ =
        warpath::testing::writeWalkScenario(dir_ / "suite" / "s.yaml", "small <&> run").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string slurp(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }

  fs::path dir_;
  std::string scenario_;
};

TEST_F(HtmlCli, RunWritesThePageAndTheReportGainsArrivalTimes) {
  const fs::path html = dir_ / "out" / "page.html";
  const fs::path report = dir_ / "report.json";
  const warpath::testing::RtsResult r = warpath::testing::rts(
      "run " + scenario_ + " --quiet --report " + report.string() + " --html " + html.string() +
      " --gif " + (dir_ / "run.gif").string() + " --frame-every 30 --frame-size 64");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string page = slurp(html);
  EXPECT_NE(page.find("small &lt;&amp;&gt; run"), std::string::npos);
  EXPECT_GE(count(page, "<svg class=\"chart\""), 2);  // arrivals and timing at least
  EXPECT_NE(page.find("data:image/gif;base64,"), std::string::npos);
  EXPECT_EQ(page.find("http"), std::string::npos);
  const json j = json::parse(slurp(report));
  ASSERT_EQ(j["arrivals"][0]["arrived_at"].size(), 2u);
  EXPECT_LE(j["arrivals"][0]["arrived_at"][0].get<double>(),
            j["arrivals"][0]["arrived_at"][1].get<double>());
  EXPECT_EQ(j["movement"]["delay"][0]["delays"].size(), 2u);
}

TEST_F(HtmlCli, TestWritesOnePageForTheFolder) {
  std::ofstream(dir_ / "suite" / "t.yaml") << "map: [unclosed\n";
  const fs::path html = dir_ / "suite.html";
  const warpath::testing::RtsResult r =
      warpath::testing::rts("test " + (dir_ / "suite").string() + " --html " + html.string());
  EXPECT_EQ(r.status, 1) << r.out;  // t.yaml is bad
  const std::string page = slurp(html);
  EXPECT_NE(page.find("1 passed, 1 failed"), std::string::npos);
  EXPECT_NE(page.find("id=\"case-1\""), std::string::npos);
  EXPECT_GE(count(page, "<svg class=\"chart\""), 2);
}

TEST_F(HtmlCli, ReportPlotDrawsAPngAndRefusesBadReports) {
  const fs::path report = dir_ / "report.json";
  ASSERT_EQ(
      warpath::testing::rts("run " + scenario_ + " --quiet --report " + report.string()).status, 0);
  const fs::path png = dir_ / "plot.png";
  warpath::testing::RtsResult r = warpath::testing::rts(
      "report plot " + report.string() + " --png " + png.string() + " --width 320 --height 240");
  ASSERT_EQ(r.status, 0) << r.out;
  auto image = render::readPng(png);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  EXPECT_EQ(image.value().width, 320);
  EXPECT_EQ(image.value().height, 240);

  std::ofstream(dir_ / "cut.json") << "{\"sim_seconds\": ";
  r = warpath::testing::rts("report plot " + (dir_ / "cut.json").string() + " --png " +
                            png.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("cut.json: not a JSON report"), std::string::npos) << r.out;
  std::ofstream(dir_ / "old.json") << R"({"sim_seconds": 5, "arrivals": [{"team": "a",
      "type": "b", "units": 1}]})";
  r = warpath::testing::rts("report plot " + (dir_ / "old.json").string() + " --png " +
                            png.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("old.json: the report has no 'arrived_at'"), std::string::npos) << r.out;
  std::ofstream(dir_ / "deep.json") << std::string(100, '[') + std::string(100, ']');
  r = warpath::testing::rts("report plot " + (dir_ / "deep.json").string() + " --png " +
                            png.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("deep.json: nested deeper than 32 levels"), std::string::npos) << r.out;
  r = warpath::testing::rts("report plot " + (dir_ / "none.json").string() + " --png " +
                            png.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("none.json: no such file"), std::string::npos) << r.out;
}

TEST_F(HtmlCli, VideoWithoutFfmpegIsAClearError) {
  const warpath::testing::RtsResult r =
      warpath::testing::shell("PATH=/nonexistent " RTS_BINARY " run " + scenario_ +
                              " --quiet --video " + (dir_ / "v.mp4").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--video: ffmpeg was not found on PATH"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace warpath::tools
