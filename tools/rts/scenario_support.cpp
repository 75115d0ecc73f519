#include "rts/scenario_support.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>

#include "pathing/planner.h"
#include "rts/cli_support.h"

namespace warpath::tools {
namespace {

// The one mutable global: set by the signal handler, read between ticks.
std::atomic<bool> gInterrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void onSignal(int) {
  gInterrupted.store(true);
}

nlohmann::json secondsOrNull(double v) {
  return v < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(v);
}

}  // namespace

nlohmann::json finiteOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json expectationsJson(const std::vector<engine::ExpectationResult>& expectations) {
  nlohmann::json list = nlohmann::json::array();
  for (const engine::ExpectationResult& e : expectations)
    list.push_back({{"text", e.text},
                    {"actual", finiteOrNull(e.actual)},
                    {"pass", e.pass},
                    {"units", e.units}});
  return list;
}

std::string failureLine(const engine::ExpectationResult& e) {
  std::string line = fmt::format("expectation \"{}\" failed: actual {:.4g}", e.text, e.actual);
  if (e.units.empty()) return line;
  const std::size_t named = std::min(e.units.size(), kUnitsNamed);
  line += fmt::format(
      " (unit{} {}", e.units.size() == 1 ? "" : "s",
      fmt::join(e.units.begin(), e.units.begin() + static_cast<std::ptrdiff_t>(named), ", "));
  if (e.units.size() > named) line += fmt::format(" and {} more", e.units.size() - named);
  return line + ")";
}

engine::Scenario loadScenarioOrThrow(const std::string& file, engine::ReplaySource* source) {
  Result<engine::Scenario> loaded =
      source ? engine::loadRecordedScenario(file, *source) : engine::loadScenario(file);
  if (!loaded.ok()) throw BadInput{loaded.error().describe()};
  return std::move(loaded).value();
}

void installInterruptHandlers() {
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
}

bool interruptRequested() {
  return gInterrupted.load();
}

RunOutcome runToEnd(engine::ScenarioRun& run, const RunLimits& limits) {
  RunOutcome outcome;
  const auto began = std::chrono::steady_clock::now();
  while (!run.done()) {
    if (limits.untilTick && run.world().tick() >= *limits.untilTick) break;
    if (interruptRequested()) {
      outcome.interrupted = true;
      break;
    }
    run.step();
    if (limits.onTick) limits.onTick(run);
  }
  outcome.wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  outcome.report = run.report();
  return outcome;
}

nlohmann::json reportJson(const RunOutcome& outcome, const engine::ScenarioRun& run) {
  using nlohmann::json;
  const engine::Report& r = outcome.report;
  json j;
  j["scenario"] = r.scenario;
  j["file"] = run.scenario().file.string();
  j["seed"] = r.seed;
  j["ticks"] = r.ticks;
  j["sim_seconds"] = r.simSeconds;
  j["duration_seconds"] =
      static_cast<double>(run.scenario().durationTicks()) / run.world().tickRate();
  j["wall_seconds"] = outcome.wallSeconds;
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(r.stateHash));
  j["state_hash"] = hash;
  j["complete"] = r.complete;
  j["interrupted"] = outcome.interrupted;
  j["units"] = run.world().units().size();

  json arrivals = json::array();
  int deaths = 0;
  for (const engine::ArrivalStats& s : r.arrivals) {
    arrivals.push_back({{"team", s.team},
                        {"type", s.type},
                        {"units", s.units},
                        {"arrived", s.arrived},
                        {"rate", s.rate},
                        {"dead", s.dead},
                        {"time_to_arrive",
                         {{"p50", secondsOrNull(s.p50)},
                          {"p90", secondsOrNull(s.p90)},
                          {"max", secondsOrNull(s.max)}}},
                        {"arrived_at", s.arrivedAt}});
    deaths += s.dead;
  }
  j["arrivals"] = arrivals;
  j["deaths"] = deaths;
  j["stuck_units"] = {{"count", r.stuckUnits.size()}, {"ids", r.stuckUnits}};
  j["no_path_units"] = r.noPath;
  j["repaths"] = r.repaths;

