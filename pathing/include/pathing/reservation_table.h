#pragma once
// Space-time reservations over cells (cooperative pathfinding, Silver 2005): which owner holds
// which cell during which half-open tick interval [from, to). A size-s agent reserves all s×s
// cells of its footprint. The table answers "is this footprint free then, and if not, whose
// is it"; deciding who may reserve what is the caller's (the engine reserves only what a
// search found free).

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <span>
#include <vector>

#include "pathing/grid_map.h"

namespace warpath::pathing {

using Tick = std::int64_t;
inline constexpr Tick kForever = std::numeric_limits<Tick>::max();

class ReservationTable {
 public:
  struct Reservation {
    Cell anchor;
    int size = 1;
    Tick from = 0;
    Tick to = 0;
    bool operator==(const Reservation&) const = default;
  };

  // `tracked`: one byte per cell, non-zero where reservations are kept (e.g. the chokepoints,
  // contestedCells()); elsewhere reserve() stores nothing and every footprint is free. Empty:
  // every cell is tracked.
  ReservationTable(int width, int height, std::vector<std::uint8_t> tracked = {});
  // Only the cells of `track` calls are tracked (none at first).
  static ReservationTable trackingNothing(int width, int height);

  // Reserves the footprint of a size-`size` agent anchored at `anchor` over [from, to) for
  // `owner` [Limit: owner < 2^32 - 1]. Cells outside the map are ignored; an empty interval
  // reserves nothing.
  void reserve(Cell anchor, int size, Tick from, Tick to, std::uint32_t owner);
  // Adds the cells non-zero in `cells` (one byte per cell) to those tracked; no-op when every
  // cell is tracked already.
  void track(std::span<const std::uint8_t> cells);
  // True when a cell of the footprint is tracked.
  bool tracks(Cell anchor, int size) const;
  // Counts the track() calls: what a caller learnt from tracks() holds while it is unchanged.
  std::uint64_t trackChanges() const { return trackChanges_; }
  // Removes every reservation `owner` holds.
  void release(std::uint32_t owner);
  // The lowest owner other than `self` holding a cell of the footprint during part of
  // [from, to); nullopt when it is free. Cells outside the map hold nothing (whether the agent
  // may stand there is the map's question).
  std::optional<std::uint32_t> blocker(Cell anchor, int size, Tick from, Tick to,
                                       std::uint32_t self) const;
  bool isFree(Cell anchor, int size, Tick from, Tick to, std::uint32_t self) const {
    return freeBut(anchor, size, from, to, self, [](std::uint32_t) { return false; });
  }
  // The same, also ignoring the owners in `ignored`.
  bool isFree(Cell anchor, int size, Tick from, Tick to, std::uint32_t self,
              std::span<const std::uint32_t> ignored) const {
    return freeBut(anchor, size, from, to, self, [&](std::uint32_t owner) {
      return std::find(ignored.begin(), ignored.end(), owner) != ignored.end();
    });
  }
  // The same, also ignoring every owner o with o < ignored.size() && ignored[o] != 0.
  bool isFree(Cell anchor, int size, Tick from, Tick to, std::uint32_t self,
              const std::vector<std::uint8_t>& ignored) const {
    return freeBut(anchor, size, from, to, self, [&](std::uint32_t owner) {
      return owner < ignored.size() && ignored[owner] != 0;
    });
  }
  // Every owner but `self` holding a cell of the footprint during part of [from, to),
  // ascending, once each.
  std::vector<std::uint32_t> holders(Cell anchor, int size, Tick from, Tick to,
                                     std::uint32_t self) const;
  // Drops the intervals that ended at or before `now`; the cost is proportional to what it
  // drops. Call it as time moves on (the engine does, once a tick).
  void forget(Tick now);
  // What `owner` reserved since it last released everything, in the order reserved (those
  // forget() has since dropped included).
  std::span<const Reservation> heldBy(std::uint32_t owner) const;
  // Cell intervals stored (memory, and what the engine's state hash counts).
  std::size_t intervalCount() const { return intervals_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Interval {
    Tick from;
    Tick to;
    std::uint32_t owner;
  };
  struct Expiry {
    Tick to;
    std::uint32_t cell;
    bool operator>(const Expiry& o) const { return to != o.to ? to > o.to : cell > o.cell; }
  };
  // f(cell index) for the footprint's cells on the map, row by row; anyCell stops at the
  // first for which f returns true, and says whether one did. Inline with freeBut: a window
  // search asks isFree of nearly every move it makes, mostly of cells holding nothing.
  template <class F>
  bool anyCell(Cell anchor, int size, F&& f) const {
    const int x0 = std::max(anchor.x, 0);
    const int y0 = std::max(anchor.y, 0);
    const int x1 = std::min(anchor.x + size, width_);
    const int y1 = std::min(anchor.y + size, height_);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        if (f(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
              static_cast<std::size_t>(x)))
          return true;
      }
    }
    return false;
  }
  template <class F>
  void forEachCell(Cell anchor, int size, F&& f) const {
    anyCell(anchor, size, [&](std::size_t cell) {
      f(cell);
      return false;
    });
  }
  // A cell's intervals, by `from`; read through occupied_ first (below).
  std::span<const Interval> heldAt(std::size_t cell) const {
    if (occupied_[cell] == 0) return {};
    return cells_[cell];
  }
  // Free for `self` when every other holder during part of [from, to) is ignored(owner).
  template <class Ignored>
  bool freeBut(Cell anchor, int size, Tick from, Tick to, std::uint32_t self,
               Ignored&& ignored) const {
    // Stops at the first interval in the way: most asks in a crowd are answered no.
    return !anyCell(anchor, size, [&](std::size_t cell) {
      for (const Interval& i : heldAt(cell)) {
        if (!(i.from < to)) break;  // the rest begin later still
        if (i.owner != self && from < i.to && !ignored(i.owner)) return true;
      }
      return false;
    });
  }

  int width_;
  int height_;
  std::vector<std::uint8_t> tracked_;  // empty: all
  // Per cell index, by `from` (ties in the order reserved): a check for [from, to) stops at
  // the first interval beginning at or after `to`, where a crowd's later reservations lie.
  std::vector<std::vector<Interval>> cells_;
  // Per cell index, nonzero while the cell holds an interval: most cells a search asks about
  // hold none, and this answers them without loading their vector from the 6 MB of headers
  // (a 512x512 map), which missed the cache on most checks (stress_2000).
  std::vector<std::uint8_t> occupied_;
  std::vector<std::vector<Reservation>> owners_;  // per owner id
  std::priority_queue<Expiry, std::vector<Expiry>, std::greater<>> expiries_;
  std::size_t intervals_ = 0;
  std::uint64_t trackChanges_ = 0;
};

}  // namespace warpath::pathing
