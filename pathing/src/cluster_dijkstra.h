#pragma once
// Dijkstra over one block of cells for one agent kind: the building block of the abstraction
// (one search from a transition reaches every other transition of its cluster) and of HAA*
// insertion (one search from the start reaches every node of its cluster at once, instead of
// one A* per node). Owns its scratch memory, sized by the largest block seen.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/invariant.h"
#include "pathing/moves.h"
#include "pathing/open_list.h"
#include "pathing/terrain_costs.h"

namespace warpath::pathing {

// The index of cell c in the per-cell arrays over block r: row by row, in a frame one cell wide
// around the block, so that every cell of the block has all eight neighbours in the arrays.
// [Limit: c in r]
inline std::size_t regionIndex(CellRect r, Cell c) {
  return static_cast<std::size_t>(c.y - r.y + 1) * static_cast<std::size_t>(r.width + 2) +
         static_cast<std::size_t>(c.x - r.x + 1);
}

// The moves of one agent kind inside one block of cells, copied once into an array over the
// block and its frame (bit d set when the move in direction d is legal and stays inside the
// block; none from the frame), so that the searches over the block, one per transition, read
// them by index without testing the block's edges on every expansion.
class RegionMoves {
 public:
  // [Limit: region inside the map]
  void load(const GridMap& map, const AgentLayer& layer, CellRect region);

  CellRect region() const { return region_; }
  std::span<const std::uint8_t> masks() const { return masks_; }

 private:
  CellRect region_;
  std::vector<std::uint8_t> masks_;
};

// The open list of ClusterDijkstra's uniform searches (moves cost 1 or √2, no heuristic).
// Popped keys never decrease, so the keys pushed through moves of one cost arrive in order and
// a FIFO queue per cost keeps them sorted: a push and a pop cost O(1), where OpenList's radix
// heap spent a third of a search on its buckets. It pops exactly what OpenList pops, so the
// searches and the graphs stay bit-identical: the smallest key, and of equal keys the last
// pushed (the radix heap keeps equal keys in push order in one bucket and drains its lowest
// bucket from the back). Entries of one key reached by a √2 move were pushed by parents about
// 0.41 cheaper than those reached by a move of 1, so before them: the last pushed first is
// the cardinal queue's run of that key from its back, then the diagonal queue's.
// Keys are OpenList::makeKey's.
class TwoCostOpenList {
 public:
  static constexpr std::uint32_t kEmpty = UINT32_MAX;

  void clear() {
    for (Queue& q : queues_) {
      q.entries.clear();
      q.begin = q.cursor = q.end = q.lastRun = 0;
      q.lastKey = kNoKey;
    }
    popping_ = kNoKey;
  }
  // `diagonal`: pushed through a move of cost √2 (else 1).
  void push(bool diagonal, std::uint64_t key, std::uint32_t node) {
    Queue& q = queues_[diagonal ? 1 : 0];
    WARPATH_INVARIANT(q.entries.empty() || q.entries.back().key <= key,
                      "two-cost open list: keys of one move cost must arrive in order");
    WARPATH_INVARIANT(popping_ == kNoKey || key > popping_,
                      "two-cost open list: a push must not tie the key being popped");
    // Counted at its first entry, a run of one key needs no scan when its turn comes.
    const std::size_t at = q.entries.size();
    // Without a branch: whether a key repeats is data, and a mispredict costs more.
    const std::size_t repeats = std::size_t{0} - static_cast<std::size_t>(q.lastKey == key);
    q.lastRun = (q.lastRun & repeats) | (at & ~repeats);
    q.lastKey = key;
    q.entries.push_back({key, node, 0});
    ++q.entries[q.lastRun].run;
  }
  // The next node, or kEmpty.
  std::uint32_t pop() {
    Queue& cardinal = queues_[0];
    Queue& diagonal = queues_[1];
    if (cardinal.cursor == cardinal.begin && diagonal.cursor == diagonal.begin && !nextKey())
      return kEmpty;
    if (cardinal.cursor > cardinal.begin) return cardinal.entries[--cardinal.cursor].node;
    return diagonal.entries[--diagonal.cursor].node;
  }

 private:
  static constexpr std::uint64_t kNoKey = UINT64_MAX;  // above any key of a path cost
  struct Entry {
    std::uint64_t key;
    std::uint32_t node;
    std::uint32_t run;  // at the first entry of a run of one key: its length
  };
  // Entries [begin, end) hold the key being popped, popped from cursor down to begin; entries
  // from end on are still to come.
  struct Queue {
    std::vector<Entry> entries;
    std::size_t begin = 0;
    std::size_t cursor = 0;
    std::size_t end = 0;
    std::size_t lastRun = 0;         // first entry of the last run
    std::uint64_t lastKey = kNoKey;  // its key
  };

