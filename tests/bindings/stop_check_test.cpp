// The stop check (lua/binding.hpp): a StopPoller polls the embedding program's check from a C
// loop, and w:step polls it inside the engine's loops, so even one huge step stops, undone.
#include <string>

#include "lua/binding.hpp"
#include "lua_fixture.hpp"

namespace {

int long_loop(lua_State* L) {
  const rigidlab::lua::StopPoller stop(L);
  for (long i = 0; i < 1'000'000'000L; ++i) stop.poll();
  return 0;
}

// Raises "stopped!" at the check's `data`-th call.
void stop_at_call(lua_State* L, void* data) {
  int& countdown = *static_cast<int*>(data);
  if (--countdown == 0) luaL_error(L, "stopped!");
}

using StopCheck = LuaFixture;

TEST_F(StopCheck, WithoutACheckNothingHappens) {
  const rigidlab::lua::StopPoller stop(L);
  EXPECT_NO_THROW(stop.poll());
}

TEST_F(StopCheck, RaisesALuaErrorFromInsideACLoop) {
  int countdown = 1000;
  rigidlab::lua::set_stop_check(L, stop_at_call, &countdown);
  lua_pushcfunction(L, long_loop);
  ASSERT_EQ(lua_pcall(L, 0, 0, 0), LUA_ERRRUN);
  EXPECT_EQ(std::string(lua_tostring(L, -1)), "stopped!");
  EXPECT_EQ(countdown, 0);
}

// One step of 10000 substeps with 1000 solver sweeps over a grid of boxes would run for hours:
// the check stops it in the middle, and the world is as it was.
TEST_F(StopCheck, StopsOneHugeStepOfTheWorldAndUndoesIt) {
  ASSERT_EQ(run("w = world{}\n"
                "w:add_plane{normal = vec3(0, 1, 0), offset = 0}\n"
                "for i = 0, 99 do\n"
                "  w:add(body.box{mass = 1, size = vec3(1, 1, 1),\n"
                "                 position = vec3(i % 10 * 1.01, 0.5 + i // 10, 0)})\n"
                "end\n"
                "w:step(0.01)\n"
                "w.substeps, w.iterations = 10000, 1000\n"
                "t0, p0, v0 = w.time, w:bodies()[50].position, w:bodies()[50].velocity"),
            "");
  int countdown = 200;
  rigidlab::lua::set_stop_check(L, stop_at_call, &countdown);
  EXPECT_EQ(run("w:step(0.01)"), "test:1: stopped!");
  EXPECT_EQ(countdown, 0);
  EXPECT_EQ(run("local b = w:bodies()[50]\n"
                "assert(w.time == t0 and b.position == p0 and b.velocity == v0)\n"
                "w.substeps = 1; w:step(0.01)\n"
                "assert(w.time == t0 + 0.01 and b.position ~= p0)"),
            "");
}

}  // namespace
