// The binding toolbox (lua/binding.hpp): the exception bridge turns every C++ exception into a
// Lua error (std::bad_alloc into Lua's own memory error), and another file can add methods
// and properties to the world type with one line each, constructor fields included.
#include <new>
#include <stdexcept>
#include <string>

#include "lua/binding.hpp"
#include "lua/world.hpp"
#include "lua_fixture.hpp"

namespace {

using rigidlab::lua::Entry;
using rigidlab::lua::Property;
using rigidlab::lua::Where;

int throws_bad_alloc(lua_State*) { throw std::bad_alloc(); }
int throws_invalid(lua_State*) { throw std::invalid_argument("width must be > 0, got -1"); }
int throws_logic(lua_State*) { throw std::logic_error("cannot add a body during a step"); }
int throws_length(lua_State*) { throw std::length_error("vector::_M_realloc_insert"); }
int protects_blaming_2(lua_State* L) {
  rigidlab::lua::protect(L, 2, [] { throw std::invalid_argument("offset overflows"); });
  return 0;
}
int protects_bad_alloc(lua_State* L) {
  return rigidlab::lua::protect(L, 1, []() -> int { throw std::bad_alloc(); });
}

const Entry throwing[] = {
    {"bad_alloc", throws_bad_alloc, "test.bad_alloc", "", ""},
    {"invalid", throws_invalid, "test.invalid", "", ""},
    {"logic", throws_logic, "test.logic", "", ""},
    {"length", throws_length, "test.length", "", ""},
    {"blame", protects_blaming_2, "test.blame", "", ""},
    {"protected_bad_alloc", protects_bad_alloc, "test.protected_bad_alloc", "", ""},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

class Bridge : public LuaFixture {
 protected:
  void SetUp() override {
    LuaFixture::SetUp();
    lua_newtable(L);
    rigidlab::lua::register_entries(L, -1, throwing);
    lua_setglobal(L, "test");
  }
  // Calls test.<name>() with lua_pcall: the status and the error value as a string.
  int call(const char* name, std::string& message) {
    lua_getglobal(L, "test");
    lua_getfield(L, -1, name);
    lua_remove(L, -2);
    const int status = lua_pcall(L, 0, 0, 0);
    const char* text = lua_tostring(L, -1);
    message = text != nullptr ? text : "(not a string)";
    lua_pop(L, 1);
    return status;
  }
};

// Lua's own memory error is LUA_ERRMEM with the message "not enough memory" and no position;
// before the bridge, a C++ bad_alloc reached Lua as "(error object is not a string)" or, under
// pcall, a random stack value.
TEST_F(Bridge, BadAllocIsLuasOwnMemoryError) {
  std::string message;
  EXPECT_EQ(call("bad_alloc", message), LUA_ERRMEM);
  EXPECT_EQ(message, "not enough memory");
  EXPECT_EQ(call("protected_bad_alloc", message), LUA_ERRMEM);
  EXPECT_EQ(message, "not enough memory");
  // As Lua's own: pcall returns it, coroutine.wrap passes it on without adding a position.
  EXPECT_EQ(run("local ok, e = pcall(test.bad_alloc)\n"
                "assert(not ok and e == 'not enough memory', tostring(e))\n"
                "local ok2, e2 = pcall(coroutine.wrap(function() test.bad_alloc() end))\n"
                "assert(not ok2 and e2 == 'not enough memory', tostring(e2))"),
            "");
  // The allocator is the state's own again: the state goes on allocating.
  EXPECT_EQ(run("local t = {} for i = 1, 1e5 do t[i] = tostring(i) end"), "");
}

TEST_F(Bridge, OtherExceptionsNameTheFunctionOrTheArgument) {
  std::string message;
  EXPECT_EQ(call("invalid", message), LUA_ERRRUN);
  EXPECT_EQ(message, "'test.invalid': width must be > 0, got -1");
  EXPECT_EQ(call("logic", message), LUA_ERRRUN);
  EXPECT_EQ(message, "'test.logic': cannot add a body during a step");
  EXPECT_EQ(call("length", message), LUA_ERRRUN);
  EXPECT_EQ(message, "'test.length': vector::_M_realloc_insert");
  EXPECT_EQ(run("test.blame(1, 2)"),
            "test:1: bad argument #2 to 'test.blame' (offset overflows)");
}

// ---- extending a type from another file ---------------------------------------------------------

double stiffness = 0.0;  // the state of the extension, for the test

void get_stiffness(lua_State* L, int object, const Property&) {
  rigidlab::lua::check_world(L, object);
  lua_pushnumber(L, stiffness);
}

void set_stiffness(lua_State* L, int object, int value, const Where& where, const Property&) {
  const double k = rigidlab::lua::check_number(L, value, where, 0.0, HUGE_VAL, "a number >= 0");
  rigidlab::lua::check_world(L, object);
  stiffness = k;
}

const Property extension_properties[] = {
    {"stiffness", get_stiffness, set_stiffness, "N/m, of the test extension", nullptr, nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

const char joints_key = 0;

// w:add_thing(x): keeps x in the extension's own table of the world; returns how many.
int world_add_thing(lua_State* L) {
  rigidlab::lua::check_world_unlocked(L, 1, "add a thing");
  rigidlab::lua::push_world_table(L, 1, &joints_key);
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, -1)) + 1;
  lua_pushvalue(L, 2);
  lua_rawseti(L, -2, n);
  lua_pushinteger(L, n);
  return 1;
}

const Entry extension_methods[] = {
    {"add_thing", world_add_thing, "world:add_thing", "w:add_thing(x) -> n", "Test."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

using Extension = LuaFixture;

TEST_F(Extension, MethodsAndPropertiesAddedFromAnotherFile) {
  stiffness = 0.0;
  rigidlab::lua::add_methods(L, rigidlab::lua::world_type, extension_methods);
  rigidlab::lua::add_properties(L, rigidlab::lua::world_type, extension_properties);
  EXPECT_EQ(run("local w = world{}\n"
                "assert(w:add_thing('a') == 1 and w:add_thing('b') == 2)\n"
                "assert(world{}:add_thing('c') == 1, 'each world has its own table')\n"
                "w.stiffness = 5\n"
                "assert(w.stiffness == 5)\n"
                "local v = world{stiffness = 7, gravity = vec3()}\n"
                "assert(v.stiffness == 7, 'a constructor field')\n"
                "assert(world.add_thing == world.add_thing, 'in the public table too')"),
            "");
  EXPECT_EQ(run("local w = world{} w.stiffness = -1"),
            "test:1: bad field 'stiffness' of world (must be a number >= 0, got -1)");
  EXPECT_EQ(run("world{stiffness = 'x'}"),
            "test:1: bad argument #1 to 'world' (field 'stiffness' must be a number, got string)");
  // The generated messages list it with the others.
  const std::string unknown = run("world{stifness = 1}");
  EXPECT_NE(unknown.find("unknown field 'stifness' (fields are: gravity, integrator, "),
            std::string::npos) << unknown;
  EXPECT_NE(unknown.find(", stiffness))"), std::string::npos) << unknown;
  const std::string read = run("return world{}.nope");
  EXPECT_NE(read.find("the fields are time, gravity,"), std::string::npos) << read;
  EXPECT_NE(read.find(", stiffness, the methods are in help(\"world\")"), std::string::npos)
      << read;
  // help("world") lists the new property and method; help("world.stiffness") shows its text.
  EXPECT_EQ(run("local lines = {}\n"
                "local real = print\n"
                "print = function(s) lines[#lines + 1] = s end\n"
                "help('world') help('world.stiffness')\n"
                "print = real\n"
                "local text = table.concat(lines, '\\n')\n"
                "assert(text:find('  stiffness: N/m, of the test extension', 1, true), text)\n"
                "assert(text:find('w:add_thing(x) -> n', 1, true), text)\n"
                "assert(text:find('world.stiffness\\n  N/m, of the test extension', 1, true), text)"),
            "");
}

}  // namespace
