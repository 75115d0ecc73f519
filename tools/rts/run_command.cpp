// `rts run`: run a scenario headless, print progress and expectations, write the report.

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "rts/cli_support.h"
#include "rts/commands.h"
#include "rts/html_report.h"
#include "rts/render_support.h"
#include "rts/scenario_support.h"
#include "rts/trace_writer.h"

namespace warpath::tools {
namespace {

struct RunOptions {
  std::string scenario;
  std::optional<std::uint64_t> seed;
  std::string report;
  std::string html;
  std::optional<std::int64_t> until;
  bool quiet = false;
  FrameOptions frames;
  TraceOptions trace;
  std::string replay;
  std::int64_t replayEvery = 1;
  int threads = 1;
};

int arrivedCount(const engine::World& world) {
  int n = 0;
  for (const engine::Unit& u : world.units())
    n += u.arrivalTick >= 0 ? 1 : 0;
  return n;
}

int stuckCount(const engine::World& world) {
  int n = 0;
  for (const engine::Unit& u : world.units())
    n += u.everStuck ? 1 : 0;
  return n;
}

int deadCount(const engine::World& world) {
  int n = 0;
  for (const engine::Unit& u : world.units())
    n += u.alive() ? 0 : 1;
  return n;
}

// A bar redrawn in place on a terminal; on a pipe, a plain line every tenth of the run (and at
// the tick the battle ended, when it ends early).
class Progress {
 public:
  Progress(std::int64_t total, bool tty) : total_(std::max<std::int64_t>(total, 1)), tty_(tty) {}

  void update(const engine::ScenarioRun& run) {
    const std::int64_t tick = run.world().tick();
    const auto tenth = std::max<std::int64_t>(total_ / 10, 1);
    if (!run.ended() &&
        (tty_ ? tick % 10 != 0 && tick != total_ : tick % tenth != 0 && tick != total_))
      return;
    constexpr int kWidth = 20;
    const auto done = static_cast<int>(std::min<std::int64_t>(tick * kWidth / total_, kWidth));
    const std::string line =
        fmt::format("tick {}/{} [{}{}] {:3d}%  units {}  arrived {}  stuck {}  dead {}{}", tick,
                    total_, std::string(static_cast<std::size_t>(done), '#'),
                    std::string(static_cast<std::size_t>(kWidth - done), ' '),
                    static_cast<int>(std::min<std::int64_t>(tick * 100 / total_, 100)),
                    run.world().units().size(), arrivedCount(run.world()), stuckCount(run.world()),
                    deadCount(run.world()), run.ended() ? "  battle over" : "");
    if (tty_) {
      fmt::print(stderr, "\r  {}", line);
      drawn_ = true;
    } else {
      fmt::print(stderr, "  {}\n", line);
    }
  }
  void finish() {
    if (drawn_) fmt::print(stderr, "\n");
  }

