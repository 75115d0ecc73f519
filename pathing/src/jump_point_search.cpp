#include "pathing/jump_point_search.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <utility>

#include "pathing/moves.h"

namespace warpath::pathing {

namespace {

// Word k of a line of 64-cell words, the cells outside [lo, hi) (the query's bounds along the
// line) cleared; 0 for a missing line or a word outside it.
std::uint64_t wordOf(const std::uint64_t* line, int words, int k, int lo, int hi) {
  if (line == nullptr || k < 0 || k >= words) return 0;
  std::uint64_t w = line[k];
  const int base = k * 64;
  if (lo > base) w = lo - base >= 64 ? 0 : w & (~std::uint64_t{0} << (lo - base));
  if (hi < base + 64) w = hi <= base ? 0 : w & ((std::uint64_t{1} << (hi - base)) - 1);
  return w;
}

// A straight jump along one line (a row, or a column) from position `from`, by `step` (+1 or
// -1), the lines beside it `sideA` and `sideB` (null where there is none): the first position
// where a cell beside the line is open after a closed one behind it (a forced neighbour), or
// `goal` (-1 when the goal is not on this line); -1 when a closed cell of the line comes first.
int scanLine(const std::uint64_t* line, const std::uint64_t* sideA, const std::uint64_t* sideB,
             int words, int from, int step, int lo, int hi, int goal) {
  const auto word = [&](const std::uint64_t* l, int k) { return wordOf(l, words, k, lo, hi); };
  const auto goalBit = [&](int k) {
    return goal >= k * 64 && goal < k * 64 + 64 ? std::uint64_t{1} << (goal - k * 64) : 0;
  };
  const int first = from + step;
  if (first < lo || first >= hi) return -1;
  int k = first >> 6;
  if (step > 0) {
    // Forced where the side is open and the cell before it (p - 1) closed.
    std::uint64_t carryA = word(sideA, k - 1) >> 63;
    std::uint64_t carryB = word(sideB, k - 1) >> 63;
    for (std::uint64_t skip = ~std::uint64_t{0} << (first & 63); k < words; ++k, skip = ~0ull) {
      const std::uint64_t c = word(line, k);
      const std::uint64_t a = word(sideA, k);
      const std::uint64_t b = word(sideB, k);
      const std::uint64_t forced = (a & ~((a << 1) | carryA)) | (b & ~((b << 1) | carryB));
      carryA = a >> 63;
      carryB = b >> 63;
      const std::uint64_t hit = (forced | goalBit(k) | ~c) & skip;
      if (hit == 0) continue;
      const int bit = std::countr_zero(hit);
      return (c >> bit) & 1u ? k * 64 + bit : -1;
    }
    return -1;
  }
  // Backward: forced where the side is open and the cell after it (p + 1) closed.
  std::uint64_t carryA = word(sideA, k + 1) & 1u;
  std::uint64_t carryB = word(sideB, k + 1) & 1u;
  const int top = first & 63;
  for (std::uint64_t keep = top == 63 ? ~0ull : (std::uint64_t{1} << (top + 1)) - 1; k >= 0;
       --k, keep = ~0ull) {
    const std::uint64_t c = word(line, k);
    const std::uint64_t a = word(sideA, k);
    const std::uint64_t b = word(sideB, k);
    const std::uint64_t forced =
        (a & ~((a >> 1) | (carryA << 63))) | (b & ~((b >> 1) | (carryB << 63)));
    carryA = a & 1u;
    carryB = b & 1u;
    const std::uint64_t hit = (forced | goalBit(k) | ~c) & keep;
    if (hit == 0) continue;
    const int bit = 63 - std::countl_zero(hit);
    return (c >> bit) & 1u ? k * 64 + bit : -1;
  }
  return -1;
}

// JPS+ tables: a cell's 8 entries, in the order of kTableSteps.
constexpr int kTableSteps[8][2] = {{1, 0}, {-1, 0}, {0, 1},  {0, -1},
                                   {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
constexpr int tableEntry(int dx, int dy) {
  if (dy == 0) return dx > 0 ? 0 : 1;
  if (dx == 0) return dy > 0 ? 2 : 3;
  return 4 + (dx > 0 ? 0 : 1) + (dy > 0 ? 0 : 2);
}
// The last step of a run from `from` to `to` that goes diagonally first, then straight (a jump
// from one jump point to the next); zero when they are the same cell.
std::pair<int, int> lastStep(Cell from, Cell to) {
  const int ax = std::abs(to.x - from.x);
  const int ay = std::abs(to.y - from.y);
  const int sx = (to.x > from.x) - (to.x < from.x);
  const int sy = (to.y > from.y) - (to.y < from.y);
  if (ax == ay) return {sx, sy};
  return ax > ay ? std::pair{sx, 0} : std::pair{0, sy};
}

// Distances are 16 bits: larger maps scan.
constexpr int kLargestTabledSide = INT16_MAX;

}  // namespace

bool JumpPointSearch::Bitmap::stands(int x, int y) const {
  const std::size_t word = static_cast<std::size_t>(y) * static_cast<std::size_t>(rowWords) +
                           static_cast<std::size_t>(x >> 6);
  return ((rows[word] >> (x & 63)) & 1u) != 0;
}

bool JumpPointSearch::Query::walkable(int x, int y) const {
  return bounds.contains({x, y}) && bits->stands(x, y);
}

const std::int16_t* JumpPointSearch::Query::entries(int x, int y) const {
  return table + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)) *
                     8;
}

std::uint32_t JumpPointSearch::Query::indexOf(int x, int y) const {
  return static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(width) +
         static_cast<std::uint32_t>(x);
}

const std::uint64_t* JumpPointSearch::Query::row(int y) const {
  if (y < bounds.y || y >= bounds.y + bounds.height) return nullptr;
  return bits->rows.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(bits->rowWords);
}

const std::uint64_t* JumpPointSearch::Query::column(int x) const {
  if (x < bounds.x || x >= bounds.x + bounds.width) return nullptr;
  return bits->columns.data() +
         static_cast<std::size_t>(x) * static_cast<std::size_t>(bits->columnWords);
}

JumpPointSearch::JumpPointSearch(const AnnotatedGrid& grid, JumpDistances distances,
                                 std::size_t tableBudget, JumpSuccessors successors)
    : grid_(grid), distances_(distances), tableBudget_(tableBudget), successors_(successors) {}

void JumpPointSearch::prepare(Agent agent) {
  if (agent.size < 1) return;
  bitmapFor(agent);
  if (tablesKept() && tableFits(agent)) tableFor(agent);
}

bool JumpPointSearch::tablesKept() const {
  const GridMap& map = grid_.map();
  return distances_ == JumpDistances::Precomputed &&
         std::max(map.width(), map.height()) <= kLargestTabledSide;
}

bool JumpPointSearch::tableFits(Agent agent) const {
  std::size_t taken = 0;
  for (const JumpTable& t : tables_) {
    if (t.agent == agent) return true;
    taken += t.distances.size() * sizeof(std::int16_t) + t.standing.size();
  }
  const GridMap& map = grid_.map();
  // 8 entries a cell, and the standing bytes of the map framed by one cell.
  const std::size_t needed =
      map.cellCount() * 8 * sizeof(std::int16_t) +
      static_cast<std::size_t>(map.width() + 2) * static_cast<std::size_t>(map.height() + 2);
  return taken + needed <= tableBudget_;
}

std::size_t JumpPointSearch::bitmapBytes() const {
  std::size_t bytes = 0;
  for (const Bitmap& b : bitmaps_)
    bytes += b.bytes();
  return bytes;
}

std::vector<LayerBytes> JumpPointSearch::layerBytes() const {
  std::vector<LayerBytes> layers;
  for (const Bitmap& b : bitmaps_) {
    std::size_t bytes = b.bytes();
    for (const JumpTable& t : tables_) {
      if (t.agent == b.agent)
        bytes += t.distances.size() * sizeof(std::int16_t) + t.standing.size();
    }
    layers.push_back({b.agent, bytes});
  }
  return layers;
}

// Where `agent` may have started or stopped standing since `revision`: the grid's changes grown
// by the agent's size up and left (a footprint anchored there covers a changed cell), clipped;
// nullopt when the grid no longer knows.
std::optional<CellRect> JumpPointSearch::standingChangedSince(Agent agent,
                                                              std::uint64_t revision) const {
  const std::optional<CellRect> changed = grid_.changedSince(revision);
  if (!changed || changed->width <= 0 || changed->height <= 0) return changed;
  const int grow = agent.size - 1;
  return grid_.map().clip(
      {changed->x - grow, changed->y - grow, changed->width + grow, changed->height + grow});
}

const JumpPointSearch::Bitmap& JumpPointSearch::bitmapFor(Agent agent) {
  auto it = std::find_if(bitmaps_.begin(), bitmaps_.end(), [&](const Bitmap& b) {
    return b.agent.size == agent.size && b.agent.capability == agent.capability;
  });
  if (it == bitmaps_.end()) {
    Bitmap fresh;
    fresh.agent = agent;
    bitmaps_.push_back(std::move(fresh));
    it = bitmaps_.end() - 1;
  } else if (it->revision == grid_.revision() && !it->rows.empty()) {
    return *it;
  }
  Bitmap& b = *it;
  const GridMap& map = grid_.map();
  const ClearanceField& clearance = grid_.clearance(agent.capability);
  // After changes the grid still knows, only their cells are set again; else every cell.
  std::optional<CellRect> area;
  if (!b.rows.empty()) area = standingChangedSince(agent, b.revision);
  b.revision = grid_.revision();
  if (!area) {
    b.rowWords = (map.width() + 63) / 64;
    b.columnWords = (map.height() + 63) / 64;
    b.rows.assign(static_cast<std::size_t>(b.rowWords) * static_cast<std::size_t>(map.height()), 0);
    b.columns.assign(
        static_cast<std::size_t>(b.columnWords) * static_cast<std::size_t>(map.width()), 0);
    area = CellRect{0, 0, map.width(), map.height()};
  }
  for (int y = area->y; y < area->y + area->height; ++y) {
    for (int x = area->x; x < area->x + area->width; ++x) {
      const std::uint64_t rowBit = std::uint64_t{1} << (x & 63);
      const std::uint64_t columnBit = std::uint64_t{1} << (y & 63);
      std::uint64_t& row =
          b.rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(b.rowWords) +
                 static_cast<std::size_t>(x >> 6)];
      std::uint64_t& column =
          b.columns[static_cast<std::size_t>(x) * static_cast<std::size_t>(b.columnWords) +
                    static_cast<std::size_t>(y >> 6)];
      if (clearance.at({x, y}) >= agent.size) {
        row |= rowBit;
        column |= columnBit;
      } else {
        row &= ~rowBit;
        column &= ~columnBit;
      }
    }
  }
  return b;
}

