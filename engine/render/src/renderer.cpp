#include "render/renderer.h"

// libOSMesa exports the GL 1.2+ entry points (glBlendFuncSeparate) directly.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "render/bitmap_font.h"
#include "render/palette.h"

namespace warpath::render {
namespace {

using pathing::CellRect;

static_assert(sizeof(Rgba) == 4, "Rgba is uploaded to GL as 4 unsigned bytes");

constexpr int kMaxResolution = 8192;

Rgba withAlpha(Rgba c, std::uint8_t a) {
  return {c.r, c.g, c.b, a};
}

// Vertices with colours, drawn with one glDrawArrays call; order is kept, so later
// primitives cover earlier ones.
class Batch {
 public:
  void vertex(Point p, Rgba c) {
    xy_.push_back(p.x);
    xy_.push_back(p.y);
    rgba_.push_back(c);
  }
  void triangle(Point a, Point b, Point c, Rgba colour) {
    vertex(a, colour);
    vertex(b, colour);
    vertex(c, colour);
  }
  void rect(float x0, float y0, float x1, float y1, Rgba colour) {
    triangle({x0, y0}, {x1, y0}, {x1, y1}, colour);
    triangle({x0, y0}, {x1, y1}, {x0, y1}, colour);
  }
  // A segment `halfWidth` wide on each side, as two triangles (kept in draw order with the
  // shapes around it, unlike GL lines).
  void thickLine(Point a, Point b, float halfWidth, Rgba colour) {
    const float dx = b.x - a.x;
    const float dy = b.y - a.y;
    const float len = std::sqrt(dx * dx + dy * dy);
    if (len <= 0.0f) return;
    const float nx = -dy / len * halfWidth;
    const float ny = dx / len * halfWidth;
    const Point p0{a.x + nx, a.y + ny}, p1{b.x + nx, b.y + ny};
    const Point p2{b.x - nx, b.y - ny}, p3{a.x - nx, a.y - ny};
    triangle(p0, p1, p2, colour);
    triangle(p0, p2, p3, colour);
  }
  void frame(float x0, float y0, float x1, float y1, float halfWidth, Rgba colour) {
    rect(x0 - halfWidth, y0 - halfWidth, x1 + halfWidth, y0 + halfWidth, colour);
    rect(x0 - halfWidth, y1 - halfWidth, x1 + halfWidth, y1 + halfWidth, colour);
    rect(x0 - halfWidth, y0 + halfWidth, x0 + halfWidth, y1 - halfWidth, colour);
    rect(x1 - halfWidth, y0 + halfWidth, x1 + halfWidth, y1 - halfWidth, colour);
  }
  void line(Point a, Point b, Rgba colour) {
    vertex(a, colour);
    vertex(b, colour);
  }

  bool empty() const { return rgba_.empty(); }
  void clear() {
    xy_.clear();
    rgba_.clear();
  }
  void draw(GLenum mode) const {
    if (empty()) return;
    glVertexPointer(2, GL_FLOAT, 0, xy_.data());
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, rgba_.data());
    glDrawArrays(mode, 0, static_cast<GLsizei>(rgba_.size()));
  }

 private:
  std::vector<float> xy_;
  std::vector<Rgba> rgba_;
};

// A unit's glyph: a regular polygon, its radius relative to the unit's size.
struct Shape {
  int sides;
  float rotation;  // [Unit: radians] of the first vertex
  float radius;    // [Unit: unit sizes]
};
constexpr float kPi = std::numbers::pi_v<float>;
constexpr std::array<Shape, 6> kShapes{{{16, 0.0f, 0.5f},
                                        {4, kPi / 4.0f, 0.6f},
                                        {3, -kPi / 2.0f, 0.62f},
                                        {4, 0.0f, 0.6f},
                                        {6, 0.0f, 0.54f},
                                        {5, -kPi / 2.0f, 0.56f}}};

GLuint uploadTexture(GLuint texture, int width, int height, const std::vector<Rgba>& texels) {
  if (texture == 0) glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               texels.data());
  return texture;
}

