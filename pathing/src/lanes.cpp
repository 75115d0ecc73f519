#include "pathing/lanes.h"

#include <algorithm>
#include <cstdlib>

#include "pathing/moves.h"

namespace warpath::pathing {

namespace {

// [Unit: cells] The shortest run of a path along one passage that gets a lane.
constexpr std::size_t kMinLaneRun = 7;
// [Unit: cells] A path kept right may be at most this much longer than the path it came from,
// per cell of footprint side plus one: 4 cells for infantry, 8 for a size-3 tank.
constexpr double kLaneDetourPerSize = 2.0;

constexpr int sign(int v) {
  return (v > 0) - (v < 0);
}

// To the right of the direction of travel at path[i], judged over a few cells either side so
// that a staircase reads as the line it follows; {0, 0} where the path runs diagonally (lanes
// are kept on passages that run along the grid).
Cell rightOf(std::span<const Cell> path, std::size_t i) {
  constexpr std::size_t kSpan = 2;
  const Cell a = path[i >= kSpan ? i - kSpan : 0];
  const Cell b = path[std::min(path.size() - 1, i + kSpan)];
  const int dx = b.x - a.x;
  const int dy = b.y - a.y;
  // y grows downward: heading (hx, hy) has (-hy, hx) on its right.
  if (std::abs(dx) > 2 * std::abs(dy)) return {0, sign(dx)};
  if (std::abs(dy) > 2 * std::abs(dx)) return {-sign(dy), 0};
  return {0, 0};
}

// laneShift where the passage across is wider than laneWidth().
constexpr int kTooWide = -2;

// How many cells along `right` the footprint at `c` moves to lie in the right half of the
// passage across it (0 when it does already); kTooWide, or -1 when the passage is too narrow
// or the path runs diagonally. `across` gets the passage's width in cells, as far as it was
// measured (up to laneWidth() + 1), or stays as it was where the path runs diagonally.
int laneShift(const ClearanceField& clearance, int size, Cell c, Cell right, int& across) {
  if (right == Cell{0, 0}) return -1;
  const auto standable = [&](int k) {
    return clearance.at({c.x + k * right.x, c.y + k * right.y}) >= size;
  };
  const int widest = laneWidth(size);
  int toLeft = 0;
  while (toLeft + size <= widest && standable(-(toLeft + 1)))
    ++toLeft;
  int toRight = 0;
  while (toLeft + toRight + size <= widest && standable(toRight + 1))
    ++toRight;
  const int width = toLeft + toRight + size;  // cells across, footprint included
  across = width;
  if (width > widest) return kTooWide;
  if (width < 2 * size) return -1;
  const int rightHalf = (width + 1) / 2;  // its first cell, counted from the left edge
  return std::clamp(rightHalf - toLeft, 0, toRight);
}

// Whether the anchors 1 to `shift` cells along `right` from `c` are standable for a size-s
// agent: a shift that far keeps the footprint on its passage, and so does any shorter one.
bool standableUpTo(const ClearanceField& clearance, int size, Cell c, Cell right, int shift) {
  for (int k = 1; k <= shift; ++k) {
    if (clearance.at({c.x + k * right.x, c.y + k * right.y}) < size) return false;
  }
  return true;
}

// Appends legal single moves from out.back() to `to`; false when a step is not legal.
bool join(const AgentLayer& layer, const GridMap& map, std::vector<Cell>& out, Cell to) {
  const std::span<const std::uint8_t> moves = layer.moveMasks();
  Cell at = out.back();
  while (at != to) {
    const int dx = sign(to.x - at.x);
    const int dy = sign(to.y - at.y);
    const std::uint8_t mask = moves[map.indexOf(at)];
    bool stepped = false;
    for (const Cell step : {Cell{dx, dy}, Cell{dx, 0}, Cell{0, dy}}) {
      const int d = directionOf(step.x, step.y);
      if (d < 0 || (mask & (1u << d)) == 0) continue;
      at = {at.x + step.x, at.y + step.y};
      out.push_back(at);
      stepped = true;
      break;
    }
    if (!stepped) return false;
  }
  return true;
}

// Through a junction (a stretch where the passage across is too wide for lanes, at most
// laneWidth() long, between two lane runs of one direction) the lane goes on along the line it
// entered on, where the anchors up to it are standable (a path already right of it stays):
// otherwise the path comes back to its own line in the junction, the shortest one, where the flows
// of both ways meet head on (the crossroads' tanks). `found` is laneShift's answer per cell,
// `shift` the lane runs' shifts.
void keepLaneThroughJunctions(const ClearanceField& clearance, int size, std::span<const Cell> path,
                              const std::vector<int>& found, std::vector<Cell>& right,
                              std::vector<int>& shift) {
  const std::size_t n = path.size();
  const auto across = [](Cell c, Cell r) { return c.x * r.x + c.y * r.y; };
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (found[i] != kTooWide || shift[i - 1] <= 0) continue;
    std::size_t end = i;  // the junction is [i, end)
    while (end + 1 < n && found[end] == kTooWide)
      ++end;
    const Cell r = right[i - 1];
    if (end + 1 < n && shift[end] > 0 && right[end] == r &&
        end - i <= static_cast<std::size_t>(laneWidth(size))) {
      const int line = across(path[i - 1], r) + shift[i - 1];
      // Where the path runs right of that line it stays (shifts only ever go right).
      const auto shiftAt = [&](std::size_t k) { return std::max(0, line - across(path[k], r)); };
      bool standable = true;
      for (std::size_t k = i; k < end && standable; ++k)
        standable = standableUpTo(clearance, size, path[k], r, shiftAt(k));
      for (std::size_t k = i; k < end && standable; ++k) {
        shift[k] = shiftAt(k);
        right[k] = r;
      }
    }
    i = end;
  }
}

// [Unit: footprints] How far beyond each end of a lane run its full shift holds; how far where
// the passage is at least kWideFootprints across.
constexpr int kHoldFootprints = 2;
constexpr int kWideHoldFootprints = 5;
constexpr int kWideFootprints = 5;

// Beyond each end of a lane run the lane holds its full shift for kHoldFootprints (where the
// anchors up to it are standable, and before the taper of a cell a step): the approach and the
// way out keep right too. Without the hold a lane ended at its passage's mouth, where a unit
// coming off the bridge and one heading onto it met head on, on the one shortest line into the
// mouth (bridge_two_way). With `fartherWhereWide`, kWideHoldFootprints where the passage is at
// least kWideFootprints across (room for two each way and more): a crowd queueing at the mouth
// of a bridge 16 wide stood in the half the other way comes out of, where its paths turned into
// their own half within two footprints of the mouth. From four footprints across (which takes
// in river_ambush's bridge for jeeps) that battle passed at 111 of 300 seeds against 201
// (docs/cooperative.md, "Lanes held farther beyond wide passages"). `shift`, `right` and `width`
// are the lanes' shifts, sides and passage widths.
void holdBeyondLanes(const ClearanceField& clearance, int size, std::span<const Cell> path,
                     const std::vector<int>& width, bool fartherWhereWide, std::vector<Cell>& right,
                     std::vector<int>& shift) {
  const std::size_t n = path.size();
  std::vector<int> held = shift;
  std::vector<Cell> heldRight = right;
  for (const bool forward : {true, false}) {
    int lane = 0;  // the shift of the last lane cell passed, held for `left` more cells
    int left = 0;
    Cell side{0, 0};
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const std::size_t i = forward ? k : n - 1 - k;
      if (shift[i] > 0) {
        lane = shift[i];
        const bool wide = fartherWhereWide && width[i] >= kWideFootprints * size;
        left = (wide ? kWideHoldFootprints : kHoldFootprints) * size;
        side = right[i];
      } else if (left > 0 && lane > held[i] &&
                 standableUpTo(clearance, size, path[i], side, lane)) {
        held[i] = lane;
        heldRight[i] = side;
        --left;
      } else {
        left = 0;
      }
    }
  }
  shift = std::move(held);
  right = std::move(heldRight);
}

}  // namespace

