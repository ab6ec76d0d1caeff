// world: bodies, gravity, springs, drag, force callbacks and a time integrator (engine/world.hpp).
//
// The world userdata holds the engine World (placement-new, destroyed by __gc) and two user
// values: 1 = the list of its body objects, in the order of the engine's body vector (so
// w:bodies() and error messages can name bodies by index and return the same objects),
// 2 = the list of force callback functions. Body objects hold the world's BodyStore by
// shared_ptr (lua/body.hpp), so they stay valid after the world is collected.
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

#include "lua/binding.hpp"
#include "lua/body.hpp"
#include "lua/contact_settings.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

const char world_metatable_key = 0;
constexpr int bodies_slot = 1;
constexpr int callbacks_slot = 2;
// w:step(dt, n): n is bounded so a typo cannot start a run of years; long runs can be split.
constexpr lua_Integer max_steps_per_call = 100'000'000;

struct LuaWorld {
  World world;
  lua_State* running = nullptr;  // the thread running w:step, for the force callbacks
};
using WorldBox = Tagged<LuaWorld>;
static_assert(alignof(WorldBox) <= 8, "Lua userdata is only 8-byte aligned");

LuaWorld& check_world(lua_State* L, int arg) {
  LuaWorld* w = test_tagged<LuaWorld>(L, arg, world_tag);
  if (w == nullptr) type_error(L, arg, "world");
  return *w;
}

// Runs an engine call, turning std::invalid_argument / std::logic_error into a Lua error
// naming the running function (raised outside the catch, STYLE.md 4).
template <class F>
void call_engine(lua_State* L, F&& f) {
  std::string message;
  try {
    f();
    return;
  } catch (const std::invalid_argument& e) {
    message = e.what();
  } catch (const std::logic_error& e) {
    message = e.what();
  }
  function_error(L, "%s", message.c_str());
}

template <std::size_t N, class Enum>
Enum check_option(lua_State* L, int arg, const char* const (&names)[N], const char* what,
                  bool in_table) {
  const bool is_string = lua_type(L, -1) == LUA_TSTRING;
  if (is_string)
    for (std::size_t i = 0; i < N; ++i)
      if (std::strcmp(lua_tostring(L, -1), names[i]) == 0) return static_cast<Enum>(i);
  std::string choices;
  for (std::size_t i = 0; i < N; ++i) choices += std::string(i ? ", " : "") + "'" + names[i] + "'";
  const std::string got =
      is_string ? "'" + std::string(lua_tostring(L, -1)) + "'" : value_type_name(L, -1);
  if (in_table)
    arg_error(L, arg, "field '%s' must be one of %s, got %s", what, choices.c_str(), got.c_str());
  field_error(L, "world", what, "must be one of %s, got %s", choices.c_str(), got.c_str());
}

// A value as error messages show it: numbers as Lua prints them but with %.14g for floats
// (1e+12, not 1000000000000.0), anything else by luaL_tolstring. Pushes the string.
const char* shown_value(lua_State* L, int index) {
  if (lua_type(L, index) == LUA_TNUMBER && !lua_isinteger(L, index))
    return lua_pushstring(L, format_number(lua_tonumber(L, index)).c_str());
  return luaL_tolstring(L, index, nullptr);
}

// Why world{} and w.gyroscopic refuse a gyroscopic setting on an rk4 world: it would be ignored.
constexpr const char* gyroscopic_rk4_rule =
    "is for the Euler integrators: rk4 always integrates the full Euler equations";

// The substeps value on top of the stack (2.0 counts as 2, as in luaL_checkinteger).
int check_substeps(lua_State* L, int arg, bool in_table) {
  lua_Integer n = 0;
  if (!to_integer(L, -1, n) || n < 1 || n > World::max_substeps) {
    const char* got = shown_value(L, -1);
    if (in_table)
      arg_error(L, arg, "field 'substeps' must be an integer from 1 to %d, got %s",
                World::max_substeps, got);
    field_error(L, "world", "substeps", "must be an integer from 1 to %d, got %s",
                World::max_substeps, got);
  }
  return static_cast<int>(n);
}