// The terrain texture: a texel per cell, in the palette's terrain colours.
GLuint uploadTerrain(GLuint texture, const pathing::GridMap& map) {
  std::vector<Rgba> texels(map.cellCount());
  for (std::size_t i = 0; i < texels.size(); ++i)
    texels[i] = palette::terrainColour(map.cells()[i]);
  return uploadTexture(texture, map.width(), map.height(), texels);
}

Status checkCamera(const CellRect& camera, int mapWidth, int mapHeight) {
  if (camera.width <= 0 || camera.height <= 0) {
    return Error{"", 0, 0,
                 "camera " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                     " is empty"};
  }
  if (camera.x >= mapWidth || camera.y >= mapHeight || camera.x + camera.width <= 0 ||
      camera.y + camera.height <= 0) {
    return Error{"", 0, 0,
                 "camera does not overlap the " + std::to_string(mapWidth) + "x" +
                     std::to_string(mapHeight) + " map"};
  }
  return Status::success();
}

}  // namespace

struct Renderer::Impl {
  OSMesaContext context = nullptr;
  Image image;
  RenderDef def;
  int mapWidth = 0;
  int mapHeight = 0;
  GLuint terrainTexture = 0;
  std::uint64_t terrainRevision = 0;  // of the terrain the texture shows
  GLuint clearanceTexture = 0;
  Batch graphLines;  // cluster borders and edges, built by setAbstractGraph
  Batch graphNodes;
  Batch tris;                                                    // per frame
  std::array<std::vector<Point>, kShapes.size()> shapeVertices;  // unit radius

  Impl() {
    for (std::size_t s = 0; s < kShapes.size(); ++s) {
      for (int k = 0; k < kShapes[s].sides; ++k) {
        const float a = kShapes[s].rotation +
                        2.0f * kPi * static_cast<float>(k) / static_cast<float>(kShapes[s].sides);
        shapeVertices[s].push_back({std::cos(a), std::sin(a)});
      }
    }
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (context == nullptr) return;
    // Destroying the context frees its textures.
    if (OSMesaGetCurrentContext() == context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context);
  }

  Status makeCurrent() {
    if (OSMesaGetCurrentContext() == context) return Status::success();
    if (!OSMesaMakeCurrent(context, image.pixels.data(), GL_UNSIGNED_BYTE, image.width,
                           image.height)) {
      return Error{"", 0, 0,
                   "OSMesaMakeCurrent failed for a " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " RGBA buffer"};
    }
    // Row 0 of the buffer is the top of the picture, as in Image.
    OSMesaPixelStore(OSMESA_Y_UP, 0);
    return Status::success();
  }

  CellRect camera() const { return def.camera.value_or(CellRect{0, 0, mapWidth, mapHeight}); }

