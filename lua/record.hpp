// w:record{every =, bodies =} and the recorder it returns (rec.t, rec:series, rec:csv,
// rec:stop). The recorder core is lua/recorder (no Lua); the world tells it of each completed
// step (World::add_step_observer).
#pragma once

#include <lua.hpp>

#include <vector>

#include "engine/math.hpp"

namespace rigidlab::lua {

// The trails of w:render{show = 'trail'}: the positions the world's newest recorder holds for
// each body it records (at most the last 2,000 samples). Raises an error on argument `arg`
// (the option table) when the world at stack index `world` has no recorder.
std::vector<std::vector<Vec3>> recorded_trails(lua_State* L, int world, int arg);

}  // namespace rigidlab::lua
