#include "rts/html_report.h"

#include <fmt/core.h>

#include <filesystem>
#include <fstream>

#include "pathing/file_read.h"
#include "rts/chart.h"
#include "rts/cli_support.h"
#include "rts/svg_plot.h"

namespace warpath::tools {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::string_view kStyle = R"(
body { font-family: sans-serif; margin: 2em; color: #222; max-width: 1100px; }
h1 { font-size: 1.5em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; }
h3 { font-size: 1.05em; margin-bottom: 0.3em; }
table { border-collapse: collapse; margin: 0.5em 0 1em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: right; }
th:first-child, td:first-child { text-align: left; }
.pass { color: #1a7f37; font-weight: bold; } .fail { color: #c0392b; font-weight: bold; }
.meta { color: #555; } .note { color: #666; font-size: 0.9em; }
svg.chart { display: block; margin: 0.5em 0; border: 1px solid #eee; }
.charts { display: flex; flex-wrap: wrap; gap: 0.5em; }
img.run { max-width: 100%; image-rendering: pixelated; border: 1px solid #ccc; }
)";

// Reading a GIF into the page: the frames folder and the GIF writer cap what they write far
// below this; a larger file is linked instead.
constexpr FileLimit kEmbeddedGifLimit{64 * kMiB, "GIFs embedded in the HTML report"};

std::string base64(std::string_view bytes) {
  constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k)
      v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k)
      out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string cell(const json& v) {
  if (v.is_null()) return "&ndash;";
  if (v.is_number_float()) return fmt::format("{:.4g}", v.get<double>());
  if (v.is_string()) return escapeXml(v.get<std::string>());
  return escapeXml(v.dump());
}

// A table of `rows` (JSON objects) with the given keys as columns.
std::string table(const json& rows,
                  const std::vector<std::pair<std::string, std::string>>& columns) {
  std::string out = "<table><tr>";
  for (const auto& [key, heading] : columns)
    out += "<th>" + escapeXml(heading) + "</th>";
  out += "</tr>";
  for (const json& row : rows) {
    out += "<tr>";
    for (const auto& [key, heading] : columns) {
      // "a.b" reaches into a nested object (time_to_arrive.p50).
      const json* v = &row;
      for (std::size_t start = 0; v != nullptr;) {
        const std::size_t dot = key.find('.', start);
        const std::string part = key.substr(start, dot - start);
        v = v->is_object() && v->contains(part) ? &(*v)[part] : nullptr;
        if (dot == std::string::npos) break;
        start = dot + 1;
      }
      out += "<td>" + (v ? cell(*v) : std::string("&ndash;")) + "</td>";
    }
    out += "</tr>";
  }
  return out + "</table>";
}

std::string passText(bool pass) {
  return pass ? "<span class=\"pass\">PASS</span>" : "<span class=\"fail\">FAIL</span>";
}

std::string relativeLink(const std::string& target, const std::string& pageDir) {
  std::error_code error;
  const fs::path rel =
      fs::relative(fs::absolute(target, error), fs::absolute(pageDir, error), error);
  return escapeXml(error || rel.empty() ? target : rel.generic_string());
}

std::string pictures(const HtmlCase& c, const std::string& pageDir) {
  std::string out;
  if (!c.gif.empty()) {
    Result<std::string> bytes = readFileCapped(c.gif, kEmbeddedGifLimit);
    if (bytes.ok()) {
      out += "<img class=\"run\" alt=\"the run as an animated GIF\" src=\"data:image/gif;base64," +
             base64(bytes.value()) + "\">";
    } else {
      out += "<p>GIF: <a href=\"" + relativeLink(c.gif, pageDir) + "\">" + escapeXml(c.gif) +
             "</a> (" + escapeXml(bytes.error().describe()) + ")</p>";
    }
  }
  if (!c.video.empty()) {
    out += "<p><video controls src=\"" + relativeLink(c.video, pageDir) +
           "\"></video><br>video: <a href=\"" + relativeLink(c.video, pageDir) + "\">" +
           escapeXml(c.video) + "</a></p>";
  }
  if (!c.framesDir.empty()) {
    out += "<p>PNG frames: <a href=\"" + relativeLink(c.framesDir, pageDir) + "\">" +
           escapeXml(c.framesDir) + "</a></p>";
  }
  return out.empty() ? out : "<h3>Pictures</h3>" + out;
}

std::string caseSection(const HtmlCase& c, const std::string& pageDir, std::size_t index) {
  std::string out = fmt::format("<section id=\"case-{}\"><h2>{}</h2>", index, escapeXml(c.name));
  if (!c.error.empty() || !c.report.is_object()) {
    return out + "<p>" + passText(false) + " " +
           escapeXml(c.error.empty() ? "no report" : c.error) + "</p></section>";
  }
  const json& r = c.report;
  const auto get = [&](const char* key) { return r.contains(key) ? r[key] : json(); };
  out += fmt::format(
      "<p class=\"meta\">{} &middot; scenario {} &middot; seed {} &middot; {} ticks, {} s "
      "simulated in {} s &middot; {} units &middot; state hash {}{}</p>",
      passText(get("passed").is_boolean() && get("passed").get<bool>()), cell(get("scenario")),
      cell(get("seed")), cell(get("ticks")), cell(get("sim_seconds")), cell(get("wall_seconds")),
      cell(get("units")), cell(get("state_hash")),
      get("complete").is_boolean() && !get("complete").get<bool>() ? " &middot; incomplete" : "");
  if (get("winner").is_string()) {
    out += "<p>Winner: <b>" + cell(get("winner")) + "</b> (" + cell(get("victory")) + ") at tick " +
           cell(get("end_tick")) + "</p>";
  }

  out += "<h3>Expectations</h3>";
  if (get("expectations").empty()) {
    out += "<p class=\"note\">none</p>";
  } else {
    out += "<table><tr><th>expectation</th><th>result</th><th>actual</th></tr>";
    for (const json& e : get("expectations")) {
      out += "<tr><td>" + cell(e.value("text", json())) + "</td><td>" +
             passText(e.value("pass", false)) + "</td><td>" + cell(e.value("actual", json())) +
             "</td></tr>";
    }
    out += "</table>";
  }

  const LineChart arrivals = arrivalChart(r);
  out += "<h3>Arrivals</h3>" + svgLineChart(arrivals);
  if (!arrivals.note.empty()) out += "<p class=\"note\">" + escapeXml(arrivals.note) + "</p>";
  out += table(get("arrivals"), {{"team", "team"},
                                 {"type", "type"},
                                 {"units", "units"},
                                 {"arrived", "arrived"},
                                 {"rate", "rate"},
                                 {"dead", "dead"},
                                 {"time_to_arrive.p50", "p50 (s)"},
                                 {"time_to_arrive.p90", "p90 (s)"},
                                 {"time_to_arrive.max", "max (s)"}});

  out += "<h3>Delays</h3>";
  const std::vector<Histogram> delays = delayHistograms(r);
  if (delays.empty()) {
    out += "<p class=\"note\">no unit arrived with a planned time to compare against</p>";
  } else {
    out += "<div class=\"charts\">";
    for (const Histogram& h : delays)
      out += svgHistogram(h);
    out += "</div>";
  }
  const json movement = get("movement");
  out += table(json::array({movement}), {{"cooperative", "cooperative"},
                                         {"window", "window"},
                                         {"waits", "waits"},
                                         {"give_ways", "give-ways"},
                                         {"deadlocks_broken", "deadlocks broken"},
                                         {"max_wait_s", "max wait (s)"}});

  const BarChart battle = battleChart(r);
  if (!battle.categories.empty()) {
    out += "<h3>Battle</h3>" + svgBarChart(battle);
    out += table(get("battle"), {{"team", "team"},
                                 {"type", "type"},
                                 {"units", "units"},
                                 {"alive", "alive"},
                                 {"losses", "losses"},
                                 {"kills", "kills"},
                                 {"shots_fired", "shots"},
                                 {"hits", "hits"},
                                 {"damage_dealt", "damage dealt"},
                                 {"damage_taken", "damage taken"}});
  }

  out += "<h3>Pathing</h3>" +
         table(json::array({get("pathing")}), {{"algo", "algorithm"},
                                               {"requests", "requests"},
                                               {"cache_hits", "cache hits"},
                                               {"searches", "searches"},
                                               {"found", "found"},
                                               {"failed", "failed"},
                                               {"expanded", "expanded"},
                                               {"max_queue", "max queue"},
                                               {"search_us", "search time (us)"},
                                               {"preprocess_ms", "preprocess ms"}});
  out += fmt::format(
      "<p>Repaths {}, units with no path {}, stuck units {}.</p>", cell(get("repaths")),
      cell(get("no_path_units")),
      cell(get("stuck_units").is_object() ? get("stuck_units").value("count", json()) : json()));

  out += "<h3>Timing</h3>" + svgBarChart(timingChart(r));
  out += table(json::array({get("timing")}), {{"ms_per_tick", "ms per tick"},
                                              {"slowest_tick_ms", "slowest tick (ms)"},
                                              {"static_boxes", "static boxes"}});
  out += pictures(c, pageDir);
  return out + "</section>";
}

}  // namespace

std::string htmlReport(const std::string& title, const std::vector<HtmlCase>& cases,
                       const std::string& pageDir) {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
                    escapeXml(title) + "</title><style>" + std::string(kStyle) +
                    "</style></head><body><h1>" + escapeXml(title) + "</h1>";
  int passed = 0;
  for (const HtmlCase& c : cases)
    passed += c.error.empty() && c.report.is_object() && c.report.value("passed", false) ? 1 : 0;
  out += fmt::format("<p>{} passed, {} failed</p>", passed,
                     cases.size() - static_cast<std::size_t>(passed));
  if (cases.size() > 1) {
    out +=
        "<table><tr><th>case</th><th>result</th><th>winner</th><th>failed expectations</th></tr>";
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const HtmlCase& c = cases[i];
      const bool ran = c.error.empty() && c.report.is_object();
      int failed = 0;
      if (ran && c.report.contains("expectations")) {
        for (const json& e : c.report["expectations"])
          failed += e.value("pass", false) ? 0 : 1;
      }
      out += fmt::format(
          "<tr><td><a href=\"#case-{}\">{}</a></td><td>{}</td><td>{}</td><td>{}</td></tr>", i,
          escapeXml(c.name), passText(ran && c.report.value("passed", false)),
          ran ? cell(c.report.value("winner", json())) : "&ndash;",
          ran ? std::to_string(failed) : escapeXml(c.error));
    }
    out += "</table>";
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    try {
      out += caseSection(cases[i], pageDir, i);
    } catch (const BadInput& e) {
      throw BadInput{cases[i].name + ": " + e.message};
    } catch (const json::exception& e) {  // a report of the wrong shape
      throw BadInput{cases[i].name + ": the report is malformed: " + e.what()};
    }
  }
  return out + "</body></html>\n";
}

void writeHtmlReport(const std::string& file, const std::string& title,
                     const std::vector<HtmlCase>& cases) {
  const fs::path parent = fs::path(file).parent_path();
  std::error_code error;
  if (!parent.empty()) fs::create_directories(parent, error);
  const std::string page = htmlReport(title, cases, parent.empty() ? "." : parent.string());
  std::ofstream out(file, std::ios::binary);
  out << page;
  if (!out) throw BadInput{"--html: cannot write '" + file + "'"};
}

}  // namespace warpath::tools
