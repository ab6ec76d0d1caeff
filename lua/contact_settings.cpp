#include "lua/contact_settings.hpp"

#include <cmath>

#include "engine/contact_solver.hpp"
#include "lua/binding.hpp"
#include "lua/world.hpp"

namespace rigidlab::lua {
namespace {

// One setting: an integer count in [min, max], or a finite number in [min, max] whose rule
// ("a finite number >= 0 (m/s)") the message states.
struct Setting {
  int ContactSettings::*count;     // or nullptr
  double ContactSettings::*value;  // or nullptr
  double min, max;
  const char* rule;                // for numbers: what it must be, with the unit
};

constexpr double unbounded = HUGE_VAL;

const Setting iterations{&ContactSettings::iterations, nullptr, 1,
                         ContactSettings::max_iterations, nullptr};
const Setting position_iterations{&ContactSettings::position_iterations, nullptr, 0,
                                  ContactSettings::max_iterations, nullptr};
const Setting restitution_threshold{nullptr, &ContactSettings::restitution_threshold, 0,
                                    unbounded, "a finite number >= 0 (m/s)"};
const Setting slop{nullptr, &ContactSettings::linear_slop, 0, unbounded,
                   "a finite number >= 0 (m)"};
const Setting baumgarte{nullptr, &ContactSettings::baumgarte, 0, 1, "a number from 0 to 1"};
const Setting max_correction{nullptr, &ContactSettings::max_correction, 0, unbounded,
                             "a finite number >= 0 (m)"};
const Setting speculative_distance{nullptr, &ContactSettings::speculative_distance, 0,
                                   unbounded, "a finite number >= 0 (m)"};

void get_setting(lua_State* L, int object, const Property& p) {
  const Setting& s = *static_cast<const Setting*>(p.data);
  const ContactSettings& settings = check_world(L, object).world.contact_settings();
  if (s.count != nullptr) lua_pushinteger(L, settings.*s.count);
  else lua_pushnumber(L, settings.*s.value);
}

void set_setting(lua_State* L, int object, int value, const Where& where, const Property& p) {
  const Setting& s = *static_cast<const Setting*>(p.data);
  lua_Integer count = 0;
  double x = 0.0;
  if (s.count != nullptr)
    count = check_integer(L, value, where, static_cast<lua_Integer>(s.min),
                          static_cast<lua_Integer>(s.max));
  else
    x = check_number(L, value, where, s.min, s.max, s.rule);
  World& w = check_world(L, object).world;
  ContactSettings settings = w.contact_settings();
  if (s.count != nullptr) settings.*s.count = static_cast<int>(count);
  else settings.*s.value = x;
  protect(L, [&] { w.set_contact_settings(settings); });
}

// The defaults in the help are those of engine/contact_solver.hpp; world_test.lua checks that
// a new world reads them.
const Property properties[] = {
    {"iterations", get_setting, set_setting,
     "velocity sweeps per substep (10); more make tall stacks and chains stiffer", nullptr,
     &iterations},
    {"position_iterations", get_setting, set_setting,
     "position-correction sweeps per substep (3; 0 = none)", nullptr, &position_iterations},
    {"restitution_threshold", get_setting, set_setting,
     "m/s (1): impacts slower than this do not bounce", nullptr, &restitution_threshold},
    {"slop", get_setting, set_setting,
     "m (0.005): overlap left uncorrected, at most 1 % of the smaller body's smallest size; it "
     "keeps resting contacts in touch (a stack sinks by about a slop per layer)",
     nullptr, &slop},
    {"baumgarte", get_setting, set_setting,
     "(0.2): fraction of the overlap beyond the slop removed per position sweep", nullptr,
     &baumgarte},
    {"max_correction", get_setting, set_setting,
     "m (0.2): largest position correction per point and sweep", nullptr, &max_correction},
    {"speculative_distance", get_setting, set_setting,
     "m (0.02): gaps up to this are contacts even when the bodies do not move toward each "
     "other (resting and stacked bodies keep their contacts); wider gaps only when the bodies "
     "meet within the step (time of impact)",
     nullptr, &speculative_distance},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void add_contact_setting_properties(lua_State* L) { add_properties(L, world_type, properties); }

const char* const contact_settings_doc =
    "Contact solver: Catto's sequential impulses as in Box2D, tuned by the fields from\n"
    "iterations to speculative_distance (below).\n"
    "Limits: a stack of 8 equal unit boxes stands 10 s at 60 Hz with the defaults (the top\n"
    "box sinks about 1 cm); taller stacks may need more iterations or substeps. With the\n"
    "euler and rk4 integrators a body resting on a contact shows v = −g Δt (euler) or −g Δt/2\n"
    "(rk4) between steps: the contact impulse acts before the step, gravity during it.";

}  // namespace rigidlab::lua
