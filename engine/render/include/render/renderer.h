#pragma once
// Headless frames through an OSMesa offscreen OpenGL context (Mesa's software rasteriser: no
// display, no GPU). A Renderer is bound to one map, whose terrain it uploads once as a texture,
// and draws FrameScenes into an RGBA image of a fixed resolution. It reads what it is given and
// keeps no reference to it.
//
// Each Renderer owns its GL context and makes it current on the calling thread for every call,
// so renderers may live side by side; one renderer is used by one thread at a time.

#include <memory>
#include <optional>
#include <string_view>

#include "pathing/annotated_grid.h"
#include "pathing/clearance.h"
#include "pathing/cluster_abstraction.h"
#include "pathing/error.h"
#include "pathing/grid_map.h"
#include "render/frame_scene.h"
#include "render/image.h"

namespace warpath::render {

// What is drawn besides terrain and units. Each switch is independent.
struct Overlays {
  bool paths = false;       // each unit's remaining waypoints as a line
  bool footprints = false;  // each unit's size x size footprint along its path
  // Each unit's reserved cooperative window as a trail coloured by time: white now, through
  // the team colour, to dark at kReservationHorizonSeconds and later; a dot marks each wait.
  bool reservations = false;
  bool clearance = false;      // heat map of the field given to setClearance()
  bool abstractGraph = false;  // the graph given to setAbstractGraph(): nodes, edges, clusters
  bool stuck = true;           // a ring around units flagged stuck
  bool arrivalZones = true;    // the scene's arrival zones, outlined in their team's colour
  bool hud = true;             // tick, time and per-team counts
  constexpr bool operator==(const Overlays&) const = default;
};

inline constexpr float kReservationHorizonSeconds = 8.0f;

// Parses a comma-separated list of overlay names to switch on (paths, footprints,
// reservations, clearance, graph, stuck, zones, hud) over `base`; "none" switches every overlay
// off; "" changes nothing.
Result<Overlays> parseOverlays(std::string_view names, Overlays base = {});

struct RenderDef {
  int width = 512;   // [Unit: pixels] [Limit: 1..8192]
  int height = 512;  // [Unit: pixels] [Limit: 1..8192]
  // The part of the map in view; the whole map when empty. The view keeps square cells,
  // centred, with the background colour around it when the aspect ratios differ.
  std::optional<pathing::CellRect> camera{};
  Overlays overlays{};
};

// The whole map at its aspect ratio, its longer side `size` pixels. [Limit: size >= 1]
RenderDef fittedDef(const pathing::GridMap& map, int size);

class Renderer {
 public:
  // Fails (never crashes) when OSMesa cannot create a context, the resolution or camera is
  // out of range, or the map is empty or larger than the largest texture.
  static Result<Renderer> create(const pathing::GridMap& map, const RenderDef& def);

  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  ~Renderer();

  int width() const;
  int height() const;
  const Overlays& overlays() const;
  void setOverlays(const Overlays& overlays);
  // [Limit: camera non-empty, overlapping the map] Empty: the whole map.
  Status setCamera(std::optional<pathing::CellRect> camera);

  // The clearance heat map: one cell's colour per clearance value (0 left clear). The field
  // must cover the renderer's map.
  Status setClearance(const pathing::ClearanceField& field);
  // The HAA* graph: nodes, inter-edges and intra-edges (only those usable by `agent` when
  // given) and cluster borders. The abstraction must have been built on the renderer's map.
  Status setAbstractGraph(const pathing::ClusterAbstraction& abstraction,
                          std::optional<pathing::Agent> agent = std::nullopt);

  // Draws one frame; image() holds it until the next call.
  Status render(const FrameScene& scene);
  const Image& image() const;

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace warpath::render
