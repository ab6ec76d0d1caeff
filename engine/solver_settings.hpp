// The settings of a world's constraint solver (engine/solver.hpp): which solver, how many
// sweeps, and the parameters of its contacts and joints.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rigidlab {

// world.solver (API.md "World and integration"):
//   soft_step: Box2D v3's soft step (E. Catto, "Solver2D"): the velocity sweeps drive position
//     errors out through soft constraints (hertz, damping ratio), the positions move with those
//     velocities, then rigid sweeps without position feedback (relax) remove the velocity the
//     feedback added. Default.
//   sequential_impulses: document 000 "Sequential impulses" as it stands (integrate forces into
//     tentative velocities, impulses on every constraint in turn, positions from the new
//     velocities), rigid rows, and the overlap then removed by moving the bodies (non-linear
//     Gauss-Seidel, Box2D v2.4's position solver).
enum class SolverKind { soft_step, sequential_impulses };
inline constexpr const char* solver_names[] = {"soft_step", "sequential_impulses"};
std::optional<SolverKind> parse_solver(std::string_view name);

struct ContactSettings {
  static constexpr int max_iterations = 1000;
  int iterations = 10;                 // velocity sweeps per substep (1 .. max_iterations;
                                       // more, to convergence, on a step where contacts
                                       // begin: engine/solver.cpp Solver::solve)
  int relax_iterations = 4;            // soft_step: rigid sweeps after the positions moved
  int position_iterations = 3;         // sequential_impulses: position sweeps (Box2D: 3)
  double restitution_threshold = 1.0;  // m/s: slower impacts do not bounce (Box2D: 1 m/s)
  double linear_slop = 0.005;          // m: overlap left uncorrected by sequential_impulses'
                                       // position sweeps; at most 1 % of the smaller body
  double baumgarte = 0.2;              // fraction of the overlap removed per position sweep
  double max_correction = 0.2;         // m: largest move per point per position sweep
  double speculative_distance = 0.02;  // m: gaps up to this are contacts (Box2D v3: 4 slops)
  double match_distance = 0.02;        // m: a point this close to one of the previous step
                                       // (same pair) continues it, when the features differ
  // soft_step's soft constraints (Box2D v3 b2WorldDef: contactHertz, contactDampingRatio,
  // jointHertz, jointDampingRatio, contactPushMaxVelocity).
  double contact_hertz = 60.0;         // Hz, of the overlap feedback per unit effective mass
  double contact_damping_ratio = 10.0;
  double joint_hertz = 60.0;           // Hz, of the equality rows of joints
  double joint_damping_ratio = 5.0;
  double contact_push_speed = 3.0;     // m/s: the fastest overlap is pushed out
};

// "" or the rule broken: "iterations must be an integer from 1 to 1000, got 0", ...
std::string contact_settings_problem(const ContactSettings& settings);

}  // namespace rigidlab
