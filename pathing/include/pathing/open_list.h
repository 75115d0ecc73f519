#pragma once
// The open list of the A*-family searches.
//
// Order: lower f first; among equal f, larger g (nearer the goal) first, which expands fewer
// nodes on open ground. Both fold into one integer key so the heap compares a single word:
// f in fixed point with 2^-24 cell resolution in the high bits, the tie-break in the low 20.
// Path costs are a + b*sqrt(2) with integer a, b; two different such values differ by far
// more than 2^-24 unless b runs into the millions, so the rounding never reorders distinct f.
//
// Speed: with a consistent heuristic the f of popped nodes never decreases, and a pushed node
// whose f equals the f just popped may be expanded next without breaking optimality. Such
// pushes (most of them on open ground, where f stays constant toward the goal) go to a LIFO
// stack and skip the heap. The rest live in a 4-ary min-heap, whose shallow depth and
// cache-line-sized sibling groups beat a binary heap for A*'s push-heavy pattern.
// Duplicates are allowed (lazy deletion): callers skip entries of nodes already closed.

#include <algorithm>
#include <cstdint>
#include <vector>

namespace warpath::pathing {

class OpenList {
 public:
  static std::uint64_t makeKey(double f, double g) {
    const auto fixedF = static_cast<std::uint64_t>(f * kFScale + 0.5);
    const auto coarseG = std::min(static_cast<std::uint64_t>(g * kTieScale), kTieMask);
    return (fixedF << kTieBits) | (kTieMask - coarseG);
  }

  void clear() {
    keys_.clear();
    nodes_.clear();
    sameF_.clear();
    poppedF_ = 0;
  }
  bool empty() const { return keys_.empty() && sameF_.empty(); }

  void push(std::uint64_t key, std::uint32_t node) {
    if ((key >> kTieBits) == poppedF_) {
      sameF_.push_back(node);
    } else {
      pushHeap(key, node);
    }
  }

  // [Limit: !empty()]
  std::uint32_t pop() {
    if (!sameF_.empty()) {
      const std::uint32_t node = sameF_.back();
      sameF_.pop_back();
      return node;
    }
    const Entry top = popHeap();
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
  static constexpr std::size_t kArity = 4;

  void pushHeap(std::uint64_t key, std::uint32_t node) {
    keys_.push_back(key);
    nodes_.push_back(node);
    siftUp(keys_.size() - 1, key, node);
  }

  void siftUp(std::size_t hole, std::uint64_t key, std::uint32_t node) {
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / kArity;
      if (keys_[parent] <= key) break;
      keys_[hole] = keys_[parent];
      nodes_[hole] = nodes_[parent];
      hole = parent;
    }
    keys_[hole] = key;
    nodes_[hole] = node;
  }

  // Bottom-up deletion: walk the hole down along the smallest children to a leaf without
  // comparing against the displaced last entry (an unpredictable branch), then sift that
  // entry up from the leaf, which is usually where it belongs anyway.
  Entry popHeap() {
    const Entry top{keys_.front(), nodes_.front()};
    const std::uint64_t lastKey = keys_.back();
    const std::uint32_t lastNode = nodes_.back();
    keys_.pop_back();
    nodes_.pop_back();
    const std::size_t n = keys_.size();
    if (n == 0) return top;
    std::size_t hole = 0;
    while (true) {
      const std::size_t first = hole * kArity + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = std::min(first + kArity, n);
      for (std::size_t c = first + 1; c < end; ++c) {
        best = keys_[c] < keys_[best] ? c : best;
      }
      keys_[hole] = keys_[best];
      nodes_[hole] = nodes_[best];
      hole = best;
    }
    siftUp(hole, lastKey, lastNode);
    return top;
  }

  // Structure of arrays: comparisons touch only the keys.
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> nodes_;
  std::vector<std::uint32_t> sameF_;
  std::uint64_t poppedF_ = 0;
};

}  // namespace warpath::pathing