// ---- constructor -----------------------------------------------------------------------------

int world_call(lua_State* L) {
  lua_remove(L, 1);  // the world table itself
  if (lua_isnone(L, 1)) lua_newtable(L);
  if (!lua_istable(L, 1)) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  static const char* const fields[] = {
      "gravity", "integrator", "gyroscopic", "substeps", "iterations", "position_iterations",
      "restitution_threshold", "slop", "baumgarte", "max_correction", "speculative_distance",
      nullptr};
  check_fields(L, 1, fields);
  const Vec3 gravity = field_vec3(L, 1, "gravity", Vec3(0, -9.81, 0), false);
  Integrator integrator = Integrator::semi_implicit;
  GyroscopicTerm gyroscopic = GyroscopicTerm::implicit;
  int substeps = 1;
  if (get_field(L, 1, "integrator") != LUA_TNIL)
    integrator = check_option<3, Integrator>(L, 1, integrator_names, "integrator", true);
  if (get_field(L, 1, "gyroscopic") != LUA_TNIL) {
    gyroscopic = check_option<3, GyroscopicTerm>(L, 1, gyroscopic_names, "gyroscopic", true);
    if (integrator == Integrator::rk4)
      arg_error(L, 1, "field 'gyroscopic' %s", gyroscopic_rk4_rule);
  }
  if (get_field(L, 1, "substeps") != LUA_TNIL) substeps = check_substeps(L, 1, true);
  ContactSettings contact;
  for (const char* const* name = contact_setting_names; *name != nullptr; ++name)
    if (get_field(L, 1, *name) != LUA_TNIL) read_contact_setting(L, 1, *name, true, contact);
  lua_settop(L, 1);

  void* memory = lua_newuserdatauv(L, sizeof(WorldBox), 2);
  auto* box = new (memory) WorldBox{world_tag, {}};
  lua_rawgetp(L, LUA_REGISTRYINDEX, &world_metatable_key);
  lua_setmetatable(L, -2);
  lua_newtable(L);
  lua_setiuservalue(L, -2, bodies_slot);
  lua_newtable(L);
  lua_setiuservalue(L, -2, callbacks_slot);
  World& w = box->value.world;
  w.set_gravity(gravity);
  w.set_integrator(integrator);
  w.set_gyroscopic(gyroscopic);
  w.set_substeps(substeps);
  w.set_contact_settings(contact);
  return 1;
}

int world_gc(lua_State* L) {
  auto* box = static_cast<WorldBox*>(lua_touserdata(L, 1));
  if (box != nullptr && box->tag == world_tag) {
    box->value.~LuaWorld();
    box->tag = 0;
  }
  return 0;
}

// ---- bodies ----------------------------------------------------------------------------------

// The handle of argument `arg`, which must be a body of this world; its 0-based index.
std::size_t check_member(lua_State* L, LuaWorld& w, int arg, BodyHandle*& handle) {
  handle = &check_body_handle(L, arg);
  if (handle->store.get() != &w.world.store()) arg_error(L, arg, "the body is not in this world");
  return w.world.store().index_of(handle->id);
}

int world_add(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  BodyHandle& handle = check_body_handle(L, 2);
  check_no_extra_args(L, 2);
  if (w.world.stepping()) stepping_error(L, 1, "add a body");
  if (handle.store.get() == &w.world.store()) arg_error(L, 2, "the body is already in this world");
  if (handle.store->world() != nullptr)
    arg_error(L, 2, "the body is already in another world (remove it there first)");
  // A lone body's own store, or the store of a world that was collected: move the body out.
  BodyStore::Id id = 0;
  call_engine(L, [&] { id = w.world.add(handle.body()); });
  handle.store->erase(handle.id);
  handle.store = w.world.shared_store();
  handle.id = id;
  lua_getiuservalue(L, 1, bodies_slot);
  lua_pushvalue(L, 2);
  lua_rawseti(L, -2, static_cast<lua_Integer>(w.world.bodies().size()));
  lua_pop(L, 1);
  lua_settop(L, 2);
  return 1;
}

