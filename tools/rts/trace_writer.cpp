#include "rts/trace_writer.h"

#include <fmt/format.h>

#include <algorithm>

#include "rts/cli_support.h"

namespace warpath::tools {

namespace {

const char* stateName(engine::UnitState s) {
  switch (s) {
    case engine::UnitState::Idle:
      return "idle";
    case engine::UnitState::WaitingPath:
      return "waiting_path";
    case engine::UnitState::Moving:
      return "moving";
    case engine::UnitState::Parked:
      return "parked";
    case engine::UnitState::NoPath:
      return "no_path";
    case engine::UnitState::Dead:
      return "dead";
  }
  return "?";
}

const char* statusName(pathing::CooperativeStatus s) {
  switch (s) {
    case pathing::CooperativeStatus::ReachedGoal:
      return "reached_goal";
    case pathing::CooperativeStatus::Windowed:
      return "windowed";
    case pathing::CooperativeStatus::Blocked:
      return "blocked";
    case pathing::CooperativeStatus::InvalidStart:
      return "invalid_start";
    case pathing::CooperativeStatus::InvalidGoal:
      return "invalid_goal";
    case pathing::CooperativeStatus::Unreachable:
      return "unreachable";
    case pathing::CooperativeStatus::Pending:
      return "pending";
  }
  return "?";
}

// What the unit follows: nothing, a hold of its footprint, a plan that only looks ahead
// (cruising), a window followed along the path, or a window kept to its times.
const char* planName(const engine::Unit& u) {
  if (!u.plan) return u.held.x >= 0 ? "hold" : "none";
  if (u.plan->cruising) return "cruising";
  return u.plan->timed ? "timed" : "window";
}

}  // namespace

TraceWriter::TraceWriter(const TraceOptions& options, const engine::Scenario& scenario)
    : options_(options), teams_(scenario.teams), out_(options.file) {
  for (const units::UnitType& t : scenario.catalogue) {
    types_.push_back(t.name);
    sizes_.push_back(t.size);
  }
  std::sort(options_.units.begin(), options_.units.end());
  out_ << "tick,unit,team,type,x,y,vx,vy,state,waypoint,path_cells,goal_x,goal_y,arrived,stuck,"
          "plan,plan_status,plan_end_tick,gate,admitted,held_x,held_y,waypoint_x,waypoint_y\n";
  if (!out_) throw BadInput{"cannot write the trace to '" + options.file + "'"};
}

void TraceWriter::onTick(const engine::World& world) {
  const std::int64_t tick = world.tick();
  if (tick % options_.every != 0) return;
  const auto name = [](const std::vector<std::string>& names, int i) {
    return i >= 0 && static_cast<std::size_t>(i) < names.size() ? names[static_cast<std::size_t>(i)]
                                                                : std::string("?");
  };
  std::string rows;
  for (const engine::Unit& u : world.units()) {
    if (!options_.units.empty() &&
        !std::binary_search(options_.units.begin(), options_.units.end(), u.id.index))
      continue;
    const engine::TimedPlan* plan = u.plan.get();
    // Where the unit's centre heads: the body centre on the waypoint (NaN without a path).
    units::Vec2 waypoint{std::nan(""), std::nan("")};
    if (u.path && u.next < u.path->cells.size())
      waypoint =
          units::anchorToCentre(u.path->cells[u.next], sizes_[static_cast<std::size_t>(u.type)]);
    fmt::format_to(
        std::back_inserter(rows),
        "{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.1f},{"
        ":.1f}\n",
        tick, u.id.index, name(teams_, u.team), name(types_, u.type), u.position.x, u.position.y,
        u.velocity.x, u.velocity.y, stateName(u.state), u.next, u.path ? u.path->cells.size() : 0,
        u.goalCell.x, u.goalCell.y, u.arrivalTick >= 0 ? 1 : 0, u.everStuck ? 1 : 0, planName(u),
        plan ? statusName(plan->status) : "",
        plan && !plan->steps.empty() ? plan->steps.back().tick : -1, plan ? plan->gate : -1,
        plan && plan->admitted ? 1 : 0, u.held.x, u.held.y, waypoint.x, waypoint.y);
    ++rows_;
  }
  out_ << rows;
  out_.flush();
  if (!out_) throw BadInput{"cannot write the trace to '" + options_.file + "'"};
}

}  // namespace warpath::tools
