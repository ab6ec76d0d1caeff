// articulation: a tree of links in reduced coordinates (engine/articulation.hpp; document 000
// "Coordinate simulation", "Featherstone's Algorithm"). The type, its properties, the
// constructor, links, state, torques, controls and the step; the algorithms' queries are in
// lua/articulation_dynamics.cpp and the link type in lua/articulation_link.cpp.
#include "lua/articulation.hpp"

#include <string>

#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

const char articulation_metatable_key = 0;
constexpr std::uint64_t articulation_tag = 0x6172'7469'7269'646cULL;  // arbitrary, distinct
constexpr int links_slot = 1;
constexpr int controls_slot = 2;
// art:step(dt, n): bounded so a typo cannot start a run of years, as w:step.
constexpr lua_Integer max_steps_per_call = 100'000'000;

using ArticulationBox = Tagged<LuaArticulation>;
static_assert(alignof(ArticulationBox) <= 8, "Lua userdata is only 8-byte aligned");

const char* const stepping_rule =
    "the articulation is stepping: cannot %s until articulation:step returns; a control may "
    "only return torques";

void check_settable(lua_State* L, int object, const Where& where) {
  if (check_articulation(L, object).art.stepping()) where.error(L, stepping_rule, "set it");
}

}  // namespace

LuaArticulation* test_articulation(lua_State* L, int index) {
  return test_tagged<LuaArticulation>(L, index, articulation_tag);
}

const TypeSpec articulation_type = {"articulation", &articulation_metatable_key, check_settable};

LuaArticulation& check_articulation(lua_State* L, int arg) {
  LuaArticulation* a = test_articulation(L, arg);
  if (a != nullptr) return *a;
  const auto* box = static_cast<const ArticulationBox*>(lua_touserdata(L, arg));
  if (box != nullptr && lua_rawlen(L, arg) == sizeof(ArticulationBox) && box->tag == 0 &&
      has_metatable(L, arg, &articulation_metatable_key))
    arg_error(L, arg, "the articulation was finalised (its __gc has run)");
  type_error(L, arg, "articulation");
}

LuaArticulation& check_articulation_unlocked(lua_State* L, int arg, const char* what) {
  LuaArticulation& a = check_articulation(L, arg);
  if (a.art.stepping()) arg_error(L, arg, stepping_rule, what);
  return a;
}

Eigen::VectorXd check_numbers(lua_State* L, int arg, const char* what) {
  const lua_Integer n = check_sequence(L, arg, "list of numbers", what);
  Eigen::VectorXd x(n);
  for (lua_Integer k = 1; k <= n; ++k) {
    const int type = lua_rawgeti(L, arg, k);
    if (type != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, -1)))
      arg_error(L, arg, "%s[%d] must be a finite number, got %s", what, static_cast<int>(k),
                type == LUA_TNUMBER ? push_shown_value(L, -1) : value_type_name(L, -1));
    x[k - 1] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return x;
}

