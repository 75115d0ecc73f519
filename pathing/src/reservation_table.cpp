#include "pathing/reservation_table.h"

#include <algorithm>
#include <utility>

namespace warpath::pathing {

ReservationTable::ReservationTable(int width, int height, std::vector<std::uint8_t> tracked)
    : width_(std::max(0, width)),
      height_(std::max(0, height)),
      tracked_(std::move(tracked)),
      cells_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_)),
      occupied_(cells_.size(), 0) {
  if (tracked_.size() != cells_.size()) tracked_.clear();
}

ReservationTable ReservationTable::trackingNothing(int width, int height) {
  return ReservationTable(
      width, height,
      std::vector<std::uint8_t>(static_cast<std::size_t>(std::max(0, width)) *
                                    static_cast<std::size_t>(std::max(0, height)),
                                0));
}

void ReservationTable::track(std::span<const std::uint8_t> cells) {
  if (tracked_.empty() || cells.size() != tracked_.size()) return;
  ++trackChanges_;
  for (std::size_t i = 0; i < cells.size(); ++i)
    tracked_[i] = static_cast<std::uint8_t>(tracked_[i] | (cells[i] != 0 ? 1 : 0));
}

void ReservationTable::reserve(Cell anchor, int size, Tick from, Tick to, std::uint32_t owner) {
  if (!(from < to) || size < 1) return;
  if (owners_.size() <= owner) owners_.resize(static_cast<std::size_t>(owner) + 1);
  owners_[owner].push_back({anchor, size, from, to});
  forEachCell(anchor, size, [&](std::size_t cell) {
    if (!tracked_.empty() && tracked_[cell] == 0) return;
    std::vector<Interval>& held = cells_[cell];
    occupied_[cell] = 1;
    held.insert(std::upper_bound(held.begin(), held.end(), from,
                                 [](Tick t, const Interval& i) { return t < i.from; }),
                {from, to, owner});
    ++intervals_;
    // Intervals that never end are dropped by release() only.
    if (to != kForever) expiries_.push({to, static_cast<std::uint32_t>(cell)});
  });
}

bool ReservationTable::tracks(Cell anchor, int size) const {
  if (tracked_.empty()) return true;
  return anyCell(anchor, size, [&](std::size_t cell) { return tracked_[cell] != 0; });
}

void ReservationTable::release(std::uint32_t owner) {
  if (owner >= owners_.size()) return;
  for (const Reservation& r : owners_[owner]) {
    forEachCell(r.anchor, r.size, [&](std::size_t cell) {
      intervals_ -=
          std::erase_if(cells_[cell], [&](const Interval& i) { return i.owner == owner; });
      occupied_[cell] = cells_[cell].empty() ? 0 : 1;
    });
  }
  owners_[owner].clear();
}

std::optional<std::uint32_t> ReservationTable::blocker(Cell anchor, int size, Tick from, Tick to,
                                                       std::uint32_t self) const {
  std::optional<std::uint32_t> found;
  forEachCell(anchor, size, [&](std::size_t cell) {
    for (const Interval& i : heldAt(cell)) {
      if (!(i.from < to)) break;  // the rest begin later still
      if (i.owner == self || !(from < i.to)) continue;
      if (!found || i.owner < *found) found = i.owner;
    }
  });
  return found;
}

std::vector<std::uint32_t> ReservationTable::holders(Cell anchor, int size, Tick from, Tick to,
                                                     std::uint32_t self) const {
  std::vector<std::uint32_t> out;
  forEachCell(anchor, size, [&](std::size_t cell) {
    for (const Interval& i : heldAt(cell)) {
      if (!(i.from < to)) break;  // the rest begin later still
      if (i.owner != self && from < i.to) out.push_back(i.owner);
    }
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void ReservationTable::forget(Tick now) {
  while (!expiries_.empty() && expiries_.top().to <= now) {
    const std::uint32_t cell = expiries_.top().cell;
    expiries_.pop();
    intervals_ -= std::erase_if(cells_[cell], [&](const Interval& i) { return i.to <= now; });
    occupied_[cell] = cells_[cell].empty() ? 0 : 1;
  }
}

std::span<const ReservationTable::Reservation> ReservationTable::heldBy(std::uint32_t owner) const {
  if (owner >= owners_.size()) return {};
  return owners_[owner];
}

}  // namespace warpath::pathing
