// The live view's history (lua/view_subject.hpp) driven without a terminal, as lua/view.cpp
// drives it: a step through w:step then stepped(), ← as back(), → as forward() and, past the
// newest state, a step. After a rewind, going forward restores the saved states: the motion is
// the same bit for bit, the force callback is not called again for the replayed steps, and a
// recorder attached to the world holds each step once, its times increasing.
#include <cmath>
#include <memory>
#include <string>

#include "lua/view_subject.hpp"
#include "lua_fixture.hpp"

namespace {

using rigidlab::lua::ViewSubject;

struct Drive {
  std::unique_ptr<ViewSubject> subject;
  std::string note;
};

void lua_step(lua_State* L) {  // what lua/view.cpp's step() does past the history's end
  lua_getfield(L, 1, "step");
  lua_pushvalue(L, 1);
  lua_pushnumber(L, 1.0 / 60);
  lua_call(L, 2, 0);
}

// The world is at index 1, the Drive a light userdata upvalue; the argument 2 is the action.
int act(lua_State* L) {
  Drive& d = *static_cast<Drive*>(lua_touserdata(L, lua_upvalueindex(1)));
  const std::string action = luaL_checkstring(L, 2);
  if (action == "open") d.subject = rigidlab::lua::world_subject(L);
  if (action == "open articulation") d.subject = rigidlab::lua::articulation_subject(L);
  if (action == "step") {
    if (!d.subject->forward(L, d.note)) {
      lua_step(L);
      d.subject->stepped(L);
    }
  }
  if (action == "back") lua_pushboolean(L, d.subject->back(L, d.note));
  if (action == "forward") lua_pushboolean(L, d.subject->forward(L, d.note));
  return action == "back" || action == "forward" ? 1 : 0;
}

class ViewHistory : public LuaFixture {
 protected:
  void SetUp() override {
    LuaFixture::SetUp();
    lua_pushlightuserdata(L, &drive_);
    lua_pushcclosure(L, act, 1);
    lua_setglobal(L, "act");
  }
  void TearDown() override {
    drive_.subject.reset();
    LuaFixture::TearDown();
  }
  Drive drive_;
};

TEST_F(ViewHistory, ForwardAfterRewindRestoresWithoutRunningCallbacksOrRecordingTwice) {
  ASSERT_EQ(run(R"lua(
    w = world{gravity = vec3(0, -9.81, 0)}
    b = w:add(body.box{mass = 1, size = vec3(0.5, 0.15, 1), angular_velocity = vec3(4, 0.05, 0.05)})
    calls = 0
    w:add_force(function() calls = calls + 1 end)
    rec = w:record{}
    act(w, "open")
    for _ = 1, 20 do act(w, "step") end
    calls_at_20, pos_at_20 = calls, b.position
    for k = 1, 5 do assert(act(w, "back"), "back " .. k) end
    assert(math.abs(w.time - 15 / 60) < 1e-12, "rewound to step 15, at t = " .. w.time)
    for k = 1, 5 do act(w, "step") end
    assert(calls == calls_at_20, "the callback ran again: " .. calls .. " calls, not " .. calls_at_20)
    assert(b.position == pos_at_20, "the replay is the state seen, bit for bit")
    assert(not act(w, "forward"), "no state after the newest")
    for _ = 1, 3 do act(w, "step") end
    assert(calls > calls_at_20, "past the history the world steps")
    local t = rec:series("t")
    assert(#t == 24, #t .. " samples, not 24 (the start and 23 steps)")
    for i = 2, #t do assert(t[i] > t[i - 1], "times increase: " .. t[i - 1] .. ", " .. t[i]) end
    assert(math.abs(t[#t] - 23 / 60) < 1e-12)
  )lua"), "");
}

TEST_F(ViewHistory, SteppingOnFromARewoundStateDropsTheRecordedFuture) {
  // The view quit while rewound leaves the world at the state shown; steps from there are a
  // new future, and the recording drops the old one (every = 2: samples at steps 0, 2, 4, ...).
  ASSERT_EQ(run(R"lua(
    w = world{gravity = vec3(0, 0, 0)}
    b = w:add(body.sphere{mass = 1, radius = 0.1, velocity = vec3(1, 0, 0)})
    rec = w:record{every = 2}
    act(w, "open")
    for _ = 1, 10 do act(w, "step") end
    for _ = 1, 4 do act(w, "back") end
    w:add_force(function(world) b:apply_force(vec3(0, 1, 0)) end)  -- a different future
    for _ = 1, 4 do w:step(1 / 60) end
    local t, y = rec:series("t"), rec:series("position", 1)
    for i = 2, #t do assert(t[i] > t[i - 1], "times increase: " .. t[i - 1] .. ", " .. t[i]) end
    local want = {0, 2, 4, 6, 8, 10}  -- steps 0 to 6 kept, then every 2 steps from step 6
    assert(#t == #want, "samples at " .. table.concat(t, " "))
    for i, s in ipairs(want) do assert(math.abs(t[i] - s / 60) < 1e-12, "sample " .. i) end
    assert(y[#y].y > 0, "the last sample is of the new future")
  )lua"), "");
}

TEST_F(ViewHistory, AnArticulationRewindsAndReplaysExactly) {
  ASSERT_EQ(run(R"lua(
    a = articulation{integrator = "rk4"}
    local first = a:add_link{joint = "revolute", axis = vec3(0, 0, 1), mass = 1, com = vec3(1, 0, 0)}
    a:add_link{parent = first, joint = "revolute", axis = vec3(0, 0, 1),
               origin = vec3(1, 0, 0), mass = 1, com = vec3(1, 0, 0)}
    calls = 0
    a:add_control(function() calls = calls + 1; return {0.5, 0} end)
    rec = a:record{}
    act(a, "open articulation")
    local q = {}
    for k = 1, 20 do act(a, "step"); q[k] = a.q end
    local calls_at_20 = calls
    for k = 1, 5 do assert(act(a, "back"), "back " .. k) end
    assert(a.q[1] == q[15][1] and a.q[2] == q[15][2], "five back is the state of step 15")
    assert(math.abs(a.time - 15 / 60) < 1e-12, "at t = " .. a.time)
    for _ = 1, 5 do act(a, "step") end
    assert(a.q[1] == q[20][1] and a.q[2] == q[20][2], "and forward again the state of step 20")
    assert(calls == calls_at_20, "the control ran again for the replayed steps")
    act(a, "step")
    assert(calls == calls_at_20 + 4, "past the history: one rk4 step, four control calls")
    local t = rec:series("t")
    assert(#t == 22, #t .. " samples, not 22")
    for i = 2, #t do assert(t[i] > t[i - 1], "times increase") end
  )lua"), "");
}

}  // namespace
