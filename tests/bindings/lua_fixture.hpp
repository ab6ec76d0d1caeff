// The fixture of the binding tests: a Lua state opened as the CLI opens it (open_all), and
// run(code), which returns "" or the error message.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "lua/rigidlab.hpp"

class LuaFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    L = luaL_newstate();
    rigidlab::lua::open_all(L);
  }
  void TearDown() override { lua_close(L); }
  // Runs code as the chunk "=test"; returns "" on success or the error message.
  std::string run(const char* code) {
    if (luaL_loadbufferx(L, code, std::strlen(code), "=test", "t") != LUA_OK ||
        lua_pcall(L, 0, 0, 0) != LUA_OK) {
      const char* message = lua_tostring(L, -1);
      std::string result = message != nullptr ? message : "(not a string)";
      lua_pop(L, 1);
      return result;
    }
    return "";
  }
  lua_State* L = nullptr;
};