  const engine::PathServiceMetrics& m = r.pathing;
  const engine::PathServiceSettings& ps = run.world().pathService().settings();
  j["pathing"] = {{"algo", std::string(pathing::toString(ps.algorithm))},
                  {"cluster_size", ps.clusterSize},
                  {"levels", ps.levels},
                  {"budget", ps.expansionBudget},
                  {"sliced", ps.sliced},
                  {"requests", m.requests},
                  {"cache_hits", m.cacheHits},
                  {"searches", m.searches},
                  {"found", m.found},
                  {"failed", m.failed},
                  {"expanded", m.expanded},
                  {"max_queue", m.maxQueue},
                  {"max_tick_expanded", m.maxTickExpanded},
                  {"slices", m.slices},
                  {"window_slices", m.windowSlices},
                  {"congestion", ps.cooperative && ps.congestion},
                  {"congested_searches", m.congestedSearches},
                  {"detours", m.detours},
                  {"search_us", m.microseconds},
                  {"preprocess_ms", m.preprocessMilliseconds}};

  const engine::MovementReport& mv = r.movement;
  json delay = json::array();
  for (const engine::DelayStats& d : mv.delay) {
    delay.push_back({{"team", d.team},
                     {"type", d.type},
                     {"arrived", d.arrived},
                     {"p50", secondsOrNull(d.p50)},
                     {"p90", secondsOrNull(d.p90)},
                     {"max", secondsOrNull(d.max)},
                     {"delays", d.delays}});
  }
  j["movement"] = {{"cooperative", mv.cooperative},
                   {"window", mv.window},
                   {"windows", mv.counters.windows},
                   {"blocked_windows", mv.counters.blockedWindows},
                   {"waits", mv.counters.waits},
                   {"give_ways", mv.counters.giveWays},
                   {"deadlocks_broken", mv.counters.deadlocksBroken},
                   {"max_wait_s", mv.maxWaitSeconds},
                   {"expanded", mv.counters.expanded},
                   {"delay", delay}};

  json battle = json::array();
  for (const engine::BattleStats& s : r.battle) {
    battle.push_back({{"team", s.team},
                      {"type", s.type},
                      {"units", s.units},
                      {"alive", s.alive},
                      {"losses", s.losses},
                      {"kills", s.kills},
                      {"shots_fired", s.shotsFired},
                      {"hits", s.hits},
                      {"damage_dealt", s.damageDealt},
                      {"damage_taken", s.damageTaken}});
  }
  j["battle"] = battle;
  j["winner"] = r.winner.empty() ? json(nullptr) : json(r.winner);
  j["victory"] = r.victory.empty() ? json(nullptr) : json(r.victory);
  j["end_tick"] = r.endTick < 0 ? json(nullptr) : json(r.endTick);
  j["triggers_fired"] = r.triggersFired;

  j["expectations"] = expectationsJson(r.expectations);
  j["passed"] = r.passed();

  // Wall time per tick, by phase: a measurement, never an input to the simulation.
  const engine::TickTiming t = run.world().meanTiming();
  const double total =
      t.pathingMicros + t.combatMicros + t.steeringMicros + t.physicsMicros + t.bookkeepingMicros;
  j["timing"] = {{"ms_per_tick", total / 1000.0},
                 {"pathing_ms", t.pathingMicros / 1000.0},
                 {"combat_ms", t.combatMicros / 1000.0},
                 {"steering_ms", t.steeringMicros / 1000.0},
                 {"physics_ms", t.physicsMicros / 1000.0},
                 {"bookkeeping_ms", t.bookkeepingMicros / 1000.0},
                 {"slowest_tick_ms", t.slowestTickMicros / 1000.0},
                 {"static_boxes", run.world().physics().stats().staticBoxes}};
  return j;
}

}  // namespace warpath::tools
