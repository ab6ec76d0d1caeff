// check_stop lets a long C loop be interrupted by the embedding program's StopCheck.
#include <gtest/gtest.h>

#include <string>

#include "lua/binding.hpp"
#include "lua/rigidlab.hpp"

namespace {

int long_loop(lua_State* L) {
  for (long i = 0; i < 1'000'000'000L; ++i) rigidlab::lua::check_stop(L);
  return 0;
}

TEST(StopCheck, WithoutACheckNothingHappens) {
  lua_State* L = luaL_newstate();
  EXPECT_NO_THROW(rigidlab::lua::check_stop(L));
  lua_close(L);
}

TEST(StopCheck, RaisesALuaErrorFromInsideACLoop) {
  lua_State* L = luaL_newstate();
  rigidlab::lua::open_all(L);
  int calls = 0;
  rigidlab::lua::set_stop_check(
      L,
      [](lua_State* L, void* data) {
        if (++*static_cast<int*>(data) == 1000) luaL_error(L, "interrupted!");
      },
      &calls);
  lua_pushcfunction(L, long_loop);
  ASSERT_EQ(lua_pcall(L, 0, 0, 0), LUA_ERRRUN);
  EXPECT_EQ(std::string(lua_tostring(L, -1)), "interrupted!");
  EXPECT_EQ(calls, 1000);
  lua_close(L);
}

}  // namespace
