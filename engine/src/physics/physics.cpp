// The only file that includes Box2D.
#include "engine/physics.h"

#include <box2d/box2d.h>

#include <vector>

#include "pathing/invariant.h"

namespace warpath::engine {

using pathing::Capability;
using pathing::Cell;
using pathing::GridMap;
using pathing::Terrain;

std::uint16_t collisionMaskFor(Capability capability) {
  std::uint16_t mask = kBlockedCategory | kUnitCategory;
  for (int slot = 0; slot < pathing::kTraversableTerrainSlots; ++slot) {
    const auto t = static_cast<Terrain>(slot);
    if (!capability.allows(t)) mask = static_cast<std::uint16_t>(mask | terrainCategory(t));
  }
  return mask;
}

struct Physics::Impl {
  b2World world{b2Vec2(0.0f, 0.0f)};
  b2Body* terrain = nullptr;
  std::vector<b2Body*> bodies;       // null once removed
  std::vector<b2Vec2> lastPosition;  // of removed bodies
};

namespace {

// Rectangles [x0, x1) x [y0, y1) in cells.
struct Box {
  int x0, x1, y0, y1;
};

// Cells whose terrain satisfies `wanted`, merged into horizontal runs per row and then runs
// with identical extent on consecutive rows into one box: few fixtures, few inner edges.
template <class Pred>
std::vector<Box> mergeCells(const GridMap& map, Pred wanted) {
  std::vector<Box> done;
  std::vector<Box> open;  // boxes ending on the previous row, ordered by x0
  for (int y = 0; y < map.height(); ++y) {
    std::vector<Box> next;
    std::size_t o = 0;
    for (int x = 0; x < map.width();) {
      if (!wanted(map.at({x, y}))) {
        ++x;
        continue;
      }
      const int x0 = x;
      while (x < map.width() && wanted(map.at({x, y})))
        ++x;
      while (o < open.size() && open[o].x0 < x0)
        done.push_back(open[o++]);
      if (o < open.size() && open[o].x0 == x0 && open[o].x1 == x) {
        Box grown = open[o++];
        grown.y1 = y + 1;
        next.push_back(grown);
      } else {
        next.push_back({x0, x, y, y + 1});
      }
    }
    while (o < open.size())
      done.push_back(open[o++]);
    open = std::move(next);
  }
  done.insert(done.end(), open.begin(), open.end());
  return done;
}

void addBox(b2Body* body, const Box& box, std::uint16_t category) {
  b2PolygonShape shape;
  const float hx = 0.5f * static_cast<float>(box.x1 - box.x0);
  const float hy = 0.5f * static_cast<float>(box.y1 - box.y0);
  shape.SetAsBox(hx, hy, b2Vec2(static_cast<float>(box.x0) + hx, static_cast<float>(box.y0) + hy),
                 0.0f);
  b2FixtureDef def;
  def.shape = &shape;
  def.friction = 0.0f;  // units slide along walls instead of sticking to them
  def.filter.categoryBits = category;
  def.filter.maskBits = kUnitCategory;
  body->CreateFixture(&def);
}

}  // namespace

Physics::Physics(const GridMap& map, std::span<const Capability> capabilities)
    : impl_(std::make_unique<Impl>()), map_(map), forbidden_(kBlockedCategory) {
  for (Capability c : capabilities)
    forbidden_ = static_cast<std::uint16_t>(forbidden_ | (collisionMaskFor(c) & ~kUnitCategory));
  buildTerrain();
}

void Physics::buildTerrain() {
  if (impl_->terrain != nullptr) impl_->world.DestroyBody(impl_->terrain);
  stats_.staticBoxes = 0;
  b2BodyDef def;
  def.type = b2_staticBody;
  impl_->terrain = impl_->world.CreateBody(&def);
  const GridMap& map = map_;
  for (int slot = 0; slot < pathing::kTraversableTerrainSlots; ++slot) {
    const auto t = static_cast<Terrain>(slot);
    if ((forbidden_ & terrainCategory(t)) == 0) continue;
    for (const Box& box : mergeCells(map, [t](Terrain cell) { return cell == t; })) {
      addBox(impl_->terrain, box, terrainCategory(t));
      ++stats_.staticBoxes;
    }
  }
  for (const Box& box :
       mergeCells(map, [](Terrain cell) { return !pathing::isTraversable(cell); })) {
    addBox(impl_->terrain, box, kBlockedCategory);
    ++stats_.staticBoxes;
  }
  // The border: one cell thick outside each side of the map.
  const int w = map.width();
  const int h = map.height();
  for (const Box& box :
       {Box{-1, w + 1, -1, 0}, Box{-1, w + 1, h, h + 1}, Box{-1, 0, 0, h}, Box{w, w + 1, 0, h}}) {
    addBox(impl_->terrain, box, kBlockedCategory);
    ++stats_.staticBoxes;
  }
}

void Physics::setTerrain(pathing::CellRect area, Terrain terrain) {
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      if (map_.contains({x, y})) map_.set({x, y}, terrain);
    }
  }
  buildTerrain();
}

