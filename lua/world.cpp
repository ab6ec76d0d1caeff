// world: bodies, gravity, springs, drag, force callbacks, planes and a time integrator
// (engine/world.hpp). The type, its properties and its methods; other files extend it through
// lua/world.hpp.
//
// The world userdata holds a LuaWorld (placement-new, destroyed by __gc) and two user values:
// 1 = the list of its body objects, in the order of the engine's body vector (so w:bodies()
// and error messages can name bodies by index and return the same objects), 2 = the tables of
// the extensions (push_world_table: the force callbacks of lua/world_forces.cpp, joints, ...).
// Body objects hold the world's BodyStore by shared_ptr (lua/body.hpp), so they stay valid
// after the world is collected.
#include "lua/world.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "lua/binding.hpp"
#include "lua/body.hpp"
#include "lua/contact_settings.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

const char world_metatable_key = 0;
constexpr int bodies_slot = 1;
constexpr int extensions_slot = 2;

using WorldBox = Tagged<LuaWorld>;
static_assert(alignof(WorldBox) <= 8, "Lua userdata is only 8-byte aligned");

void check_world_settable(lua_State* L, int object, const Where& where) {
  if (check_world(L, object).world.stepping())
    where.error(L, "the world is stepping: it cannot be set until world:step returns; force "
                   "callbacks may only apply forces");
}

}  // namespace

const TypeSpec world_type = {"world", &world_metatable_key, check_world_settable};

LuaWorld* test_world(lua_State* L, int index) {
  return test_tagged<LuaWorld>(L, index, world_tag);
}

LuaWorld& check_world(lua_State* L, int arg) {
  LuaWorld* w = test_world(L, arg);
  if (w != nullptr) return *w;
  // A world whose __gc has run has its tag cleared but keeps its size and metatable.
  const auto* box = static_cast<const WorldBox*>(lua_touserdata(L, arg));
  if (box != nullptr && lua_rawlen(L, arg) == sizeof(WorldBox) && box->tag == 0 &&
      has_metatable(L, arg, &world_metatable_key))
    arg_error(L, arg, "the world was finalised (its __gc has run; it is used from a finaliser)");
  type_error(L, arg, "world");
}

LuaWorld& check_world_unlocked(lua_State* L, int arg, const char* what) {
  LuaWorld& w = check_world(L, arg);
  if (w.world.stepping()) stepping_error(L, arg, what);
  return w;
}

std::size_t check_member(lua_State* L, const LuaWorld& w, int value, const Where& where) {
  const BodyHandle* handle = test_body(L, value);
  if (handle == nullptr) {
    check_body_handle(L, value, where);  // raises: not a body, or a finalised one
  }
  const BodyStore& store = *w.world.shared_store();
  if (handle->store.get() != &store)
    where.error(L, "must be a body in this world (w:add it first), got a body in %s",
                handle->store->world() != nullptr ? "another world" : "no world");
  return store.index_of(handle->id);
}

void push_world_body(lua_State* L, int world, std::size_t index) {
  lua_getiuservalue(L, world, bodies_slot);
  lua_rawgeti(L, -1, static_cast<lua_Integer>(index) + 1);
  lua_remove(L, -2);
}

void push_world_table(lua_State* L, int world, const void* key) {
  world = lua_absindex(L, world);
  lua_getiuservalue(L, world, extensions_slot);
  if (lua_rawgetp(L, -1, key) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_rawsetp(L, -3, key);
  }
  lua_remove(L, -2);
}