namespace {

// The sweeps that fill a layer's JPS+ table from its framed byte map (1: the agent stands there,
// with a closed frame around the map). An entry extends the entry of the cell one step along
// (a straight one, or one that stops where a straight jump ends at a jump point), so each
// direction is swept against itself.
class TableSweeps {
 public:
  TableSweeps(const std::vector<std::uint8_t>& standing, int width, int height,
              std::vector<std::int16_t>& distances)
      : standing_(standing), width_(width), height_(height), distances_(distances) {}

  void all() {
    for (int e = 0; e < 4; ++e) {
      for (int line = 0, lines = kTableSteps[e][0] != 0 ? height_ : width_; line < lines; ++line)
        straightLine(e, line);
    }
    // A diagonal entry reads the row one step along only, so rows go in its order.
    for (int e = 4; e < 8; ++e) {
      const int dy = kTableSteps[e][1];
      for (int row = 0; row < height_; ++row) {
        const int y = dy > 0 ? height_ - 1 - row : row;
        for (int x = 0; x < width_; ++x)
          update(x, y, e);
      }
    }
  }

  // After the cells of `changed` (and only those) changed in the byte map: the rows and columns
  // of straight entries that read them, whole, then the diagonal entries that read a changed
  // cell or entry, and upstream along each diagonal while entries keep changing.
  void around(CellRect changed) {
    const int x0 = changed.x;
    const int x1 = changed.x + changed.width - 1;
    const int y0 = changed.y;
    const int y1 = changed.y + changed.height - 1;
    for (int e = 0; e < 4; ++e) {
      const bool rows = kTableSteps[e][0] != 0;
      const int lo = std::max(0, (rows ? y0 : x0) - 1);
      const int hi = std::min((rows ? height_ : width_) - 1, (rows ? y1 : x1) + 1);
      for (int line = lo; line <= hi; ++line)
        straightLine(e, line);
    }
    std::vector<std::uint32_t> seen(static_cast<std::size_t>(width_), 0);
    std::uint32_t stamp = 0;
    std::vector<int> before;
    std::vector<int> now;
    const int seedX0 = std::max(0, x0 - 2);
    const int seedX1 = std::min(width_ - 1, x1 + 2);
    for (int e = 4; e < 8; ++e) {
      const int dx = kTableSteps[e][0];
      const int dy = kTableSteps[e][1];
      before.clear();
      for (int row = 0; row < height_; ++row) {
        const int y = dy > 0 ? height_ - 1 - row : row;
        now.clear();
        ++stamp;
        const auto visit = [&](int x) {
          if (x < 0 || x >= width_ || seen[static_cast<std::size_t>(x)] == stamp) return;
          seen[static_cast<std::size_t>(x)] = stamp;
          if (update(x, y, e)) now.push_back(x);
        };
        if (y >= y0 - 2 && y <= y1 + 2) {
          for (int x = 0; x < width_; ++x)
            visit(x);
        } else {
          for (int x = seedX0; x <= seedX1; ++x)
            visit(x);
          for (const int x : before)
            visit(x - dx);
        }
        std::swap(before, now);
      }
    }
  }

