#pragma once
// Jump point search (Harabor & Grastien 2011) on agent layers: for an agent of size s and a
// capability, the grid is uniform-cost (the anchor can stand on a cell or not), so the
// symmetry pruning of JPS applies to every size and capability. Moves follow the annotated
// grid's rules (moves.h): a diagonal step needs both cells beside it, so no corner is cut, and
// the pruning is the one for that rule (a straight jump stops where a cell beside it opens
// after a blocked one behind, and turns there only toward such a side, its forced neighbour; a
// diagonal jump stops where a straight jump from it would).
// Optimal: its paths are as long as AA*'s (they may take other, equally short, cells).
//
// JPS+ (Harabor & Grastien 2012): with JumpDistances::Precomputed the jumps read, for each cell
// of the agent's layer and each of the 8 directions, how far the next jump point or wall is,
// from a table built at the layer's first query (and repaired around the cells where the agent's
// standing changed after the grid's terrain changes).
// A jump is then one lookup plus a test for the goal, and, as in JPS2 (Harabor & Grastien 2014),
// a diagonal jump point is never pushed (its straight jumps are taken from the node that
// expands the run), so it expands 3-4x fewer jump points than the scanning search: paths as
// short, not always through the same cells. A jump point from which the goal is in sight (a
// diagonal run toward it, then a straight one, read from the table hop by hop) pushes the goal
// alone, as warthog's JPS2+ does.
//
// A query object owns its scratch memory and reuses it; the AnnotatedGrid may be shared.

#include <cstdint>
#include <optional>
#include <vector>

#include "pathing/annotated_grid.h"
#include "pathing/open_list.h"
#include "pathing/search.h"

namespace warpath::pathing {

// How a jump finds its end: by scanning the layer's bit maps (64 cells a word), or by looking
// it up in a table of jump distances precomputed per layer (JPS+: 16 bytes a cell and layer).
enum class JumpDistances : std::uint8_t { Scanned, Precomputed };

// Which successors an expanded jump point reached by a straight move gets. ForcedOnly (the
// default): straight on, and a turn only to a side that opens there after a blocked cell
// behind (its forced neighbours), as JPS prunes; with JPS+, a jump point from which the goal is
// in sight (a diagonal run toward it, then a straight one) gets the goal alone.
// EverySide: straight on and every turn to either side, which the jumps then follow; what
// queries did before replay format 10 (more jump points expanded, the same path lengths, at
// times other cells), kept so that older replays play back as recorded.
enum class JumpSuccessors : std::uint8_t { ForcedOnly, EverySide };

// [Unit: bytes] what JPS+ tables may take in all, by default: 512 MiB, a 512x512 layer taking
// 4.3 MB, 2048x2048 69 MB and 4096x4096 285 MB. A layer whose table would pass it is scanned.
inline constexpr std::size_t kDefaultJumpTableBudget = std::size_t{512} << 20;

// [Unit: bytes] the memory kept for one agent kind (a layer).
struct LayerBytes {
  Agent agent;
  std::size_t bytes = 0;
};

class JumpPointSearch {
 public:
  // `tableBudget` [Unit: bytes]: with JumpDistances::Precomputed, the tables of the layers in
  // use may take this much in all; a layer first asked about when the next table would pass
  // it has its queries scanned instead (as short, slower, as JumpDistances::Scanned answers
  // them).
  explicit JumpPointSearch(const AnnotatedGrid& grid,
                           JumpDistances distances = JumpDistances::Scanned,
                           std::size_t tableBudget = kDefaultJumpTableBudget,
                           JumpSuccessors successors = JumpSuccessors::ForcedOnly);

  // Finds a shortest path for `agent` from `start` to `goal` (anchor cells), uniform costs
  // (a diagonal step costs √2). When found and `path` is not null, it receives every cell from
  // start to goal inclusive. metrics.expanded counts jump points expanded; metrics.generated
  // the jump points pushed, and the cells the jumps scanned are not counted.
  PathResult findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                      const SearchLimits& limits = {});
  // The same query sliced (search.h), counting jump points expanded.
  PathStatus beginPath(Agent agent, Cell start, Cell goal, const SearchLimits& limits = {});
  PathStatus updatePath(std::uint64_t maxExpansions);
  PathResult finalizePath(std::vector<Cell>* path);
  std::uint64_t expandedSoFar() const { return result_.metrics.expanded; }
  // For a planner that runs this one's queries inside its own and times them (PhaseTiming).
  void stopTimingPhases() { timing_.stopTimingPhases(); }
  // Builds now what `agent`'s first query would (its layer's bit maps and, with
  // JumpDistances::Precomputed, its jump table if the budget has room), so that no query
  // carries the cost.
  void prepare(Agent agent);
  std::uint64_t nextStepExpansions() const { return 1; }