void Physics::moveBody(BodyId body, units::Vec2 centre) {
  if (!known(body) || impl_->bodies[body.index] == nullptr) return;
  b2Body* b = impl_->bodies[body.index];
  b->SetTransform(b2Vec2(static_cast<float>(centre.x), static_cast<float>(centre.y)), 0.0f);
  b->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
}

Physics::~Physics() = default;

BodyId Physics::addBody(units::Vec2 centre, double radius, Capability capability,
                        std::uint32_t owner) {
  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.userData.pointer = owner;
  def.position.Set(static_cast<float>(centre.x), static_cast<float>(centre.y));
  def.fixedRotation = true;
  b2Body* body = impl_->world.CreateBody(&def);
  b2CircleShape shape;
  shape.m_radius = static_cast<float>(radius);
  b2FixtureDef fixture;
  fixture.shape = &shape;
  fixture.density = 1.0f;  // mass grows with the body's area: tanks shove infantry aside
  fixture.friction = 0.0f;
  fixture.filter.categoryBits = kUnitCategory;
  fixture.filter.maskBits = collisionMaskFor(capability);
  body->CreateFixture(&fixture);
  impl_->bodies.push_back(body);
  impl_->lastPosition.push_back(def.position);
  ++stats_.bodies;
  return BodyId{static_cast<std::uint32_t>(impl_->bodies.size() - 1)};
}

bool Physics::known(BodyId body) const {
  const bool ok = body.valid() && body.index < impl_->bodies.size();
  WARPATH_INVARIANT(ok, "a body handle this Physics never gave out");
  return ok;
}

void Physics::freeze(BodyId body) {
  if (!known(body)) return;
  b2Body* b = impl_->bodies[body.index];
  if (b == nullptr) return;
  b->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
  b->SetType(b2_staticBody);
}

void Physics::setBraced(BodyId body, bool braced) {
  if (!known(body)) return;
  b2Body* b = impl_->bodies[body.index];
  if (b == nullptr || b->GetType() != b2_dynamicBody) return;
  b->ResetMassData();
  if (!braced) return;
  b2MassData mass;
  b->GetMassData(&mass);
  mass.mass *= kBracedMassFactor;
  mass.I *= kBracedMassFactor;
  b->SetMassData(&mass);
}

void Physics::removeBody(BodyId body) {
  if (!known(body)) return;
  b2Body*& b = impl_->bodies[body.index];
  if (b == nullptr) return;
  impl_->lastPosition[body.index] = b->GetPosition();
  impl_->world.DestroyBody(b);
  b = nullptr;
  --stats_.bodies;
}

void Physics::setVelocity(BodyId body, units::Vec2 velocity) {
  if (!known(body) || impl_->bodies[body.index] == nullptr) return;
  impl_->bodies[body.index]->SetLinearVelocity(
      b2Vec2(static_cast<float>(velocity.x), static_cast<float>(velocity.y)));
}

void Physics::step(double dt) {
  constexpr int kVelocityIterations = 8;
  constexpr int kPositionIterations = 3;
  impl_->world.Step(static_cast<float>(dt), kVelocityIterations, kPositionIterations);
}

void Physics::touching(BodyId body, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!known(body) || impl_->bodies[body.index] == nullptr) return;
  for (const b2ContactEdge* e = impl_->bodies[body.index]->GetContactList(); e != nullptr;
       e = e->next) {
    if (e->contact->IsTouching() && e->other->GetType() == b2_dynamicBody)
      out.push_back(static_cast<std::uint32_t>(e->other->GetUserData().pointer));
  }
}

units::Vec2 Physics::position(BodyId body) const {
  if (!known(body)) return {};
  const b2Body* b = impl_->bodies[body.index];
  const b2Vec2 p = b != nullptr ? b->GetPosition() : impl_->lastPosition[body.index];
  return {static_cast<double>(p.x), static_cast<double>(p.y)};
}

units::Vec2 Physics::velocity(BodyId body) const {
  if (!known(body)) return {};
  const b2Body* b = impl_->bodies[body.index];
  const b2Vec2 v = b != nullptr ? b->GetLinearVelocity() : b2Vec2(0.0f, 0.0f);
  return {static_cast<double>(v.x), static_cast<double>(v.y)};
}

}  // namespace warpath::engine