  // Sets the viewport and projection for map space (cell units, y down); returns pixels per
  // cell.
  float enterMapSpace() const {
    const CellRect cam = camera();
    const double scale = std::min(static_cast<double>(image.width) / cam.width,
                                  static_cast<double>(image.height) / cam.height);
    const int vw = std::max(1, static_cast<int>(std::lround(scale * cam.width)));
    const int vh = std::max(1, static_cast<int>(std::lround(scale * cam.height)));
    glViewport((image.width - vw) / 2, (image.height - vh) / 2, vw, vh);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(cam.x, cam.x + cam.width, cam.y + cam.height, cam.y, -1.0, 1.0);
    return static_cast<float>(scale);
  }
  void enterPixelSpace() const {
    glViewport(0, 0, image.width, image.height);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0.0, image.width, image.height, 0.0, -1.0, 1.0);
  }

  void drawTexture(GLuint texture) const {
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    const float w = static_cast<float>(mapWidth);
    const float h = static_cast<float>(mapHeight);
    const std::array<float, 8> xy{0, 0, w, 0, w, h, 0, h};
    const std::array<float, 8> uv{0, 0, 1, 0, 1, 1, 0, 1};
    glDisableClientState(GL_COLOR_ARRAY);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, xy.data());
    glTexCoordPointer(2, GL_FLOAT, 0, uv.data());
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glDisable(GL_TEXTURE_2D);
  }

  void addUnitShape(const UnitView& u, float radius, float pixel, Rgba fill, Rgba outline) {
    const auto& unit = shapeVertices[static_cast<std::size_t>(u.type) % kShapes.size()];
    const float border = std::min(radius * 0.3f, std::max(pixel, radius * 0.12f));
    const auto polygon = [&](float r, Rgba colour) {
      for (std::size_t k = 0; k < unit.size(); ++k) {
        const Point& a = unit[k];
        const Point& b = unit[(k + 1) % unit.size()];
        tris.triangle(u.centre, {u.centre.x + a.x * r, u.centre.y + a.y * r},
                      {u.centre.x + b.x * r, u.centre.y + b.y * r}, colour);
      }
    };
    polygon(radius, outline);
    polygon(radius - border, fill);
  }

  void addUnits(const FrameScene& scene, float ppc) {
    const float pixel = 1.0f / ppc;
    const auto radiusOf = [&](const UnitView& u) {
      const float r = kShapes[static_cast<std::size_t>(u.type) % kShapes.size()].radius *
                      static_cast<float>(std::max(1, u.size));
      return std::max(r, 2.0f * pixel);  // stay visible when cells are smaller than pixels
    };
    // Wrecks under the living.
    for (const UnitView& u : scene.units) {
      if (u.state != UnitState::Wreck) continue;
      const float r = radiusOf(u) * 0.85f;
      addUnitShape(u, r, pixel, palette::kWreck, palette::kWreckMark);
      const float d = r * 0.6f;
      const float hw = std::max(pixel * 0.75f, r * 0.1f);
      tris.thickLine({u.centre.x - d, u.centre.y - d}, {u.centre.x + d, u.centre.y + d}, hw,
                     palette::kWreckMark);
      tris.thickLine({u.centre.x - d, u.centre.y + d}, {u.centre.x + d, u.centre.y - d}, hw,
                     palette::kWreckMark);
    }
    for (const UnitView& u : scene.units) {
      if (u.state == UnitState::Wreck) continue;
      const float r = radiusOf(u);
      addUnitShape(u, r, pixel, palette::teamColour(u.team), palette::kBlack);
      // Facing: a dark wedge from the centre to the rim.
      const float cx = std::cos(u.facing);
      const float cy = std::sin(u.facing);
      const float base = std::max(pixel, r * 0.22f);
      tris.triangle({u.centre.x + cx * r, u.centre.y + cy * r},
                    {u.centre.x - cy * base, u.centre.y + cx * base},
                    {u.centre.x + cy * base, u.centre.y - cx * base}, palette::kBlack);
    }
    // Health bars above damaged units.
    for (const UnitView& u : scene.units) {
      if (u.state == UnitState::Wreck || u.hp >= 1.0f) continue;
      const float r = radiusOf(u);
      const float halfW = std::max(r, 4.0f * pixel);
      const float h = std::max(2.0f * pixel, 0.12f * static_cast<float>(u.size));
      const float y1 = u.centre.y - r - pixel;
      const float x0 = u.centre.x - halfW;
      tris.rect(x0, y1 - h, u.centre.x + halfW, y1, palette::kHpLost);
      tris.rect(x0, y1 - h, x0 + 2.0f * halfW * std::clamp(u.hp, 0.0f, 1.0f), y1, palette::kHpGood);
    }
    // Shots over the units: instant tracers as thin lines, shells as short streaks.
    for (const Tracer& t : scene.shots) {
      const Rgba colour = palette::teamColour(t.team);
      if (!t.projectile) {
        tris.thickLine(t.from, t.to, std::max(pixel * 0.5f, 0.05f), colour);
        continue;
      }
      const float hw = std::max(pixel, 0.1f);
      tris.thickLine(t.from, t.to, hw, colour);
      tris.rect(t.to.x - hw * 1.5f, t.to.y - hw * 1.5f, t.to.x + hw * 1.5f, t.to.y + hw * 1.5f,
                palette::kWhite);
    }
    if (def.overlays.stuck) {
      for (const UnitView& u : scene.units) {
        if (!u.stuck || u.state == UnitState::Wreck) continue;
        const float r = radiusOf(u) + 2.0f * pixel;
        tris.frame(u.centre.x - r, u.centre.y - r, u.centre.x + r, u.centre.y + r, pixel,
                   palette::kStuck);
      }
    }
  }

  void addPaths(const FrameScene& scene, float ppc) {
    const float pixel = 1.0f / ppc;
    if (def.overlays.footprints) {
      for (const UnitView& u : scene.units) {
        if (u.state == UnitState::Wreck) continue;
        const float half = static_cast<float>(std::max(1, u.size)) / 2.0f;
        const Rgba colour = withAlpha(palette::teamColour(u.team), 70);
        for (const Point& p : u.path)
          tris.rect(p.x - half, p.y - half, p.x + half, p.y + half, colour);
      }
    }
    if (def.overlays.paths) {
      for (const UnitView& u : scene.units) {
        if (u.state == UnitState::Wreck || u.path.empty()) continue;
        const Rgba colour = palette::teamColour(u.team);
        Point from = u.centre;
        for (const Point& p : u.path) {
          tris.thickLine(from, p, std::max(pixel * 0.75f, 0.08f), colour);
          from = p;
        }
      }
    }
  }

  void addReservations(const FrameScene& scene, float ppc) {
    if (!def.overlays.reservations) return;
    const float pixel = 1.0f / ppc;
    const float width = std::max(pixel * 1.5f, 0.15f);
    for (const UnitView& u : scene.units) {
      if (u.state == UnitState::Wreck || u.window.size() != u.windowSeconds.size()) continue;
      const Rgba team = palette::teamColour(u.team);
      const auto colourAt = [&](float seconds) {
        // White now, the team's colour half way to the horizon, dark at it.
        const float t = std::clamp(seconds / kReservationHorizonSeconds, 0.0f, 1.0f);
        const auto mix = [](std::uint8_t a, std::uint8_t b, float k) {
          return static_cast<std::uint8_t>(
              std::lround(static_cast<float>(a) * (1.0f - k) + static_cast<float>(b) * k));
        };
        const float k = t < 0.5f ? t * 2.0f : (t - 0.5f) * 2.0f;
        const Rgba from = t < 0.5f ? Rgba{255, 255, 255, 230} : team;
        const Rgba to = t < 0.5f ? team : Rgba{20, 20, 30, 230};
        return Rgba{mix(from.r, to.r, k), mix(from.g, to.g, k), mix(from.b, to.b, k), 230};
      };
      Point from = u.centre;
      float fromSeconds = 0.0f;
      for (std::size_t i = 0; i < u.window.size(); ++i) {
        const Point& p = u.window[i];
        const float seconds = u.windowSeconds[i];
        if (p == from && i > 0) {
          // A wait: a dot where the unit stands still.
          tris.rect(p.x - width, p.y - width, p.x + width, p.y + width, colourAt(seconds));
        } else {
          tris.thickLine(from, p, width, colourAt(0.5f * (fromSeconds + seconds)));
        }
        from = p;
        fromSeconds = seconds;
      }
    }
  }

  void addZones(const FrameScene& scene, float ppc) {
    const float pixel = 1.0f / ppc;
    for (const ArrivalZone& z : scene.arrivalZones) {
      const Rgba colour = palette::teamColour(z.team);
      const float x0 = static_cast<float>(z.area.x);
      const float y0 = static_cast<float>(z.area.y);
      const float x1 = x0 + static_cast<float>(z.area.width);
      const float y1 = y0 + static_cast<float>(z.area.height);
      tris.rect(x0, y0, x1, y1, withAlpha(colour, 48));
      tris.frame(x0, y0, x1, y1, pixel, colour);
    }
  }

  void addText(float x, float y, float scale, std::string_view text, Rgba colour) {
    for (const char c : text) {
      const auto rows = glyphRows(c);
      for (int r = 0; r < kGlyphHeight; ++r) {
        for (int col = 0; col < kGlyphWidth; ++col) {
          if ((rows[static_cast<std::size_t>(r)] >> (kGlyphWidth - 1 - col) & 1) == 0) continue;
          const float px = x + static_cast<float>(col) * scale;
          const float py = y + static_cast<float>(r) * scale;
          tris.rect(px, py, px + scale, py + scale, colour);
        }
      }
      x += static_cast<float>(kGlyphAdvance) * scale;
    }
  }

  void addHud(const FrameScene& scene) {
    const float s = static_cast<float>(std::max(1, std::min(image.width, image.height) / 256));
    const float lineHeight = static_cast<float>(kGlyphHeight + 3) * s;
    const float margin = 2.0f * s;
    std::vector<std::string> lines;
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, "TICK %lld  TIME %.1fS",
                  static_cast<long long>(scene.tick), scene.seconds);
    lines.emplace_back(buffer);
    for (const TeamCounts& t : scene.teams) {
      std::snprintf(buffer, sizeof buffer, "ALIVE %d ARRIVED %d DEAD %d", t.alive, t.arrived,
                    t.dead);
      lines.emplace_back(buffer);
    }
    const float swatch = static_cast<float>(kGlyphHeight) * s;
    std::size_t longest = 0;
    for (const std::string& l : lines)
      longest = std::max(longest, l.size());
    const float width =
        swatch + s * 2.0f + static_cast<float>(longest * kGlyphAdvance) * s + 2.0f * margin;
    const float height = lineHeight * static_cast<float>(lines.size()) + 2.0f * margin - 3.0f * s;
    tris.rect(0, 0, width, height, withAlpha(palette::kBlack, 170));
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const float y = margin + lineHeight * static_cast<float>(i);
      float x = margin;
      if (i > 0) {
        tris.rect(x, y, x + swatch, y + swatch, palette::teamColour(static_cast<int>(i - 1)));
      }
      x += swatch + 2.0f * s;
      addText(x, y, s, lines[i], palette::kWhite);
    }
  }

  // On a dark strip, shrunk to one font pixel a pixel when the line is too long at the HUD's
  // scale.
  void addCaption(const std::string& caption) {
    float s = static_cast<float>(std::max(1, std::min(image.width, image.height) / 256));
    if (static_cast<float>(caption.size() * kGlyphAdvance) * s > static_cast<float>(image.width))
      s = 1.0f;
    const float height = static_cast<float>(kGlyphHeight + 4) * s;
    const float top = static_cast<float>(image.height) - height;
    tris.rect(0, top, static_cast<float>(image.width), static_cast<float>(image.height),
              withAlpha(palette::kBlack, 200));
    addText(2.0f * s, top + 2.0f * s, s, caption, palette::kWhite);
  }

  Status render(const FrameScene& scene) {
    if (Status s = makeCurrent(); !s) return s;
    const Rgba bg = palette::kBackground;
    glClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    // Keep destination alpha at 1 so the image stays opaque under translucent overlays.
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

    if (scene.terrain != nullptr && scene.terrainRevision != terrainRevision) {
      if (scene.terrain->width() != mapWidth || scene.terrain->height() != mapHeight)
        return Error{"", 0, 0, "the scene's terrain is not the size of the renderer's map"};
      terrainTexture = uploadTerrain(terrainTexture, *scene.terrain);
      terrainRevision = scene.terrainRevision;
    }
    const float ppc = enterMapSpace();
    glDisable(GL_BLEND);  // opaque, and the largest area drawn: no need to read the target
    drawTexture(terrainTexture);
    glEnable(GL_BLEND);
    if (def.overlays.clearance && clearanceTexture != 0) drawTexture(clearanceTexture);
    if (def.overlays.abstractGraph) {
      graphLines.draw(GL_LINES);
      graphNodes.draw(GL_TRIANGLES);
    }
    tris.clear();
    if (def.overlays.arrivalZones) addZones(scene, ppc);
    addPaths(scene, ppc);
    addReservations(scene, ppc);
    addUnits(scene, ppc);
    tris.draw(GL_TRIANGLES);

    if (def.overlays.hud || !scene.caption.empty()) {
      enterPixelSpace();
      tris.clear();
      if (def.overlays.hud) addHud(scene);
      if (!scene.caption.empty()) addCaption(scene.caption);
      tris.draw(GL_TRIANGLES);
    }
    glFinish();
    if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
      return Error{"", 0, 0, "OpenGL error " + std::to_string(error) + " while rendering"};
    }
    return Status::success();
  }
};

