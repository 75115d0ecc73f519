#include "view/viewer.h"

#include <SDL.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "render/palette.h"
#include "render/png_io.h"
#include "render/renderer.h"
#include "render/world_scene.h"

namespace warpath::view {
namespace {

struct SdlSession {
  SdlSession() : ok(SDL_Init(SDL_INIT_VIDEO) == 0) {}
  ~SdlSession() { SDL_Quit(); }
  SdlSession(const SdlSession&) = delete;
  SdlSession& operator=(const SdlSession&) = delete;
  bool ok;
};

struct WindowDeleter {
  void operator()(SDL_Window* w) const { SDL_DestroyWindow(w); }
};
struct RendererDeleter {
  void operator()(SDL_Renderer* r) const { SDL_DestroyRenderer(r); }
};
struct TextureDeleter {
  void operator()(SDL_Texture* t) const { SDL_DestroyTexture(t); }
};

Status sdlFailure(const std::string& what) {
  return Error{"", 0, 0, what + ": " + SDL_GetError()};
}

std::string mismatchText(const engine::HashMismatch& m) {
  char text[160];
  std::snprintf(text, sizeof text,
                "tick %" PRId64 ": state hash differs: expected %016" PRIx64 ", actual %016" PRIx64,
                m.tick, m.expected, m.actual);
  return text;
}

// The overlays keys 1-7 switch, in order.
constexpr std::array<bool render::Overlays::*, 7> kOverlayKeys = {
    &render::Overlays::paths,        &render::Overlays::footprints, &render::Overlays::stuck,
    &render::Overlays::arrivalZones, &render::Overlays::hud,        &render::Overlays::clearance,
    &render::Overlays::reservations};

constexpr double kMinSpeed = 1.0 / 16.0;
constexpr double kMaxSpeed = 64.0;
constexpr double kJumpSeconds = 10.0;  // shift+arrow

// What the keys change, and the re-simulation they ask for.
class Session {
 public:
  Session(engine::ReplayPlayback& playback, render::Renderer& renderer, const ViewerDef& def)
      : playback_(playback), renderer_(renderer), speed_(def.speed), playing_(!def.paused) {}

  const engine::World& world() const { return playback_.run().world(); }
  bool playing() const { return playing_; }
  bool quit() const { return quit_; }
  const Status& failure() const { return failure_; }

  // Moves to `target` (clamped to the replay), re-simulating from tick 0 to go back.
  void seek(std::int64_t target) {
    target = std::clamp<std::int64_t>(target, 0, playback_.replay().lastTick());
    if (target < world().tick()) playback_.restart();
    while (world().tick() < target && failure_.ok()) {
      if (const auto m = playback_.step()) failure_ = Error{"", 0, 0, mismatchText(*m)};
    }
  }

  // Plays `wallSeconds` of time at the current speed; pauses at the end.
  void advance(double wallSeconds) {
    if (!playing_) return;
    budget_ += wallSeconds * world().tickRate() * speed_;
    // At most a second of simulation a frame, so a slow frame does not snowball.
    budget_ = std::min(budget_, world().tickRate() * std::max(speed_, 1.0));
    const auto ticks = static_cast<std::int64_t>(budget_);
    budget_ -= static_cast<double>(ticks);
    seek(world().tick() + ticks);
    if (playback_.done()) playing_ = false;
  }

