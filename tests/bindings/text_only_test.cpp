// lua/text_only.cpp: load, loadfile, dofile and require load source only. Binary chunks (as
// string.dump makes them) are refused with a message that says why, mode "b" is an argument
// error, and corrupted binary chunks, which crash Lua's undump, never reach it.
#include "lua/text_only.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "lua_fixture.hpp"

namespace {

class TextOnly : public LuaFixture {
 protected:
  void SetUp() override {
    LuaFixture::SetUp();
    char pattern[] = "/tmp/rigidlab-text-only-XXXXXX";
    dir = mkdtemp(pattern);
    write("text.lua", "return 'text', ...");
    ASSERT_EQ(run("local f = assert(io.open(..., 'wb')) f:write(string.dump(function() return 1 end)) f:close()",
                  dir + "/binary.luac"),
              "");
    lua_pushstring(L, dir.c_str());
    lua_setglobal(L, "dir");
    ASSERT_EQ(run("package.path = dir .. '/?.lua;' .. dir .. '/?.luac'"), "");
  }
  void TearDown() override {
    LuaFixture::TearDown();
    std::system(("rm -rf '" + dir + "'").c_str());
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
  }
  using LuaFixture::run;
  // Runs code with one string argument (its `...`).
  std::string run(const char* code, const std::string& argument) {
    if (luaL_loadbufferx(L, code, std::strlen(code), "=test", "t") != LUA_OK) return "syntax";
    lua_pushstring(L, argument.c_str());
    if (lua_pcall(L, 1, 0, 0) == LUA_OK) return "";
    std::string message = lua_tostring(L, -1);
    lua_pop(L, 1);
    return message;
  }
  std::string dir;
};

constexpr const char* refused = "attempt to load a binary chunk (rigidlab loads text only)";

TEST_F(TextOnly, LoadRefusesBinaryStringsAndReaders) {
  EXPECT_EQ(run("local f, e = load(string.dump(function() end))\n"
                "assert(f == nil and e == ...)",
                refused),
            "");
  // A reader function whose first piece is a binary chunk.
  EXPECT_EQ(run("local d, done = string.dump(function() end), false\n"
                "local f, e = load(function() if done then return nil end done = true return d end)\n"
                "assert(f == nil and e == ...)",
                refused),
            "");
}

TEST_F(TextOnly, LoadRefusesModeB) {
  for (const char* mode : {"b", "bt", "tb", ""}) {
    const std::string code = std::string("load('return 1', 'c', '") + mode + "')";
    EXPECT_EQ(run(code.c_str()), std::string("test:1: bad argument #3 to 'load' (mode must be "
                                             "\"t\": rigidlab loads text only, got \"") +
                                     mode + "\")");
  }
  EXPECT_EQ(run("load('return 1', 'c', {})"),
            "test:1: bad argument #3 to 'load' (string expected, got table)");
}

TEST_F(TextOnly, LoadStillLoadsText) {
  EXPECT_EQ(run("assert(load('return 1 + 1')() == 2)"), "");
  EXPECT_EQ(run("assert(load('return x', 'chunk', 't', {x = 5})() == 5)"), "");
  EXPECT_EQ(run("assert(load('return x', nil, nil, {x = 6})() == 6)"), "");
  EXPECT_EQ(run("local f, e = load('return +', '=c') assert(f == nil and e:find('unexpected'))"), "");
  EXPECT_EQ(run("local parts = {'return ', '4'}\n"
                "assert(load(function() return table.remove(parts, 1) end)() == 4)"),
            "");
}

TEST_F(TextOnly, LoadfileAndDofile) {
  EXPECT_EQ(run("local f, e = loadfile(dir .. '/binary.luac') assert(f == nil and e == ...)",
                dir + "/binary.luac: " + refused),
            "");
  EXPECT_EQ(run("loadfile(dir .. '/text.lua', 'b')"),
            "test:1: bad argument #2 to 'loadfile' (mode must be \"t\": rigidlab loads text "
            "only, got \"b\")");
  EXPECT_EQ(run("assert(loadfile(dir .. '/text.lua', 't', {})() == 'text')"), "");
  EXPECT_EQ(run("assert(dofile(dir .. '/text.lua') == 'text')"), "");
  EXPECT_EQ(run("dofile(dir .. '/binary.luac')"), dir + "/binary.luac: " + refused);
}

TEST_F(TextOnly, RequireLoadsTextModulesOnly) {
  EXPECT_EQ(run("local v, file = require('text') assert(v == 'text' and file:find('text.lua'))"), "");
  const std::string error = run("require('binary')");
  EXPECT_NE(error.find("error loading module 'binary' from file '" + dir + "/binary.luac':"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find(refused), std::string::npos) << error;
  EXPECT_NE(run("require('absent')").find("no file '" + dir + "/absent.lua'"), std::string::npos);
}

// The audit's crash: mutated string.dump output given to load. Nothing reaches undump.
TEST_F(TextOnly, CorruptedBinaryChunksAreRefusedNotRun) {
  EXPECT_EQ(run("local d = string.dump(function(a, b) local t = {a, b} return t[1] + t[2] * 3 end)\n"
                "math.randomseed(7)\n"
                "for i = 1, 2000 do\n"
                "  local bytes = {d:byte(1, -1)}\n"
                "  for k = 1, 3 do local p = math.random(20, #bytes) bytes[p] = math.random(0, 255) end\n"
                "  local f, e = load(string.char(table.unpack(bytes)))\n"
                "  assert(f == nil and e:find('binary chunk'))\n"
                "  assert(not pcall(load, string.char(table.unpack(bytes)), 'x', 'b'))\n"
                "end"),
            "");
}

}  // namespace