RenderDef fittedDef(const pathing::GridMap& map, int size) {
  const int longest = std::max({map.width(), map.height(), 1});
  const auto side = [&](int cells) {
    return std::max(1, static_cast<int>(std::lround(static_cast<double>(size) * cells / longest)));
  };
  return RenderDef{.width = side(map.width()), .height = side(map.height())};
}

Result<Overlays> parseOverlays(std::string_view names, Overlays base) {
  static constexpr std::pair<std::string_view, bool Overlays::*> kSwitches[] = {
      {"paths", &Overlays::paths},
      {"footprints", &Overlays::footprints},
      {"reservations", &Overlays::reservations},
      {"clearance", &Overlays::clearance},
      {"graph", &Overlays::abstractGraph},
      {"stuck", &Overlays::stuck},
      {"zones", &Overlays::arrivalZones},
      {"hud", &Overlays::hud}};
  Overlays o = base;
  std::size_t start = 0;
  while (start <= names.size()) {
    const std::size_t comma = std::min(names.find(',', start), names.size());
    const std::string_view name = names.substr(start, comma - start);
    const auto* match = std::find_if(std::begin(kSwitches), std::end(kSwitches),
                                     [&](const auto& entry) { return entry.first == name; });
    if (name.empty()) {
      // "" or a stray comma: nothing to switch
    } else if (name == "none") {
      for (const auto& entry : kSwitches)
        o.*entry.second = false;
    } else if (match != std::end(kSwitches)) {
      o.*match->second = true;
    } else {
      return Error{"", 0, 0,
                   "unknown overlay '" + std::string(name) +
                       "' (expected paths, footprints, reservations, clearance, graph, stuck, "
                       "zones, hud or none)"};
    }
    start = comma + 1;
  }
  return o;
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Result<Renderer> Renderer::create(const pathing::GridMap& map, const RenderDef& def) {
  if (def.width < 1 || def.height < 1 || def.width > kMaxResolution ||
      def.height > kMaxResolution) {
    return Error{"", 0, 0,
                 "resolution " + std::to_string(def.width) + "x" + std::to_string(def.height) +
                     " is outside 1x1..8192x8192"};
  }
  if (map.width() < 1 || map.height() < 1) return Error{"", 0, 0, "the map is empty"};
  if (def.camera) {
    if (Status s = checkCamera(*def.camera, map.width(), map.height()); !s) return s.error();
  }
  auto impl = std::make_unique<Impl>();
  impl->def = def;
  impl->mapWidth = map.width();
  impl->mapHeight = map.height();
  impl->image = Image(def.width, def.height, palette::kBackground);
  // Fixed-function GL 2.1 in a compatibility profile: all this renderer uses, and what Mesa's
  // software rasterisers (llvmpipe, softpipe) provide.
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            2,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            1,
                            0};
  impl->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (impl->context == nullptr) {
    return Error{"", 0, 0, "OSMesa could not create an OpenGL 2.1 compatibility context"};
  }
  if (Status s = impl->makeCurrent(); !s) return s.error();
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  if (map.width() > maxTexture || map.height() > maxTexture) {
    return Error{"", 0, 0,
                 "the " + std::to_string(map.width()) + "x" + std::to_string(map.height()) +
                     " map exceeds the largest texture OSMesa offers (" +
                     std::to_string(maxTexture) + ")"};
  }
  impl->terrainTexture = uploadTerrain(0, map);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    return Error{"", 0, 0,
                 "OpenGL error " + std::to_string(error) + " while uploading the terrain"};
  }
  return Renderer(std::move(impl));
}