  void key(const SDL_Keysym& k) {
    const bool shift = (k.mod & KMOD_SHIFT) != 0;
    const auto jump = static_cast<std::int64_t>(std::llround(kJumpSeconds * world().tickRate()));
    switch (k.sym) {
      case SDLK_SPACE:
        playing_ = !playing_ && !playback_.done();
        budget_ = 0.0;
        break;
      case SDLK_RIGHT:
      case SDLK_PERIOD:
        playing_ = playing_ && shift;
        seek(world().tick() + (shift ? jump : 1));
        break;
      case SDLK_LEFT:
        playing_ = playing_ && shift;
        seek(world().tick() - (shift ? jump : 1));
        break;
      case SDLK_HOME:
        seek(0);
        break;
      case SDLK_END:
        seek(playback_.replay().lastTick());
        break;
      case SDLK_PLUS:
      case SDLK_EQUALS:
      case SDLK_KP_PLUS:
        speed_ = std::min(speed_ * 2.0, kMaxSpeed);
        break;
      case SDLK_MINUS:
      case SDLK_KP_MINUS:
        speed_ = std::max(speed_ / 2.0, kMinSpeed);
        break;
      case SDLK_c:
        showType_ = (showType_ + 1) % playback_.scenario().catalogue.size();
        showType(showType_);
        break;
      case SDLK_h:
        help_ = !help_;
        break;
      case SDLK_q:
      case SDLK_ESCAPE:
        quit_ = true;
        break;
      default:
        if (k.sym >= SDLK_1 && k.sym < SDLK_1 + static_cast<int>(kOverlayKeys.size())) {
          render::Overlays o = renderer_.overlays();
          bool& on = o.*kOverlayKeys[static_cast<std::size_t>(k.sym - SDLK_1)];
          on = !on;
          renderer_.setOverlays(o);
        }
    }
  }

  // The clearance heat map and the graph again (a renderer made for a new window size).
  void refresh() { showType(showType_); }

  // The clearance heat map shows where units of catalogue type `type` may stand, the graph
  // the edges they may use.
  void showType(std::size_t type) {
    const units::UnitType& t = playback_.scenario().catalogue[type];
    if (Status s = renderer_.setClearance(world().grid().clearance(t.capability)); !s) failure_ = s;
    if (const pathing::ClusterAbstraction* graph = world().pathService().abstraction()) {
      if (Status s = renderer_.setAbstractGraph(*graph, t.agent()); !s) failure_ = s;
    }
  }

  std::string status() const {
    char text[96];
    std::snprintf(text, sizeof text, "%s  tick %" PRId64 "/%" PRId64 "  x%g",
                  playing_ ? "playing" : "paused", world().tick(), playback_.replay().lastTick(),
                  speed_);
    return text;
  }

  std::string caption() const {
    if (!help_) return {};
    return "SPACE PLAY  ./RIGHT STEP  LEFT BACK  SHIFT 10S  HOME END  +- SPEED  1-7 OVERLAYS  "
           "C TYPE  H HELP  Q QUIT";
  }

 private:
  engine::ReplayPlayback& playback_;
  render::Renderer& renderer_;
  double speed_;
  bool playing_;
  double budget_ = 0.0;  // [Unit: ticks] owed to playback, fractional
  bool help_ = true;
  bool quit_ = false;
  std::size_t showType_ = 0;  // the catalogue type clearance and graph are shown for
  Status failure_ = Status::success();
};

// One frame's scripted input: a key, or a new window size.
struct ScriptStep {
  SDL_Keysym key{};
  int width = 0;  // > 0: resize the window to width x height instead
  int height = 0;
};

// The steps `names` stand for, or a failure naming the first unknown key.
Status scriptedSteps(const std::vector<std::string>& names, std::vector<ScriptStep>& steps) {
  constexpr std::string_view kShift = "shift+";
  constexpr std::string_view kWindow = "window=";
  for (const std::string& name : names) {
    ScriptStep step;
    SDL_Keysym& k = step.key;
    std::string key = name;
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower.starts_with(kWindow)) {
      const auto size = parseWindowSize(std::string_view(name).substr(kWindow.size()));
      if (!size) return Error{"", 0, 0, "'" + name + "': the size must be WxH, each 16..8192"};
      step.width = size->first;
      step.height = size->second;
      steps.push_back(step);
      continue;
    }
    if (lower.starts_with(kShift) && name.size() > kShift.size()) {
      k.mod = KMOD_LSHIFT;
      key = name.substr(kShift.size());
    }
    k.sym = SDL_GetKeyFromName(key.c_str());
    if (k.sym == SDLK_UNKNOWN) return Error{"", 0, 0, "unknown key '" + name + "'"};
    steps.push_back(step);
  }
  return Status::success();
}

// The largest rectangle of the map's shape that fits a `width` x `height` window, centred.
SDL_Rect fitted(const pathing::GridMap& map, int width, int height) {
  const double scale = std::min(static_cast<double>(width) / std::max(map.width(), 1),
                                static_cast<double>(height) / std::max(map.height(), 1));
  SDL_Rect r;
  r.w = std::clamp(static_cast<int>(std::lround(map.width() * scale)), 1, 8192);
  r.h = std::clamp(static_cast<int>(std::lround(map.height() * scale)), 1, 8192);
  r.x = (width - r.w) / 2;
  r.y = (height - r.h) / 2;
  return r;
}

// The window's pixels as the last frame left them.
Status writeScreenshot(SDL_Renderer* sdl, const std::string& file) {
  int w = 0;
  int h = 0;
  if (SDL_GetRendererOutputSize(sdl, &w, &h) != 0) return sdlFailure("cannot read the window size");
  render::Image shot(w, h);
  if (SDL_RenderReadPixels(sdl, nullptr, SDL_PIXELFORMAT_RGBA32, shot.pixels.data(), w * 4) != 0)
    return sdlFailure("cannot read the window's pixels");
  return render::writePng(file, shot);
}

}  // namespace