 private:
  bool open(int x, int y) const {
    return standing_[static_cast<std::size_t>(y + 1) * static_cast<std::size_t>(width_ + 2) +
                     static_cast<std::size_t>(x + 1)] != 0;
  }
  std::int16_t& entry(int x, int y, int e) {
    return distances_[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                       static_cast<std::size_t>(x)) *
                          8 +
                      static_cast<std::size_t>(e)];
  }
  // A straight jump along (dx, dy) ends at p when a cell beside the line opens at p after a
  // closed one behind it (as scanLine finds it).
  bool forced(int px, int py, int dx, int dy) const {
    if (dx != 0) {
      return (open(px, py - 1) && !open(px - dx, py - 1)) ||
             (open(px, py + 1) && !open(px - dx, py + 1));
    }
    return (open(px - 1, py) && !open(px - 1, py - dy)) ||
           (open(px + 1, py) && !open(px + 1, py - dy));
  }
  // Sets entry e of (x, y) from the cells and entries one step along; true when it changed.
  bool update(int x, int y, int e) {
    const int dx = kTableSteps[e][0];
    const int dy = kTableSteps[e][1];
    const int nx = x + dx;
    const int ny = y + dy;
    std::int16_t value = 0;
    if (dx == 0 || dy == 0) {
      if (open(nx, ny)) value = forced(nx, ny, dx, dy) ? 1 : extend(entry(nx, ny, e));
    } else if (open(nx, y) && open(x, ny) && open(nx, ny)) {
      const bool stops =
          entry(nx, ny, tableEntry(dx, 0)) > 0 || entry(nx, ny, tableEntry(0, dy)) > 0;
      value = stops ? 1 : extend(entry(nx, ny, e));
    }
    std::int16_t& slot = entry(x, y, e);
    if (slot == value) return false;
    slot = value;
    return true;
  }
  // One step further than the entry one step along: away from it when that is a jump point.
  static std::int16_t extend(int next) {
    return static_cast<std::int16_t>(next > 0 ? next + 1 : next - 1);
  }
  // A whole row (east, west) or column (south, north) of a straight direction.
  void straightLine(int e, int line) {
    const int dx = kTableSteps[e][0];
    const int dy = kTableSteps[e][1];
    const int length = dx != 0 ? width_ : height_;
    for (int i = 0; i < length; ++i) {
      const int along = (dx + dy) > 0 ? length - 1 - i : i;
      if (dx != 0) {
        update(along, line, e);
      } else {
        update(line, along, e);
      }
    }
  }

