#pragma once
// The HTML report of `rts run --html` and `rts test --html`: one self-contained page (inline
// SVG charts and CSS, the GIF as a data URI; no script, no network) drawn from the report JSON
// of each run (reportJson), so a page can be made from saved reports too.

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace warpath::tools {

// One run on the page.
struct HtmlCase {
  std::string name;       // what the section is headed with (the scenario file, a seed)
  nlohmann::json report;  // reportJson's object; null when the run could not be made
  std::string error;      // why not (a bad scenario file); empty when it ran
  std::string gif;        // the run's GIF, embedded; empty: none
  std::string framesDir;  // the run's PNG frames folder, linked relative to the page
  std::string video;      // the run's video, linked relative to the page

  static HtmlCase ran(std::string name, nlohmann::json report) {
    HtmlCase c;
    c.name = std::move(name);
    c.report = std::move(report);
    return c;
  }
  static HtmlCase failed(std::string name, std::string error) {
    HtmlCase c;
    c.name = std::move(name);
    c.error = std::move(error);
    return c;
  }
};

// The page's text; `pageDir` is the folder the page is written to (for relative links). Throws
// BadInput naming the case when a report lacks what a chart needs.
std::string htmlReport(const std::string& title, const std::vector<HtmlCase>& cases,
                       const std::string& pageDir);

// Writes the page to `file`, creating its folder; throws BadInput when it cannot.
void writeHtmlReport(const std::string& file, const std::string& title,
                     const std::vector<HtmlCase>& cases);

}  // namespace warpath::tools
