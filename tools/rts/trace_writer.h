#pragma once
// `rts run --trace`: every unit's state tick by tick as CSV (position, velocity, order state,
// waypoint, cooperative plan), to follow a unit through a jam that the frames only show.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "engine/scenario.h"
#include "engine/world.h"

namespace warpath::tools {

struct TraceOptions {
  std::string file;                  // empty: no trace
  std::int64_t every = 1;            // a row per unit every N ticks
  std::vector<std::uint32_t> units;  // unit indices to trace; empty: all
  bool wanted() const { return !file.empty(); }
};

// Writes the header on open and a row per traced unit on each tick that is a multiple of
// `every` (tick 0 included). Each tick's rows are flushed, so an interrupted run keeps what it
// wrote.
class TraceWriter {
 public:
  TraceWriter(const TraceOptions& options, const engine::Scenario& scenario);
  void onTick(const engine::World& world);
  std::int64_t rows() const { return rows_; }

 private:
  TraceOptions options_;
  std::vector<std::string> teams_;
  std::vector<std::string> types_;
  std::vector<int> sizes_;  // per type: footprint side, for a waypoint's body centre
  std::ofstream out_;
  std::int64_t rows_ = 0;
};

}  // namespace warpath::tools