int world_remove(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  BodyHandle* handle = nullptr;
  const std::size_t index = check_member(L, w, 2, handle);
  check_no_extra_args(L, 2);
  if (w.world.stepping()) stepping_error(L, 1, "remove a body");
  auto own = std::make_shared<BodyStore>();
  Body body;
  call_engine(L, [&] { body = w.world.remove(handle->id); });
  handle->id = own->insert(body);
  handle->store = std::move(own);
  // Shift the body objects after it down by one, as table.remove.
  lua_getiuservalue(L, 1, bodies_slot);
  const lua_Integer n = static_cast<lua_Integer>(w.world.bodies().size()) + 1;
  for (lua_Integer i = static_cast<lua_Integer>(index) + 1; i < n; ++i) {
    lua_rawgeti(L, -1, i + 1);
    lua_rawseti(L, -2, i);
  }
  lua_pushnil(L);
  lua_rawseti(L, -2, n);
  return 0;
}

int world_bodies(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  const lua_Integer n = static_cast<lua_Integer>(w.world.bodies().size());
  lua_getiuservalue(L, 1, bodies_slot);
  lua_createtable(L, static_cast<int>(n), 0);
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -2, i);
    lua_rawseti(L, -2, i);
  }
  return 1;
}

// ---- force elements --------------------------------------------------------------------------

// Field `name` of the table at 1, which must be a body of this world; its index, or no_body
// when absent and not required.
std::size_t field_member(lua_State* L, LuaWorld& w, const char* name, bool required) {
  if (get_field(L, 2, name) == LUA_TNIL) {
    lua_pop(L, 1);
    if (required) arg_error(L, 2, "field '%s' is required", name);
    return no_body;
  }
  BodyHandle* handle = test_body(L, -1);
  if (handle == nullptr) {
    const char* got = value_type_name(L, -1);
    arg_error(L, 2, "field '%s' must be a body, got %s", name, got);
  }
  if (handle->store.get() != &w.world.store())
    arg_error(L, 2, "field '%s' is a body that is not in this world (w:add it first)", name);
  lua_pop(L, 1);
  return w.world.store().index_of(handle->id);
}

double field_nonnegative(lua_State* L, const char* name, double fallback, bool required) {
  const double x = field_finite(L, 2, name, fallback, required);
  if (!(x >= 0.0)) arg_error(L, 2, "field '%s' must be >= 0, got %s", name, format_number(x).c_str());
  return x;
}

int world_add_spring(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  if (w.world.stepping()) stepping_error(L, 1, "add a spring");
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  check_no_extra_args(L, 2);
  static const char* const fields[] = {"a", "a_point", "b", "b_point", "anchor", "k",
                                       "damping", "rest_length", nullptr};
  check_fields(L, 2, fields);
  Spring s;
  s.a = field_member(L, w, "a", true);
  s.b = field_member(L, w, "b", false);
  const bool has_anchor = get_field(L, 2, "anchor") != LUA_TNIL;
  const bool has_b_point = get_field(L, 2, "b_point") != LUA_TNIL;
  lua_pop(L, 2);
  if (s.b == no_body && !has_anchor)
    arg_error(L, 2, "field 'b' (a body) or 'anchor' (a world point) is required");
  if (s.b != no_body && has_anchor) arg_error(L, 2, "fields 'b' and 'anchor' exclude each other");
  if (s.b == no_body && has_b_point) arg_error(L, 2, "field 'b_point' needs field 'b'");
  if (s.a == s.b) arg_error(L, 2, "fields 'a' and 'b' must be different bodies");
  s.a_point = field_vec3(L, 2, "a_point", Vec3::Zero(), false);
  s.b_point = field_vec3(L, 2, "b_point", Vec3::Zero(), false);
  s.anchor = field_vec3(L, 2, "anchor", Vec3::Zero(), false);
  s.stiffness = field_nonnegative(L, "k", 0.0, true);
  s.damping = field_nonnegative(L, "damping", 0.0, false);
  s.rest_length = field_nonnegative(L, "rest_length", 0.0, false);
  call_engine(L, [&] { w.world.add_spring(s); });
  return 0;
}

