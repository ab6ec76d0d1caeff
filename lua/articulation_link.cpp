// link: one link of an articulation (art:add_link, art.links, art:link). Its fields describe the
// link as added (read-only: the model of an articulation does not change) and its joint's
// current coordinate; its methods give its pose and velocity at the articulation's state.
#include <string>

#include "lua/articulation.hpp"

namespace rigidlab::lua {
namespace {

const char link_metatable_key = 0;
constexpr std::uint64_t link_tag = 0x6c69'6e6b'7269'646cULL;  // arbitrary, distinct
constexpr int articulation_slot = 1;

using LinkBox = Tagged<int>;

// The link object at `index`: pushes its articulation and returns the link index, else a type
// error ("link expected, got number").
int check_link(lua_State* L, int index) {
  int link = 0;
  if (!test_link(L, index, &link)) type_error(L, index, "link");
  return link;
}

// The articulation of the link object at 1 (self), pushed, and the link's index.
struct SelfLink {
  LuaArticulation* articulation;
  int link;
  int object;  // stack index of the pushed articulation
};
SelfLink self_link(lua_State* L) {
  const int link = check_link(L, 1);
  const int object = lua_gettop(L);
  return {&check_articulation(L, object), link, object};
}

const LinkSpec& spec_of(lua_State* L, int object, int link) {
  return check_articulation(L, object).art.model().links()[link].spec;
}

// ---- properties ------------------------------------------------------------------------------

void get_index(lua_State* L, int object, const Property&) {
  const int link = check_link(L, object);
  lua_pop(L, 1);
  lua_pushinteger(L, link + 1);
}

template <class Push>
void with_spec(lua_State* L, int object, Push&& push) {
  const int link = check_link(L, object);
  const int articulation = lua_gettop(L);
  const LinkSpec spec = spec_of(L, articulation, link);
  lua_pop(L, 1);
  push(spec, articulation, link);
}

void get_name(lua_State* L, int object, const Property&) {
  with_spec(L, object, [L](const LinkSpec& s, int, int) {
    if (s.name.empty())
      lua_pushnil(L);
    else
      lua_pushlstring(L, s.name.data(), s.name.size());
  });
}

void get_parent(lua_State* L, int object, const Property&) {
  const int link = check_link(L, object);
  const int articulation = lua_gettop(L);
  const int parent = spec_of(L, articulation, link).parent;
  if (parent < 0)
    lua_pushnil(L);
  else
    push_link(L, articulation, parent);
  lua_remove(L, articulation);
}

void get_joint(lua_State* L, int object, const Property&) {
  with_spec(L, object, [L](const LinkSpec& s, int, int) {
    lua_pushstring(L, joint_type_names[int(s.joint)]);
  });
}

// Vec3 fields of the spec: the Property's data is the member pointer.
void get_spec_vec3(lua_State* L, int object, const Property& p) {
  const auto member = *static_cast<Vec3 LinkSpec::* const*>(p.data);
  with_spec(L, object, [L, member](const LinkSpec& s, int, int) { push_vec3(L, s.*member); });
}
const Vec3 LinkSpec::*const axis_member = &LinkSpec::axis;
const Vec3 LinkSpec::*const origin_member = &LinkSpec::origin;
const Vec3 LinkSpec::*const com_member = &LinkSpec::com;

void get_mass(lua_State* L, int object, const Property&) {
  with_spec(L, object, [L](const LinkSpec& s, int, int) { lua_pushnumber(L, s.mass); });
}

void get_inertia(lua_State* L, int object, const Property&) {
  with_spec(L, object, [L](const LinkSpec& s, int, int) { push_mat3(L, s.inertia); });
}

// The link's entry of q or qd (nil for a fixed joint), or its 1-based index in them.
template <bool rate, bool index>
void get_coordinate(lua_State* L, int object, const Property&) {
  const int link = check_link(L, object);
  const Articulation& art = check_articulation(L, lua_gettop(L)).art;
  const Link& l = art.model().links()[link];
  const int at = rate ? l.v_index : l.q_index;
  lua_pop(L, 1);
  if (at < 0)
    lua_pushnil(L);
  else if (index)
    lua_pushinteger(L, at + 1);
  else
    lua_pushnumber(L, rate ? art.v()[at] : art.q()[at]);
}

void get_articulation(lua_State* L, int object, const Property&) { check_link(L, object); }

const Property properties[] = {
    {"index", get_index, nullptr, "its number in the articulation (1 = first added)",
     "links keep their number", nullptr},
    {"name", get_name, nullptr, "the name given to add_link, or nil", "fixed by add_link",
     nullptr},
    {"parent", get_parent, nullptr, "the parent link, or nil for the base", "fixed by add_link",
     nullptr},
    {"joint", get_joint, nullptr, "\"revolute\", \"prismatic\" or \"fixed\"", "fixed by add_link",
     nullptr},
    {"axis", get_spec_vec3, nullptr, "vec3, the joint axis (unit, parent frame)",
     "fixed by add_link", &axis_member},
    {"origin", get_spec_vec3, nullptr, "vec3, the joint position in the parent frame (m)",
     "fixed by add_link", &origin_member},
    {"com", get_spec_vec3, nullptr, "vec3, the centre of mass in the link frame (m)",
     "fixed by add_link", &com_member},
    {"mass", get_mass, nullptr, "kg", "fixed by add_link", nullptr},
    {"inertia", get_inertia, nullptr, "mat3 about the COM, link frame (kg·m²)",
     "fixed by add_link", nullptr},
    {"q", get_coordinate<false, false>, nullptr,
     "its joint coordinate (rad or m), nil for a fixed joint", "set it with art:set_state",
     nullptr},
    {"qd", get_coordinate<true, false>, nullptr, "its joint rate (rad/s or m/s), or nil",
     "set it with art:set_state", nullptr},
    {"q_index", get_coordinate<false, true>, nullptr, "its entry's number in art.q, or nil",
     "fixed by add_link", nullptr},
    {"qd_index", get_coordinate<true, true>, nullptr,
     "its entry's number in art.qd and the torques, or nil", "fixed by add_link", nullptr},
    {"articulation", get_articulation, nullptr, "the articulation it belongs to",
     "fixed by add_link", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

// ---- methods ---------------------------------------------------------------------------------

// A vector of the link now: link:position(), link:angular_velocity().
template <Vec3 (Articulation::*query)(int)>
int link_vector(lua_State* L) {
  check_no_extra_args(L, 1);
  const SelfLink s = self_link(L);
  push_finite(L, (s.articulation->art.*query)(s.link), 1);
  return 1;
}

int link_orientation(lua_State* L) {
  check_no_extra_args(L, 1);
  const SelfLink s = self_link(L);
  push_finite(L, unit(Quat(s.articulation->art.link_rotation(s.link))), 1);
  return 1;
}

// A vector of the link's point p (link frame; optional: default its origin) now:
// link:to_world(p), link:point_velocity([p]).
template <Vec3 (Articulation::*query)(int, const Vec3&), bool optional>
int link_point_vector(lua_State* L) {
  check_link(L, 1);
  lua_pop(L, 1);
  const Vec3 p = optional && lua_isnoneornil(L, 2)
                     ? Vec3::Zero()
                     : Vec3(check_vec3(L, 2, Where::argument(2, "point")));
  check_no_extra_args(L, 2);
  const SelfLink s = self_link(L);
  push_finite(L, (s.articulation->art.*query)(s.link, p), 2);
  return 1;
}

int link_tostring(lua_State* L) {
  const SelfLink s = self_link(L);
  const LinkSpec& spec = s.articulation->art.model().links()[s.link].spec;
  lua_pushfstring(L, "link(%d%s%s, %s)", s.link + 1, spec.name.empty() ? "" : " ",
                  spec.name.c_str(), joint_type_names[int(spec.joint)]);
  return 1;
}

const Entry methods[] = {
    {"position", link_vector<&Articulation::link_position>, "link:position",
     "link:position() -> vec3",
     "The world position of the link frame's origin (its joint), m."},
    {"orientation", link_orientation, "link:orientation", "link:orientation() -> quat",
     "The rotation from the link frame to the world."},
    {"to_world", link_point_vector<&Articulation::point_position, false>, "link:to_world",
     "link:to_world(p) -> vec3",
     "The world position of point p given in the link frame (m)."},
    {"point_velocity", link_point_vector<&Articulation::point_velocity, true>,
     "link:point_velocity",
     "link:point_velocity([p]) -> vec3",
     "The world velocity of the link's point p (link frame, default its origin), m/s."},
    {"angular_velocity", link_vector<&Articulation::angular_velocity>, "link:angular_velocity",
     "link:angular_velocity() -> vec3", "The link's angular velocity, world frame, rad/s."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__tostring", link_tostring, "link.__tostring", "tostring(link)",
     "Short form: link(2 forearm, revolute)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

const TypeSpec link_type = {"link", &link_metatable_key, nullptr};

bool test_link(lua_State* L, int index, int* link) {
  const int* value = test_tagged<int>(L, index, link_tag);
  if (value == nullptr || !has_metatable(L, index, &link_metatable_key)) return false;
  lua_getiuservalue(L, index, articulation_slot);
  *link = *value;
  return true;
}

int check_link_of(lua_State* L, int object, int value, const Where& where) {
  object = lua_absindex(L, object);
  const int count = check_articulation(L, object).art.model().link_count();
  int link = 0;
  lua_Integer number = 0;
  if (test_link(L, value, &link)) {
    const bool same = lua_rawequal(L, -1, object);
    lua_pop(L, 1);
    if (!same) where.error(L, "must be a link of this articulation, got a link of another one");
    return link;
  }
  if (lua_type(L, value) == LUA_TNUMBER) {
    if (!to_integer(L, value, number) || number < 1 || number > count)
      where.error(L, "must be a link number from 1 to %d, got %s", count,
                  push_shown_value(L, value));
    return static_cast<int>(number - 1);
  }
  if (lua_type(L, value) == LUA_TSTRING) {
    std::size_t length = 0;
    const char* name = check_name(L, value, where, &length);
    const int found = check_articulation(L, object).art.model().find_link({name, length});
    if (found < 0) where.error(L, "no link is called '%s'", name);
    return found;
  }
  where.type_error(L, value, "link, link number or name");
}

void append_link_object(lua_State* L, int object, int link) {
  object = lua_absindex(L, object);
  auto* box = static_cast<LinkBox*>(lua_newuserdatauv(L, sizeof(LinkBox), 1));
  box->tag = link_tag;
  box->value = link;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &link_metatable_key);
  lua_setmetatable(L, -2);
  lua_pushvalue(L, object);
  lua_setiuservalue(L, -2, articulation_slot);
  lua_getiuservalue(L, object, 1);  // the articulation's list of links
  lua_insert(L, -2);
  lua_rawseti(L, -2, link + 1);
  lua_pop(L, 1);
}

// The `link` type's table is in the library (as `recorder` is), so that help() lists it,
// help("link:position") and help(link) find it, and the fuzz harness, which reads the names
// to call from the library, calls its methods.
void open_articulation_link(lua_State* L, int lib) {
  lua_newtable(L);  // the `link` topic's table (links are made by art:add_link)
  const int table = lua_gettop(L);
  new_type(L, link_type, table, metamethods);
  add_properties(L, link_type, properties);
  add_methods(L, link_type, methods);
  register_topic(L, table, "link",
                 "A link of an articulation (art:add_link, art.links, art:link). Read-only\n"
                 "fields describe it as added; methods give its pose and velocity now.");
  lua_setfield(L, lib, "link");
}

}  // namespace rigidlab::lua
