// Every binding that changes engine state is all-or-nothing (issue 12 item 5): when memory
// runs out in the middle of w:add (as under rigidlab --max-memory), the engine and the world's
// Lua list must still agree. Before, the engine took the body and then the Lua list failed to
// grow: the world said 5 bodies, #w:bodies() 4, and the retry said "already in this world".
// Each test refuses every allocation from the n-th on during one call, for n = 1, 2, ... until
// the call needs no more, and checks the world afterwards with memory back.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "alloc_injector.hpp"
#include "lua/rigidlab.hpp"

namespace {

std::string run(lua_State* L, const char* code) {
  if (luaL_loadbufferx(L, code, std::strlen(code), "=code", "t") == LUA_OK &&
      lua_pcall(L, 0, 0, 0) == LUA_OK)
    return "";
  const char* message = lua_tostring(L, -1);
  std::string result = message != nullptr ? message : "(not a string)";
  lua_pop(L, 1);
  return result;
}

// Runs `setup`, then `call` with allocations refused from the n-th on, then `check` (with the
// global `succeeded` telling whether the call did) for every n. Returns how many runs failed.
int sweep(const char* setup, const char* call, const char* check) {
  int failures = 0;
  for (long n = 1; n < 100000; ++n) {
    Injector injector;
    lua_State* L = lua_newstate(&Injector::allocate, &injector);
    rigidlab::lua::open_all(L);
    EXPECT_EQ(run(L, setup), "");
    injector.count = 0;
    injector.first_refused = n;
    injector.refuse_one = false;
    const std::string error = run(L, call);
    const bool refused = injector.refused;
    injector.first_refused = -1;
    if (!error.empty()) {
      ++failures;
      EXPECT_NE(error.find("not enough memory"), std::string::npos) << n << ": " << error;
    }
    lua_pushboolean(L, error.empty());
    lua_setglobal(L, "succeeded");
    EXPECT_EQ(run(L, check), "") << "refusing every allocation from the " << n << "-th on";
    lua_close(L);
    if (!refused) return failures;
  }
  ADD_FAILURE() << "the call never ran to its end";
  return failures;
}

// Four bodies fill the list's array part (4 slots): the fifth makes it grow.
const char* const four_bodies = R"(
  w = world{}
  for i = 1, 4 do w:add(body.sphere{mass = 1, radius = 0.5, position = vec3(3 * i, 0, 0)}) end
  f = body.sphere{mass = 1, radius = 0.5, position = vec3(0, 5, 0)}
  function engine_count() return tonumber(tostring(w):match("^world%((%d+) bod")) end
)";

TEST(AllOrNothing, AddUnderMemoryPressure) {
  const int failures = sweep(four_bodies, "w:add(f)", R"(
    local list = w:bodies()
    assert(#list == engine_count(), "Lua list " .. #list .. ", engine " .. engine_count())
    if succeeded then
      assert(#list == 5 and list[5] == f, "added")
    else
      assert(#list == 4, "nothing added")
      w:add(f)  -- the retry works: the body is in no world
      assert(#w:bodies() == 5 and engine_count() == 5 and w:bodies()[5] == f, "retry")
    end
    w:step(0.01)
  )");
  EXPECT_GT(failures, 0) << "no run failed: the test refused nothing inside w:add";
}

TEST(AllOrNothing, RemoveUnderMemoryPressure) {
  sweep(four_bodies, "w:remove(w:bodies()[2])", R"(
    local list = w:bodies()
    assert(#list == engine_count(), "Lua list " .. #list .. ", engine " .. engine_count())
    assert(#list == (succeeded and 3 or 4), "removed or not")
    for i, b in ipairs(list) do assert(tostring(b):find("sphere"), i) end
    w:step(0.01)
  )");
}

TEST(AllOrNothing, AddForceUnderMemoryPressure) {
  const int failures = sweep(R"(
    w = world{}
    w:add(body.sphere{mass = 1, radius = 0.5})
    calls = 0
    for i = 1, 4 do w:add_force(function() calls = calls + 1 end) end
  )", "w:add_force(function() calls = calls + 1 end)", R"(
    calls = 0
    w:step(0.01)  -- semi_implicit: one force evaluation per step
    assert(calls == (succeeded and 5 or 4), "callbacks run: " .. calls)
  )");
  EXPECT_GT(failures, 0) << "no run failed: the test refused nothing inside w:add_force";
}

}  // namespace
