// Memory exhaustion anywhere is a clean Lua error: a script of representative API calls runs
// with an allocator that refuses the N-th allocation, for every N from 1 to the number the
// script makes (and again refusing every allocation from the N-th on), in the libraries'
// opening too. Each run must end either normally or with "not enough memory", never a crash
// (the sanitizer build runs this under ASan), and the state must stay usable afterwards. This
// is what rigidlab --max-memory relies on: its allocator (cli/limits.cpp) returns NULL past
// the cap in the same way.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "alloc_injector.hpp"
#include "lua/rigidlab.hpp"

namespace {

// Every kind of object and call: worlds with contacts, springs, drag and a Lua force, removal
// and collection, the math types, inertia, motion, ode, collide, lesson, csv.
const char* const script = R"(
local csv_path = ...
local w = world{integrator = "rk4", iterations = 20}
w:add_plane{normal = vec3(0, 1, 0), offset = 0}
local bs = {}
for i = 1, 8 do
  bs[i] = w:add(body.sphere{mass = 1, radius = 0.3, position = vec3(i * 0.5, 1 + i * 0.1, 0)})
end
local bx = w:add(body.box{mass = 2, size = vec3(1, 1, 1), position = vec3(0, 3, 0)})
w:add_force(function(wd, t) bx:apply_force(vec3(0, 1, 0)) end)
w:add_spring{a = bs[1], b = bs[2], k = 10}
w:add_drag{body = bs[3], linear = 0.1}
w:step(0.01, 20)
local c, p = w:contacts(), w:planes()
w:remove(bs[4])
collectgarbage()
local semi = world{substeps = 3}
semi:add(body.box{mass = 1, size = vec3(1, 2, 3), angular_velocity = vec3(1, 2, 3)})
semi:step(0.01, 5)
local m = mat3(2, 1, 0, 1, 3, 0, 0, 0, 4)
local values, axes = m:eigen()
local inv, t = m:inverse(), tostring(m * values)
local mass, com, I = inertia.mesh({vec3(), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)},
                                  {{1, 3, 2}, {1, 2, 4}, {1, 4, 3}, {2, 3, 4}})
inertia.composite({{mass = 1, com = vec3(), inertia = mat3.identity()},
                   {mass = 2, com = vec3(1, 0, 0), inertia = inertia.solid_sphere(2, 1)}})
inertia.points({{mass = 1, pos = vec3(1, 0, 0)}, {mass = 2, pos = vec3(0, 1, 0)}})
motion.simulate{method = "rk4", accel = function(t, x, v) return -x end, x0 = 1, v0 = 0,
                dt = 0.1, steps = 20}
ode.step("rk4", function(t, y) return {-y[1], y[1]} end, 0, {1, 0}, 0.1)
collide.resolve(bs[5], bs[6], {point = vec3(), normal = vec3(0, 1, 0), restitution = 0.5})
collide.impulse_1d(1, 2, 3, -1, 0.5)
for i = 1, 50 do
  local q = quat.axis_angle(vec3(1, 2, 3), i) * quat(1, 0, 0, 0)
  local v = q:rotate(vec3(1, 0, 0)) + vec3(1, 1, 1)
  local s = tostring(q) .. tostring(v)
end
local l = lesson{id = "x", title = "t", source = "s",
                 steps = {{title = "a", text = "b", run = function() end}}}
csv.write(csv_path, {x = {1, 2}, y = {3, 4}}, {"x", "y"})
local ok2, e = pcall(body, {mass = -1, inertia = mat3.identity()})
string.rep("x", 1000):gsub("x", "y")
)";

class AllocationFailure : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/rigidlab-alloc-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir = pattern;
  }
  void TearDown() override {
    std::remove((dir + "/out.csv").c_str());
    rmdir(dir.c_str());
  }

  // Opens the libraries and runs the script, all in protected mode; returns "" or the error.
  // `opened`: the libraries opened.
  std::string run(lua_State* L) {
    lua_pushcfunction(L, [](lua_State* L) {
      auto& self = *static_cast<AllocationFailure*>(lua_touserdata(L, 1));
      rigidlab::lua::open_all(L);
      self.opened = true;
      if (luaL_loadbufferx(L, script, std::strlen(script), "=script", "t") != LUA_OK)
        return lua_error(L);
      lua_pushstring(L, (self.dir + "/out.csv").c_str());
      lua_call(L, 1, 0);
      return 0;
    });
    lua_pushlightuserdata(L, this);
    opened = false;
    if (lua_pcall(L, 1, 0, 0) == LUA_OK) return "";
    const char* message = lua_tostring(L, -1);
    std::string result = message != nullptr ? message : "(not a string)";
    lua_pop(L, 1);
    return result.empty() ? "(empty message)" : result;
  }

  // After a refused allocation the state still works once memory is back.
  static bool still_usable(lua_State* L, Injector& injector) {
    injector.first_refused = -1;
    const char* code = "collectgarbage() local w = world{} w:add(body.sphere{mass = 1, radius = 1})"
                       " w:step(0.01) return vec3(1, 2, 3):cross(vec3(0, 0, 1)).x";
    if (luaL_loadbufferx(L, code, std::strlen(code), "=after", "t") != LUA_OK ||
        lua_pcall(L, 0, 1, 0) != LUA_OK)
      return false;
    return lua_tonumber(L, -1) == 2.0;
  }

  // Runs the script refusing allocation N (one, or all from N on) for N = 1, 2, ... until a
  // run refuses nothing. Returns how many runs ended in an error.
  long sweep(bool refuse_one) {
    long errors = 0;
    for (long n = 1;; ++n) {
      Injector injector;
      injector.first_refused = n;
      injector.refuse_one = refuse_one;
      lua_State* L = lua_newstate(&Injector::allocate, &injector);
      if (L == nullptr) continue;  // refused while creating the state: NULL, not a crash
      const std::string error = run(L);
      if (!error.empty()) {
        ++errors;
        EXPECT_NE(error.find("not enough memory"), std::string::npos)
            << "refusing allocation " << n << (refuse_one ? "" : " on") << ": " << error;
      }
      if (injector.refused && opened)
        EXPECT_TRUE(still_usable(L, injector)) << "after refusing allocation " << n;
      lua_close(L);
      if (!injector.refused) {
        EXPECT_GT(n, 1000) << "the script makes too few allocations to mean much";
        return errors;
      }
    }
  }

  std::string dir;
  bool opened = false;
};

TEST_F(AllocationFailure, TheScriptRunsWithoutInjection) {
  Injector injector;
  lua_State* L = lua_newstate(&Injector::allocate, &injector);
  EXPECT_EQ(run(L), "");
  lua_close(L);
  EXPECT_GT(injector.count, 1000);
}

// One refusal: Lua collects garbage and tries again, so most runs succeed; none may crash.
TEST_F(AllocationFailure, OneRefusedAllocationAnywhere) { sweep(true); }

// Every allocation from the N-th on refused: each run that reaches N ends in the error.
TEST_F(AllocationFailure, MemoryRunningOutAnywhere) {
  const long errors = sweep(false);
  EXPECT_GT(errors, 1000);
}

}  // namespace
