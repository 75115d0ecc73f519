#pragma once
// What `rts replay` and `rts view` share: reading a replay and starting its playback, with
// problems thrown as BadInput ("FILE: problem", exit 2).

#include <string>

#include "engine/replay.h"

namespace warpath::tools {

engine::Replay readReplayOrThrow(const std::string& file);
// `replay` must outlive the playback.
engine::ReplayPlayback openPlaybackOrThrow(const engine::Replay& replay, const std::string& file);

}  // namespace warpath::tools