int Renderer::width() const {
  return impl_->image.width;
}
int Renderer::height() const {
  return impl_->image.height;
}
const Overlays& Renderer::overlays() const {
  return impl_->def.overlays;
}
void Renderer::setOverlays(const Overlays& overlays) {
  impl_->def.overlays = overlays;
}
const Image& Renderer::image() const {
  return impl_->image;
}
Status Renderer::render(const FrameScene& scene) {
  return impl_->render(scene);
}

Status Renderer::setCamera(std::optional<pathing::CellRect> camera) {
  if (camera) {
    if (Status s = checkCamera(*camera, impl_->mapWidth, impl_->mapHeight); !s) return s;
  }
  impl_->def.camera = camera;
  return Status::success();
}

Status Renderer::setClearance(const pathing::ClearanceField& field) {
  if (field.width() != impl_->mapWidth || field.height() != impl_->mapHeight) {
    return Error{"", 0, 0,
                 "the clearance field is " + std::to_string(field.width()) + "x" +
                     std::to_string(field.height()) + ", the map " +
                     std::to_string(impl_->mapWidth) + "x" + std::to_string(impl_->mapHeight)};
  }
  if (Status s = impl_->makeCurrent(); !s) return s;
  std::vector<Rgba> texels(field.values().size(), Rgba{0, 0, 0, 0});
  for (std::size_t i = 0; i < texels.size(); ++i) {
    const auto v = field.values()[i];
    if (v == 0) continue;
    const std::size_t heat = std::min<std::size_t>(v, palette::kHeat.size()) - 1;
    texels[i] = withAlpha(palette::kHeat[heat], 150);
  }
  impl_->clearanceTexture =
      uploadTexture(impl_->clearanceTexture, field.width(), field.height(), texels);
  return Status::success();
}

