#include "lua/contact_settings.hpp"

#include <cmath>

#include "engine/solver_settings.hpp"
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
const Setting relax_iterations{&ContactSettings::relax_iterations, nullptr, 0,
                               ContactSettings::max_iterations, nullptr};
const Setting contact_hertz{nullptr, &ContactSettings::contact_hertz, 0, unbounded,
                            "a finite number >= 0 (Hz)"};
const Setting contact_damping_ratio{nullptr, &ContactSettings::contact_damping_ratio, 0,
                                    unbounded, "a finite number >= 0"};
const Setting joint_hertz{nullptr, &ContactSettings::joint_hertz, 0, unbounded,
                          "a finite number >= 0 (Hz)"};
const Setting joint_damping_ratio{nullptr, &ContactSettings::joint_damping_ratio, 0, unbounded,
                                  "a finite number >= 0"};
const Setting contact_push_speed{nullptr, &ContactSettings::contact_push_speed, 0, unbounded,
                                 "a finite number >= 0 (m/s)"};

void get_solver(lua_State* L, int object, const Property&) {
  lua_pushstring(L, solver_names[static_cast<int>(check_world(L, object).world.solver())]);
}

void set_solver(lua_State* L, int object, int value, const Where& where, const Property&) {
  const auto kind = static_cast<SolverKind>(check_option(L, value, where, solver_names));
  World& w = check_world(L, object).world;
  protect(L, [&] { w.set_solver(kind); });
}

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

// The defaults in the help are those of engine/solver_settings.hpp; world_test.lua checks that
// a new world reads them.
const Property properties[] = {
    {"solver", get_solver, set_solver,
     "\"soft_step\" (default) or \"sequential_impulses\": how contacts and joints are solved",
     nullptr, nullptr},
    {"iterations", get_setting, set_setting,
     "velocity sweeps per substep (10); more make tall stacks and chains stiffer. New "
     "contacts have no warm start yet, so a substep sweeps on to convergence (at most 1000) "
     "where they begin: sequential_impulses wherever any begins, soft_step where new "
     "touching contacts form a chain under a body longer than the sweeps carry a load down. "
     "soft_step stops early once they have converged (without joints): a resting stack "
     "takes two; w:solver_report() lists the sweeps run",
     nullptr, &iterations},
    {"relax_iterations", get_setting, set_setting,
     "soft_step: rigid sweeps after the positions moved (4)", nullptr, &relax_iterations},
    {"position_iterations", get_setting, set_setting,
     "sequential_impulses: position-correction sweeps per substep (3; 0 = none)", nullptr,
     &position_iterations},
    {"restitution_threshold", get_setting, set_setting,
     "m/s (1): impacts slower than this do not bounce", nullptr, &restitution_threshold},
    {"slop", get_setting, set_setting,
     "m (0.005): sequential_impulses leaves this overlap uncorrected, at most 1 % of the "
     "smaller body's smallest size (a stack sinks by about a slop per layer); soft_step "
     "pushes an overlap out to 4 % of it (0.2 mm), not to touching",
     nullptr, &slop},
    {"baumgarte", get_setting, set_setting,
     "(0.2): sequential_impulses: fraction of the overlap beyond the slop removed per position "
     "sweep", nullptr, &baumgarte},
    {"max_correction", get_setting, set_setting,
     "m (0.2): sequential_impulses: largest position correction per point and sweep", nullptr,
     &max_correction},
    {"contact_hertz", get_setting, set_setting,
     "Hz (60): soft_step: stiffness of the overlap feedback of a contact (twice that against "
     "a static body or plane), Box2D's soft contact", nullptr, &contact_hertz},
    {"contact_damping_ratio", get_setting, set_setting,
     "(10): soft_step: damping ratio of that feedback", nullptr, &contact_damping_ratio},
    {"joint_hertz", get_setting, set_setting,
     "Hz (60): soft_step: stiffness of the position feedback of joints", nullptr, &joint_hertz},
    {"joint_damping_ratio", get_setting, set_setting,
     "(5): soft_step: damping ratio of that feedback", nullptr, &joint_damping_ratio},
    {"contact_push_speed", get_setting, set_setting,
     "m/s (3): soft_step: the fastest an overlap is pushed out", nullptr, &contact_push_speed},
    {"speculative_distance", get_setting, set_setting,
     "m (0.02): gaps up to this are contacts even when the bodies do not move toward each "
     "other (resting and stacked bodies keep their contacts); wider gaps only when the bodies "
     "meet within the step (time of impact)",
     nullptr, &speculative_distance},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void add_contact_setting_properties(lua_State* L) { add_properties(L, world_type, properties); }

const char* const contact_settings_doc =
    "Solver (w.solver): contacts and joints are rows of one solver (Box2D v3's stages).\n"
    "\"soft_step\" (default): rigid velocity sweeps, the overlap pushed out by soft rows of\n"
    "contact_hertz and contact_damping_ratio that move positions only (to 4 % of the slop,\n"
    "so a face's corners stay touching), then relax sweeps at the moved positions.\n"
    "\"sequential_impulses\": document 000's three steps (forces into velocities, impulses\n"
    "for every constraint in turn, positions from the new velocities), then the overlap\n"
    "beyond the slop removed by moving the bodies. Either way a bounce is taken in the step\n"
    "of the impact: the state a step leaves is its end state.\n"
    "Limits: a column of 20 unit boxes stands at 60 Hz with the defaults (soft_step; the top\n"
    "box ends within 0.1 mm of where it started) when it is aligned; tilt its boxes by 1e-4\n"
    "rad and at one substep it buckles (both solvers: ten sweeps leave it soft), while 15\n"
    "stand within 3 mm and 2 substeps hold 20 within 2 mm. With sequential_impulses each\n"
    "layer sinks by about a slop. With the euler and rk4 integrators a body resting on a\n"
    "contact shows v = −g Δt (euler) or −g Δt/2 (rk4) between steps: the contact impulse\n"
    "acts at the start of the step, gravity during it.";

}  // namespace rigidlab::lua