  // [Unit: bytes] the bit maps kept for the agent kinds asked about so far: where each can
  // stand, by rows and by columns (2 bits a cell a kind), built at its first query and again
  // when the grid's terrain changes.
  std::size_t bitmapBytes() const;
  // The bit maps and, when precomputed, jump distance tables, per layer asked about so far.
  std::vector<LayerBytes> layerBytes() const;
  // JPS+: tables built whole (a layer's first query, or a change over more than an eighth of
  // the map) and repaired around a terrain change, so far.
  struct TableCounts {
    std::uint64_t builds = 0;
    std::uint64_t repairs = 0;
    std::uint64_t overBudget = 0;  // queries scanned because their layer's table would not fit
  };
  TableCounts tableCounts() const { return tableCounts_; }
  // JPS+: the table of `agent`'s layer on the grid as it is now (built or repaired first): for
  // each cell (row-major) 8 entries, east, west, south, north, then south-east, south-west,
  // north-east, north-west: the steps to the jump point that jump ends at (> 0), else minus the
  // steps it can take before a wall. For tests and tools that inspect it.
  const std::vector<std::int16_t>& jumpDistances(Agent agent) { return tableFor(agent).distances; }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;

  // Where one agent kind can stand, a bit a cell, 64 cells a word: rows (x along a row) and
  // columns (y along a column), so that a straight jump tests 64 cells at once either way.
  struct Bitmap {
    Agent agent;
    std::uint64_t revision = 0;
    int rowWords = 0;
    int columnWords = 0;
    std::vector<std::uint64_t> rows;
    std::vector<std::uint64_t> columns;

    bool stands(int x, int y) const;  // (x, y) inside the map
    std::size_t bytes() const { return (rows.size() + columns.size()) * sizeof(std::uint64_t); }
  };
  const Bitmap& bitmapFor(Agent agent);
  std::optional<CellRect> standingChangedSince(Agent agent, std::uint64_t revision) const;

  // JPS+: for each cell (row-major) and direction (kTableDirections), the steps to the jump
  // point the jump from that cell ends at (> 0), else minus the steps it can take before a wall
  // (<= 0); the goal is not in it (a query tests for its goal as it reads).
  struct JumpTable {
    Agent agent;
    std::uint64_t revision = 0;
    std::vector<std::int16_t> distances;
    std::vector<std::uint8_t> standing;  // the layer it was built for, framed (a byte a cell)
  };
  const JumpTable& tableFor(Agent agent);
  // Whether queries read tables at all: JumpDistances::Precomputed, on a map whose distances
  // fit 16 bits.
  bool tablesKept() const;
  // Whether `agent`'s layer has a table, or room for one within the budget.
  bool tableFits(Agent agent) const;

  // What the jumps of one query read: where the agent can stand (its bit maps), inside the
  // map (or the query's region), and the goal.
  struct Query {
    const Bitmap* bits = nullptr;
    const std::int16_t* table = nullptr;  // JPS+ (null: scan); never with a region
    int width = 0;
    CellRect bounds;
    Cell goal;

    bool walkable(int x, int y) const;
    std::uint32_t indexOf(int x, int y) const;
    const std::uint64_t* row(int y) const;  // row y's words (null outside the bounds)
    const std::uint64_t* column(int x) const;
    const std::int16_t* entries(int x, int y) const;  // JPS+: (x, y)'s 8 table entries
  };

  // The three phases of a query, untimed (the public calls time them: PhaseTiming).
  void begin(Agent agent, Cell start, Cell goal, const SearchLimits& limits);
  void search(std::uint64_t maxExpansions);
  void finish(std::vector<Cell>* path);
  void resetScratch();
  std::uint32_t jump(const Query& q, int x, int y, int dx, int dy) const;
  std::uint32_t jumpStraight(const Query& q, int x, int y, int dx, int dy) const;
  // JPS+: the end of a jump (kNoCell at a wall), read from the table.
  static constexpr Cell kNoCell{-1, -1};
  Cell jumpByTable(const Query& q, int x, int y, int dx, int dy) const;
  // JPS+: whether the agent can take `steps` moves along (dx, dy) from `from`, hopping from
  // jump point to jump point by the table.
  bool runReaches(const Query& q, Cell from, int dx, int dy, int steps) const;
  // JPS+: whether q.goal is reached from `from` by a diagonal run toward it and then a
  // straight one (the octile distance).
  bool goalInSight(const Query& q, Cell from) const;

  const AnnotatedGrid& grid_;
  JumpDistances distances_;
  std::size_t tableBudget_;
  JumpSuccessors successors_;
  // The query under way (its result's status Pending until done).
  Query query_;
  Cell start_;
  SearchLimits limits_;
  PathResult result_;
  PhaseTiming timing_;
  // The last agent kind queried and its layer in the grid (which keeps it where it is), so
  // that a run of queries for one kind skips the grid's locked look-up.
  Agent layerAgent_{0, {}};
  const AgentLayer* layer_ = nullptr;
  std::vector<Bitmap> bitmaps_;
  std::vector<JumpTable> tables_;
  TableCounts tableCounts_;
  // A cell's search state, together so that reaching a cell touches one cache line.
  struct Node {
    std::uint32_t stamp;   // generation << 1 | closed
    std::uint32_t parent;  // the jump point the cell was reached from
    double g;
  };
  std::vector<Node> nodes_;
  std::vector<Cell> successorScratch_;  // an expansion's jump points, before they are pushed
  OpenList open_;
  std::uint32_t generation_ = 0;
};

}  // namespace warpath::pathing
