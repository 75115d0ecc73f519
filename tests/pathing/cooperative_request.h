#pragma once
// A cooperative request for the pathing tests: an agent moving 10 ticks a cell on every terrain,
// waits of 5 ticks, the window given and a hold of 10 ticks, as owner 1.

#include "pathing/cooperative_search.h"

namespace warpath::pathing {

inline CooperativeRequest requestFor(Agent agent, Cell start, Cell goal, Tick window) {
  CooperativeRequest r;
  r.agent = agent;
  r.start = start;
  r.goal = goal;
  r.self = 1;
  r.ticksPerCell.fill(10.0);
  r.waitTicks = 5;
  r.window = window;
  r.maxWindow = 4 * window;
  r.holdTicks = 10;
  return r;
}

}  // namespace warpath::pathing
