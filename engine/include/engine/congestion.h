#pragma once
// Congestion-aware routes (issue 12, docs/cooperative.md): the queues that form where many
// units' routes meet at one narrow place (a bridge, a gap, a door), and the wait expected
// there, which the path service adds to the HAA* graph's edges (pathing::EdgeSurcharge) so
// that a long route takes a free bridge when the detour costs less than the wait.
//
// Narrow places, per capability: cells of the capability whose run across (the shorter of the
// row and the column of such cells through them) is at most kNarrowWidth cells; each 8-connected
// set of them is one place, as wide as the median of its cells' runs (ragged banks do not narrow
// a bridge). Each place is a queue served first come, first served, both ways together. A
// delivered path books its unit there: its arrival (now, plus the path's length up to the place
// at the unit's top speed, plus the waits at the places before it) and the time it holds the
// place (its body's length along the flow, 3/4 of its size plus a quarter cell, over its speed
// and the files of bodies that fit side by side). A unit arriving at t waits for the queue of
// those booked to arrive by t: max(0, its end - t). A unit's bookings are replaced by its next
// path's and dropped when it dies; a booking leaves the queue once the queue has served it.
// Everything is in booking order and simulated seconds, so it is deterministic.

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "engine/handle.h"
#include "pathing/annotated_grid.h"
#include "pathing/haa_star.h"

namespace warpath::engine {

// [Unit: cells] the widest run across that still makes a cell part of a narrow place.
inline constexpr int kNarrowWidth = 8;

class Congestion {
  struct Layer;  // (defined below; Surcharge keeps a reference to its agent's)

 public:
  // The grid must outlive this; `clusterSize` is the HAA* graph's.
  Congestion(const pathing::AnnotatedGrid& grid, int clusterSize);

  // The terrain changed: narrow places are found again when next asked for, and every booking
  // goes (the units whose routes the change touches plan again and book again).
  void terrainChanged();

  // [Unit: s] The wait `path` (anchor cells of an agent moving at `speed` cells/s, from now)
  // would meet at the narrow places it crosses (cancel the unit's own bookings first).
  double waitAlong(pathing::Agent agent, double speed, std::span<const pathing::Cell> path,
                   double now);
  // Replaces `unit`'s bookings by those of `path`.
  void book(UnitId unit, pathing::Agent agent, double speed, std::span<const pathing::Cell> path,
            double now);
  void cancel(UnitId unit);

  // The surcharge for one request: the waits at the narrow places an abstract edge enters,
  // reached at cost g from the start, in the graph's cost unit (cells at `speed`, or seconds
  // under terrain costs, `seconds`).
  class Surcharge final : public pathing::EdgeSurcharge {
   public:
    Surcharge(Congestion& congestion, pathing::Agent agent, double speed, double now, bool seconds)
        : congestion_(congestion), agent_(agent), speed_(speed), now_(now), seconds_(seconds) {}
    double on(const pathing::ClusterAbstraction& graph, std::uint32_t from,
              const pathing::AbstractEdge& edge, double g) const override;
    // No cluster of the level-2 cluster has a queue near (so `on` is 0 inside it).
    bool freeWithin(const pathing::ClusterAbstraction& graph, int levelTwoCluster) const override;

   private:
    // The agent's layer: looked up once, not on every edge the search relaxes.
    Layer& layer() const;

    Congestion& congestion_;
    pathing::Agent agent_;
    double speed_;
    double now_;
    bool seconds_;
    mutable std::size_t layer_ = SIZE_MAX;  // index into layers_, checked before each use
  };

  // Places with a queue not yet served at `now` (for the report and tests).
  std::size_t queuesAt(double now);

 private:
  struct Booking {
    UnitId unit;
    double arrival = 0.0;  // [Unit: s]
    double hold = 0.0;     // [Unit: s]
  };
  struct Place {
    int width = 0;  // [Unit: cells]
    std::vector<Booking> bookings;
    // Served in order of arrival (then unit index): arrivals and the queue's end after each.
    bool dirty = false;
    std::vector<double> arrivals;
    std::vector<double> ends;
  };
  // The narrow places of one capability.
  struct Layer {
    std::uint32_t capability = 0;
    std::vector<std::int32_t> placeOf;  // per cell; -1: not narrow
    std::vector<Place> places;
    std::vector<std::vector<std::int32_t>> placesInCluster;
  };

  Layer& layerFor(pathing::Capability capability);
  // [Unit: s] the wait at `place` for a unit arriving at t.
  double waitAt(Place& place, double t);
  // Walks `cells` (the first reached `startSeconds` from now) calling visit(place index, arrival
  // time), which returns the wait there, at each narrow place entered; returns the waits summed.
  template <class Visit>
  double walk(Layer& layer, double speed, double now, std::span<const pathing::Cell> cells,
              double startSeconds, Visit&& visit);
  bool anyQueueNear(Layer& layer, int cluster, double now);
  int clusterOf(pathing::Cell c) const {
    return (c.y / clusterSize_) * clustersX_ + c.x / clusterSize_;
  }

  const pathing::AnnotatedGrid& grid_;
  int clusterSize_;
  int clustersX_;
  std::vector<Layer> layers_;
  // Per unit index, the (layer, place) pairs it is booked at.
  std::unordered_map<std::uint32_t, std::vector<std::pair<std::size_t, std::int32_t>>> booked_;
  std::vector<pathing::Cell> edgeCells_;  // scratch
};

}  // namespace warpath::engine
