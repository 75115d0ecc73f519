#include "rts/replay_support.h"

#include "rts/cli_support.h"

namespace warpath::tools {

engine::Replay readReplayOrThrow(const std::string& file) {
  Result<engine::Replay> replay = engine::readReplay(file);
  if (!replay.ok()) throw BadInput{replay.error().describe()};
  return std::move(replay).value();
}

engine::ReplayPlayback openPlaybackOrThrow(const engine::Replay& replay, const std::string& file) {
  Result<engine::ReplayPlayback> playback = engine::ReplayPlayback::open(replay, file);
  if (!playback.ok()) throw BadInput{playback.error().describe()};
  return std::move(playback).value();
}

}  // namespace warpath::tools