int world_add_drag(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  if (w.world.stepping()) stepping_error(L, 1, "add drag");
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  check_no_extra_args(L, 2);
  static const char* const fields[] = {"body", "linear", "angular", nullptr};
  check_fields(L, 2, fields);
  Drag d;
  d.body = field_member(L, w, "body", true);
  d.linear = field_nonnegative(L, "linear", 0.0, false);
  d.angular = field_nonnegative(L, "angular", 0.0, false);
  call_engine(L, [&] { w.world.add_drag(d); });
  return 0;
}

// ---- contacts --------------------------------------------------------------------------------

int world_add_plane(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  if (lua_isnoneornil(L, 2)) {  // w:add_plane() is the floor y >= 0
    lua_settop(L, 1);
    lua_newtable(L);
  }
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  // Counted as the other errors of this method count: the table is argument #1.
  if (lua_gettop(L) > 2)
    arg_error(L, 3, "no more than 1 argument (the table) expected, got %d", lua_gettop(L) - 1);
  static const char* const fields[] = {"normal", "offset", "restitution", "friction", nullptr};
  check_fields(L, 2, fields);
  const Vec3 normal = field_vec3(L, 2, "normal", Vec3::UnitY(), false);
  if (normal == Vec3::Zero())
    arg_error(L, 2, "field 'normal' must be a non-zero vector, got (%s, %s, %s)",
              format_number(normal.x()).c_str(), format_number(normal.y()).c_str(),
              format_number(normal.z()).c_str());
  const double offset = field_finite(L, 2, "offset", 0.0, false);
  double restitution = 0.0, friction = 0.0;
  read_material_fields(L, 2, restitution, friction);
  if (w.world.stepping()) stepping_error(L, 1, "add a plane");
  std::size_t index = 0;
  call_engine(L, [&] {
    index = w.world.add_plane(make_plane(normal, offset, restitution, friction));
  });
  lua_pushinteger(L, static_cast<lua_Integer>(index) + 1);
  return 1;
}

void set_number_field(lua_State* L, const char* name, double x) {
  lua_pushnumber(L, x);
  lua_setfield(L, -2, name);
}

void set_vec3_field(lua_State* L, const char* name, const Vec3& v) {
  push_vec3(L, v);
  lua_setfield(L, -2, name);
}

int world_planes(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  const std::vector<Plane>& planes = w.world.planes();
  lua_createtable(L, static_cast<int>(planes.size()), 0);
  for (std::size_t i = 0; i < planes.size(); ++i) {
    lua_createtable(L, 0, 4);
    set_vec3_field(L, "normal", planes[i].normal);
    set_number_field(L, "offset", planes[i].offset);
    set_number_field(L, "restitution", planes[i].restitution);
    set_number_field(L, "friction", planes[i].friction);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
  }
  return 1;
}

// Sets field `name` of the table on top to the body object of engine index `index`.
void set_body_field(lua_State* L, const char* name, std::size_t index) {
  lua_getiuservalue(L, 1, bodies_slot);
  lua_rawgeti(L, -1, static_cast<lua_Integer>(index) + 1);
  lua_setfield(L, -3, name);
  lua_pop(L, 1);
}

// The touching points of the last substep, all with one convention: the normal points from a
// to b and the impulses are b's (a got the opposite). Against a plane, a is the plane (field
// a = nil, plane = its index) and b the body: the normal is the plane's, the impulses the
// body's.
int world_contacts(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  lua_newtable(L);
  lua_Integer n = 0;
  for (const ContactInfo& c : w.world.contacts()) {
    if (!touched(c)) continue;
    lua_createtable(L, 0, 10);
    if (c.a == no_body) {
      lua_pushinteger(L, static_cast<lua_Integer>(c.plane) + 1);
      lua_setfield(L, -2, "plane");
    } else {
      set_body_field(L, "a", c.a);
    }
    set_body_field(L, "b", c.b);
    set_vec3_field(L, "point", c.point);
    set_vec3_field(L, "normal", c.normal);
    set_number_field(L, "depth", c.depth);
    set_number_field(L, "normal_impulse", c.normal_impulse);
    set_vec3_field(L, "friction_impulse", c.friction_impulse);
    set_number_field(L, "restitution", c.restitution);
    set_number_field(L, "friction", c.friction);
    lua_rawseti(L, -2, ++n);
  }
  return 1;
}

