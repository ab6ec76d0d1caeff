// The world's force elements (force callbacks, springs, drag), planes, contacts and w:step:
// the methods of lua/world.cpp that attach things to bodies by index or run Lua code inside
// the engine. Each reads every argument and option field first (their metamethods may add or
// remove bodies, or finalise the world by hand), then takes the world and the body indices
// (lua/world.hpp), and changes nothing when it fails.
#include <functional>
#include <string>
#include <vector>

#include "lua/binding.hpp"
#include "lua/body.hpp"
#include "lua/world.hpp"

namespace rigidlab::lua {
namespace {

// The world's list of force callback functions (push_world_table).
const char callbacks_key = 0;
// w:step(dt, n): n is bounded so a typo cannot start a run of years; long runs can be split.
constexpr lua_Integer max_steps_per_call = 100'000'000;

// ---- force callbacks -------------------------------------------------------------------------

// The world userdata is argument 1 of the running w:step on box->running: callbacks get it and
// the stage time. A Lua error raised inside propagates (as a C++ exception, Lua being compiled
// as C++) through World::step, which undoes the step.
void call_lua_force(LuaWorld& box, lua_Integer index, double t) {
  lua_State* L = box.running;
  luaL_checkstack(L, 4, "force callback");
  push_world_table(L, 1, &callbacks_key);
  lua_rawgeti(L, -1, index);
  lua_pushvalue(L, 1);
  lua_pushnumber(L, t);
  lua_call(L, 2, 0);
  lua_pop(L, 1);
}

int world_add_force(lua_State* L) {
  check_world(L, 1);
  if (lua_type(L, 2) != LUA_TFUNCTION) type_error(L, 2, "function");
  check_no_extra_args(L, 2);
  LuaWorld& w = check_world_unlocked(L, 1, "add a force");
  push_world_table(L, 1, &callbacks_key);
  const auto index = static_cast<lua_Integer>(lua_rawlen(L, 3)) + 1;
  lua_pushvalue(L, 2);
  lua_rawseti(L, 3, index);  // may raise Lua's memory error: nothing has changed yet
  LuaWorld* box = &w;
  const Failure failure = try_call([&] {
    w.world.add_force([box, index](World&, double t) { call_lua_force(*box, index, t); });
  });
  if (failure) {
    lua_pushnil(L);
    lua_rawseti(L, 3, index);
    failure.raise(L);
  }
  return 0;
}

// ---- springs and drag ------------------------------------------------------------------------

// Pushes the option fields `names` of the table at 2, in order: they are read (and their
// metamethods run) before anything else is looked at.
void push_fields(lua_State* L, std::initializer_list<const char*> names) {
  for (const char* name : names) get_field(L, 2, name);
}

// The body of field `name` (its value at stack `value`) in world w: its id, or no_body_id when
// absent and not required.
BodyId field_member(lua_State* L, const LuaWorld& w, int value, const char* name,
                    bool required) {
  if (lua_isnil(L, value)) {
    if (required) arg_error(L, 2, "field '%s' is required", name);
    return no_body_id;
  }
  return w.world.store().id_at(check_member(L, w, value, Where::field(2, name)));
}

int world_add_spring(lua_State* L) {
  check_world(L, 1);
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  check_no_extra_args(L, 2);
  static const char* const fields[] = {"a", "a_point", "b", "b_point", "anchor", "k",
                                       "damping", "rest_length", nullptr};
  check_fields(L, 2, fields);
  Spring s;
  s.a_point = field_vec3(L, 2, "a_point", Vec3::Zero(), false);
  s.b_point = field_vec3(L, 2, "b_point", Vec3::Zero(), false);
  s.anchor = field_vec3(L, 2, "anchor", Vec3::Zero(), false);
  s.stiffness = field_nonnegative(L, 2, "k", 0.0, true);
  s.damping = field_nonnegative(L, 2, "damping", 0.0, false);
  s.rest_length = field_nonnegative(L, 2, "rest_length", 0.0, false);
  lua_settop(L, 2);
  push_fields(L, {"a", "b", "anchor", "b_point"});  // 3, 4, 5, 6: kept alive on the stack
  // Every field has been read: no Lua code runs from here on until the spring is added.
  const LuaWorld& w = check_world_unlocked(L, 1, "add a spring");
  s.a = field_member(L, w, 3, "a", true);
  s.b = field_member(L, w, 4, "b", false);
  const bool has_anchor = !lua_isnil(L, 5), has_b_point = !lua_isnil(L, 6);
  if (!s.b.valid() && !has_anchor)
    arg_error(L, 2, "field 'b' (a body) or 'anchor' (a world point) is required");
  if (s.b.valid() && has_anchor) arg_error(L, 2, "fields 'b' and 'anchor' exclude each other");
  if (!s.b.valid() && has_b_point) arg_error(L, 2, "field 'b_point' needs field 'b'");
  if (s.a == s.b) arg_error(L, 2, "fields 'a' and 'b' must be different bodies");
  protect(L, 2, [&] { check_world(L, 1).world.add_spring(s); });
  return 0;
}

int world_add_drag(lua_State* L) {
  check_world(L, 1);
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  check_no_extra_args(L, 2);
  static const char* const fields[] = {"body", "linear", "angular", nullptr};
  check_fields(L, 2, fields);
  Drag d;
  d.linear = field_nonnegative(L, 2, "linear", 0.0, false);
  d.angular = field_nonnegative(L, 2, "angular", 0.0, false);
  lua_settop(L, 2);
  push_fields(L, {"body"});  // 3
  LuaWorld& w = check_world_unlocked(L, 1, "add drag");
  d.body = field_member(L, w, 3, "body", true);
  protect(L, 2, [&] { w.world.add_drag(d); });
  return 0;
}

// ---- planes and contacts ---------------------------------------------------------------------

int world_add_plane(lua_State* L) {
  check_world(L, 1);
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
    arg_error(L, 2, "field 'normal' must be a non-zero vector, got (0, 0, 0)");
  const double offset = field_finite(L, 2, "offset", 0.0, false);
  double restitution = 0.0, friction = 0.0;
  read_material_fields(L, 2, restitution, friction);
  LuaWorld& w = check_world_unlocked(L, 1, "add a plane");
  // The plane as the engine stores it (unit normal, offset/|normal|): a normal too short for
  // its offset is the table's fault, "bad argument #1 to 'world:add_plane' (offset / |normal|
  // must be finite, ...)".
  const Plane plane =
      protect(L, 2, [&] { return make_plane(normal, offset, restitution, friction); });
  const std::size_t index = protect(L, 2, [&] { return w.world.add_plane(plane); });
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

// Lua allocations below may run finalisers, which may change the world (w:add_plane, w:step):
// the lists are copied before any table is made.
int world_planes(lua_State* L) {
  const std::vector<Plane> planes = check_world(L, 1).world.planes();
  check_no_extra_args(L, 1);
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

// The touching points of the last substep, all with one convention: the normal points from a
// to b and the impulses are b's (a got the opposite). Against a plane, a is the plane (field
// a = nil, plane = its index) and b the body: the normal is the plane's, the impulses the
// body's.
int world_contacts(lua_State* L) {
  const World& world = check_world(L, 1).world;
  const std::vector<ContactInfo> contacts = world.contacts();
  check_no_extra_args(L, 1);
  lua_newtable(L);
  lua_Integer n = 0;
  for (const ContactInfo& c : contacts) {
    if (!touched(c)) continue;
    lua_createtable(L, 0, 10);
    if (!c.a.valid()) {
      lua_pushinteger(L, static_cast<lua_Integer>(c.plane) + 1);
      lua_setfield(L, -2, "plane");
    } else {
      push_world_body(L, 1, world.store().index_of(c.a));
      lua_setfield(L, -2, "a");
    }
    push_world_body(L, 1, world.store().index_of(c.b));
    lua_setfield(L, -2, "b");
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
  if (!lua_isnoneornil(L, 3))
    n = check_integer(L, 3, Where::argument(3, "n"), 1, max_steps_per_call);
  check_no_extra_args(L, 3);
  if (w.world.stepping())  // self is the bad argument: "calling 'world:step' on bad self (...)"
    arg_error(L, 1, "the world is already stepping: a force callback cannot step its own world");
  lua_settop(L, 1);
  // The engine polls the stop check (Ctrl-C, a time limit) inside its long loops: a step of
  // any size can be stopped, and that step is then undone (the ones before it are kept).
  const StopPoller stop(L);
  const std::function<void()> poll = [&stop] { stop.poll(); };
  RunningState running(w, L);
  Failure failure;  // the engine's own errors (lua/binding.hpp protect, spelt out)
  try {
    w.world.step(dt, static_cast<long>(n), poll);
  } catch (const std::bad_alloc& e) {
    failure.hold(e);
  } catch (const std::exception& e) {
    failure.hold(e);
  } catch (...) {
    // A Lua error from a force callback or the stop check unwinds through here as a C++
    // exception (Lua built as C++), its message on top of this thread's stack (ldo.c
    // luaD_throw): it gets the steps kept appended, then goes on. (The engine's own errors
    // say so themselves.)
    if (n > 1 && lua_type(L, -1) == LUA_TSTRING) {
      lua_pushfstring(L, "%s (%I of %I steps completed; the world is at t = %s s)",
                      lua_tostring(L, -1), static_cast<lua_Integer>(w.world.steps_completed()), n,
                      format_number(w.world.time()).c_str());
      lua_replace(L, -2);
    }
    throw;
  }
  if (failure) failure.raise(L);
  return 0;
}

const Entry methods[] = {
    {"add_force", world_add_force, "world:add_force", "w:add_force(fn)",
     "fn(w, t) is called at every force evaluation (once per substep for the Euler methods,\n"
     "at each of the four stages of rk4, the bodies then holding the stage's state and\n"
     "w.time = t) and applies forces with b:apply_force / b:apply_torque. An error in fn\n"
     "stops w:step: the step it happened in is undone, the steps before it are kept."},
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
     "Contacts are solved by the world's solver (w.solver) with `iterations` sweeps;\n"
     "impacts faster than restitution_threshold bounce with the pair's restitution (see\n"
     "help(\"world\") for the solver's settings and limits)."},
    {"step", world_step, "world:step", "w:step(dt [, n])",
     "Advances the world by n steps (default 1) of dt seconds, each in `substeps` substeps,\n"
     "with the world's integrator and solver. Forces applied with b:apply_force before the\n"
     "call act during the first step and are then cleared. If any body would get a\n"
     "non-finite state, a force callback raises an error, or the run is stopped (Ctrl-C, a\n"
     "limit), the step it happened in is undone and the steps before it are kept; the error\n"
     "names the body (its index in w:bodies()) and the time, and says how many of the n\n"
     "steps completed. The state a step leaves is the state at the end of the step: after an\n"
     "impact, the velocities are the post-impact ones. n is at most 100000000."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_world_forces(lua_State* L) { add_methods(L, world_type, methods); }

}  // namespace rigidlab::lua