  const std::vector<std::uint8_t>& standing_;
  int width_;
  int height_;
  std::vector<std::int16_t>& distances_;
};

}  // namespace

// Built at the layer's first query; after the grid's terrain changes, the entries around the
// cells where the agent's standing changed are swept again (the whole table when they spread
// over more than an eighth of the map).
const JumpPointSearch::JumpTable& JumpPointSearch::tableFor(Agent agent) {
  auto it = std::find_if(tables_.begin(), tables_.end(),
                         [&](const JumpTable& t) { return t.agent == agent; });
  if (it == tables_.end()) {
    tables_.push_back(JumpTable{agent, 0, {}, {}});
    it = tables_.end() - 1;
  } else if (it->revision == grid_.revision() && !it->distances.empty()) {
    return *it;
  }
  JumpTable& t = *it;
  const bool fresh = t.distances.empty();
  // Known before bitmapFor brings the bit maps up to date.
  const std::optional<CellRect> known =
      fresh ? std::nullopt : standingChangedSince(agent, t.revision);
  const Bitmap& bits = bitmapFor(agent);
  const GridMap& map = grid_.map();
  const int width = map.width();
  const int height = map.height();
  const std::size_t framed = static_cast<std::size_t>(width + 2);
  t.revision = grid_.revision();
  if (fresh) {
    t.standing.assign(framed * static_cast<std::size_t>(height + 2), 0);
    t.distances.assign(map.cellCount() * 8, 0);
  }
  // The byte map set again where the standing may have changed (the grid's changes it still
  // knows, else everywhere), and the bounding box of the cells where it did.
  const CellRect area = known.value_or(CellRect{0, 0, width, height});
  int x0 = width, y0 = height, x1 = -1, y1 = -1;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const auto now = static_cast<std::uint8_t>(bits.stands(x, y));
      std::uint8_t& slot =
          t.standing[static_cast<std::size_t>(y + 1) * framed + static_cast<std::size_t>(x + 1)];
      if (slot == now) continue;
      slot = now;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  if (y1 < 0 && !fresh) return t;  // this layer did not change
  TableSweeps sweeps(t.standing, width, height, t.distances);
  const auto changed = [&] {
    return static_cast<std::size_t>(x1 - x0 + 1) * static_cast<std::size_t>(y1 - y0 + 1);
  };
  if (!fresh && changed() * 8 <= map.cellCount()) {
    sweeps.around({x0, y0, x1 - x0 + 1, y1 - y0 + 1});
    ++tableCounts_.repairs;
  } else {
    sweeps.all();
    ++tableCounts_.builds;
  }
  return t;
}