// The world userdata is argument 1 of the running w:step on box->running: callbacks get it and
// the stage time. A Lua error raised inside propagates (as a C++ exception, Lua being compiled
// as C++) through World::step, which undoes the step.
void call_lua_force(LuaWorld& box, lua_Integer index, double t) {
  lua_State* L = box.running;
  luaL_checkstack(L, 4, "force callback");
  lua_getiuservalue(L, 1, callbacks_slot);
  lua_rawgeti(L, -1, index);
  lua_pushvalue(L, 1);
  lua_pushnumber(L, t);
  lua_call(L, 2, 0);
  lua_pop(L, 1);
}

int world_add_force(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  if (lua_type(L, 2) != LUA_TFUNCTION) type_error(L, 2, "function");
  check_no_extra_args(L, 2);
  if (w.world.stepping()) stepping_error(L, 1, "add a force");
  lua_getiuservalue(L, 1, callbacks_slot);
  const lua_Integer index = static_cast<lua_Integer>(luaL_len(L, -1)) + 1;
  lua_pushvalue(L, 2);
  lua_rawseti(L, -2, index);
  LuaWorld* box = &w;
  call_engine(L, [&] {
    w.world.add_force([box, index](World&, double t) { call_lua_force(*box, index, t); });
  });
  return 0;
}

// ---- stepping --------------------------------------------------------------------------------

// Sets and restores the thread that runs the callbacks (RAII: errors unwind through here).
class RunningState {
 public:
  RunningState(LuaWorld& w, lua_State* L) : world_(w), previous_(w.running) { w.running = L; }
  ~RunningState() { world_.running = previous_; }
  RunningState(const RunningState&) = delete;
  RunningState& operator=(const RunningState&) = delete;

 private:
  LuaWorld& world_;
  lua_State* previous_;
};

int world_step(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  const double dt = check_positive(L, 2, "dt");
  lua_Integer n = 1;
  if (!lua_isnoneornil(L, 3)) {
    if (lua_type(L, 3) != LUA_TNUMBER) type_error(L, 3, "number");
    if (!to_integer(L, 3, n) || n < 1 || n > max_steps_per_call)  // 2.0 counts as 2
      arg_error(L, 3, "n must be an integer from 1 to %d, got %s", int(max_steps_per_call),
                shown_value(L, 3));
  }
  check_no_extra_args(L, 3);
  if (w.world.stepping())  // self is the bad argument: "calling 'world:step' on bad self (...)"
    arg_error(L, 1, "the world is already stepping: a force callback cannot step its own world");
  lua_settop(L, 1);
  // The engine polls the stop check (Ctrl-C, a time limit) inside its long loops: a step of
  // any size can be stopped, and is then undone.
  const StopPoller stop(L);
  const std::function<void()> poll = [&stop] { stop.poll(); };
  RunningState running(w, L);
  std::string message;
  try {
    w.world.step(dt, static_cast<long>(n), poll);
    return 0;
  } catch (const StepError& e) {
    message = e.what();
  } catch (const std::invalid_argument& e) {
    message = e.what();
  } catch (const std::logic_error& e) {
    message = e.what();
  }
  function_error(L, "%s", message.c_str());
  return 0;
}

// ---- totals ----------------------------------------------------------------------------------

int world_kinetic_energy(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, w.world.kinetic_energy());
  return 1;
}

int world_potential_energy(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, w.world.potential_energy());
  return 1;
}

int world_energy(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  lua_pushnumber(L, w.world.energy());
  return 1;
}