Status Renderer::setAbstractGraph(const pathing::ClusterAbstraction& abstraction,
                                  std::optional<pathing::Agent> agent) {
  const pathing::GridMap& map = abstraction.grid().map();
  if (map.width() != impl_->mapWidth || map.height() != impl_->mapHeight) {
    return Error{"", 0, 0,
                 "the abstraction was built on a " + std::to_string(map.width()) + "x" +
                     std::to_string(map.height()) + " map, the renderer's is " +
                     std::to_string(impl_->mapWidth) + "x" + std::to_string(impl_->mapHeight)};
  }
  Batch& edges = impl_->graphLines;
  Batch& nodes = impl_->graphNodes;
  edges.clear();
  nodes.clear();
  for (int c = 0; c < abstraction.clusterCount(); ++c) {
    const CellRect b = abstraction.clusterBounds(c);
    const float x0 = static_cast<float>(b.x), y0 = static_cast<float>(b.y);
    const float x1 = x0 + static_cast<float>(b.width), y1 = y0 + static_cast<float>(b.height);
    edges.line({x0, y0}, {x1, y0}, palette::kClusterBorder);
    edges.line({x0, y0}, {x0, y1}, palette::kClusterBorder);
  }
  const auto centre = [&](std::uint32_t node) {
    const pathing::Cell c = abstraction.nodeCell(node);
    return Point{static_cast<float>(c.x) + 0.5f, static_cast<float>(c.y) + 0.5f};
  };
  for (std::uint32_t n = 0; n < abstraction.nodeCount(); ++n) {
    for (const pathing::AbstractEdge& e : abstraction.edgesOf(n)) {
      if (e.target < n || (agent && !e.usableBy(*agent))) continue;  // each pair once
      edges.line(centre(n), centre(e.target), e.intra ? palette::kIntraEdge : palette::kInterEdge);
    }
  }
  for (std::uint32_t n = 0; n < abstraction.nodeCount(); ++n) {
    const Point p = centre(n);
    nodes.rect(p.x - 0.4f, p.y - 0.4f, p.x + 0.4f, p.y + 0.4f, palette::kGraphNode);
  }
  return Status::success();
}

}  // namespace warpath::render
