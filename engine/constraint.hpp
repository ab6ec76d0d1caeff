// How a joint plugs into the world's solver (engine/solver.hpp): as a set of rows
// (engine/constraint_row.hpp) that it rebuilds from the bodies' poses at every substep. The
// solver then treats them like the contact rows: warm starts them from the impulses they ended
// the previous step with, sweeps them (soft_step: with soft position feedback, then relaxed
// rigidly; sequential_impulses: rigidly, then moves the bodies to remove the position error),
// and hands the impulses back.
//
// A row is one of four kinds:
//   equality   J v = 0 and C = 0: a bilateral row (any sign of λ). The ball joint's three
//              point rows, a hinge's two angular rows, ...
//   limit      C ≥ 0: a one-sided row (λ ≥ 0). While C > 0 it only keeps the bodies from
//              crossing C = 0 within the substep (speculative, v ≥ −C/h, as a contact gap);
//              once violated it pushes back like a contact.
//   spring     a damped oscillator of C toward 0 with its own hertz and damping ratio per
//              unit effective mass (a joint spring, Box2D's soft joint spring).
//   motor      document 000 "PD controller" on C = θ − θd: τ = −kp C + kv (θ̇d − Ċ), the
//              force (or torque) bounded by max_force.
// Spring and motor rows are integrated exactly over the substep (engine/solver.cpp, "spring
// and motor rows"); their impulse is bounded by max_force·h.
// The world frame throughout; C in m for linear rows, rad for angular rows.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/body.hpp"
#include "engine/body_store.hpp"
#include "engine/constraint_row.hpp"

namespace rigidlab {

struct JointRow {
  enum class Kind : std::uint8_t { equality, limit, motor, spring };
  Kind kind = Kind::equality;
  Jacobian jacobian;               // at the present poses (engine/constraint_row.hpp)
  double error = 0.0;              // C (m or rad)
  double target_velocity = 0.0;    // motor: θ̇d (m/s or rad/s)
  double max_force = unbounded;    // motor: bound of |force| (N or N m)
  double hertz = 0.0;              // spring (> 0)
  double damping_ratio = 0.0;      // spring
  double kp = 0.0, kv = 0.0;       // motor: N/m or N m/rad, N s/m or N m s/rad
  // A joint's equality rows are solved together as one block: the first row of the block
  // says how many rows it has (2 to 6); the others say 0.
  std::uint8_t block = 1;
};

// The base of every joint. Owned by the world (World::add_constraint); body b may be
// no_body_id for a joint to the world.
class Constraint {
 public:
  // `collide`: whether the two bodies still collide with each other (Box2D's collideConnected;
  // off by default, as jointed parts usually touch where they are joined).
  Constraint(BodyId a, BodyId b, bool collide = false) : a_(a), b_(b), collide_(collide) {}
  virtual ~Constraint() = default;
  Constraint(const Constraint&) = delete;
  Constraint& operator=(const Constraint&) = delete;

  BodyId body_a() const { return a_; }
  BodyId body_b() const { return b_; }
  bool collide() const { return collide_; }
  // The number of rows: fixed while the joint is in a world (an inactive limit is still a row,
  // e.g. with a large C: it then never pushes).
  virtual int row_count() const = 0;
  // Writes row_count() rows for the bodies' present poses; b is nullptr for the world.
  virtual void build_rows(const Body& a, const Body* b, JointRow* rows) const = 0;
  // Follows the bodies' motion (a hinge counts its turns): called at every substep before
  // build_rows, and by nothing else.
  virtual void track(const Body&, const Body*) {}
  // The energy stored in the joint's springs (J) at the bodies' present poses.
  virtual double potential_energy(const Body&, const Body*) const { return 0.0; }
  // Where the joint attaches, in world coordinates, for drawing: the point carried by a and
  // the point carried by b (a fixed world point when b is the world). They coincide for a
  // joint that holds its anchor and are a rod's two ends for a distance joint.
  virtual void attachment_points(const Body& a, const Body* b, Vec3& on_a, Vec3& on_b) const = 0;
  // The accumulated impulse of each row over the last substep (N s or N m s, in the order the
  // rows are built; empty before the first step). The next step is warm started from them.
  const std::vector<double>& impulses() const { return impulses_; }
  // What the joint's rows gave body b over the last step (a got the opposite): the linear
  // impulse (N s) and the angular impulse of the angular rows (N m s); and the force of the
  // motor row in the last substep (N or N m; 0 without a motor).
  const Vec3& step_impulse() const { return step_impulse_; }
  const Vec3& step_angular_impulse() const { return step_angular_impulse_; }
  double motor_force() const { return motor_force_; }
  // The world's serial number of the joint (World::add_constraint), for handles.
  std::uint64_t serial() const { return serial_; }

 protected:
  // The rows changed (limits or a motor added): no warm start from the old ones.
  void forget_impulses() { impulses_.clear(); }
  // State that follows the motion (a hinge's angle, counted in turns): saved with the
  // impulses by the world's undo and saved states.
  double tracked_ = 0.0;

 private:
  friend class Solver;
  friend class World;
  BodyId a_, b_;
  bool collide_;
  std::vector<double> impulses_;
  Vec3 step_impulse_ = Vec3::Zero();
  Vec3 step_angular_impulse_ = Vec3::Zero();
  double motor_force_ = 0.0;
  std::uint64_t serial_ = 0;
};

}  // namespace rigidlab
