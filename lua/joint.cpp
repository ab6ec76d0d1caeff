// The joint binding (API.md "Joints"): w:add_joint{...}, the joint object's fields and
// methods, w:remove_joint, w:joints, w:solver_report. A joint object is a handle: the
// world's serial number of the joint (engine/world.hpp find_constraint) and, as its user
// value, the world; reading a joint that was removed (w:remove_joint, or the removal of one
// of its bodies) is an error that says so. The world keeps its joints' objects (by serial
// number) so that w:joints() returns the same objects w:add_joint did.
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "engine/joint.hpp"
#include "lua/binding.hpp"
#include "lua/body.hpp"
#include "lua/modules.hpp"
#include "lua/world.hpp"

namespace rigidlab::lua {
namespace {

const char joint_metatable_key = 0;
const char joints_key = 0;  // the world's table: serial number -> joint object
constexpr std::uint64_t joint_tag = 0x6a6f'696e'7472'6c62ULL;
constexpr int world_slot = 1;  // the joint object's user value: its world

struct LuaJoint {
  std::uint64_t serial;
  JointKind type;
};

const TypeSpec joint_type = {"joint", &joint_metatable_key, nullptr};

LuaJoint& check_joint(lua_State* L, int arg) {
  LuaJoint* j = test_tagged<LuaJoint>(L, arg, joint_tag);
  if (j == nullptr) type_error(L, arg, "joint");
  return *j;
}

// The engine joint of the joint object at `object`, with its bodies, or an error in the form
// of the place asking: a field read ("bad field 'angle' of joint (...)") or a method's self.
struct Resolved {
  LuaWorld* world;
  Joint* joint;
  const Body* a;
  const Body* b;  // nullptr: the world
};

Resolved resolve(lua_State* L, int object, const char* field = nullptr) {
  const LuaJoint& handle = check_joint(L, object);
  lua_getiuservalue(L, object, world_slot);
  LuaWorld* w = test_world(L, -1);
  lua_pop(L, 1);
  Joint* joint = w == nullptr ? nullptr
                              : static_cast<Joint*>(w->world.find_constraint(handle.serial));
  if (joint == nullptr) {
    const char* why = w == nullptr ? "its world was finalised"
                                   : "the joint was removed from its world (w:remove_joint, or "
                                     "one of its bodies was removed)";
    if (field != nullptr) field_error(L, "joint", field, "%s", why);
    arg_error(L, 1, "%s", why);
  }
  const BodyStore& store = w->world.store();
  const Body* b = joint->body_b().valid() ? &store.get(joint->body_b()) : nullptr;
  return {w, joint, &store.get(joint->body_a()), b};
}

// ---- reading the definition -------------------------------------------------------------------

// The fields each type takes beyond type, a, b, anchor.
bool takes(JointKind type, const std::string& field) {
  const bool axis = type != JointKind::ball && type != JointKind::fixed &&
                    type != JointKind::distance;
  const bool driven = driven_coordinate(type) != JointCoordinate::none;
  if (field == "axis") return axis;
  if (field == "pitch") return type == JointKind::screw;
  if (field == "a_point" || field == "b_point" || field == "min" || field == "max")
    return type == JointKind::distance;
  if (field == "anchor") return type != JointKind::distance;
  if (field == "lower" || field == "upper" || field == "spring" || field == "motor")
    return driven;
  return true;
}

// A number field of the option table at `table` (stack index), named `name` in messages as
// field `label` of argument `arg`; absent: `fallback`.
double number_field(lua_State* L, int table, int arg, const char* name, const char* label,
                    double fallback, double min, double max, const char* rule) {
  const int index = lua_gettop(L) + 1;
  lua_getfield(L, table, name);
  if (lua_isnil(L, index)) {
    lua_pop(L, 1);
    return fallback;
  }
  const double x = check_number(L, index, Where::field(arg, label), min, max, rule);
  lua_pop(L, 1);
  return x;
}

// motor = {target =, target_rate =, kp =, kv =, max_torque =}, the table at `table`.
JointMotor read_motor(lua_State* L, int table, int arg) {
  static const char* const fields[] = {"target", "target_rate", "kp", "kv", "max_torque", nullptr};
  check_fields(L, table, fields, Where::argument(arg, "field 'motor':"));
  JointMotor m;
  m.target = number_field(L, table, arg, "target", "motor.target", 0.0, -HUGE_VAL, HUGE_VAL,
                          "finite (rad or m)");
  m.target_rate = number_field(L, table, arg, "target_rate", "motor.target_rate", 0.0,
                               -HUGE_VAL, HUGE_VAL, "finite (rad/s or m/s)");
  m.kp = number_field(L, table, arg, "kp", "motor.kp", 0.0, 0.0, HUGE_VAL,
                      "a finite number >= 0 (N m/rad or N/m)");
  m.kv = number_field(L, table, arg, "kv", "motor.kv", 0.0, 0.0, HUGE_VAL,
                      "a finite number >= 0 (N m s/rad or N s/m)");
  const int index = lua_gettop(L) + 1;
  lua_getfield(L, table, "max_torque");  // math.huge allowed: unbounded
  if (!lua_isnil(L, index)) {
    if (lua_type(L, index) != LUA_TNUMBER) Where::field(arg, "motor.max_torque").type_error(L, index, "number");
    m.max_force = lua_tonumber(L, index);
    if (!(m.max_force > 0.0))
      Where::field(arg, "motor.max_torque")
          .error(L, "must be > 0 (N m, or N for a slider; math.huge for no limit), got %s",
                 format_number(m.max_force).c_str());
  }
  lua_pop(L, 1);
  return m;
}

JointSpring read_spring(lua_State* L, int table, int arg) {
  static const char* const fields[] = {"hertz", "damping_ratio", "rest", nullptr};
  check_fields(L, table, fields, Where::argument(arg, "field 'spring':"));
  JointSpring s;
  const int index = lua_gettop(L) + 1;
  if (lua_getfield(L, table, "hertz") == LUA_TNIL)
    Where::field(arg, "spring.hertz").error(L, "is required (Hz, > 0)");
  s.hertz = check_number(L, index, Where::field(arg, "spring.hertz"), 0.0, HUGE_VAL,
                         "a finite number > 0 (Hz)");
  if (!(s.hertz > 0.0))
    Where::field(arg, "spring.hertz").error(L, "must be a finite number > 0 (Hz), got 0");
  lua_pop(L, 1);
  s.damping_ratio = number_field(L, table, arg, "damping_ratio", "spring.damping_ratio", 0.0,
                                 0.0, HUGE_VAL, "a finite number >= 0");
  s.rest = number_field(L, table, arg, "rest", "spring.rest", 0.0, -HUGE_VAL, HUGE_VAL,
                        "finite (rad or m)");
  return s;
}

int world_add_joint(lua_State* L) {
  check_world(L, 1);
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  check_no_extra_args(L, 2);
  static const char* const fields[] = {"type",  "a",     "b",      "anchor",  "axis",
                                       "lower", "upper", "spring", "motor",   "pitch",
                                       "a_point", "b_point", "min",  "max",   "collide",
                                       nullptr};
  check_fields(L, 2, fields);
  JointDef def;
  lua_settop(L, 2);
  lua_getfield(L, 2, "type");  // 3
  if (lua_isnil(L, 3))
    arg_error(L, 2, "field 'type' is required (one of 'ball', 'hinge', 'slider', "
                    "'cylindrical', 'planar', 'screw', 'fixed', 'distance')");
  def.type = static_cast<JointKind>(check_option(L, 3, Where::field(2, "type"), joint_kind_names));
  for (const char* f : fields) {
    if (f == nullptr || takes(def.type, f)) continue;
    if (get_field(L, 2, f) != LUA_TNIL)
      arg_error(L, 2, "field '%s' is not for a %s joint (see help(\"joint.%s\"))", f,
                joint_kind_names[static_cast<int>(def.type)],
                joint_kind_names[static_cast<int>(def.type)]);
    lua_pop(L, 1);
  }
  const bool uses_axis = takes(def.type, "axis");
  if (uses_axis) {
    if (get_field(L, 2, "axis") == LUA_TNIL)
      arg_error(L, 2, "field 'axis' is required for a %s joint (a world direction)",
                joint_kind_names[static_cast<int>(def.type)]);
    lua_pop(L, 1);
    def.axis = field_vec3(L, 2, "axis", Vec3::UnitY(), true);
    if (def.axis.isZero())
      arg_error(L, 2, "field 'axis' must be a non-zero vector, got (0, 0, 0)");
  }
  def.pitch = field_finite(L, 2, "pitch", 0.0, false);
  def.a_point = field_vec3(L, 2, "a_point", Vec3::Zero(), false);
  def.b_point = field_vec3(L, 2, "b_point", Vec3::Zero(), false);
  if (get_field(L, 2, "min") != LUA_TNIL) def.min_length = field_nonnegative(L, 2, "min", 0, true);
  lua_pop(L, 1);
  if (get_field(L, 2, "max") != LUA_TNIL) {
    const int index = lua_gettop(L);
    def.max_length = check_number(L, index, Where::field(2, "max"), 0.0, HUGE_VAL,
                                  "a number > 0 (m; math.huge for none)");
  }
  lua_pop(L, 1);
  def.lower = number_field(L, 2, 2, "lower", "lower", -HUGE_VAL, -HUGE_VAL, HUGE_VAL,
                           "a number (rad or m)");
  def.upper = number_field(L, 2, 2, "upper", "upper", HUGE_VAL, -HUGE_VAL, HUGE_VAL,
                           "a number (rad or m)");
  if (get_field(L, 2, "spring") != LUA_TNIL) {
    if (!lua_istable(L, -1)) Where::field(2, "spring").type_error(L, lua_gettop(L), "table");
    def.spring = read_spring(L, lua_gettop(L), 2);
  }
  lua_pop(L, 1);
  if (get_field(L, 2, "motor") != LUA_TNIL) {
    if (!lua_istable(L, -1)) Where::field(2, "motor").type_error(L, lua_gettop(L), "table");
    def.motor = read_motor(L, lua_gettop(L), 2);
  }
  lua_pop(L, 1);
  if (get_field(L, 2, "collide") != LUA_TNIL)
    def.collide = check_boolean(L, lua_gettop(L), Where::field(2, "collide"));
  lua_pop(L, 1);
  const bool has_anchor = get_field(L, 2, "anchor") != LUA_TNIL;  // 4
  lua_pop(L, 1);
  const Vec3 anchor = field_vec3(L, 2, "anchor", Vec3::Zero(), false);
  const bool has_b_point = get_field(L, 2, "b_point") != LUA_TNIL;
  lua_pop(L, 1);
  lua_settop(L, 3);
  get_field(L, 2, "a");  // 4
  get_field(L, 2, "b");  // 5
  // Every field has been read: no Lua code runs from here on until the joint is added.
  LuaWorld& w = check_world_unlocked(L, 1, "add a joint");
  if (lua_isnil(L, 4)) arg_error(L, 2, "field 'a' (a body) is required");
  const std::size_t a_index = check_member(L, w, 4, Where::field(2, "a"));
  const std::size_t b_index = lua_isnil(L, 5) ? no_body : check_member(L, w, 5, Where::field(2, "b"));
  if (a_index == b_index) arg_error(L, 2, "fields 'a' and 'b' must be different bodies");
  World& world = w.world;
  def.a = world.store().id_at(a_index);
  def.b = b_index == no_body ? no_body_id : world.store().id_at(b_index);
  def.anchor = has_anchor ? anchor : world.bodies()[a_index].position;
  if (def.type == JointKind::distance && b_index == no_body && !has_b_point)
    arg_error(L, 2, "field 'b_point' (the world point the rod hangs from) is required for a "
                    "distance joint to the world");
  // The Lua object first (its allocation may fail), then the joint.
  const std::uint64_t serial = world.next_joint_serial();
  auto* box = static_cast<Tagged<LuaJoint>*>(lua_newuserdatauv(L, sizeof(Tagged<LuaJoint>), 1));
  *box = {joint_tag, {serial, def.type}};
  lua_rawgetp(L, LUA_REGISTRYINDEX, &joint_metatable_key);
  lua_setmetatable(L, -2);
  lua_pushvalue(L, 1);
  lua_setiuservalue(L, -2, world_slot);  // 6
  push_world_table(L, 1, &joints_key);   // 7
  lua_pushvalue(L, 6);
  lua_rawseti(L, 7, static_cast<lua_Integer>(serial));
  LuaWorld& again = check_world(L, 1);  // allocations above may have run finalisers
  const Failure failure = try_call([&] {
    World& wd = again.world;
    const BodyStore& store = wd.store();
    if (!store.contains(def.a) || (def.b.valid() && !store.contains(def.b)))
      throw std::invalid_argument("a body of the joint left the world while it was made");
    const Body* b = def.b.valid() ? &store.get(def.b) : nullptr;
    wd.add_constraint(std::make_unique<Joint>(def, store.get(def.a), b));
  });
  if (failure) {
    lua_pushnil(L);
    lua_rawseti(L, 7, static_cast<lua_Integer>(serial));
    failure.raise(L, 2);
  }
  lua_settop(L, 6);
  return 1;
}

int world_remove_joint(lua_State* L) {
  check_world(L, 1);
  check_joint(L, 2);
  check_no_extra_args(L, 2);
  LuaWorld& w = check_world_unlocked(L, 1, "remove a joint");
  lua_getiuservalue(L, 2, world_slot);
  const bool same = lua_rawequal(L, -1, 1);
  lua_pop(L, 1);
  if (!same) arg_error(L, 2, "the joint belongs to another world");
  Constraint* joint = w.world.find_constraint(check_joint(L, 2).serial);
  if (joint == nullptr) arg_error(L, 2, "the joint was already removed from this world");
  const std::uint64_t serial = joint->serial();
  protect(L, 2, [&] { w.world.remove_constraint(*joint); });
  push_world_table(L, 1, &joints_key);
  lua_pushnil(L);
  lua_rawseti(L, -2, static_cast<lua_Integer>(serial));
  return 0;
}

int world_joints(lua_State* L) {
  check_world(L, 1);
  check_no_extra_args(L, 1);
  const std::size_t count = check_world(L, 1).world.constraint_count();
  lua_createtable(L, static_cast<int>(count), 0);  // 2
  push_world_table(L, 1, &joints_key);             // 3
  // The list may allocate; serials are read again each time through the world.
  for (std::size_t i = 0; i < count; ++i) {
    World& world = check_world(L, 1).world;
    if (i >= world.constraint_count()) break;
    lua_rawgeti(L, 3, static_cast<lua_Integer>(world.constraint(i).serial()));
    lua_rawseti(L, 2, static_cast<lua_Integer>(i) + 1);
  }
  lua_settop(L, 2);
  return 1;
}

int world_solver_report(lua_State* L) {
  check_world(L, 1);
  check_no_extra_args(L, 1);
  const std::size_t n = check_world(L, 1).world.solver_report().size();
  lua_createtable(L, static_cast<int>(n), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double>& report = check_world(L, 1).world.solver_report();
    if (i >= report.size()) break;
    lua_pushnumber(L, report[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
  }
  return 1;
}

// ---- the joint's fields ----------------------------------------------------------------------

void get_type(lua_State* L, int object, const Property&) {
  lua_pushstring(L, joint_kind_names[static_cast<int>(check_joint(L, object).type)]);
}

void get_body(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  const bool is_a = p.data == nullptr;
  const BodyId id = is_a ? r.joint->body_a() : r.joint->body_b();
  if (!id.valid()) {
    lua_pushnil(L);
    return;
  }
  const std::size_t index = r.world->world.store().index_of(id);
  lua_getiuservalue(L, object, world_slot);
  push_world_body(L, lua_gettop(L), index);
  lua_remove(L, -2);
}

void get_angle(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  if (!has_angle(r.joint->type()))
    field_error(L, "joint", p.name, "a %s joint has no angle (hinge, cylindrical, planar and "
                "screw joints have)", joint_kind_names[static_cast<int>(r.joint->type())]);
  lua_pushnumber(L, r.joint->angle(*r.a, r.b));
}

void get_offset(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  if (!has_offset(r.joint->type()))
    field_error(L, "joint", p.name, "a %s joint has no offset (slider, cylindrical and screw "
                "joints have)", joint_kind_names[static_cast<int>(r.joint->type())]);
  lua_pushnumber(L, r.joint->offset(*r.a, r.b));
}

void get_rate(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  const JointKind t = r.joint->type();
  if (driven_coordinate(t) == JointCoordinate::none && t != JointKind::distance)
    field_error(L, "joint", p.name, "a %s joint has no single coordinate (hinge, slider, "
                "cylindrical, screw and distance joints have)", joint_kind_names[static_cast<int>(t)]);
  lua_pushnumber(L, r.joint->rate(*r.a, r.b));
}

void get_length(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  if (r.joint->type() != JointKind::distance)
    field_error(L, "joint", p.name, "only distance joints have a length");
  lua_pushnumber(L, r.joint->length(*r.a, r.b));
}

void get_impulse(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  push_finite(L, p.data == nullptr ? r.joint->step_impulse() : r.joint->step_angular_impulse(),
              1);
}

void get_motor_torque(lua_State* L, int object, const Property& p) {
  lua_pushnumber(L, resolve(L, object, p.name).joint->motor_force());
}

void get_anchor(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  push_finite(L, r.joint->world_anchor(*r.a), 1);
}

void get_axis(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  push_finite(L, r.joint->world_axis(r.b), 1);
}

void get_limit(lua_State* L, int object, const Property& p) {
  const Resolved r = resolve(L, object, p.name);
  lua_pushnumber(L, p.data == nullptr ? r.joint->lower() : r.joint->upper());
}

void get_pitch(lua_State* L, int object, const Property& p) {
  lua_pushnumber(L, resolve(L, object, p.name).joint->pitch());
}

void get_collide(lua_State* L, int object, const Property& p) {
  lua_pushboolean(L, resolve(L, object, p.name).joint->collide());
}

const char upper_marker = 0;  // Property::data of the second of a pair

const Property properties[] = {
    {"type", get_type, nullptr,
     "\"ball\", \"hinge\", \"slider\", \"cylindrical\", \"planar\", \"screw\", \"fixed\" or "
     "\"distance\" (help(\"joint.hinge\"), ...)", "it is chosen at creation", nullptr},
    {"a", get_body, nullptr, "the first body", "a joint keeps its bodies", nullptr},
    {"b", get_body, nullptr, "the second body, or nil: the world", "a joint keeps its bodies",
     &upper_marker},
    {"angle", get_angle, nullptr,
     "rad: the turn of a relative to b about the axis (right hand), 0 at creation, counted "
     "past ±π in whole turns (hinge, cylindrical, planar, screw)", "it follows the bodies",
     nullptr},
    {"offset", get_offset, nullptr,
     "m: the displacement of a's anchor from b's along the axis, 0 at creation (slider, "
     "cylindrical, screw)", "it follows the bodies", nullptr},
    {"rate", get_rate, nullptr,
     "rad/s or m/s: d/dt of the driven coordinate (hinge, screw: angle; slider, cylindrical: "
     "offset; distance: length)", "it follows the bodies", nullptr},
    {"length", get_length, nullptr, "m: distance joints, the distance between the two points",
     "it follows the bodies", nullptr},
    {"impulse", get_impulse, nullptr,
     "vec3, N s: the linear constraint impulse b received in the last step (a got the "
     "opposite)", "the solver sets it", nullptr},
    {"angular_impulse", get_impulse, nullptr,
     "vec3, N m s: the angular impulse of the joint's angular rows on b in the last step (a "
     "got the opposite)", "the solver sets it", &upper_marker},
    {"motor_torque", get_motor_torque, nullptr,
     "N m (N for an offset): the motor's torque in the last substep, 0 without a motor",
     "the solver sets it", nullptr},
    {"anchor", get_anchor, nullptr, "vec3, m: the anchor as a carries it now (world)",
     "it follows the bodies", nullptr},
    {"axis", get_axis, nullptr, "vec3: the unit axis as b (or the world) carries it now",
     "it follows the bodies", nullptr},
    {"lower", get_limit, nullptr, "the lower limit (-math.huge: none)", "use j:set_limits",
     nullptr},
    {"upper", get_limit, nullptr, "the upper limit (math.huge: none)", "use j:set_limits",
     &upper_marker},
    {"pitch", get_pitch, nullptr, "m per turn (screw joints; 0 for others)",
     "it is chosen at creation", nullptr},
    {"collide", get_collide, nullptr,
     "whether a and b still collide with each other (default false: jointed parts often touch "
     "where they are joined)",
     "it is chosen at creation", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

// ---- the joint's methods ---------------------------------------------------------------------

int joint_error(lua_State* L) {
  check_joint(L, 1);
  check_no_extra_args(L, 1);
  const Resolved r = resolve(L, 1);
  double position = 0.0, angle = 0.0;
  r.joint->error(*r.a, r.b, position, angle);
  lua_pushnumber(L, position);
  lua_pushnumber(L, angle);
  return 2;
}

// A changed joint wakes its bodies' sleeping island (engine/islands.hpp): a new motor target
// must not wait for something else to wake them.
void wake_bodies(const Resolved& r) {
  World& w = r.world->world;
  w.wake(r.joint->body_a());
  if (r.joint->body_b().valid()) w.wake(r.joint->body_b());
}

// j:set_motor / j:set_spring: reads the table (or nil) at argument 2 with `read`, then
// changes the joint with `set`.
template <class T, class Read, class Set>
int set_drive(lua_State* L, Read read, Set set, const char* what) {
  check_joint(L, 1);
  check_no_extra_args(L, 2);
  std::optional<T> drive;
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_istable(L, 2)) type_error(L, 2, "table or nil");
    drive = read(L, 2, 2);
  }
  const Resolved r = resolve(L, 1);
  if (r.world->world.stepping()) stepping_error(L, 1, what);
  protect(L, 2, [&] {
    set(*r.joint, drive);
    wake_bodies(r);
  });
  return 0;
}

int joint_set_motor(lua_State* L) {
  return set_drive<JointMotor>(
      L, read_motor, [](Joint& j, const std::optional<JointMotor>& m) { j.set_motor(m); },
      "change a joint's motor");
}

int joint_set_spring(lua_State* L) {
  return set_drive<JointSpring>(
      L, read_spring, [](Joint& j, const std::optional<JointSpring>& s) { j.set_spring(s); },
      "change a joint's spring");
}

int joint_set_limits(lua_State* L) {
  check_joint(L, 1);
  check_no_extra_args(L, 3);
  const double lower = lua_isnoneornil(L, 2) ? -HUGE_VAL
                                             : check_number(L, 2, Where::argument(2, "lower"),
                                                            -HUGE_VAL, HUGE_VAL, "a number");
  const double upper = lua_isnoneornil(L, 3) ? HUGE_VAL
                                             : check_number(L, 3, Where::argument(3, "upper"),
                                                            -HUGE_VAL, HUGE_VAL, "a number");
  const Resolved r = resolve(L, 1);
  if (r.world->world.stepping()) stepping_error(L, 1, "change a joint's limits");
  protect(L, 2, [&] {
    r.joint->set_limits(lower, upper);
    wake_bodies(r);
  });
  return 0;
}

int joint_tostring(lua_State* L) {
  const LuaJoint& j = check_joint(L, 1);
  lua_pushfstring(L, "joint: %s (%p)", joint_kind_names[static_cast<int>(j.type)],
                  lua_topointer(L, 1));
  return 1;
}

const Entry methods[] = {
    {"error", joint_error, "joint:error", "j:error() -> position_error, angle_error",
     "How far the joint is from holding: the root sum of squares of the errors of its rows\n"
     "that hold (equality rows, and limits that are violated), in m and in rad."},
    {"set_motor", joint_set_motor, "joint:set_motor",
     "j:set_motor{target =, target_rate =, kp =, kv =, max_torque =} or j:set_motor(nil)",
     "A PD motor on the joint's coordinate (document 000 \"PD controller\"):\n"
     "τ = kp (target − θ) + kv (target_rate − θ̇), clamped to ±max_torque (a force for an\n"
     "offset). Solved inside the velocity iterations and integrated exactly over each\n"
     "substep, so a stiff motor stays stable. Defaults: 0 for all but max_torque (math.huge).\n"
     "nil removes the motor."},
    {"set_spring", joint_set_spring, "joint:set_spring",
     "j:set_spring{hertz =, damping_ratio =, rest =} or j:set_spring(nil)",
     "A soft spring on the joint's coordinate toward rest (rad or m): a damped oscillator of\n"
     "`hertz` and `damping_ratio` per unit effective mass, integrated exactly. nil removes it."},
    {"set_limits", joint_set_limits, "joint:set_limits", "j:set_limits(lower, upper)",
     "Limits of the joint's coordinate (rad for an angle, m for an offset); nil for none.\n"
     "A limit row acts only when violated, or when the coordinate would cross it in the\n"
     "substep (speculative)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {{"__tostring", joint_tostring, "joint.__tostring", "tostring(j)", ""},
                             {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry world_methods[] = {
    {"add_joint", world_add_joint, "world:add_joint",
     "w:add_joint{type =, a =, b =, anchor =, axis =, lower =, upper =, ...} -> joint",
     "A joint between body a and body b (nil: the world), in maximal coordinates: rows of the\n"
     "world's solver (document 000 \"Kinematic pair\", \"Sequential impulses\"). type: \"ball\",\n"
     "\"hinge\", \"slider\", \"cylindrical\", \"planar\", \"screw\", \"fixed\", \"distance\"\n"
     "(help(\"joint.hinge\") and so on). anchor (world point, default a's position) and axis\n"
     "(world direction, any length; required where the type has one) are taken now: the joint\n"
     "holds the relation they have at creation. lower/upper limit the coordinate; spring =\n"
     "{hertz =, damping_ratio =, rest =}; motor = {target =, target_rate =, kp =, kv =,\n"
     "max_torque =}. Distance: a_point, b_point (body frames; for the world a world point),\n"
     "min, max (a rope). collide (default false): whether a and b still collide with each\n"
     "other. help(\"joint\") lists the joint's fields."},
    {"remove_joint", world_remove_joint, "world:remove_joint", "w:remove_joint(j)",
     "Removes the joint. Removing a body removes its joints too."},
    {"joints", world_joints, "world:joints", "w:joints() -> {joint, ...}",
     "The world's joints, in the order they were added."},
    {"solver_report", world_solver_report, "world:solver_report",
     "w:solver_report() -> {error, ...}",
     "After a step: one entry per velocity iteration of its last substep, the largest\n"
     "constraint velocity error (m/s or rad/s) of any joint row or contact before that\n"
     "iteration updated it (a row resting at a bound of its impulse counts as satisfied):\n"
     "the iterations converging."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

// help("joint.hinge") and so on: the table of API.md "Joints" with what each coordinate is.
struct TypeHelp {
  const char* name;
  const char* qualified;
  const char* doc;
};
const TypeHelp type_help[] = {
    {"ball", "joint.ball",
     "ball joint (spherical pair, 000 \"Kinematic pair\"): 3 rotational DOF. The anchor\n"
             "points of a and b coincide (3 rows). Fields: anchor. No angle, offset or rate."},
    {"hinge", "joint.hinge",
     "hinge joint (revolute pair): 1 rotational DOF about `axis` through `anchor` (3\n"
              "point rows, 2 angular rows). angle: of a relative to b about the axis, right\n"
              "hand, 0 at creation, counted in turns. lower/upper (rad), spring, motor (N m)."},
    {"slider", "joint.slider",
     "slider joint (prismatic pair): 1 translational DOF along `axis` (2 point rows\n"
               "across it, 3 angular rows). offset: of a's anchor from b's along the axis (m,\n"
               "0 at creation). lower/upper (m), spring, motor (its max_torque a force, N)."},
    {"cylindrical", "joint.cylindrical",
     "cylindrical joint: 1 rotation about and 1 translation along `axis` (2 point\n"
                    "rows, 2 angular rows). angle and offset as hinge and slider; lower/upper,\n"
                    "spring and motor act on the offset (m)."},
    {"planar", "joint.planar",
     "planar joint: 2 translations in the plane normal to `axis` and 1 rotation about\n"
               "it (1 point row along the normal, 2 angular rows). angle about the normal. No\n"
               "limits, spring or motor."},
    {"screw", "joint.screw",
     "screw joint: 1 coupled DOF, offset = pitch·angle/(2π): `pitch` m of travel along\n"
              "`axis` per turn (2 point rows, 2 angular rows, 1 coupled row). lower/upper,\n"
              "spring and motor act on the angle (rad)."},
    {"fixed", "joint.fixed",
     "fixed joint: 0 DOF, a and b move as one (3 point rows, 3 angular rows)."},
    {"distance", "joint.distance",
     "distance joint: a rigid rod between a_point (a's frame) and b_point (b's\n"
                 "frame, or a world point) of the length at creation (1 row, the ends' turning\n"
                 "free: a point-mass pendulum). With min and/or max a rope or a limit: rows only\n"
                 "when the length would leave [min, max]. length and rate (of the length)."},
};

}  // namespace

void open_joint(lua_State* L, int lib) {
  lua_newtable(L);  // the type's table: help("joint"), help(j)
  const int table = lua_gettop(L);
  new_type(L, joint_type, table, metamethods);
  add_properties(L, joint_type, properties);
  add_methods(L, joint_type, methods);
  register_topic(L, table, "joint",
                 "A joint made by w:add_joint{...} (maximal coordinates, solved with contacts by\n"
                 "the world's solver). Types: help(\"joint.ball\"), help(\"joint.hinge\"),\n"
                 "\"joint.slider\", \"joint.cylindrical\", \"joint.planar\", \"joint.screw\",\n"
                 "\"joint.fixed\", \"joint.distance\".");
  for (const TypeHelp& t : type_help) {
    lua_newtable(L);
    register_topic(L, -1, t.qualified, t.doc);
    lua_setfield(L, table, t.name);
  }
  lua_setfield(L, lib, "joint");
  add_methods(L, world_type, world_methods);
}

}  // namespace rigidlab::lua
