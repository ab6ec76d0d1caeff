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
//   motor      J v = target_velocity with |λ| ≤ max_impulse: a velocity drive (rigid, no
//              position feedback).
//   spring     a soft row pulling C to 0 with its own hertz and damping ratio (make_soft), its
//              impulse bounded by max_impulse: a joint spring, or a PD drive written as one.
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
  double target_velocity = 0.0;    // motor: the J v it drives toward (m/s or rad/s)
  double max_impulse = unbounded;  // motor, spring: bound of |λ| over a substep (N s, N m s)
  double hertz = 0.0;              // spring
  double damping_ratio = 0.0;      // spring
};

// The base of every joint. Owned by the world (World::add_constraint); body b may be
// no_body_id for a joint to the world.
class Constraint {
 public:
  Constraint(BodyId a, BodyId b) : a_(a), b_(b) {}
  virtual ~Constraint() = default;
  Constraint(const Constraint&) = delete;
  Constraint& operator=(const Constraint&) = delete;

  BodyId body_a() const { return a_; }
  BodyId body_b() const { return b_; }
  // The number of rows: fixed while the joint is in a world (an inactive limit is still a row,
  // e.g. with a large C: it then never pushes).
  virtual int row_count() const = 0;
  // Writes row_count() rows for the bodies' present poses; b is nullptr for the world.
  virtual void build_rows(const Body& a, const Body* b, JointRow* rows) const = 0;
  // The accumulated impulse of each row over the last step (N s or N m s, in the order the
  // rows are built; empty before the first step). The next step is warm started from them.
  const std::vector<double>& impulses() const { return impulses_; }

 private:
  friend class Solver;
  BodyId a_, b_;
  std::vector<double> impulses_;
};

}  // namespace rigidlab