void JumpPointSearch::resetScratch() {
  const std::size_t cells = grid_.map().cellCount();
  if (nodes_.size() != cells) {
    nodes_.assign(cells, Node{0, kNone, 0.0});
    generation_ = 0;
  }
  if (++generation_ == (1u << 31)) {  // wrapped: forget every stamp
    for (Node& n : nodes_)
      n.stamp = 0;
    generation_ = 1;
  }
  open_.clear();
}

// From (x, y), straight along (dx, dy): the first cell with a neighbour beside the line that
// opens after a blocked cell behind it (only a path turning there reaches that neighbour
// optimally), or the goal; kNone at a wall.
std::uint32_t JumpPointSearch::jumpStraight(const Query& q, int x, int y, int dx, int dy) const {
  if (dx != 0) {
    const int at = scanLine(q.row(y), q.row(y - 1), q.row(y + 1), q.bits->rowWords, x, dx,
                            q.bounds.x, q.bounds.x + q.bounds.width, q.goal.y == y ? q.goal.x : -1);
    return at < 0 ? kNone : q.indexOf(at, y);
  }
  const int at = scanLine(q.column(x), q.column(x - 1), q.column(x + 1), q.bits->columnWords, y, dy,
                          q.bounds.y, q.bounds.y + q.bounds.height, q.goal.x == x ? q.goal.y : -1);
  return at < 0 ? kNone : q.indexOf(x, at);
}

// From (x, y) along (dx, dy), straight or diagonal. A diagonal step needs both cells beside
// it; a diagonal jump stops at a cell from which either straight jump finds something.
std::uint32_t JumpPointSearch::jump(const Query& q, int x, int y, int dx, int dy) const {
  if (dx == 0 || dy == 0) return jumpStraight(q, x, y, dx, dy);
  for (;;) {
    if (!q.walkable(x + dx, y) || !q.walkable(x, y + dy) || !q.walkable(x + dx, y + dy))
      return kNone;
    x += dx;
    y += dy;
    const std::uint32_t at = q.indexOf(x, y);
    if ((Cell{x, y} == q.goal) || jumpStraight(q, x, y, dx, 0) != kNone ||
        jumpStraight(q, x, y, 0, dy) != kNone)
      return at;
  }
}