std::vector<Cell> keepRight(const AnnotatedGrid& grid, Agent agent, std::span<const Cell> path,
                            LaneRules rules) {
  std::vector<Cell> unchanged(path.begin(), path.end());
  const std::size_t n = path.size();
  if (n < 3 || agent.size < 1) return unchanged;
  const ClearanceField& clearance = grid.clearance(agent.capability);
  const AgentLayer& layer = grid.layer(agent);
  const GridMap& map = grid.map();
  std::vector<Cell> right(n);
  std::vector<int> shift(n, 0);
  std::vector<int> width(n, 0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    right[i] = rightOf(path, i);
    shift[i] = laneShift(clearance, agent.size, path[i], right[i], width[i]);
  }
  const std::vector<int> found = shift;
  // Only a passage the path runs along for kMinLaneRun cells gets lanes: through a shorter one
  // (a gap, or a small map's whole width) local avoidance lets two units by, and a lane there
  // only bends the path.
  for (std::size_t i = 1; i + 1 < n;) {
    if (shift[i] < 0) {
      shift[i++] = 0;
      continue;
    }
    std::size_t end = i + 1;  // the run is [i, end)
    while (end + 1 < n && shift[end] >= 0 && right[end] == right[i])
      ++end;
    if (end - i < kMinLaneRun) std::fill(shift.begin() + i, shift.begin() + end, 0);
    i = end;
  }
  if (rules.throughJunctions)
    keepLaneThroughJunctions(clearance, agent.size, path, found, right, shift);
  if (rules.holdBeyond)
    holdBeyondLanes(clearance, agent.size, path, width, rules.holdFartherWhereWide, right, shift);
  // A lane begins before its passage and ends after it: a shift carries over to the cells
  // around, a cell less each, where the anchors it crosses are standable.
  const auto carry = [&](std::size_t from, std::size_t to) {
    const int s = shift[from] - 1;
    if (s <= shift[to] || !standableUpTo(clearance, agent.size, path[to], right[from], s)) return;
    shift[to] = s;
    right[to] = right[from];
  };
  for (std::size_t i = 2; i + 1 < n; ++i)
    carry(i - 1, i);
  for (std::size_t i = n - 2; i-- > 1;)
    carry(i + 1, i);
  // Where two shifted cells cannot be joined, the shifts there go and the path is tried again.
  constexpr int kAttempts = 8;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    // At most a cell more per step, from 0 at both ends (shrinking keeps a shift standable:
    // every anchor between the path and its shifted cell was found standable).
    for (std::size_t i = 1; i < n; ++i)
      shift[i] = std::min(shift[i], shift[i - 1] + 1);
    shift[n - 1] = 0;
    for (std::size_t i = n - 1; i-- > 0;)
      shift[i] = std::min(shift[i], shift[i + 1] + 1);
    if (std::all_of(shift.begin(), shift.end(), [](int s) { return s == 0; })) return unchanged;
    std::vector<Cell> out{path.front()};
    std::size_t failed = n;
    for (std::size_t i = 1; i < n && failed == n; ++i) {
      const Cell to{path[i].x + shift[i] * right[i].x, path[i].y + shift[i] * right[i].y};
      if (!join(layer, map, out, to)) failed = i;
    }
    // A lane is worth a short detour, not a long one: a lone unit pays it for nothing. Keeping
    // right at one passage costs about its shift there and back: a few cells, or up to twice
    // the shift across a passage wide enough for several footprints (detourByShift).
    if (failed == n) {
      const double detour = pathCost(out) - pathCost(path);
      double allowed = kLaneDetourPerSize * (agent.size + 1);
      if (rules.detourByShift)
        allowed = std::max(allowed, 2.0 * *std::max_element(shift.begin(), shift.end()));
      return detour <= allowed ? out : unchanged;
    }
    shift[failed - 1] = 0;
    shift[failed] = 0;
  }
  return unchanged;
}

}  // namespace warpath::pathing