namespace {

// ---- properties ------------------------------------------------------------------------------

// The gyroscopic setting of a new world: an rk4 world must keep it (rk4 ignores the setting).
GyroscopicTerm default_gyroscopic() {
  static const GyroscopicTerm term = World().gyroscopic();
  return term;
}

// Why a gyroscopic setting is refused on an rk4 world: it would be ignored.
constexpr const char* gyroscopic_rk4_rule =
    "must not be set on an rk4 world: it is for the Euler integrators (rk4 always integrates "
    "the full Euler equations)";

void get_time(lua_State* L, int object, const Property&) {
  lua_pushnumber(L, check_world(L, object).world.time());
}

void get_gravity(lua_State* L, int object, const Property&) {
  push_vec3(L, check_world(L, object).world.gravity());
}

void set_gravity(lua_State* L, int object, int value, const Where& where, const Property&) {
  const Vec3 g = check_vec3(L, value, where);
  World& w = check_world(L, object).world;
  protect(L, [&] { w.set_gravity(g); });
}

void get_integrator(lua_State* L, int object, const Property&) {
  lua_pushstring(L, integrator_names[static_cast<int>(check_world(L, object).world.integrator())]);
}

void set_integrator(lua_State* L, int object, int value, const Where& where, const Property&) {
  const auto integrator = static_cast<Integrator>(check_option(L, value, where, integrator_names));
  World& w = check_world(L, object).world;
  // rk4 ignores the gyroscopic setting, so one that is not the default must be undone first.
  const GyroscopicTerm gyroscopic = w.gyroscopic();
  if (integrator == Integrator::rk4 && gyroscopic != default_gyroscopic())
    where.error(L, "'rk4' ignores world.gyroscopic = '%s' (rk4 always integrates the full Euler "
                "equations): set world.gyroscopic = '%s' first",
                gyroscopic_names[static_cast<int>(gyroscopic)],
                gyroscopic_names[static_cast<int>(default_gyroscopic())]);
  w.set_integrator(integrator);
}

void get_gyroscopic(lua_State* L, int object, const Property&) {
  lua_pushstring(L, gyroscopic_names[static_cast<int>(check_world(L, object).world.gyroscopic())]);
}

void set_gyroscopic(lua_State* L, int object, int value, const Where& where, const Property&) {
  const auto term = static_cast<GyroscopicTerm>(check_option(L, value, where, gyroscopic_names));
  World& w = check_world(L, object).world;
  if (w.integrator() == Integrator::rk4) where.error(L, "%s", gyroscopic_rk4_rule);
  w.set_gyroscopic(term);
}

void get_substeps(lua_State* L, int object, const Property&) {
  lua_pushinteger(L, check_world(L, object).world.substeps());
}

void set_substeps(lua_State* L, int object, int value, const Where& where, const Property&) {
  const auto n = static_cast<int>(check_integer(L, value, where, 1, World::max_substeps));
  World& w = check_world(L, object).world;
  protect(L, [&] { w.set_substeps(n); });
}

// Sleeping islands (engine/islands.hpp).
void get_sleeping(lua_State* L, int object, const Property&) {
  lua_pushboolean(L, check_world(L, object).world.sleeping());
}

void set_sleeping(lua_State* L, int object, int value, const Where& where, const Property&) {
  const bool on = check_boolean(L, value, where);
  World& w = check_world(L, object).world;
  protect(L, [&] { w.set_sleeping(on); });
}

void get_sleeping_count(lua_State* L, int object, const Property&) {
  lua_pushinteger(L, static_cast<lua_Integer>(check_world(L, object).world.sleeping_count()));
}

// sleep_linear, sleep_angular, sleep_time: the member of SleepSettings named by the property.
template <double SleepSettings::*member>
void get_sleep_setting(lua_State* L, int object, const Property&) {
  lua_pushnumber(L, check_world(L, object).world.sleep_settings().*member);
}

template <double SleepSettings::*member>
void set_sleep_setting(lua_State* L, int object, int value, const Where& where, const Property&) {
  const double x = check_number(L, value, where, 0.0, HUGE_VAL, "finite and > 0");
  if (!(x > 0.0)) where.error(L, "must be finite and > 0, got %s", push_shown_value(L, value));
  World& w = check_world(L, object).world;
  SleepSettings s = w.sleep_settings();
  s.*member = x;
  protect(L, [&] { w.set_sleep_settings(s); });
}

const Property properties[] = {
    {"time", get_time, nullptr, "s, the world's clock", "it advances with w:step", nullptr},
    {"gravity", get_gravity, set_gravity, "vec3, m/s², default vec3(0, -9.81, 0)", nullptr,
     nullptr},
    {"integrator", get_integrator, set_integrator,
     "\"euler\", \"semi_implicit\" (default) or \"rk4\"", nullptr, nullptr},
    {"gyroscopic", get_gyroscopic, set_gyroscopic,
     "how the Euler methods treat ω × Iω (see above); not for rk4", nullptr, nullptr},
    {"substeps", get_substeps, set_substeps, "equal substeps per w:step(dt), default 1", nullptr,
     nullptr},
    {"sleeping", get_sleeping, set_sleeping,
     "boolean, default false: islands at rest fall asleep (see world); false wakes all",
     nullptr, nullptr},
    {"sleep_linear", get_sleep_setting<&SleepSettings::linear>,
     set_sleep_setting<&SleepSettings::linear>,
     "m/s, default 0.05: a slower body (or every point of one with a shape) is at rest",
     nullptr, nullptr},
    {"sleep_angular", get_sleep_setting<&SleepSettings::angular>,
     set_sleep_setting<&SleepSettings::angular>,
     "rad/s, default 2°/s (0.0349): slower counts as at rest", nullptr, nullptr},
    {"sleep_time", get_sleep_setting<&SleepSettings::time>,
     set_sleep_setting<&SleepSettings::time>,
     "s, default 0.5: how long a whole island must be at rest to fall asleep", nullptr, nullptr},
    {"sleeping_count", get_sleeping_count, nullptr, "the number of sleeping bodies",
     "it counts what the steps put to sleep", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

// ---- constructor and finaliser ---------------------------------------------------------------

int world_call(lua_State* L) {
  lua_remove(L, 1);  // the world table itself
  if (lua_isnone(L, 1)) lua_newtable(L);
  if (!lua_istable(L, 1)) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  check_fields(L, 1, constructor_fields(L, world_type));
  void* memory = lua_newuserdatauv(L, sizeof(WorldBox), 2);
  auto* box = static_cast<WorldBox*>(memory);
  box->tag = 0;  // tagged once whole: a bad_alloc leaves a userdata that is no world
  new (&box->value) LuaWorld();
  box->tag = world_tag;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &world_metatable_key);
  lua_setmetatable(L, -2);
  for (int slot : {bodies_slot, extensions_slot}) {
    lua_newtable(L);
    lua_setiuservalue(L, -2, slot);
  }
  set_from_table(L, world_type, 2, 1);  // the new world is unknown to the table's metamethods
  return 1;
}

// A world's __gc, run by the collector or by hand (debug.getmetatable(w).__gc(w)): refused
// while the world steps, since the step uses it (the collector never finalises a stepping
// world: w:step holds it); after it, the world is no world (check_world says "finalised"), so
// a second call does nothing.
int world_gc(lua_State* L) {
  LuaWorld* w = test_world(L, 1);
  if (w == nullptr) return 0;
  if (w->world.stepping())
    arg_error(L, 1, "the world is stepping: it cannot be finalised until world:step returns");
  w->~LuaWorld();
  static_cast<WorldBox*>(lua_touserdata(L, 1))->tag = 0;
  return 0;
}

int world_tostring(lua_State* L) {
  const World& w = check_world(L, 1).world;
  const std::size_t n = w.bodies().size();
  lua_pushfstring(L, "world(%d bod%s, t=%s, %s)", static_cast<int>(n), n == 1 ? "y" : "ies",
                  format_number(w.time()).c_str(),
                  integrator_names[static_cast<int>(w.integrator())]);
  return 1;
}

// ---- bodies ----------------------------------------------------------------------------------

// w:add(b): the Lua list grows first (the only part that allocates on Lua's side), then the
// engine takes the body; a failure of either leaves both as they were.
int world_add(lua_State* L) {
  LuaWorld& w = check_world_unlocked(L, 1, "add a body");
  BodyHandle& handle = check_body_handle(L, 2);
  check_no_extra_args(L, 2);
  if (handle.store.get() == &w.world.store()) arg_error(L, 2, "the body is already in this world");
  if (handle.store->world() != nullptr)
    arg_error(L, 2, "the body is already in another world (remove it there first)");
  const auto n = static_cast<lua_Integer>(w.world.bodies().size()) + 1;
  lua_getiuservalue(L, 1, bodies_slot);
  lua_pushvalue(L, 2);
  lua_rawseti(L, 3, n);  // may raise Lua's memory error: nothing has changed yet
  BodyStore::Id id;
  if (const Failure failure = try_call([&] { id = w.world.add(handle.body()); })) {
    lua_pushnil(L);
    lua_rawseti(L, 3, n);  // frees nothing, allocates nothing
    failure.raise(L);
  }
  // A lone body's own store, or the store of a world that was collected: the body moves out.
  // Erasing only frees (a failure to record the free id leaves that store consistent).
  std::shared_ptr<BodyStore> old = std::move(handle.store);
  try_call([&] { old->erase(handle.id); });
  handle.store = w.world.shared_store();
  handle.id = id;
  lua_settop(L, 2);
  return 1;
}

// w:remove(b): the body's own new store is made first, then the engine lets go of it, then the
// Lua list closes the gap (no allocation).
int world_remove(lua_State* L) {
  LuaWorld& w = check_world_unlocked(L, 1, "remove a body");
  const std::size_t index = check_member(L, w, 2, Where::argument(2));
  check_no_extra_args(L, 2);
  BodyHandle& handle = check_body_handle(L, 2);
  auto own = protect(L, [&] {
    auto store = std::make_shared<BodyStore>();
    store->insert(handle.body());
    return store;
  });
  protect(L, [&] { w.world.remove(handle.id); });
  handle.store = std::move(own);
  handle.id = handle.store->id_at(0);
  lua_getiuservalue(L, 1, bodies_slot);  // shift the later bodies down, as table.remove
  const auto n = static_cast<lua_Integer>(w.world.bodies().size()) + 1;
  for (lua_Integer i = static_cast<lua_Integer>(index) + 1; i < n; ++i) {
    lua_rawgeti(L, -1, i + 1);
    lua_rawseti(L, -2, i);
  }
  lua_pushnil(L);
  lua_rawseti(L, -2, n);
  return 0;
}

int world_bodies(lua_State* L) {
  const World& w = check_world(L, 1).world;
  check_no_extra_args(L, 1);
  const auto n = static_cast<lua_Integer>(w.bodies().size());
  lua_getiuservalue(L, 1, bodies_slot);
  lua_createtable(L, static_cast<int>(n), 0);
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -2, i);
    lua_rawseti(L, -2, i);
  }
  return 1;
}