// The jump of jump(), read from the JPS+ table: the table's end, unless the goal comes first
// (ahead on a straight line within reach, or on the line of a straight jump from a cell of the
// diagonal run that reaches it: the cell in the goal's row or column, the nearer one).
Cell JumpPointSearch::jumpByTable(const Query& q, int x, int y, int dx, int dy) const {
  const int v = q.entries(x, y)[tableEntry(dx, dy)];
  const int reach = v > 0 ? v : -v;
  const int aheadX = (q.goal.x - x) * dx;
  const int aheadY = (q.goal.y - y) * dy;
  if (dx == 0 || dy == 0) {
    const bool onLine = dx != 0 ? q.goal.y == y : q.goal.x == x;
    const int toGoal = dx != 0 ? aheadX : aheadY;
    if (onLine && toGoal > 0 && toGoal <= reach) return q.goal;
  } else if (aheadX > 0 && aheadY > 0) {
    const int k = std::min(aheadX, aheadY);
    if (k <= reach) {
      const int cx = x + k * dx;
      const int cy = y + k * dy;
      if (k == v) return {cx, cy};
      const std::int16_t* at = q.entries(cx, cy);
      const int s = aheadX > aheadY ? at[tableEntry(dx, 0)] : at[tableEntry(0, dy)];
      if (std::abs(aheadX - aheadY) <= (s > 0 ? s : -s)) return {cx, cy};
    }
  }
  return v > 0 ? Cell{x + v * dx, y + v * dy} : kNoCell;
}

bool JumpPointSearch::runReaches(const Query& q, Cell from, int dx, int dy, int steps) const {
  const int entry = tableEntry(dx, dy);
  for (int run = 0; run < steps;) {
    const int v = q.entries(from.x, from.y)[entry];
    if (v <= 0) return run - v >= steps;  // -v more steps before the wall
    run += v;                             // on from one jump point to the next
    from = {from.x + v * dx, from.y + v * dy};
  }
  return true;
}

bool JumpPointSearch::goalInSight(const Query& q, Cell from) const {
  const Cell goal = q.goal;
  const int dx = (goal.x > from.x) - (goal.x < from.x);
  const int dy = (goal.y > from.y) - (goal.y < from.y);
  const int ax = std::abs(goal.x - from.x);
  const int ay = std::abs(goal.y - from.y);
  const int diagonal = std::min(ax, ay);
  if (diagonal > 0 && !runReaches(q, from, dx, dy, diagonal)) return false;
  if (ax == ay) return true;
  const Cell turn{from.x + diagonal * dx, from.y + diagonal * dy};
  return ax > ay ? runReaches(q, turn, dx, 0, ax - diagonal)
                 : runReaches(q, turn, 0, dy, ay - diagonal);
}

PathResult JumpPointSearch::findPath(Agent agent, Cell start, Cell goal, std::vector<Cell>* path,
                                     const SearchLimits& limits) {
  return timing_.whole([&] {
    begin(agent, start, goal, limits);
    search(kUnboundedExpansions);
    finish(path);
    return result_;
  });
}

PathStatus JumpPointSearch::beginPath(Agent agent, Cell start, Cell goal,
                                      const SearchLimits& limits) {
  const QueryClock clock = timing_.phaseClock();
  begin(agent, start, goal, limits);
  result_.metrics.microseconds += clock.elapsedMicroseconds();
  return result_.status;
}

PathStatus JumpPointSearch::updatePath(std::uint64_t maxExpansions) {
  if (result_.status != PathStatus::Pending || maxExpansions == 0) return result_.status;
  const QueryClock clock = timing_.phaseClock();
  search(maxExpansions);
  result_.metrics.microseconds += clock.elapsedMicroseconds();
  return result_.status;
}

PathResult JumpPointSearch::finalizePath(std::vector<Cell>* path) {
  const QueryClock clock = timing_.phaseClock();
  finish(path);
  result_.metrics.microseconds += clock.elapsedMicroseconds();
  return result_;
}

