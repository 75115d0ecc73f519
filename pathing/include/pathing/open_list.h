#pragma once
// The open list of the A*-family searches.
//
// Order: lower f first; among equal f, larger g (nearer the goal) first, which expands fewer
// nodes on open ground. Both fold into one integer key: f in fixed point with 2^-24 cell
// resolution in the high bits, the tie-break in the low 20. Path costs are a + b*sqrt(2) with
// integer a, b; two different such values differ by far more than 2^-24 unless b runs into
// the millions, so the rounding never reorders distinct f.
//
// Speed: with a consistent heuristic the f of popped nodes never decreases, and a pushed node
// whose f equals the f just popped may be expanded next without breaking optimality. Such
// pushes (most of them on open ground, where f stays constant toward the goal) go to a LIFO
// stack. The rest have keys above the last key popped, so the open list is a *monotone*
// priority queue and a radix heap serves it: a push is an append to the bucket named by the
// highest bit in which the key differs from the last popped key, and a pop rescans only the
// lowest non-empty bucket. Measured against the 4-ary heap it replaced, it removed most of
// the branch mispredictions that made up half of an expansion on the bg512 maps.
// Duplicates are allowed (lazy deletion): callers skip entries of nodes already closed.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "pathing/invariant.h"

namespace warpath::pathing {

class OpenList {
 public:
  static std::uint64_t makeKey(double f, double g) {
    const auto fixedF = static_cast<std::uint64_t>(f * kFScale + 0.5);
    const auto coarseG = static_cast<std::uint64_t>(g * kTieScale);
    return (fixedF << kTieBits) | (kTieMask - (coarseG < kTieMask ? coarseG : kTieMask));
  }

  void clear() {
    for (std::uint64_t used = occupied_; used != 0; used &= used - 1) {
      buckets_[static_cast<std::size_t>(std::countr_zero(used))].clear();
    }
    buckets_[kBucketCount - 1].clear();
    occupied_ = 0;
    size_ = 0;
    sameF_.clear();
    lastKey_ = 0;
    poppedF_ = 0;
  }
  bool empty() const { return size_ == 0 && sameF_.empty(); }

  void push(std::uint64_t key, std::uint32_t node) {
    // Monotone: with a consistent heuristic no f falls below the last popped. A larger drop
    // than rounding (kFSlack) means an inconsistent heuristic or a negative edge cost, which
    // would silently cost optimality (the entry would be expanded next, out of order).
    WARPATH_INVARIANT((key >> kTieBits) + kFSlack >= poppedF_,
                      "open list: f must not decrease (heuristic inconsistent?)");
    // Rounding of g + h may put an equal f one unit below the last popped: treat it as equal.
    if ((key >> kTieBits) <= poppedF_) {
      sameF_.push_back(node);
      return;
    }
    insert({key, node});
    ++size_;
  }

  // [Limit: !empty(); a programming error, checked as an invariant in debug and sanitizer
  // builds]
  std::uint32_t pop() {
    WARPATH_INVARIANT(!empty(), "open list: pop() on an empty list");
    if (!sameF_.empty()) {
      const std::uint32_t node = sameF_.back();
      sameF_.pop_back();
      return node;
    }
    if (buckets_[0].empty()) refill();
    const Entry top = buckets_[0].back();
    buckets_[0].pop_back();
    if (buckets_[0].empty()) occupied_ &= ~std::uint64_t{1};
    --size_;
    poppedF_ = top.key >> kTieBits;
    return top.node;
  }

 private:
  struct Entry {
    std::uint64_t key;
    std::uint32_t node;
  };
  static constexpr int kTieBits = 20;
  static constexpr std::uint64_t kTieMask = (std::uint64_t{1} << kTieBits) - 1;
  static constexpr double kFScale = 16777216.0;  // 2^24
  static constexpr double kTieScale = 64.0;      // g resolution of the tie-break: 1/64 cell
  // Fixed-point f units (2^-24 cell each) by which a pushed f may undercut the last popped
  // through floating-point rounding alone: 2^-20 cell, far above any rounding of g + h.
  static constexpr std::uint64_t kFSlack = 16;
  // Bucket 0 holds keys equal to the last popped; bucket b > 0 keys whose highest bit
  // differing from it is bit b - 1.
  static constexpr std::size_t kBucketCount = 65;

  std::size_t bucketOf(std::uint64_t key) const {
    return static_cast<std::size_t>(64 - std::countl_zero(key ^ lastKey_));
  }

  void insert(const Entry& entry) {
    const std::size_t b = bucketOf(entry.key);
    buckets_[b].push_back(entry);
    if (b < 64) occupied_ |= std::uint64_t{1} << b;
  }

  // Moves the lowest non-empty bucket's entries down, keyed on its minimum. Every entry of
  // bucket b shares the bits above b - 1 with the minimum, so each lands in a lower bucket.
  void refill() {
    const std::size_t b =
        occupied_ != 0 ? static_cast<std::size_t>(std::countr_zero(occupied_)) : kBucketCount - 1;
    std::vector<Entry>& source = buckets_[b];
    std::uint64_t smallest = source.front().key;
    for (const Entry& e : source)
      smallest = e.key < smallest ? e.key : smallest;
    lastKey_ = smallest;
    occupied_ &= ~(std::uint64_t{1} << (b & 63));
    for (const Entry& e : source)
      insert(e);
    source.clear();
  }

  std::array<std::vector<Entry>, kBucketCount> buckets_;
  std::uint64_t occupied_ = 0;  // bit b set when buckets_[b] (b < 64) is non-empty
  std::size_t size_ = 0;        // entries in the buckets
  std::vector<std::uint32_t> sameF_;
  std::uint64_t lastKey_ = 0;
  std::uint64_t poppedF_ = 0;
};

// The open list of uniform Dijkstra searches (moves cost 1 or √2, no heuristic): ClusterDijkstra's
// and the cooperative search's corridor.
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
  // No entry left to pop (entries of nodes already settled count).
  bool empty() const {
    for (const Queue& q : queues_) {
      if (q.cursor > q.begin || q.end < q.entries.size()) return false;
    }
    return true;
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

}  // namespace warpath::pathing