// ---- totals ----------------------------------------------------------------------------------

template <double (World::*total)() const>
int world_total(lua_State* L) {
  const double x = (check_world(L, 1).world.*total)();
  check_no_extra_args(L, 1);
  lua_pushnumber(L, x);
  return 1;
}

int world_linear_momentum(lua_State* L) {
  const Vec3 p = check_world(L, 1).world.linear_momentum();
  check_no_extra_args(L, 1);
  push_finite(L, p, 1);
  return 1;
}

int world_angular_momentum(lua_State* L) {
  const World& w = check_world(L, 1).world;
  const Vec3 about =
      lua_isnoneornil(L, 2) ? Vec3::Zero() : Vec3(check_vec3(L, 2, Where::argument(2, "point")));
  check_no_extra_args(L, 2);
  push_finite(L, w.angular_momentum(about), 1);
  return 1;
}

const Entry methods[] = {
    {"add", world_add, "world:add", "w:add(b) -> b",
     "Adds body b to the world and returns it. A body belongs to at most one world."},
    {"remove", world_remove, "world:remove", "w:remove(b)",
     "Removes body b; it keeps its state and can be added again. Springs and drag attached to\n"
     "it are removed with it."},
    {"bodies", world_bodies, "world:bodies", "w:bodies() -> {body, ...}",
     "A new list of the world's bodies in the order they were added (error messages of\n"
     "w:step name bodies by this index)."},
    {"kinetic_energy", world_total<&World::kinetic_energy>, "world:kinetic_energy",
     "w:kinetic_energy() -> number", "Σ ½ m v² + ½ ω·I ω over the bodies (J)."},
    {"potential_energy", world_total<&World::potential_energy>, "world:potential_energy",
     "w:potential_energy() -> number",
     "Gravity −Σ m g·x (zero at the world origin) plus springs Σ ½ k (L − rest_length)² (J)."},
    {"energy", world_total<&World::energy>, "world:energy", "w:energy() -> number",
     "Kinetic plus potential energy (J)."},
    {"linear_momentum", world_linear_momentum, "world:linear_momentum",
     "w:linear_momentum() -> vec3", "Σ m v (kg m/s)."},
    {"angular_momentum", world_angular_momentum, "world:angular_momentum",
     "w:angular_momentum([point]) -> vec3",
     "Σ (x − point) × m v + I_world ω about the world point (default the origin) (kg m²/s)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__tostring", world_tostring, "world.__tostring", "tostring(w)",
     "Short form: world(3 bodies, t=1.5, semi_implicit)."},
    {"__gc", world_gc, "world.__gc", "",
     "Releases the world (refused while it steps); its bodies stay valid."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry call_entry[] = {
    {"__call", world_call, "world",
     "world{gravity =, integrator =, gyroscopic =, substeps =, sleeping =, ...} -> world",
     "A world of rigid bodies; the option table sets any of the settable fields below.\n"
     "integrator: \"euler\" (explicit: positions from the old velocities), \"semi_implicit\"\n"
     "(default; velocities first, positions from the new ones) or \"rk4\" (classical 4th\n"
     "order on the whole state, gyroscopic term included); gyroscopic, for the Euler methods:\n"
     "\"conserving\" (default; exact rotations about the principal axes: a torque-free body\n"
     "keeps L to round-off and its energy without drift), \"implicit\" (one Newton step on\n"
     "ω × Iω per substep: stable, but loses energy and ‖L‖), \"explicit\" (gains energy) or\n"
     "\"off\" (refused on an rk4 world, which would ignore it; switching to rk4 needs the\n"
     "default gyroscopic setting); substeps (default 1) per w:step(dt).\n"
     "sleeping (default false, opt-in): an island of bodies (linked by contacts, touching or\n"
     "within the speculative distance, joints and springs; the floor links nothing) whose\n"
     "every body has moved slower than sleep_linear and turned slower than sleep_angular (or,\n"
     "with a shape, whose every point moved slower than sleep_linear) for sleep_time falls\n"
     "asleep: its velocities are set to zero (they were below the tolerances) and the steps\n"
     "skip it until an awake body touches it or you change one of its bodies or joints\n"
     "(b:wake() wakes it). Off by default: a small pendulum or a slowly rolling ball must not\n"
     "freeze unless you ask. A world with a force callback keeps every body awake.\n"
     "Contacts: bodies with a shape collide with each other and with planes (w:add_plane)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_world(lua_State* L, int lib) {
  lua_newtable(L);  // the callable `world` table
  const int table = lua_gettop(L);
  new_type(L, world_type, table, metamethods);
  add_properties(L, world_type, properties);
  add_contact_setting_properties(L);
  add_methods(L, world_type, methods);
  open_world_forces(L);
  lua_newtable(L);
  register_entries(L, -1, call_entry);
  lua_pushliteral(L, "world");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, table);
  // The topic's text lives as long as the program: help() keeps the pointer.
  static const std::string doc = std::string(call_entry[0].doc) + "\n" + contact_settings_doc;
  register_topic(L, table, "world", doc.c_str());
  lua_setfield(L, lib, "world");
}

}  // namespace rigidlab::lua