void JumpPointSearch::begin(Agent agent, Cell start, Cell goal, const SearchLimits& limits) {
  result_ = PathResult{};
  result_.status = PathStatus::Pending;
  start_ = start;
  limits_ = limits;
  if (agent.size >= 1 && (layer_ == nullptr || !(layerAgent_ == agent))) {
    layer_ = &grid_.layer(agent);
    layerAgent_ = agent;
  }
  if (const auto answer =
          screenQuery(grid_, agent, start, goal, limits, agent.size >= 1 ? layer_ : nullptr)) {
    result_.status = *answer;
  } else {
    const GridMap& map = grid_.map();
    bool tabled = tablesKept() && !limits.region;
    if (tabled && !tableFits(agent)) {
      tabled = false;
      ++tableCounts_.overBudget;
    }
    query_.table = tabled ? tableFor(agent).distances.data() : nullptr;
    query_.bits = &bitmapFor(agent);
    query_.width = map.width();
    query_.bounds = limits.region.value_or(CellRect{0, 0, map.width(), map.height()});
    query_.goal = goal;
    resetScratch();
    const std::uint32_t startIndex = map.indexOf(start);
    nodes_[startIndex] = {generation_ << 1, kNone, 0.0};
    open_.push(OpenList::makeKey(octileDistance(goal.x - start.x, goal.y - start.y), 0.0),
               startIndex);
    ++result_.metrics.generated;
  }
}