std::optional<std::pair<int, int>> parseWindowSize(std::string_view text) {
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string_view::npos) return std::nullopt;
  const auto side = [](std::string_view digits) -> std::optional<int> {
    int v = 0;
    if (digits.empty() || digits.size() > 4) return std::nullopt;
    for (const char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + (c - '0');
    }
    if (v < 16 || v > 8192) return std::nullopt;
    return v;
  };
  const auto w = side(text.substr(0, x));
  const auto h = side(text.substr(x + 1));
  if (!w || !h) return std::nullopt;
  return std::pair{*w, *h};
}

Status runViewer(engine::ReplayPlayback& playback, const ViewerDef& def) {
  if (def.size < 16 || def.size > 8192) return Error{"", 0, 0, "size must be 16..8192"};
  if (!(def.speed > 0.0)) return Error{"", 0, 0, "speed must be positive"};
  const bool customWindow = def.windowWidth != 0 || def.windowHeight != 0;
  if (customWindow && (std::min(def.windowWidth, def.windowHeight) < 16 ||
                       std::max(def.windowWidth, def.windowHeight) > 8192))
    return Error{"", 0, 0, "window size must be 16..8192 pixels each way"};
  const engine::Scenario& scenario = playback.scenario();
  const pathing::GridMap& map = scenario.grid->map();
  const render::RenderDef initial = render::fittedDef(map, def.size);
  const int windowWidth = customWindow ? def.windowWidth : initial.width;
  const int windowHeight = customWindow ? def.windowHeight : initial.height;
  SDL_Rect view = fitted(map, windowWidth, windowHeight);
  auto created = render::Renderer::create(map, {.width = view.w, .height = view.h});
  if (!created) return created.error();
  render::Renderer renderer = std::move(created).value();

  // No GL anywhere in SDL: a GL context of its own (an OpenGL renderer, or the GL texture SDL
  // puts behind a software renderer's window surface) would leave OSMesa's draws failing.
  SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
  SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
  const SdlSession sdl;
  if (!sdl.ok) return sdlFailure("cannot start SDL video");
  const std::unique_ptr<SDL_Window, WindowDeleter> window(
      SDL_CreateWindow("warpath", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, windowWidth,
                       windowHeight, SDL_WINDOW_SHOWN | SDL_WINDOW_RESIZABLE));
  if (!window) return sdlFailure("cannot open a window");
  // Copying one image a frame needs no GPU.
  const std::unique_ptr<SDL_Renderer, RendererDeleter> sdlRenderer(
      SDL_CreateRenderer(window.get(), -1, SDL_RENDERER_SOFTWARE));
  if (!sdlRenderer) return sdlFailure("cannot create an SDL renderer");
  const auto makeTexture = [&](int w, int h) {
    return std::unique_ptr<SDL_Texture, TextureDeleter>(SDL_CreateTexture(
        sdlRenderer.get(), SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, w, h));
  };
  std::unique_ptr<SDL_Texture, TextureDeleter> texture = makeTexture(view.w, view.h);
  if (!texture) return sdlFailure("cannot create a texture");

  std::vector<ScriptStep> script;
  if (Status s = scriptedSteps(def.keys, script); !s) return s;
  Session session(playback, renderer, def);
  session.showType(0);
  const int teams = static_cast<int>(scenario.teams.size());
  constexpr double kFrameSeconds = 1.0 / 60.0;
  std::uint64_t last = SDL_GetTicks64();
  for (int frame = 0; def.framesThenExit <= 0 || frame < def.framesThenExit; ++frame) {
    if (static_cast<std::size_t>(frame) < script.size()) {
      const ScriptStep& step = script[static_cast<std::size_t>(frame)];
      if (step.width > 0) {
        SDL_SetWindowSize(window.get(), step.width, step.height);
      } else {
        SDL_Event typed{};
        typed.type = SDL_KEYDOWN;
        typed.key.keysym = step.key;
        SDL_PushEvent(&typed);
      }
    }
    SDL_Event event;
    while (SDL_PollEvent(&event) != 0) {
      if (event.type == SDL_QUIT) return Status::success();
      if (event.type == SDL_KEYDOWN) session.key(event.key.keysym);
    }
    if (session.quit()) break;
    // A test run (framesThenExit) plays at a fixed 60 frames a second of simulated wall time,
    // so what it draws does not depend on the machine's speed.
    const std::uint64_t now = SDL_GetTicks64();
    session.advance(def.framesThenExit > 0 ? kFrameSeconds
                                           : static_cast<double>(now - last) / 1000.0);
    last = now;
    if (!session.failure().ok()) return session.failure();

    // A resized window gets a renderer of its own size, so the map stays sharp.
    int outW = 0;
    int outH = 0;
    if (SDL_GetRendererOutputSize(sdlRenderer.get(), &outW, &outH) != 0)
      return sdlFailure("cannot read the window size");
    const SDL_Rect wanted = fitted(map, std::max(outW, 1), std::max(outH, 1));
    if (wanted.w != view.w || wanted.h != view.h) {
      auto resized = render::Renderer::create(map, {.width = wanted.w, .height = wanted.h});
      if (!resized) return resized.error();
      resized.value().setOverlays(renderer.overlays());
      renderer = std::move(resized).value();
      session.refresh();
      texture = makeTexture(wanted.w, wanted.h);
      if (!texture) return sdlFailure("cannot create a texture");
    }
    view = wanted;

    render::FrameScene scene = render::sceneOf(session.world(), teams);
    scene.caption = session.caption();
    if (Status s = renderer.render(scene); !s) return s;
    const render::Image& image = renderer.image();
    if (SDL_UpdateTexture(texture.get(), nullptr, image.pixels.data(), image.width * 4) != 0)
      return sdlFailure("cannot update the texture");
    constexpr render::Rgba kEdge = render::palette::kBackground;
    SDL_SetRenderDrawColor(sdlRenderer.get(), kEdge.r, kEdge.g, kEdge.b, 255);
    SDL_RenderClear(sdlRenderer.get());
    SDL_RenderCopy(sdlRenderer.get(), texture.get(), nullptr, &view);
    const bool lastFrame = def.framesThenExit > 0 && frame + 1 == def.framesThenExit;
    if (lastFrame && !def.screenshot.empty()) {
      if (Status s = writeScreenshot(sdlRenderer.get(), def.screenshot); !s) return s;
    }
    SDL_RenderPresent(sdlRenderer.get());
    SDL_SetWindowTitle(window.get(), ("warpath  " + session.status()).c_str());
    if (def.framesThenExit <= 0 && !session.playing()) SDL_Delay(15);  // idle: spare the CPU
  }
  return Status::success();
}

}  // namespace warpath::view
