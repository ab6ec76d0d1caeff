// The queries of an articulation at its current state, each one algorithm of the engine:
// forward dynamics (articulated-body algorithm, engine/aba) and its three loops' quantities,
// inverse dynamics and bias forces (recursive Newton-Euler, engine/rnea), the mass matrix
// (composite rigid body, engine/crba), the Jacobian of a link point and virtual forces,
// energies and momentum (engine/articulation_kinematics).
#include "lua/articulation.hpp"

namespace rigidlab::lua {
namespace {

// tau for the queries that take one: the argument at `arg` (a list), checked by the engine.
Eigen::VectorXd optional_numbers(lua_State* L, int arg, const char* what, bool* given) {
  *given = !lua_isnoneornil(L, arg);
  return *given ? check_numbers(L, arg, what) : Eigen::VectorXd();
}

// q̈ for the given tau, or for the held torques plus the controls (run on this thread).
const Eigen::VectorXd& run_forward_dynamics(lua_State* L, LuaArticulation& a,
                                            const Eigen::VectorXd& tau, bool given) {
  if (given) return protect(L, 2, [&]() -> const Eigen::VectorXd& {
      return a.art.forward_dynamics(tau);
    });
  ControlThread thread(a, L);
  return protect(L, [&]() -> const Eigen::VectorXd& { return a.art.forward_dynamics(); });
}

int articulation_forward_dynamics(lua_State* L) {
  check_articulation(L, 1);
  bool given = false;
  const Eigen::VectorXd tau = optional_numbers(L, 2, "tau", &given);
  check_no_extra_args(L, 2);
  lua_settop(L, 1);  // the controls run with the articulation at 1
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::VectorXd qdd = run_forward_dynamics(L, a, tau, given);
  push_numbers(L, qdd);
  return 1;
}

int articulation_applied_torques(lua_State* L) {
  check_no_extra_args(L, 1);
  LuaArticulation& a = check_articulation(L, 1);
  ControlThread thread(a, L);
  const Eigen::VectorXd tau = protect(L, [&] { return a.art.applied_torques(); });
  push_numbers(L, tau);
  return 1;
}

int articulation_inverse_dynamics(lua_State* L) {
  check_articulation(L, 1);
  const Eigen::VectorXd qdd = check_numbers(L, 2, "qdd");
  check_no_extra_args(L, 2);
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::VectorXd tau = protect(L, 2, [&] { return a.art.inverse_dynamics(qdd); });
  push_numbers(L, tau);
  return 1;
}

int articulation_mass_matrix(lua_State* L) {
  check_no_extra_args(L, 1);
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::MatrixXd M = protect(L, [&] { return a.art.mass_matrix(); });
  push_rows(L, M);
  return 1;
}

int articulation_bias_forces(lua_State* L) {
  check_no_extra_args(L, 1);
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::VectorXd bias = protect(L, [&] { return a.art.bias_forces(); });
  push_numbers(L, bias);
  return 1;
}

// ---- the three loops -------------------------------------------------------------------------

void set_numbers(lua_State* L, const char* name, const Eigen::Ref<const Eigen::VectorXd>& x) {
  push_numbers(L, x);
  lua_setfield(L, -2, name);
}

void set_rows(lua_State* L, const char* name, const Eigen::Ref<const Eigen::MatrixXd>& m) {
  push_rows(L, m);
  lua_setfield(L, -2, name);
}

void set_number(lua_State* L, const char* name, double x) {
  lua_pushnumber(L, x);
  lua_setfield(L, -2, name);
}

// The quantities of body `i` after the algorithm (see engine/articulation_kinematics.hpp).
void push_body_loops(lua_State* L, const ArticulationModel& model, const ArticulationWorkspace& ws,
                     int i) {
  lua_createtable(L, 0, 10);
  set_numbers(L, "v", ws.v[i]);
  set_numbers(L, "c", ws.c[i]);
  set_rows(L, "IA", ws.IA[i]);
  set_numbers(L, "pA", ws.pA[i]);
  set_numbers(L, "a", ws.a[i]);
  if (i == 0) return;
  set_numbers(L, "p", ws.p[i]);
  if (model.links()[i - 1].v_index < 0) return;
  set_numbers(L, "s", ws.S[i]);
  set_numbers(L, "h", ws.U[i]);
  set_number(L, "d", ws.D[i]);
  set_number(L, "u", ws.u[i]);
}

int articulation_aba_trace(lua_State* L) {
  check_articulation(L, 1);
  bool given = false;
  const Eigen::VectorXd tau = optional_numbers(L, 2, "tau", &given);
  check_no_extra_args(L, 2);
  lua_settop(L, 1);
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::VectorXd qdd = run_forward_dynamics(L, a, tau, given);
  // Copied before any table is made: an allocation may run a finaliser that uses `a`.
  const ArticulationModel model = a.art.model();
  const ArticulationWorkspace ws = a.art.workspace();
  lua_createtable(L, 0, 3);
  set_numbers(L, "qdd", qdd);
  lua_createtable(L, model.link_count(), 0);
  for (int k = 0; k < model.link_count(); ++k) {
    push_body_loops(L, model, ws, k + 1);
    lua_rawseti(L, -2, k + 1);
  }
  lua_setfield(L, -2, "links");
  if (model.free_base()) {
    push_body_loops(L, model, ws, 0);
    lua_setfield(L, -2, "base");
  }
  return 1;
}

// ---- kinematics ------------------------------------------------------------------------------

int articulation_jacobian(lua_State* L) {
  check_articulation(L, 1);
  const Vec3 point =
      lua_isnoneornil(L, 3) ? Vec3::Zero() : Vec3(check_vec3(L, 3, Where::argument(3, "point")));
  check_no_extra_args(L, 3);
  const int link = check_link_of(L, 1, 2, Where::argument(2, "link"));
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::MatrixXd J = protect(L, [&] { return a.art.jacobian(link, point); });
  push_rows(L, J);
  return 1;
}

int articulation_virtual_force(lua_State* L) {
  check_articulation(L, 1);
  const Vec3 point = check_vec3(L, 3, Where::argument(3, "point"));
  const Vec3 force = check_vec3(L, 4, Where::argument(4, "force"));
  const Vec3 torque =
      lua_isnoneornil(L, 5) ? Vec3::Zero() : Vec3(check_vec3(L, 5, Where::argument(5, "torque")));
  check_no_extra_args(L, 5);
  const int link = check_link_of(L, 1, 2, Where::argument(2, "link"));
  LuaArticulation& a = check_articulation(L, 1);
  const Eigen::VectorXd tau =
      protect(L, [&] { return a.art.virtual_force(link, point, force, torque); });
  if (!tau.allFinite()) overflow_error(L, 4, "the result", "an entry");
  push_numbers(L, tau);
  return 1;
}

template <double (Articulation::*total)()>
int articulation_total(lua_State* L) {
  check_no_extra_args(L, 1);
  LuaArticulation& a = check_articulation(L, 1);
  lua_pushnumber(L, (a.art.*total)());
  return 1;
}

// Linear (kg m/s) or angular (kg m²/s, about the world origin) momentum.
template <bool angular>
int articulation_momentum(lua_State* L) {
  check_no_extra_args(L, 1);
  Vec3 momentum[2];
  check_articulation(L, 1).art.momentum(momentum[0], momentum[1]);
  push_finite(L, momentum[angular ? 1 : 0], 1);
  return 1;
}

int articulation_center_of_mass(lua_State* L) {
  check_no_extra_args(L, 1);
  Vec3 com;
  const double mass = check_articulation(L, 1).art.center_of_mass(com);
  push_finite(L, com, 1);
  lua_pushnumber(L, mass);
  return 2;
}

const Entry methods[] = {
    {"forward_dynamics", articulation_forward_dynamics, "articulation:forward_dynamics",
     "art:forward_dynamics([tau]) -> qdd",
     "The joint accelerations now, by Featherstone's articulated-body algorithm (document\n"
     "000 \"Featherstone's Algorithm\": three loops over the links, O(n)), for tau, or without\n"
     "it for the held torques plus the controls (what a step would use)."},
    {"aba_trace", articulation_aba_trace, "articulation:aba_trace", "art:aba_trace([tau]) -> t",
     "forward_dynamics with the quantities of its three loops: t.qdd, and per link\n"
     "t.links[i] with v (velocity), c (v × s q̇), p (bias force of the link alone:\n"
     "v × I v − weight), IA and pA (articulated inertia, 6 rows, and bias force: the\n"
     "document's I^accu, p^accu), s, h = IA s, d = sᵀh, u = τ − hᵀc − sᵀpA (moving joints\n"
     "only) and a (acceleration); a free base's in t.base. Spatial vectors are lists of 6\n"
     "numbers (angular part first: ω, v or moment, force), in link coordinates."},
    {"inverse_dynamics", articulation_inverse_dynamics, "articulation:inverse_dynamics",
     "art:inverse_dynamics(qdd) -> tau",
     "The generalised forces that give accelerations qdd now: M qdd + C qd + g (recursive\n"
     "Newton-Euler). With qd = 0 and qdd = 0 it is the gravity compensation g(q)."},
    {"mass_matrix", articulation_mass_matrix, "articulation:mass_matrix",
     "art:mass_matrix() -> rows", "M(q) as a list of rows (composite-rigid-body algorithm)."},
    {"bias_forces", articulation_bias_forces, "articulation:bias_forces",
     "art:bias_forces() -> list", "C(q, qd) qd + g(q): inverse dynamics with qdd = 0."},
    {"applied_torques", articulation_applied_torques, "articulation:applied_torques",
     "art:applied_torques() -> tau", "The held torques plus every control's, now."},
    {"jacobian", articulation_jacobian, "articulation:jacobian",
     "art:jacobian(link [, point]) -> rows",
     "6 rows by #qd: the world linear velocity of the link's point (link frame, default its\n"
     "origin; rows 1-3) and the link's world angular velocity (rows 4-6) per unit qd."},
    {"virtual_force", articulation_virtual_force, "articulation:virtual_force",
     "art:virtual_force(link, point, force [, torque]) -> tau",
     "tau = Jᵀ F: the generalised forces that act as a world force (N) at the link's point\n"
     "(link frame), and a world torque (N·m) on it, would (document 000 \"Virtual forces\")."},
    {"kinetic_energy", articulation_total<&Articulation::kinetic_energy>,
     "articulation:kinetic_energy", "art:kinetic_energy() -> number",
     "½ qdᵀ M qd = Σ ½ m v_com² + ½ ωᵀ I ω over the links (J)."},
    {"potential_energy", articulation_total<&Articulation::potential_energy>,
     "articulation:potential_energy", "art:potential_energy() -> number",
     "−Σ m g·x_com (J), zero at the world origin."},
    {"energy", articulation_total<&Articulation::energy>, "articulation:energy",
     "art:energy() -> number", "Kinetic plus potential energy (J)."},
    {"linear_momentum", articulation_momentum<false>, "articulation:linear_momentum",
     "art:linear_momentum() -> vec3", "Σ m v_com (kg m/s)."},
    {"angular_momentum", articulation_momentum<true>, "articulation:angular_momentum",
     "art:angular_momentum() -> vec3",
     "Σ x_com × m v_com + I_world ω about the world origin (kg m²/s)."},
    {"center_of_mass", articulation_center_of_mass, "articulation:center_of_mass",
     "art:center_of_mass() -> vec3, mass", "The world centre of mass (m) and total mass (kg)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_articulation_dynamics(lua_State* L) { add_methods(L, articulation_type, methods); }

}  // namespace rigidlab::lua