 private:
  std::int64_t total_;
  bool tty_;
  bool drawn_ = false;
};

// Whether the run is a battle: the scenario has victory conditions or an end_battle, or combat
// is on with two teams or more and an armed unit type. Travel-only runs print no battle summary.
bool isBattle(const engine::Scenario& scenario) {
  if (!scenario.victory.empty()) return true;
  for (const engine::TriggerSpec& t : scenario.triggers) {
    for (const engine::ActionSpec& a : t.actions)
      if (a.kind == engine::ActionKind::EndBattle) return true;
  }
  if (!scenario.settings.combat.enabled || scenario.teams.size() < 2) return false;
  return std::any_of(scenario.catalogue.begin(), scenario.catalogue.end(),
                     [](const units::UnitType& t) { return t.weapon.has_value(); });
}

// The winner and, per team, its losses by type, kills and shots.
void printBattle(const engine::Scenario& scenario, const engine::Report& report, double tickRate) {
  if (!report.winner.empty()) {
    fmt::print("winner: {} ({}) at tick {} ({:.1f} s)\n", report.winner, report.victory,
               report.endTick, static_cast<double>(report.endTick) / tickRate);
  } else if (report.endTick >= 0) {
    fmt::print("winner: none ({}) at tick {} ({:.1f} s)\n", report.victory, report.endTick,
               static_cast<double>(report.endTick) / tickRate);
  } else {
    fmt::print("winner: none (no victory condition met)\n");
  }
  for (const std::string& team : scenario.teams) {
    int units = 0, losses = 0, kills = 0, shots = 0, hits = 0;
    std::string byType;
    for (const engine::BattleStats& s : report.battle) {
      if (s.team != team) continue;
      units += s.units;
      losses += s.losses;
      kills += s.kills;
      shots += s.shotsFired;
      hits += s.hits;
      if (s.losses > 0)
        byType += fmt::format("{}{} {}", byType.empty() ? "" : ", ", s.type, s.losses);
    }
    fmt::print("  {}: lost {} of {}{}; {} kills, {} shots, {} hits\n", team, losses, units,
               byType.empty() ? "" : " (" + byType + ")", kills, shots, hits);
  }
}

// Under a failed expectation, the first units it counts against and where each got to: the
// units to follow with --trace.
void printUnitsAgainst(const engine::ExpectationResult& e, const engine::Scenario& scenario,
                       const engine::World& world) {
  constexpr std::size_t kShown = 8;
  const double rate = world.tickRate();
  const std::vector<engine::Unit>& units = world.units();
  std::size_t shown = 0;
  for (const std::uint32_t index : e.units) {
    if (index >= units.size()) continue;
    if (shown++ == kShown) {
      fmt::print("  and {} more\n", e.units.size() - kShown);
      break;
    }
    const engine::Unit& u = units[index];
    const std::string who =
        fmt::format("unit {} ({} {})", index, scenario.teams.at(static_cast<std::size_t>(u.team)),
                    scenario.catalogue.at(static_cast<std::size_t>(u.type)).name);
    const std::string stuck = u.everStuck ? ", flagged stuck" : "";
    if (u.arrivalTick >= 0) {
      const std::string sinceOrder =
          u.orderTick > 0 ? fmt::format(" ({:.1f} s after its order)",
                                        static_cast<double>(u.arrivalTick - u.orderTick) / rate)
                          : "";
      fmt::print("  {}: arrived at {:.1f} s{}{}\n", who, static_cast<double>(u.arrivalTick) / rate,
                 sinceOrder, stuck);
      continue;
    }
    // Cells from the body's centre to the nearest point of the goal area.
    const pathing::CellRect& a = u.goalArea;
    const double dx = std::max({a.x - u.position.x, 0.0, u.position.x - (a.x + a.width)});
    const double dy = std::max({a.y - u.position.y, 0.0, u.position.y - (a.y + a.height)});
    fmt::print("  {}: {} at ({:.1f}, {:.1f}), {:.1f} cells from its goal area{}\n", who,
               u.alive() ? "not arrived," : "dead,", u.position.x, u.position.y,
               std::sqrt(dx * dx + dy * dy), stuck);
  }
}

engine::ReplayEnd endOf(const RunOutcome& outcome) {
  if (outcome.interrupted) return engine::ReplayEnd::Interrupted;
  return outcome.report.complete ? engine::ReplayEnd::Complete : engine::ReplayEnd::Stopped;
}

int runRun(const RunOptions& options) {
  engine::ReplaySource source;
  engine::Scenario scenario =
      loadScenarioOrThrow(options.scenario, options.replay.empty() ? nullptr : &source);
  // Threads change how fast the graphs are built and repaired, never what they hold.
  scenario.settings.pathing.buildThreads = options.threads;
  if (options.until && *options.until > scenario.durationTicks()) {
    throw BadInput{"--until: must be between 0 and " + std::to_string(scenario.durationTicks()) +
                   " (the scenario's duration in ticks), got " + std::to_string(*options.until)};
  }
  prepareOutputPath(options.report, "--report");
  prepareOutputPath(options.html, "--html");
  prepareOutputPath(options.frames.video, "--video");
  prepareOutputPath(options.replay, "--replay");
  prepareOutputPath(options.trace.file, "--trace");
  engine::ScenarioRun run(scenario, options.seed);
  installInterruptHandlers();

  std::optional<engine::ReplayWriter> replay;
  if (!options.replay.empty()) {
    source.seed = options.seed.value_or(scenario.settings.seed);
    source.hashEvery = options.replayEvery;
    Result<engine::ReplayWriter> opened = engine::ReplayWriter::open(options.replay, source);
    if (!opened.ok()) throw BadInput{opened.error().describe()};
    replay.emplace(std::move(opened).value());
    if (Status s = replay->record(run); !s)
      throw BadInput{s.error().describe()};  // the tick-0 orders
  }

  const std::int64_t total =
      options.until ? std::min(*options.until, scenario.durationTicks()) : scenario.durationTicks();
  Progress progress(total, isatty(STDERR_FILENO) != 0);
  RunLimits limits;
  limits.untilTick = options.until;
  if (!options.quiet) limits.onTick = [&](const engine::ScenarioRun& r) { progress.update(r); };
  std::optional<FrameRecorder> frames;
  if (options.frames.wanted()) {
    frames.emplace(options.frames, run.world().grid().map(), run.world().tickRate(),
                   static_cast<int>(scenario.teams.size()));
    frames->onTick(run.world());  // the start
    limits.onTick = [&frames, display = limits.onTick](const engine::ScenarioRun& r) {
      if (display) display(r);
      frames->onTick(r.world());
    };
  }
  std::optional<TraceWriter> trace;
  if (options.trace.wanted()) {
    trace.emplace(options.trace, scenario);
    trace->onTick(run.world());  // the start
    limits.onTick = [&trace, before = limits.onTick](const engine::ScenarioRun& r) {
      if (before) before(r);
      trace->onTick(r.world());
    };
  }
  if (replay) {
    limits.onTick = [&replay, before = limits.onTick](const engine::ScenarioRun& r) {
      if (before) before(r);
      if (Status s = replay->record(r); !s) throw BadInput{s.error().describe()};
    };
  }
  const RunOutcome outcome = runToEnd(run, limits);
  progress.finish();
  if (replay) {
    if (Status s = replay->finish(run, endOf(outcome)); !s) throw BadInput{s.error().describe()};
    if (!options.quiet) fmt::print("replay: {}\n", options.replay);
  }
  if (frames) {
    const int written = frames->finish();
    if (!options.quiet) {
      fmt::print("frames: {} written{}\n", written, options.frames.destinations());
    }
  }

  if (trace && !options.quiet)
    fmt::print("trace: {} ({} rows)\n", options.trace.file, trace->rows());
  const engine::Report& report = outcome.report;
  if (!options.quiet) {
    if (isBattle(scenario)) printBattle(scenario, report, run.world().tickRate());
    for (const engine::ExpectationResult& e : report.expectations) {
      fmt::print("expectation \"{}\": {} ({:.4g})\n", e.text, e.pass ? "PASS" : "FAIL", e.actual);
      if (!e.pass) printUnitsAgainst(e, scenario, run.world());
    }
    const engine::TickTiming t = run.world().meanTiming();
    fmt::print(
        "{} ticks, {:.1f} s simulated in {:.2f} s; {:.3f} ms/tick (pathing {:.3f}, combat {:.3f}, "
        "steering {:.3f}, physics {:.3f}, bookkeeping {:.3f}); state hash {:016x}\n",
        report.ticks, report.simSeconds, outcome.wallSeconds,
        (t.pathingMicros + t.combatMicros + t.steeringMicros + t.physicsMicros +
         t.bookkeepingMicros) /
            1000.0,
        t.pathingMicros / 1000.0, t.combatMicros / 1000.0, t.steeringMicros / 1000.0,
        t.physicsMicros / 1000.0, t.bookkeepingMicros / 1000.0, report.stateHash);
  }
  const nlohmann::json json = reportJson(outcome, run);
  if (!options.report.empty()) {
    std::ofstream out(options.report);
    out << json.dump(2) << '\n';
    if (!out) throw BadInput{"cannot write the report to '" + options.report + "'"};
    if (!options.quiet) fmt::print("report: {}\n", options.report);
  }
  if (!options.html.empty()) {
    HtmlCase pageCase = HtmlCase::ran(options.scenario, json);
    pageCase.gif = options.frames.gif;
    pageCase.framesDir = options.frames.framesDir;
    pageCase.video = options.frames.video;
    writeHtmlReport(options.html, "warpath run: " + report.scenario, {pageCase});
    if (!options.quiet) fmt::print("html: {}\n", options.html);
  }
  if (outcome.interrupted) {
    fmt::print(stderr, "rts: interrupted at tick {}; the report is partial\n", report.ticks);
    return kExitFailed;
  }
  return report.passed() ? kExitOk : kExitFailed;
}

}  // namespace

void registerRunCommand(CLI::App& app, CommandRunner& run) {
  auto [cmd, options] = addSubcommand<RunOptions>(
      app, run, "run",
      "Run a scenario headless; exit 0 when every expectation holds, 1 when one fails", runRun);
  cmd->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  cmd->add_option("--seed", options->seed, "Replace the scenario's seed");
  cmd->add_option("--threads", options->threads,
                  "Threads that search the HAA* graph's clusters at once when it is built at the "
                  "start and repaired after terrain changes (the same run for any count)")
      ->check(CLI::Range(1, pathing::kMaxBuildThreads))
      ->capture_default_str();
  cmd->add_option("--report", options->report, "Write the report (JSON) to this file");
  cmd->add_option("--html", options->html,
                  "Write a self-contained HTML page: expectations, arrival curves, delays, battle, "
                  "pathing and timing charts, the GIF");
  cmd->add_option("--until", options->until,
                  "Stop after this tick (at most the scenario's duration in ticks)")
      ->check(wholeNumberIn(0, engine::kMaxScenarioTicks));
  cmd->add_flag("--quiet", options->quiet, "Print nothing but errors");
  addFrameOptions(*cmd, options->frames, "--frame-every");
  cmd->add_option("--trace", options->trace.file,
                  "Write every unit's state tick by tick as CSV: position, velocity, order state, "
                  "waypoint, goal, cooperative plan (docs/report.md, \"Traces\")");
  cmd->add_option("--trace-every", options->trace.every,
                  "A trace row per unit every N ticks (default 1)")
      ->check(wholeNumberIn(1, engine::kMaxScenarioTicks));
  cmd->add_option("--trace-units", options->trace.units,
                  "Trace only these units, by index (as in the trace's unit column): 0,5,17")
      ->delimiter(',');
  cmd->add_option("--replay", options->replay,
                  "Write a self-contained replay (scenario, files, seed, orders, state hashes)");
  cmd->add_option("--replay-every", options->replayEvery,
                  "Record the state hash every N ticks (default 1)")
      ->check(wholeNumberIn(1, engine::kMaxScenarioTicks));
}

}  // namespace warpath::tools