int world_linear_momentum(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  check_no_extra_args(L, 1);
  push_finite(L, w.world.linear_momentum(), 1);
  return 1;
}

int world_angular_momentum(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  const Vec3 about = lua_isnoneornil(L, 2) ? Vec3::Zero() : check_vec3(L, 2);
  check_no_extra_args(L, 2);
  push_finite(L, w.world.angular_momentum(about), 1);
  return 1;
}

// ---- fields ----------------------------------------------------------------------------------

int world_index(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "";
  if (std::strcmp(key, "time") == 0) lua_pushnumber(L, w.world.time());
  else if (std::strcmp(key, "gravity") == 0) push_vec3(L, w.world.gravity());
  else if (std::strcmp(key, "integrator") == 0)
    lua_pushstring(L, integrator_names[static_cast<int>(w.world.integrator())]);
  else if (std::strcmp(key, "gyroscopic") == 0)
    lua_pushstring(L, gyroscopic_names[static_cast<int>(w.world.gyroscopic())]);
  else if (std::strcmp(key, "substeps") == 0) lua_pushinteger(L, w.world.substeps());
  else if (is_contact_setting(key)) push_contact_setting(L, key, w.world.contact_settings());
  else {
    lua_pushvalue(L, 2);
    if (lua_type(L, 2) == LUA_TSTRING && lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
    field_error(L, "world", push_key_name(L, 2),
                "no such field; the fields are time, gravity, integrator, gyroscopic, substeps, "
                "iterations, position_iterations, restitution_threshold, slop, baumgarte, "
                "max_correction, speculative_distance, the methods are in help(\"world\")");
  }
  return 1;
}

int world_newindex(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "";
  const auto is = [key](const char* name) { return std::strcmp(key, name) == 0; };
  if (is("time")) field_error(L, "world", "time", "read-only: it advances with w:step");
  if (!is("gravity") && !is("integrator") && !is("gyroscopic") && !is("substeps") &&
      !is_contact_setting(key))
    field_error(L, "world", push_key_name(L, 2),
                "no such field; the settable fields are gravity, integrator, gyroscopic, substeps, "
                "iterations, position_iterations, restitution_threshold, slop, baumgarte, "
                "max_correction, speculative_distance");
  if (w.world.stepping())
    field_error(L, "world", key, "the world is stepping: it cannot be set until world:step returns");
  lua_settop(L, 3);
  if (is("gravity")) {
    w.world.set_gravity(check_field_vec3(L, "world", "gravity", 3));
  } else if (is("integrator")) {
    // rk4 ignores the gyroscopic setting, so one that is not the default must be undone first
    // (as world{} refuses integrator = "rk4" with a gyroscopic field).
    const Integrator integrator =
        check_option<3, Integrator>(L, 3, integrator_names, "integrator", false);
    const GyroscopicTerm gyroscopic = w.world.gyroscopic();
    if (integrator == Integrator::rk4 && gyroscopic != GyroscopicTerm::implicit)
      field_error(L, "world", "integrator", "'rk4' ignores world.gyroscopic = '%s' (rk4 always "
                  "integrates the full Euler equations): set world.gyroscopic = 'implicit' first",
                  gyroscopic_names[static_cast<int>(gyroscopic)]);
    w.world.set_integrator(integrator);
  } else if (is("gyroscopic")) {
    const GyroscopicTerm gyroscopic =
        check_option<3, GyroscopicTerm>(L, 3, gyroscopic_names, "gyroscopic", false);
    if (w.world.integrator() == Integrator::rk4)
      field_error(L, "world", "gyroscopic", "it %s", gyroscopic_rk4_rule);
    w.world.set_gyroscopic(gyroscopic);
  } else if (is_contact_setting(key)) {
    ContactSettings contact = w.world.contact_settings();
    read_contact_setting(L, 3, key, false, contact);
    w.world.set_contact_settings(contact);
  } else {
    w.world.set_substeps(check_substeps(L, 3, false));
  }
  return 0;
}

int world_tostring(lua_State* L) {
  LuaWorld& w = check_world(L, 1);
  const std::size_t n = w.world.bodies().size();
  lua_pushfstring(L, "world(%d bod%s, t=%s, %s)", static_cast<int>(n), n == 1 ? "y" : "ies",
                  format_number(w.world.time()).c_str(),
                  integrator_names[static_cast<int>(w.world.integrator())]);
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
    {"add_force", world_add_force, "world:add_force", "w:add_force(fn)",
     "fn(w, t) is called at every force evaluation (once per substep for the Euler methods,\n"
     "at each of the four stages of rk4, the bodies then holding the stage's state and\n"
     "w.time = t) and applies forces with b:apply_force / b:apply_torque. An error in fn\n"
     "stops w:step and leaves the world as before the call."},
    {"add_spring", world_add_spring, "world:add_spring",
     "w:add_spring{a =, a_point =, b =, b_point =, anchor =, k =, damping =, rest_length =}",
     "A Hooke spring with a damper along its line, from a_point of body a (body coordinates,\n"
     "default the COM) to b_point of body b, or to the world point `anchor` when there is no\n"
     "b. Force on a: (k (L − rest_length) + damping · (relative velocity of the ends)·u) u,\n"
     "u the unit vector from a's end to b's end; −that on b. k (N/m) required; damping\n"
     "(N s/m) and rest_length (m) default 0, so by default the spring pulls the ends together."},
    {"add_drag", world_add_drag, "world:add_drag", "w:add_drag{body =, linear =, angular =}",
     "Linear drag on a body: F = −linear · v (N s/m), τ = −angular · ω (N m s). Default 0."},
    {"add_plane", world_add_plane, "world:add_plane",
     "w:add_plane{normal =, offset =, restitution =, friction =} -> index",
     "A static plane: bodies with a shape (body.sphere, body.box) stay in the half-space\n"
     "normal·x >= offset. normal (vec3, any non-zero length; default vec3(0, 1, 0)) and offset\n"
     "(m, default 0) as given: the plane is stored with the unit normal and offset/|normal|.\n"
     "restitution in [0, 1] (default 0) and friction >= 0 (default 0.6) combine with the\n"
     "body's as e = max, μ = √(μa μb). Returns the plane's index (w:planes(), contacts)."},
    {"planes", world_planes, "world:planes", "w:planes() -> {{normal =, offset =, ...}, ...}",
     "The planes, each as {normal = unit vec3, offset = m, restitution =, friction =}."},
    {"contacts", world_contacts, "world:contacts", "w:contacts() -> {contact, ...}",
     "The contact points of the last step (its last substep), each a table\n"
     "{a = body or nil, plane = index or nil, b = body, point = vec3, normal = vec3, depth =,\n"
     "normal_impulse =, friction_impulse = vec3, restitution =, friction =}.\n"
     "The normal points from a to b; b received the impulse normal_impulse·normal +\n"
     "friction_impulse (N s) and a its opposite. Against a plane, a is nil, plane is the\n"
     "plane's index and b the body: the normal is the plane's and the impulses the body's.\n"
     "point (m) is where the surfaces meet (midway between them); depth (m) is the overlap\n"
     "when the step began (negative: a gap the step closed). For a contact found ahead of\n"
     "an impact in the step, point and normal are those of the moment the bodies touch.\n"
     "Contacts are solved by sequential impulses (Catto, GDC 2005) with `iterations` sweeps;\n"
     "impacts faster than restitution_threshold bounce with the pair's restitution (see\n"
     "help(\"world\") for the solver's settings and limits)."},
    {"kinetic_energy", world_kinetic_energy, "world:kinetic_energy", "w:kinetic_energy() -> number",
     "Σ ½ m v² + ½ ω·I ω over the bodies (J)."},
    {"potential_energy", world_potential_energy, "world:potential_energy",
     "w:potential_energy() -> number",
     "Gravity −Σ m g·x (zero at the world origin) plus springs Σ ½ k (L − rest_length)² (J)."},
    {"energy", world_energy, "world:energy", "w:energy() -> number",
     "Kinetic plus potential energy (J)."},
    {"linear_momentum", world_linear_momentum, "world:linear_momentum",
     "w:linear_momentum() -> vec3", "Σ m v (kg m/s)."},
    {"angular_momentum", world_angular_momentum, "world:angular_momentum",
     "w:angular_momentum([point]) -> vec3",
     "Σ (x − point) × m v + I_world ω about the world point (default the origin) (kg m²/s)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__newindex", world_newindex, "world.__newindex", "w.gravity = g",
     "Sets gravity, integrator, gyroscopic, substeps or a contact solver setting (see\n"
     "help(\"world\"))."},
    {"__tostring", world_tostring, "world.__tostring", "tostring(w)",
     "Short form: world(3 bodies, t=1.5, semi_implicit)."},
    {"__gc", world_gc, "world.__gc", "", "Releases the world; its bodies stay valid."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry index_entry[] = {
    {"__index", world_index, "world.__index", "w.time, w:method()", "Fields and methods."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry step_entry[] = {
    {"step", world_step, "world:step", "w:step(dt [, n])",
     "Advances the world by n steps (default 1) of dt seconds, each in `substeps` substeps,\n"
     "with the world's integrator. Forces applied with b:apply_force before the call act\n"
     "during the first step and are then cleared. If any body would get a non-finite state,\n"
     "or a force callback raises an error, nothing is changed and the error names the body\n"
     "(its index in w:bodies()) and the time. n is at most 100000000."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry call_entry[] = {
    {"__call", world_call, "world",
     "world{gravity =, integrator =, gyroscopic =, substeps =, iterations =, "
     "position_iterations =, restitution_threshold =, slop =, baumgarte =, max_correction =, "
     "speculative_distance =} -> world",
     "A world of rigid bodies. gravity (vec3, m/s²) default vec3(0, -9.81, 0);\n"
     "integrator: \"euler\" (explicit: positions from the old velocities), \"semi_implicit\"\n"
     "(default; velocities first, positions from the new ones) or \"rk4\" (classical 4th\n"
     "order on the whole state, gyroscopic term included); gyroscopic, for the Euler methods:\n"
     "\"implicit\" (default; one Newton step on ω × Iω per substep, stable), \"explicit\" (gains\n"
     "energy) or \"off\" (refused on an rk4 world, which would ignore it; switching to rk4\n"
     "needs gyroscopic = \"implicit\"); substeps (default 1) per w:step(dt).\n"
     "Contacts: bodies with a shape collide with each other and with planes (w:add_plane).\n"
     "Fields: time (read-only), gravity, integrator, gyroscopic, substeps and the contact\n"
     "solver settings below (read/write).\n"
     "Methods: add, remove, bodies, add_force, add_spring, add_drag, add_plane, planes,\n"
     "contacts, step, kinetic_energy, potential_energy, energy, linear_momentum,\n"
     "angular_momentum."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

// Registers the methods into the table at `table_index`.
void register_methods(lua_State* L, int table_index) {
  register_entries(L, table_index, methods);
  register_entries(L, table_index, step_entry);
}

}  // namespace

void open_world(lua_State* L, int lib) {
  new_metatable(L, "world", &world_metatable_key);
  register_entries(L, -1, metamethods);
  lua_newtable(L);  // methods, the upvalue of __index
  register_methods(L, -1);
  register_entries(L, -2, index_entry, 1);
  lua_pop(L, 1);

  lua_newtable(L);  // the callable `world` table
  register_methods(L, -1);  // world.step(w, dt) works as w:step(dt)
  lua_newtable(L);
  register_entries(L, -1, call_entry);
  lua_pushliteral(L, "world");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  // The topic's text lives as long as the program: help() keeps the pointer.
  static const std::string doc = std::string(call_entry[0].doc) + "\n" + contact_settings_doc;
  register_topic(L, -1, "world", doc.c_str());
  lua_setfield(L, lib, "world");
}

}  // namespace rigidlab::lua
