#include "lua/contact_settings.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include "lua/binding.hpp"

namespace rigidlab::lua {
namespace {

// One setting: an integer count or a number in [min, max], with its unit for messages.
struct Setting {
  const char* name;
  int ContactSettings::*count;     // or nullptr
  double ContactSettings::*value;  // or nullptr
  double min, max;
  const char* rule;  // what a bad value is told, after "must be "
};

constexpr double unbounded = HUGE_VAL;

const Setting settings_table[] = {
    {"iterations", &ContactSettings::iterations, nullptr, 1, ContactSettings::max_iterations,
     "an integer from 1 to 1000"},
    {"position_iterations", &ContactSettings::position_iterations, nullptr, 0,
     ContactSettings::max_iterations, "an integer from 0 to 1000"},
    {"restitution_threshold", nullptr, &ContactSettings::restitution_threshold, 0, unbounded,
     "a finite number >= 0 (m/s)"},
    {"slop", nullptr, &ContactSettings::linear_slop, 0, unbounded, "a finite number >= 0 (m)"},
    {"baumgarte", nullptr, &ContactSettings::baumgarte, 0, 1, "a number from 0 to 1"},
    {"max_correction", nullptr, &ContactSettings::max_correction, 0, unbounded,
     "a finite number >= 0 (m)"},
    {"speculative_distance", nullptr, &ContactSettings::speculative_distance, 0, unbounded,
     "a finite number >= 0 (m)"},
};

const Setting* find(const char* name) {
  for (const Setting& s : settings_table)
    if (std::strcmp(s.name, name) == 0) return &s;
  return nullptr;
}

// The value on top of the stack as messages show it: numbers with %.14g, else the type name
// (or the string itself).
std::string shown(lua_State* L) {
  if (lua_type(L, -1) == LUA_TNUMBER && !lua_isinteger(L, -1))
    return format_number(lua_tonumber(L, -1));
  if (lua_type(L, -1) == LUA_TNUMBER || lua_type(L, -1) == LUA_TSTRING)
    return lua_tostring(L, -1);
  return value_type_name(L, -1);
}

}  // namespace

const char* const contact_setting_names[] = {
    "iterations", "position_iterations", "restitution_threshold", "slop",
    "baumgarte",  "max_correction",      "speculative_distance",  nullptr};

bool is_contact_setting(const char* name) { return find(name) != nullptr; }

void read_contact_setting(lua_State* L, int arg, const char* name, bool in_table,
                          ContactSettings& settings) {
  const Setting& s = *find(name);
  bool ok = lua_type(L, -1) == LUA_TNUMBER;
  if (ok && s.count != nullptr) {
    ok = lua_isinteger(L, -1) && lua_tointeger(L, -1) >= s.min && lua_tointeger(L, -1) <= s.max;
    if (ok) settings.*s.count = static_cast<int>(lua_tointeger(L, -1));
  } else if (ok) {
    const double x = lua_tonumber(L, -1);
    ok = std::isfinite(x) && x >= s.min && x <= s.max;
    if (ok) settings.*s.value = x;
  }
  if (ok) return;
  const std::string got = shown(L);
  if (in_table) arg_error(L, arg, "field '%s' must be %s, got %s", name, s.rule, got.c_str());
  field_error(L, "world", name, "must be %s, got %s", s.rule, got.c_str());
}

void push_contact_setting(lua_State* L, const char* name, const ContactSettings& settings) {
  const Setting& s = *find(name);
  if (s.count != nullptr) lua_pushinteger(L, settings.*s.count);
  else lua_pushnumber(L, settings.*s.value);
}

const char* const contact_settings_doc =
    "Contact solver (Catto's sequential impulses as in Box2D; fields of the world, read/write):\n"
    "  iterations (10): velocity sweeps per substep; more make tall stacks and chains stiffer.\n"
    "  position_iterations (3): position-correction sweeps per substep (0 = none).\n"
    "  restitution_threshold (1 m/s): impacts slower than this do not bounce.\n"
    "  slop (0.005 m): overlap left uncorrected, at most 1 % of the smaller body's smallest\n"
    "    size; it keeps resting contacts in touch (a stack sinks by about a slop per layer).\n"
    "  baumgarte (0.2): fraction of the overlap beyond the slop removed per position sweep.\n"
    "  max_correction (0.2 m): largest position correction per point and sweep.\n"
    "  speculative_distance (0.02 m): gaps up to this are contacts even when the bodies do\n"
    "    not move toward each other (resting and stacked bodies keep their contacts); wider\n"
    "    gaps only when the bodies meet within the step (time of impact).\n"
    "Limits: a stack of 8 equal unit boxes stands 10 s at 60 Hz with these defaults (the top\n"
    "box sinks about 1 cm); taller stacks may need more iterations or substeps. With the\n"
    "euler and rk4 integrators a body resting on a contact shows v = −g Δt (euler) or −g Δt/2\n"
    "(rk4) between steps: the contact impulse acts before the step, gravity during it.";

}  // namespace rigidlab::lua