  // Starts on the smallest key left; false when none is.
  bool nextKey() {
    bool any = false;
    std::uint64_t key = 0;
    for (Queue& q : queues_) {
      q.begin = q.cursor = q.end;
      if (q.end == q.entries.size()) continue;
      key = any ? std::min(key, q.entries[q.end].key) : q.entries[q.end].key;
      any = true;
    }
    if (!any) return false;
    popping_ = key;
    for (Queue& q : queues_) {
      if (q.end < q.entries.size() && q.entries[q.end].key == key) q.end += q.entries[q.end].run;
      q.cursor = q.end;
    }
    return true;
  }

  std::array<Queue, 2> queues_;
  std::uint64_t popping_ = kNoKey;  // the key being popped, kNoKey before the first
};

class ClusterDijkstra {
 public:
  // Settles cells of `region` reachable from `source` (inside it) in cost order, and stops
  // early once every cell of `targets` that lies in the region is settled. Moves cost their
  // length, or with `costs` (built for the layer's agent) their travel time.
  // [Limit: region inside the map, source in region]
  void run(const GridMap& map, const AgentLayer& layer, CellRect region, Cell source,
           std::span<const Cell> targets, const CostField* costs = nullptr);
  // The same over moves loaded beforehand, for several searches over one block.
  // [Limit: source in moves.region()]
  void run(const RegionMoves& moves, Cell source, std::span<const Cell> targets,
           const CostField* costs = nullptr);

  bool reached(Cell c) const { return region_.contains(c) && stamp_[local(c)] == settledStamp(); }
  // [Limit: reached(c)]
  double cost(Cell c) const { return g_[local(c)]; }
  // Directions of the moves from the source to `target`, in order. [Limit: reached(target)]
  void appendSteps(Cell target, std::vector<std::uint8_t>* steps) const;
  // The smallest of `values` (one per cell, indexed by regionIndex) along `steps` from the
  // source: on the cells they walk, source included, and for each diagonal on the two cells
  // beside it (no corner cutting). With clearances, the largest agent the path admits. Walks
  // the steps appendSteps gave, not the search tree again: no chain of dependent loads.
  // [Limit: steps from appendSteps]
  int smallestAlong(std::span<const std::uint8_t> steps,
                    std::span<const std::uint8_t> values) const;
  std::uint64_t expanded() const { return expanded_; }
  std::uint64_t generated() const { return generated_; }

 private:
  // run() for one model of move costs, so the uniform one's inner loop has no branch on it.
  template <bool kWeighted>
  void search(const RegionMoves& moves, Cell source, std::span<const Cell> targets,
              const CostField* costs);

  std::size_t local(Cell c) const { return regionIndex(region_, c); }
  std::uint32_t settledStamp() const { return generation_ * 4 + 2; }

  RegionMoves ownMoves_;  // for run() on a layer
  CellRect region_;
  std::size_t start_ = 0;             // the source's index
  std::vector<std::uint32_t> stamp_;  // generation*4 + {1 open, 2 settled}, +3 target marker
  std::vector<std::uint32_t> target_;
  std::vector<double> g_;
  std::vector<std::uint8_t> via_;        // direction of the move that reached the cell
  std::vector<std::uint8_t> unsettled_;  // moves to cells not settled yet
  OpenList open_;                        // weighted searches
  TwoCostOpenList twoCost_;              // uniform ones
  std::uint32_t generation_ = 0;
  std::uint64_t expanded_ = 0;
  std::uint64_t generated_ = 0;
};

// The connected parts of one block of cells for one agent kind, moving inside the block only:
// cells of different parts cannot reach each other by a path inside it, so a search inside the
// block need not look for them. Owns its scratch memory.
class RegionComponents {
 public:
  void label(const RegionMoves& moves);
  // 0 where the agent has no move inside the region (cannot stand, or stands walled in);
  // equal non-zero parts <=> joined inside the region.
  // [Limit: c in the labelled region]
  std::uint32_t partOf(Cell c) const { return part_[regionIndex(region_, c)]; }

 private:
  CellRect region_;
  std::vector<std::uint32_t> part_;
  std::vector<std::uint32_t> stack_;
};

}  // namespace warpath::pathing