void push_numbers(lua_State* L, const Eigen::Ref<const Eigen::VectorXd>& x) {
  lua_createtable(L, static_cast<int>(x.size()), 0);
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    lua_pushnumber(L, x[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

void push_rows(lua_State* L, const Eigen::Ref<const Eigen::MatrixXd>& m) {
  lua_createtable(L, static_cast<int>(m.rows()), 0);
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    push_numbers(L, m.row(r).transpose());
    lua_rawseti(L, -2, r + 1);
  }
}

void push_link(lua_State* L, int object, int link) {
  lua_getiuservalue(L, object, links_slot);
  lua_rawgeti(L, -1, link + 1);
  lua_remove(L, -2);
}

namespace {

// ---- properties ------------------------------------------------------------------------------

void get_time(lua_State* L, int object, const Property&) {
  lua_pushnumber(L, check_articulation(L, object).art.time());
}

void get_q(lua_State* L, int object, const Property&) {
  push_numbers(L, check_articulation(L, object).art.q());
}

void get_qd(lua_State* L, int object, const Property&) {
  push_numbers(L, check_articulation(L, object).art.v());
}

void get_torques(lua_State* L, int object, const Property&) {
  push_numbers(L, check_articulation(L, object).art.torques());
}

void get_base(lua_State* L, int object, const Property&) {
  lua_pushstring(L, base_type_names[int(check_articulation(L, object).art.model().base())]);
}

void get_links(lua_State* L, int object, const Property&) {
  const int n = check_articulation(L, object).art.model().link_count();
  lua_createtable(L, n, 0);
  for (int k = 0; k < n; ++k) {
    push_link(L, object, k);
    lua_rawseti(L, -2, k + 1);
  }
}

void get_gravity(lua_State* L, int object, const Property&) {
  push_vec3(L, check_articulation(L, object).art.gravity());
}

void set_gravity(lua_State* L, int object, int value, const Where& where, const Property&) {
  const Vec3 g = check_vec3(L, value, where);
  Articulation& art = check_articulation(L, object).art;
  protect(L, [&] { art.set_gravity(g); });
}

void get_integrator(lua_State* L, int object, const Property&) {
  lua_pushstring(L, integrator_names[int(check_articulation(L, object).art.integrator())]);
}

void set_integrator(lua_State* L, int object, int value, const Where& where, const Property&) {
  const auto integrator = static_cast<Integrator>(check_option(L, value, where, integrator_names));
  check_articulation(L, object).art.set_integrator(integrator);
}

const Property properties[] = {
    {"time", get_time, nullptr, "s, the articulation's clock", "it advances with art:step",
     nullptr},
    {"gravity", get_gravity, set_gravity, "vec3, m/s², default vec3(0, -9.81, 0)", nullptr,
     nullptr},
    {"integrator", get_integrator, set_integrator,
     "\"euler\", \"semi_implicit\" (default) or \"rk4\", as a world's", nullptr, nullptr},
    {"q", get_q, nullptr,
     "a new list: joint coordinates (rad, m); a free base's x, y, z, qw, qx, qy, qz first",
     "set it with art:set_state(q, qd)", nullptr},
    {"qd", get_qd, nullptr,
     "a new list: joint rates (rad/s, m/s); a free base's world velocity and ω first",
     "set it with art:set_state(q, qd)", nullptr},
    {"torques", get_torques, nullptr, "a new list: the held generalised forces (N·m, N)",
     "set them with art:set_torques(tau)", nullptr},
    {"base", get_base, nullptr, "\"fixed\" or \"free\"", "it is chosen by articulation{base =}",
     nullptr},
    {"links", get_links, nullptr, "a new list of the link objects, in the order added",
     "add links with art:add_link{...}", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

// ---- constructor and finaliser ---------------------------------------------------------------

int articulation_call(lua_State* L) {
  lua_remove(L, 1);  // the articulation table itself
  if (lua_isnone(L, 1)) lua_newtable(L);
  if (!lua_istable(L, 1)) type_error(L, 1, "table");
  check_no_extra_args(L, 1);
  static const char* const extra[] = {"base", "position", "orientation", nullptr};
  check_fields(L, 1, constructor_fields(L, articulation_type, extra));
  BaseType base = BaseType::fixed;
  if (get_field(L, 1, "base") != LUA_TNIL)
    base = static_cast<BaseType>(
        check_option(L, -1, Where::field(1, "base"), base_type_names));
  lua_pop(L, 1);
  const Vec3 position = field_vec3(L, 1, "position", Vec3::Zero(), false);
  Quat orientation = Quat::Identity();
  if (get_field(L, 1, "orientation") != LUA_TNIL) {
    const Quat* q = test_quat(L, -1);
    if (q == nullptr) Where::field(1, "orientation").type_error(L, -1, "quat");
    orientation = *q;
  }
  lua_pop(L, 1);
  void* memory = lua_newuserdatauv(L, sizeof(ArticulationBox), 2);
  auto* box = static_cast<ArticulationBox*>(memory);
  box->tag = 0;  // tagged once whole: a failure leaves a userdata that is no articulation
  const Failure failure = try_call([&] {
    new (&box->value) LuaArticulation{Articulation(base, position, orientation), nullptr};
  });
  if (failure) failure.raise(L, 1);
  box->tag = articulation_tag;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &articulation_metatable_key);
  lua_setmetatable(L, -2);
  for (int slot : {links_slot, controls_slot}) {
    lua_newtable(L);
    lua_setiuservalue(L, -2, slot);
  }
  set_from_table(L, articulation_type, 2, 1);  // gravity, integrator
  return 1;
}

int articulation_gc(lua_State* L) {
  LuaArticulation* a = test_articulation(L, 1);
  if (a == nullptr) return 0;
  if (a->art.stepping())
    arg_error(L, 1, "the articulation is stepping: it cannot be finalised until step returns");
  a->~LuaArticulation();
  static_cast<ArticulationBox*>(lua_touserdata(L, 1))->tag = 0;
  return 0;
}

int articulation_tostring(lua_State* L) {
  const Articulation& art = check_articulation(L, 1).art;
  const int n = art.model().link_count();
  lua_pushfstring(L, "articulation(%d link%s, %d dof, %s base, t=%s, %s)", n, n == 1 ? "" : "s",
                  art.model().nv(), base_type_names[int(art.model().base())],
                  format_number(art.time()).c_str(), integrator_names[int(art.integrator())]);
  return 1;
}

// ---- links -----------------------------------------------------------------------------------

// The mass properties and joint of a link spec from the option table at 2 (its __index may
// run Lua code: everything is read before the articulation is looked at again).
LinkSpec read_link_fields(lua_State* L) {
  LinkSpec spec;
  if (get_field(L, 2, "joint") != LUA_TNIL)
    spec.joint = static_cast<JointType>(
        check_option(L, -1, Where::field(2, "joint"), joint_type_names));
  lua_pop(L, 1);
  spec.axis = field_vec3(L, 2, "axis", Vec3::UnitZ(), false);
  spec.origin = field_vec3(L, 2, "origin", Vec3::Zero(), false);
  spec.mass = field_nonnegative(L, 2, "mass", 1.0, false);
  spec.com = field_vec3(L, 2, "com", Vec3::Zero(), false);
  if (get_field(L, 2, "inertia") != LUA_TNIL) {
    const Mat3* inertia = test_mat3(L, -1);
    if (inertia == nullptr) Where::field(2, "inertia").type_error(L, -1, "mat3");
    spec.inertia = *inertia;
  }
  lua_pop(L, 1);
  if (get_field(L, 2, "name") != LUA_TNIL) spec.name = check_name(L, -1, Where::field(2, "name"));
  lua_pop(L, 1);
  return spec;
}

// The engine states a link's rule starting with the field's name ("axis must be non-zero
// ..."): said as "bad argument #1 to 'articulation:add_link' (field 'axis' must be ...)".
[[noreturn]] void raise_link_failure(lua_State* L, const Failure& failure) {
  if (failure.out_of_memory()) failure.raise(L);
  const std::string message = failure.what();
  for (const char* field : {"axis", "origin", "com", "mass", "inertia", "name"}) {
    const std::string prefix = std::string(field) + " ";
    if (message.rfind(prefix, 0) == 0)
      arg_error(L, 2, "field '%s' %s", field, message.c_str() + prefix.size());
  }
  failure.raise(L, 2);
}

int articulation_add_link(lua_State* L) {
  check_articulation(L, 1);
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  check_no_extra_args(L, 2);
  static const char* const fields[] = {"parent", "joint", "axis", "origin", "mass",
                                       "inertia", "com", "name", nullptr};
  check_fields(L, 2, fields);
  LinkSpec spec = read_link_fields(L);
  lua_settop(L, 2);
  get_field(L, 2, "parent");  // 3: kept on the stack
  // Every field has been read: no Lua code runs from here until the link is added.
  LuaArticulation& a = check_articulation_unlocked(L, 1, "add a link");
  spec.parent = lua_isnil(L, 3) ? -1 : check_link_of(L, 1, 3, Where::field(2, "parent"));
  // The link object first (it may raise Lua's memory error: nothing has changed yet), then
  // the engine's link; a refused link takes its object out again.
  const int link = a.art.model().link_count();
  append_link_object(L, 1, link);
  const Failure failure = try_call([&] {
    if (a.art.model().link_count() != link)  // a finaliser run by that allocation added one
      throw std::invalid_argument("the articulation changed while the link was being added");
    a.art.add_link(spec);
  });
  if (failure) {
    lua_getiuservalue(L, 1, links_slot);
    lua_pushnil(L);
    lua_rawseti(L, -2, link + 1);
    raise_link_failure(L, failure);
  }
  push_link(L, 1, link);
  return 1;
}

int articulation_link(lua_State* L) {
  check_articulation(L, 1);
  check_no_extra_args(L, 2);
  push_link(L, 1, check_link_of(L, 1, 2, Where::argument(2, "link")));
  return 1;
}

// ---- state and torques -----------------------------------------------------------------------

int articulation_set_state(lua_State* L) {
  check_articulation(L, 1);
  const Eigen::VectorXd q = check_numbers(L, 2, "q");
  const Eigen::VectorXd qd = check_numbers(L, 3, "qd");
  check_no_extra_args(L, 3);
  LuaArticulation& a = check_articulation_unlocked(L, 1, "set the state");
  const Failure failure = try_call([&] { a.art.set_state(q, qd); });
  if (failure) {  // blame the list that breaks the rule
    const std::string message = failure.what();
    failure.raise(L, message.rfind("qd", 0) == 0 ? 3 : 2);
  }
  return 0;
}

int articulation_set_torques(lua_State* L) {
  check_articulation(L, 1);
  const Eigen::VectorXd tau = check_numbers(L, 2, "tau");
  check_no_extra_args(L, 2);
  LuaArticulation& a = check_articulation_unlocked(L, 1, "set the torques");
  protect(L, 2, [&] { a.art.set_torques(tau); });
  return 0;
}

// ---- controls --------------------------------------------------------------------------------

// Calls control `index` as fn(art, t) on the thread evaluating the articulation (argument 1 of
// the running art:step or query is the articulation) and adds the list it returns (or nothing
// for nil) to tau. A Lua error raised inside propagates, as a C++ exception (Lua is compiled as
// C++), through Articulation::step, which puts the state back.
void call_control(LuaArticulation& a, lua_Integer index, double t, Eigen::VectorXd& tau) {
  lua_State* L = a.running;
  luaL_checkstack(L, 5, "articulation control");
  lua_getiuservalue(L, 1, controls_slot);
  lua_rawgeti(L, -1, index);
  lua_pushvalue(L, 1);
  lua_pushnumber(L, t);
  lua_call(L, 2, 1);
  const int result = lua_gettop(L);
  const auto n = static_cast<lua_Integer>(tau.size());
  if (!lua_isnil(L, result)) {
    if (!lua_istable(L, result) || static_cast<lua_Integer>(lua_rawlen(L, result)) != n)
      function_error(
          L, "control %d must return nil or a list of %d numbers (tau), got %s",
          static_cast<int>(index), static_cast<int>(n),
          lua_istable(L, result) ? lua_pushfstring(L, "a list of %d", int(lua_rawlen(L, result)))
                                 : value_type_name(L, result));
    for (lua_Integer k = 1; k <= n; ++k) {
      lua_rawgeti(L, result, k);
      if (lua_type(L, -1) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, -1)))
        function_error(L, "control %d returned a tau whose entry %d is not a finite number (%s)",
                       static_cast<int>(index), static_cast<int>(k),
                       lua_type(L, -1) == LUA_TNUMBER ? push_shown_value(L, -1)
                                                      : value_type_name(L, -1));
      tau[k - 1] += lua_tonumber(L, -1);
      lua_pop(L, 1);
    }
  }
  lua_settop(L, result - 2);
}

int articulation_add_control(lua_State* L) {
  check_articulation(L, 1);
  if (lua_type(L, 2) != LUA_TFUNCTION) type_error(L, 2, "function");
  check_no_extra_args(L, 2);
  LuaArticulation& a = check_articulation_unlocked(L, 1, "add a control");
  lua_getiuservalue(L, 1, controls_slot);
  const auto index = static_cast<lua_Integer>(lua_rawlen(L, 3)) + 1;
  lua_pushvalue(L, 2);
  lua_rawseti(L, 3, index);  // may raise Lua's memory error: nothing has changed yet
  LuaArticulation* box = &a;
  const Failure failure = try_call([&] {
    a.art.add_control([box, index](double t, Eigen::VectorXd& tau) {
      call_control(*box, index, t, tau);
    });
  });
  if (failure) {
    lua_pushnil(L);
    lua_rawseti(L, 3, index);
    failure.raise(L);
  }
  return 0;
}

int articulation_clear_controls(lua_State* L) {
  check_no_extra_args(L, 1);
  LuaArticulation& a = check_articulation_unlocked(L, 1, "clear the controls");
  a.art.clear_controls();
  lua_newtable(L);
  lua_setiuservalue(L, 1, controls_slot);
  return 0;
}

// ---- step ------------------------------------------------------------------------------------

int articulation_step(lua_State* L) {
  check_articulation(L, 1);
  const double dt = check_positive(L, 2, "dt");
  lua_Integer n = 1;
  if (!lua_isnoneornil(L, 3))
    n = check_integer(L, 3, Where::argument(3, "n"), 1, max_steps_per_call);
  check_no_extra_args(L, 3);
  LuaArticulation& a = check_articulation(L, 1);
  if (a.art.stepping())  // self is the bad argument: "calling 'articulation:step' on bad self"
    arg_error(L, 1, "the articulation is already stepping: a control cannot step it");
  lua_settop(L, 1);
  const StopPoller stop(L);
  const std::function<void()> poll = [&stop] { stop.poll(); };
  ControlThread thread(a, L);
  protect(L, [&] { a.art.step(dt, static_cast<int>(n), poll); });
  return 0;
}

const Entry methods[] = {
    {"add_link", articulation_add_link, "articulation:add_link",
     "art:add_link{parent =, joint =, axis =, origin =, mass =, inertia =, com =, name =} "
     "-> link",
     "Adds a link and returns it. parent: a link of this articulation (object, number or\n"
     "name) or nil for the base. joint: \"revolute\" (default; turns by q rad about axis),\n"
     "\"prismatic\" (slides q m along axis) or \"fixed\". axis (default vec3(0, 0, 1)) and\n"
     "origin (the joint's position, default the parent's origin) are in the parent's frame;\n"
     "at q = 0 the link frame is the parent frame moved to origin. mass (kg, default 1),\n"
     "com (the centre of mass in the link frame, default 0) and inertia (mat3 about the com,\n"
     "link frame; default 0: a point mass). Each moving joint adds one entry to q, qd and\n"
     "the torques, in the order added."},
    {"link", articulation_link, "articulation:link", "art:link(n or name) -> link",
     "The link numbered n (1 = the first added) or called name."},
    {"set_state", articulation_set_state, "articulation:set_state", "art:set_state(q, qd)",
     "Sets the joint coordinates and rates (lists as art.q and art.qd). A free base's\n"
     "orientation must be a unit quaternion (w, x, y, z)."},
    {"set_torques", articulation_set_torques, "articulation:set_torques", "art:set_torques(tau)",
     "Holds the generalised forces tau (a list as art.qd: N·m for revolute, N for prismatic\n"
     "joints; a free base's world force and torque first) until changed. Document 000\n"
     "\"Joint torques\": a motor at each joint."},
    {"add_control", articulation_add_control, "articulation:add_control", "art:add_control(fn)",
     "fn(art, t) returns a list of generalised forces (or nil) added to the held torques at\n"
     "every evaluation of the dynamics (each RK4 stage, with art.q, art.qd and art.time set to\n"
     "the stage): PD controllers, muscles, anything written in Lua. It may read the\n"
     "articulation but not change it."},
    {"clear_controls", articulation_clear_controls, "articulation:clear_controls",
     "art:clear_controls()", "Removes every control function."},
    {"step", articulation_step, "articulation:step", "art:step(dt [, n])",
     "Advances n (default 1) steps of dt seconds with art.integrator. A step that would leave\n"
     "NaN or Inf, or meets singular dynamics, or whose control raises an error, leaves the\n"
     "state and time as before that step and raises the error."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__tostring", articulation_tostring, "articulation.__tostring", "tostring(art)",
     "Short form: articulation(3 links, 3 dof, fixed base, t=0, rk4)."},
    {"__gc", articulation_gc, "articulation.__gc", "",
     "Releases the articulation (refused while it steps)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry call_entry[] = {
    {"__call", articulation_call, "articulation",
     "articulation{base =, gravity =, integrator =, position =, orientation =} -> art",
     "An articulated body in reduced coordinates (document 000 \"Coordinate simulation\",\n"
     "\"Featherstone's Algorithm\"): a tree of links on revolute, prismatic and fixed joints,\n"
     "whose state is only the joint coordinates q and rates qd. base: \"fixed\" (default: the\n"
     "base frame stays at position, orientation) or \"free\" (a massless frame that floats:\n"
     "its position, orientation and velocities come first in q and qd; give it mass with\n"
     "links on fixed joints). gravity (default vec3(0, -9.81, 0)) and integrator as a\n"
     "world's. Forward dynamics by Featherstone's articulated-body algorithm (O(n))."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_articulation(lua_State* L, int lib) {
  lua_newtable(L);  // the callable `articulation` table
  const int table = lua_gettop(L);
  new_type(L, articulation_type, table, metamethods);
  add_properties(L, articulation_type, properties);
  add_methods(L, articulation_type, methods);
  open_articulation_dynamics(L);
  open_articulation_link(L, lib);
  lua_newtable(L);
  register_entries(L, -1, call_entry);
  lua_pushliteral(L, "articulation");
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, table);
  register_topic(L, table, "articulation", call_entry[0].doc);
  lua_setfield(L, lib, "articulation");
}

}  // namespace rigidlab::lua
