#include "engine/solver.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "engine/integrators.hpp"

namespace rigidlab {

void Solver::begin(std::size_t body_count) {
  bodies_.resize(body_count + 1);
  accelerations_.resize(body_count + 1);
  bodies_[body_count] = SolverBody{};  // the ground: never moves
  accelerations_[body_count] = Acceleration{};
}

// ---- prepare ---------------------------------------------------------------------------------

void Solver::prepare(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
                     const std::vector<Plane>& planes, const std::vector<JointRef>& joints,
                     double h) {
  h_ = h;
  // The push velocities start at zero each substep, with the bodies' mass properties.
  pushes_.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    pushes_[i].inverse_mass = bodies_[i].inverse_mass;
    pushes_[i].inverse_inertia = bodies_[i].inverse_inertia;
    pushes_[i].velocity = pushes_[i].angular_velocity = Vec3::Zero();
  }
  contacts_.find(bodies, ids, planes, bodies_.data(), accelerations_.data(), settings, h);
  joints_ = &joints;
  rows_.clear();
  const Softness joint_soft = make_soft(settings.joint_hertz, settings.joint_damping_ratio, h);
  for (const JointRef& joint : joints) {
    const int count = joint.constraint->row_count();
    scratch_.resize(static_cast<std::size_t>(count));
    joint.constraint->build_rows(bodies[joint.a], joint.b == no_body ? nullptr : &bodies[joint.b],
                                 scratch_.data());
    const std::uint32_t a = static_cast<std::uint32_t>(joint.a);
    const std::uint32_t b = static_cast<std::uint32_t>(joint.b == no_body ? ground() : joint.b);
    for (const JointRow& spec : scratch_) {
      Row r{};
      r.row.jacobian = spec.jacobian;
      prepare_row(r.row, bodies_[a], bodies_[b]);
      r.a = a, r.b = b;
      r.kind = spec.kind;
      r.error = spec.error;
      r.soft = joint_soft;
      switch (spec.kind) {
        case JointRow::Kind::equality:
          break;
        case JointRow::Kind::limit:
          r.row.lower = 0.0;
          break;
        case JointRow::Kind::motor:
          r.row.lower = -spec.max_impulse, r.row.upper = spec.max_impulse;
          r.bias = -spec.target_velocity;
          r.soft = rigid_softness;
          break;
        case JointRow::Kind::spring:
          r.row.lower = -spec.max_impulse, r.row.upper = spec.max_impulse;
          r.soft = make_soft(spec.hertz, spec.damping_ratio, h);
          break;
      }
      rows_.push_back(r);
    }
  }
}

// ---- warm start, solve, relax ------------------------------------------------------------------

void Solver::warm_start() {
  contacts_.warm_start(bodies_.data());
  const double scale = last_h_ > 0.0 ? h_ / last_h_ : 1.0;
  std::size_t next = 0;
  for (const JointRef& joint : *joints_) {
    const std::vector<double>& kept = joint.constraint->impulses_;
    const std::size_t count = static_cast<std::size_t>(joint.constraint->row_count());
    for (std::size_t k = 0; k < count; ++k) {
      Row& r = rows_[next + k];
      if (k < kept.size())
        r.row.impulse = std::clamp(scale * kept[k], r.row.lower, r.row.upper);
      apply_row(r.row, bodies_[r.a], bodies_[r.b], r.row.impulse);
    }
    next += count;
  }
}

// The velocity bias of a joint row and its softness in the velocity sweeps (engine/constraint.hpp,
// the row kinds): equality rows rigid; limits speculative while C > 0, else rigid; motors their
// target; springs their own soft row.
double Solver::joint_bias(const Row& r, Softness& soft) const {
  soft = rigid_softness;
  switch (r.kind) {
    case JointRow::Kind::equality:
      return 0.0;
    case JointRow::Kind::limit:
      return r.error > 0.0 ? r.error / h_ : 0.0;  // may close within the substep, no more
    case JointRow::Kind::motor:
      return r.bias;
    case JointRow::Kind::spring:
      soft = r.soft;
      return soft.mass_scale * soft.bias_rate * r.error;
  }
  return 0.0;
}

double Solver::sweep_joints(bool forward) {
  double largest = 0.0;
  const std::size_t n = rows_.size();
  for (std::size_t k = 0; k < n; ++k) {
    Row& r = rows_[forward ? k : n - 1 - k];
    Softness soft;
    const double bias = joint_bias(r, soft);
    largest = std::max(largest, solve_row(r.row, bodies_[r.a], bodies_[r.b], bias, soft));
  }
  return largest;
}

// soft_step's position feedback for the joints' equality rows and violated limits, on the
// push velocities (see the header): Box2D's soft joint row with joint_hertz and
// joint_damping_ratio.
void Solver::push_joints(bool forward) {
  const std::size_t n = rows_.size();
  for (std::size_t k = 0; k < n; ++k) {
    Row& r = rows_[forward ? k : n - 1 - k];
    const bool pushes = r.kind == JointRow::Kind::equality ||
                        (r.kind == JointRow::Kind::limit && r.error <= 0.0);
    if (!pushes) continue;
    ConstraintRow row = r.row;
    row.impulse = r.push_impulse;
    solve_row(row, pushes_[r.a], pushes_[r.b], r.soft.mass_scale * r.soft.bias_rate * r.error,
              r.soft);
    r.push_impulse = row.impulse;
  }
}

