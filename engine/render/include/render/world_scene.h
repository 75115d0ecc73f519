#pragma once
// The one place that reads the engine's World for drawing: fills a FrameScene from the world's
// current state. Kept apart from rts_render (target rts_render_world) so the renderer does not
// follow every change of the World API.

#include "engine/world.h"
#include "render/frame_scene.h"

namespace warpath::render {

// Units (centre, size and hp from their type, team, type index, facing along their velocity or
// else towards their next waypoint, remaining path, currently stuck), per-team counts (a unit
// whose hp is 0 is dead: drawn as a wreck while its wreck stands, not at all once cleared),
// shots fired in the last tick as tracers, and the goal areas of the current orders as
// arrival zones. `teamCount` rows in the HUD at least.
FrameScene sceneOf(const engine::World& world, int teamCount = 0);

}  // namespace warpath::render