void JumpPointSearch::search(std::uint64_t maxExpansions) {
  if (result_.status != PathStatus::Pending || maxExpansions == 0) return;
  const GridMap& map = grid_.map();
  const Query& q = query_;
  const Cell goal = q.goal;
  PathResult& result = result_;
  const std::uint32_t goalIndex = map.indexOf(goal);
  const std::uint32_t openStamp = generation_ << 1;
  const std::uint32_t closedStamp = openStamp | 1u;
  const auto heuristic = [&](int x, int y) { return octileDistance(goal.x - x, goal.y - y); };
  const std::uint64_t end = sliceEnd(result.metrics.expanded, maxExpansions);

  PathStatus status = PathStatus::Unreachable;
  while (!open_.empty()) {
    if (result.metrics.expanded >= end) {
      status = PathStatus::Pending;
      break;
    }
    const std::uint32_t current = open_.pop();
    Node& node = nodes_[current];
    if (node.stamp == closedStamp) continue;  // a dearer duplicate
    node.stamp = closedStamp;
    ++result.metrics.expanded;
    if (current == goalIndex) {
      result.cost = node.g;
      status = PathStatus::Found;
      break;
    }
    if (result.metrics.expanded >= limits_.maxExpanded) {
      status = PathStatus::BudgetExhausted;
      break;
    }
    const Cell here = map.cellAt(current);
    const double g = node.g;
    // The directions worth jumping in: all from the start; else the way the parent came, the
    // cardinal parts of a diagonal, and after a straight move the turns successors_ allows.
    int dirs[kDirectionCount][2];
    int count = 0;
    const auto add = [&](int dx, int dy) {
      dirs[count][0] = dx;
      dirs[count][1] = dy;
      ++count;
    };
    if (node.parent == kNone) {
      for (const Direction& dir : kDirections)
        add(dir.dx, dir.dy);
    } else {
      const auto [dx, dy] = lastStep(map.cellAt(node.parent), here);
      if (dx != 0 && dy != 0) {
        add(dx, dy);
        add(dx, 0);
        add(0, dy);
      } else {
        // Straight: on, and turning only to a side that opens here after a blocked cell behind
        // (a forced neighbour; any other side cell is reached as well without passing here).
        add(dx, dy);
        const int acrossX = dx == 0 ? 1 : 0;  // the sides: -across and +across
        const int acrossY = dy == 0 ? 1 : 0;
        bool turns[2];
        for (int i = 0; i < 2; ++i) {
          const int sx = (2 * i - 1) * acrossX;
          const int sy = (2 * i - 1) * acrossY;
          turns[i] = successors_ == JumpSuccessors::EverySide ||
                     (!q.walkable(here.x + sx - dx, here.y + sy - dy) &&
                      q.walkable(here.x + sx, here.y + sy));
        }
        // Diagonal turns before straight ones, as queries always took them.
        for (int i = 0; i < 2; ++i) {
          if (turns[i]) add(dx + (2 * i - 1) * acrossX, dy + (2 * i - 1) * acrossY);
        }
        for (int i = 0; i < 2; ++i) {
          if (turns[i]) add((2 * i - 1) * acrossX, (2 * i - 1) * acrossY);
        }
      }
    }
    // A jump point reached from `current` by a diagonal run and then a straight one (either
    // may be none): an octile path.
    // Collected first, then pushed in one loop below (one place to inline).
    std::vector<Cell>& found = successorScratch_;
    found.clear();
    const auto reach = [&](Cell there) { found.push_back(there); };
    // The goal in sight (a diagonal run toward it, then a straight one) is the only successor
    // worth pushing: it is reached at the octile distance, and no path through here reaches
    // it more cheaply. Looked for only when its way is one of the successors' (a look costs
    // a diagonal run).
    const int towardX = (goal.x > here.x) - (goal.x < here.x);
    const int towardY = (goal.y > here.y) - (goal.y < here.y);
    const bool goalsWay = std::any_of(
        dirs, dirs + count, [&](const int* d) { return d[0] == towardX && d[1] == towardY; });
    if (successors_ == JumpSuccessors::ForcedOnly && q.table && goalsWay && goalInSight(q, here)) {
      reach(goal);
      count = 0;
    }
    for (int k = 0; k < count; ++k) {
      const int dx = dirs[k][0];
      const int dy = dirs[k][1];
      if (q.table == nullptr || dx == 0 || dy == 0) {
        if (q.table) {
          if (const Cell next = jumpByTable(q, here.x, here.y, dx, dy); next != kNoCell)
            reach(next);
        } else if (const std::uint32_t next = jump(q, here.x, here.y, dx, dy); next != kNone) {
          reach(map.cellAt(next));
        }
        continue;
      }
      // JPS+ (as JPS2, Harabor & Grastien 2014): a diagonal jump point is never pushed. Its
      // successors are its natural ones (a diagonal move has no forced neighbour when corners
      // are not cut), so they are reached from here at once: the straight jumps from each
      // stop of the diagonal run, and the run goes on.
      for (Cell at = jumpByTable(q, here.x, here.y, dx, dy); at != kNoCell;
           at = jumpByTable(q, at.x, at.y, dx, dy)) {
        if (at == goal) {
          reach(at);
          break;
        }
        if (const Cell next = jumpByTable(q, at.x, at.y, dx, 0); next != kNoCell) reach(next);
        if (const Cell next = jumpByTable(q, at.x, at.y, 0, dy); next != kNoCell) reach(next);
      }
    }
    for (const Cell there : found) {
      const std::uint32_t next = q.indexOf(there.x, there.y);
      const double ng = g + octileDistance(there.x - here.x, there.y - here.y);
      Node& reached = nodes_[next];
      if (reached.stamp == closedStamp || (reached.stamp == openStamp && ng >= reached.g)) continue;
      reached = {openStamp, current, ng};
      open_.push(OpenList::makeKey(ng + heuristic(there.x, there.y), ng), next);
      ++result.metrics.generated;
    }
  }
  result.status = status;
}

void JumpPointSearch::finish(std::vector<Cell>* path) {
  if (path) path->clear();
  if (result_.status == PathStatus::Found && path) {
    const GridMap& map = grid_.map();
    const std::uint32_t startIndex = map.indexOf(start_);
    // Jump points are joined by a diagonal run and then a straight one (JPS: either alone):
    // fill in their cells, backwards.
    for (std::uint32_t at = map.indexOf(query_.goal); at != startIndex; at = nodes_[at].parent) {
      const Cell from = map.cellAt(nodes_[at].parent);
      Cell c = map.cellAt(at);
      for (;;) {
        path->push_back(c);
        const auto [dx, dy] = lastStep(from, c);
        if (dx == 0 && dy == 0) break;
        c = {c.x - dx, c.y - dy};
        if (c == from) break;
      }
    }
    path->push_back(start_);
    std::reverse(path->begin(), path->end());
  }
}

}  // namespace warpath::pathing