// Joints first, then contacts, as Box2D v3's stages; sweeps alternate direction (symmetric
// Gauss-Seidel). soft_step sweeps its position feedback too, on the push velocities.
void Solver::solve() {
  const bool soft = kind == SolverKind::soft_step;
  report_.clear();
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    if (poll != nullptr) poll->tick(contacts_.point_count() + rows_.size());
    const bool forward = sweep % 2 == 0;
    const double joints = sweep_joints(forward);
    const double contacts = contacts_.sweep(bodies_.data(), NormalMode::velocity, forward);
    report_.push_back(std::max(joints, contacts));
    if (soft) {
      push_joints(forward);
      contacts_.sweep(pushes_.data(), NormalMode::push, forward);
    }
  }
}

void Solver::integrate_positions() {
  if (getenv("SDEBUG") && bodies_.size() > 1) fprintf(stderr, "after solve w0=(%g %g %g)\n", bodies_[0].angular_velocity.x(), bodies_[0].angular_velocity.y(), bodies_[0].angular_velocity.z());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    SolverBody& b = bodies_[i];
    b.delta_position = h_ * (b.velocity + pushes_[i].velocity);
    b.delta_rotation = h_ * (b.angular_velocity + pushes_[i].angular_velocity);
  }
  contacts_.positions_moved(bodies_.data());
}

void Solver::relax() {
  if (kind != SolverKind::soft_step) return;
  for (int sweep = 0; sweep < settings.relax_iterations; ++sweep) {
    if (poll != nullptr) poll->tick(contacts_.point_count() + rows_.size());
    const bool forward = sweep % 2 == 0;
    sweep_joints(forward);
    contacts_.sweep(bodies_.data(), NormalMode::relax, forward);
  }
}

void Solver::restitution() {
  if (getenv("SDEBUG") && bodies_.size() > 1) fprintf(stderr, "before restitution w0=(%g %g %g)\n", bodies_[0].angular_velocity.x(), bodies_[0].angular_velocity.y(), bodies_[0].angular_velocity.z());
  contacts_.restitution(bodies_.data(), accelerations_.data(), poll);
  if (getenv("SDEBUG") && bodies_.size() > 1) fprintf(stderr, "after restitution w0=(%g %g %g)\n", bodies_[0].angular_velocity.x(), bodies_[0].angular_velocity.y(), bodies_[0].angular_velocity.z());
}

// ---- sequential_impulses' position correction ----------------------------------------------------

std::size_t Solver::correct_positions(std::vector<Body>& bodies) {
  if (kind != SolverKind::sequential_impulses) return all_finite;
  std::size_t first_bad = contacts_.correct_positions(bodies, poll);
  correct_joint_positions(bodies, *joints_);
  for (const JointRef& joint : *joints_) {
    if (!state_is_finite(bodies[joint.a])) first_bad = std::min(first_bad, joint.a);
    if (joint.b != no_body && !state_is_finite(bodies[joint.b]))
      first_bad = std::min(first_bad, joint.b);
  }
  return first_bad;
}

// Non-linear Gauss-Seidel on the joints' equality rows and violated limits (Box2D v2.4
// b2Joint::SolvePositionConstraints): each row rebuilt at the present poses, then the position
// impulse −β C/K (C clamped to max_correction) moves both bodies along W Jᵀ.
void Solver::correct_joint_positions(std::vector<Body>& bodies,
                                     const std::vector<JointRef>& joints) {
  for (int sweep = 0; sweep < settings.position_iterations; ++sweep) {
    for (const JointRef& joint : joints) {
      Body& a = bodies[joint.a];
      Body* b = joint.b == no_body ? nullptr : &bodies[joint.b];
      const SolverBody& sa = bodies_[joint.a];
      const SolverBody& sb = bodies_[joint.b == no_body ? ground() : joint.b];
      scratch_.resize(static_cast<std::size_t>(joint.constraint->row_count()));
      joint.constraint->build_rows(a, b, scratch_.data());
      for (const JointRow& row : scratch_) {
        const bool holds = row.kind == JointRow::Kind::equality ||
                           (row.kind == JointRow::Kind::limit && row.error < 0.0);
        if (!holds) continue;
        const double k = coupling(row.jacobian, row.jacobian, sa, sb);
        if (!(k > 0.0)) continue;
        const double c =
            std::clamp(row.error, -settings.max_correction, settings.max_correction);
        const double lambda = -settings.baumgarte * c / k;
        const Jacobian& j = row.jacobian;
        if (sa.inverse_mass > 0.0) {
          a.position -= sa.inverse_mass * lambda * j.linear;
          a.orientation = rotate_by(a.orientation, -lambda * (sa.inverse_inertia * j.angular_a), 1.0);
        }
        if (b != nullptr && sb.inverse_mass > 0.0) {
          b->position += sb.inverse_mass * lambda * j.linear;
          b->orientation = rotate_by(b->orientation, lambda * (sb.inverse_inertia * j.angular_b), 1.0);
        }
      }
    }
  }
}

// ---- store -------------------------------------------------------------------------------------

void Solver::store() {
  contacts_.store(h_);
  std::size_t next = 0;
  for (const JointRef& joint : *joints_) {
    std::vector<double>& kept = joint.constraint->impulses_;
    const std::size_t count = static_cast<std::size_t>(joint.constraint->row_count());
    kept.resize(count);
    for (std::size_t k = 0; k < count; ++k) kept[k] = rows_[next + k].row.impulse;
    next += count;
  }
  last_h_ = h_;
}

}  // namespace rigidlab
