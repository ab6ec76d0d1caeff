#include "engine/solver.hpp"

#include <algorithm>

#include "engine/integrators.hpp"
#include "engine/joint.hpp"

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
  bodies_in_ = &bodies;
  rows_.clear();
  groups_.clear();
  blocks_.clear();
  fuse_pushes_ = true;
  tree_.clear(bodies_.size());
  tree_rows_.clear();
  tree_offers_.clear();
  const Softness joint_soft = make_soft(settings.joint_hertz, settings.joint_damping_ratio, h);
  const double warm_scale = last_h_ > 0.0 ? h_ / last_h_ : 1.0;
  for (const JointRef& joint : joints) {
    const std::vector<double>& kept = joint.constraint->impulses_;
    const Body* b = joint.b == no_body ? nullptr : &bodies[joint.b];
    joint.constraint->track(bodies[joint.a], b);
    const int count = joint.constraint->row_count();
    scratch_.resize(static_cast<std::size_t>(count));
    ahead_.resize(static_cast<std::size_t>(count));
    joint.constraint->build_rows(bodies[joint.a], b, scratch_.data());
    const std::uint32_t a_slot = static_cast<std::uint32_t>(joint.a);
    const std::uint32_t b_slot = static_cast<std::uint32_t>(b == nullptr ? ground() : joint.b);
    build_rows_ahead(*joint.constraint, bodies[joint.a], b, a_slot, b_slot);
    for (std::size_t k = 0; k < scratch_.size(); ++k) {
      const JointRow& spec = scratch_[k];
      Row r = make_row(spec, a_slot, b_slot);
      r.soft = joint_soft;
      if (spec.kind == JointRow::Kind::equality)
        r.bias = (ahead_[k].error - spec.error) / h -
                 row_velocity(r.row, bodies_[a_slot], bodies_[b_slot]);
      if (spec.kind == JointRow::Kind::spring || spec.kind == JointRow::Kind::motor)
        prepare_oscillator(r, spec);
      if (spec.kind == JointRow::Kind::motor) fuse_pushes_ = false;
      // The warm start (applied by warm_start): the impulse the row ended the previous step
      // with, scaled by the ratio of the time steps, read here while the joint is at hand.
      if (k < kept.size()) r.row.impulse = std::clamp(warm_scale * kept[k], r.row.lower, r.row.upper);
      rows_.push_back(r);
    }
    group_rows(rows_.size() - scratch_.size());
  }
  rigid_factor_.valid = soft_factor_.valid = false;
  if (kind == SolverKind::soft_step && !tree_offers_.empty()) build_tree(joint_soft.compliance());
}

// Offers a group of equality rows to the joint forest (a joint's block, or the single equality
// row of a joint that has only one); taken unless it would close a loop. soft_step only:
// sequential_impulses stays document 000's solver, row blocks swept one after the other (the
// lessons "sequential-impulses" and "kinematic-pairs" reproduce its sweeps by hand).
void Solver::offer_to_tree(const Group& g) {
  if (kind != SolverKind::soft_step) return;
  const Row* rows = &rows_[g.first];
  if (g.size == 1 && !(rows[0].kind == JointRow::Kind::equality && rows[0].row.mass > 0.0)) return;
  Jacobian jacobians[JointTree::max_rows];
  for (int i = 0; i < g.size; ++i) jacobians[i] = rows[i].row.jacobian;
  tree_.offer(rows[0].a, rows[0].b, jacobians, g.size, bodies_.data());
  tree_offers_.push_back(static_cast<std::uint32_t>(groups_.size() - 1));
}

// The forest: only trees without a loop (a tree that a refused joint would have closed, the
// whole of joint_grid's lattice for one, stays with Gauss-Seidel: measured on a 25 x 25 grid of
// hinges, a spanning forest solved exactly with Gauss-Seidel for the loops' joints cost 2.4 to
// 2.6 times the step and left the worst joint error after 4 s at 4.4 cm against 2.0 cm). Ordered
// and factored for the rigid velocity rows and for the soft position rows.
void Solver::build_tree(double compliance) {
  tree_.drop_looped();
  for (std::size_t k = 0; k < tree_offers_.size(); ++k) {
    if (!tree_.taken(k)) continue;
    Group& g = groups_[tree_offers_[k]];
    g.tree = true;
    for (std::uint32_t i = 0; i < g.size; ++i) {
      rows_[g.first + i].tree = true;
      tree_rows_.push_back(g.first + i);
    }
  }
  tree_.order();
  tree_bias_.resize(tree_rows_.size());
  tree_impulse_.resize(tree_rows_.size());
  tree_.factor(bodies_.data(), 0.0, rigid_factor_);
  tree_.factor(bodies_.data(), compliance, soft_factor_);
}

// A rigid row of `spec` between two solver slots, its effective mass at their present inverse
// inertias; limits one-sided.
Solver::Row Solver::make_row(const JointRow& spec, std::uint32_t a, std::uint32_t b) const {
  Row r{};
  r.row.jacobian = spec.jacobian;
  prepare_row(r.row, bodies_[a], bodies_[b]);
  r.a = a, r.b = b;
  r.kind = spec.kind;
  r.error = spec.error;
  r.block = JointBlocks::none;
  if (spec.kind == JointRow::Kind::limit) r.row.lower = 0.0;
  return r;
}

// The groups of a joint's rows from `first` on (JointRow::block), each block of equality rows
// with the inverse of its K, kept as the sweeps read it (engine/joint_blocks.hpp); a block
// whose K cannot be inverted (neither body can move along some row) is solved row by row.
void Solver::group_rows(std::size_t first) {
  for (std::size_t k = 0; k < scratch_.size();) {
    const int size = std::clamp<int>(scratch_[k].block, 1, max_block);
    Group g{static_cast<std::uint32_t>(first + k), 1, 0};
    if (size > 1 && k + static_cast<std::size_t>(size) <= scratch_.size()) {
      Row* rows = &rows_[first + k];
      Jacobian jacobians[max_block];
      double bias[max_block], push_bias[max_block];
      for (int i = 0; i < size; ++i) {
        jacobians[i] = rows[i].row.jacobian;
        bias[i] = rows[i].bias;
        push_bias[i] = rows[0].soft.mass_scale * rows[0].soft.bias_rate * rows[i].error;
      }
      g.block = blocks_.add(rows[0].a, rows[0].b, jacobians, size, bodies_[rows[0].a],
                            bodies_[rows[0].b], bias, push_bias, rows[0].soft);
      if (g.block != JointBlocks::none) {
        g.size = static_cast<std::uint8_t>(size);
        for (int i = 0; i < size; ++i) rows[i].block = g.block, rows[i].block_row = i;
      }
    }
    if (g.size > 1) {
      groups_.push_back(g);
      offer_to_tree(g);
      k += g.size;
    } else {
      for (int i = 0; i < size; ++i) groups_.push_back({static_cast<std::uint32_t>(first + k + i), 1, 0});
      if (size == 1) offer_to_tree(groups_.back());
      k += static_cast<std::size_t>(size);
    }
  }
}

// Where the sweeps keep a row's accumulated impulse (velocity or push): in its block, or in
// the row.
double& Solver::impulse(Row& r, bool push) {
  if (r.block != JointBlocks::none)
    return push ? blocks_.push_impulse(r.block, r.block_row) : blocks_.impulse(r.block, r.block_row);
  return push ? r.push_impulse : r.row.impulse;
}

// The curvature of an equality row (second order in h). Solved with its Jacobian J at the
// start of the substep, a row would leave J v' = 0, but the bodies then move on a line while
// the constraint curves: a pendulum's bob leaves its circle by h²v²/2L, and the next substep,
// its rod turned by Δθ = v h/L, removes v sin Δθ of its speed: a loss of Δθ² of the kinetic
// energy per substep (the period at 80° came out 1.6 % short at 240 Hz). So the row's
// velocity target is the one that makes C vanish at the END of the substep to second order,
//   C(x + h v') ≈ C + h J v' + R = 0,   R = C(x + h v) − C − h J v ≈ ½ h² vᵀ(∂²C) v,
// with R measured on the rows built again at the poses the free velocities reach in h; the
// position error C itself is left to each solver's position stage (soft_step's pushes,
// sequential_impulses' position pass). This is SHAKE's condition (the constraint force along
// the start-of-step gradient, the constraint met at the end of the step; Ryckaert, Ciccotti
// and Berendsen 1977): a symplectic scheme, so a pendulum's energy stays bounded instead of
// drifting, and J v' = −R/h is its linearisation.
void Solver::build_rows_ahead(Constraint& joint, const Body& a, const Body* b,
                              std::uint32_t a_slot, std::uint32_t b_slot) {
  Body a_ahead = a;
  a_ahead.position += h_ * bodies_[a_slot].velocity;
  a_ahead.orientation = orientation_ahead(a, a_slot);
  if (b == nullptr) {
    joint.build_rows(a_ahead, nullptr, ahead_.data());
    return;
  }
  Body b_ahead = *b;
  b_ahead.position += h_ * bodies_[b_slot].velocity;
  b_ahead.orientation = orientation_ahead(*b, b_slot);
  joint.build_rows(a_ahead, &b_ahead, ahead_.data());
}

// The orientation the position stage gives `body` (solver slot `slot`) if the solve leaves its
// angular velocity as it is now, by the integrator's own function (orientation_after): with
// gyroscopic = "conserving" that is not exp(h ω) q but the splitting's turn, which differs by
// O(h²) per substep (it turns by about h (ω_start + ω_end)/2). Built at exp(h ω) q, the rows
// of a spinning top on a ball pivot (box 0.3 x 0.2 x 0.1 m, 1 kg, 20 rad/s about its axis,
// pivot 0.3 m from its centre, semi_implicit at 1 ms, soft_step) missed the pose the top
// reached, and the pivot came apart by up to 0.84 mm in 5 s (the position feedback pulling it
// back each substep); built here, by 1e-10 m.
Quat Solver::orientation_ahead(const Body& body, std::uint32_t slot) const {
  const SolverBody& s = bodies_[slot];
  if (stages != nullptr) return orientation_after(*stages, body, slot, s.angular_velocity, h_);
  return rotate_by(body.orientation, s.angular_velocity, h_);
}

// The curvature R/h again, at the poses the solved velocities reach: SHAKE's iteration (the
// first R was measured along the free velocities, which the constraint impulses then turn; the
// error left is R(v_solved) − R(v_free) = O(h² |v| |Δv| / L) per substep). Run once, after the
// first sweep, for the joints of the forest, whose rows that sweep solved exactly; the next
// sweep solves them again for the new targets. Measured on issue 14's chain of 10 links (no
// contacts between the links): the worst joint error over 10 s from 1.4 mm to 0.06 mm at one
// substep. Joints left to Gauss-Seidel keep their first R: after one sweep their velocities
// are far from solved, and a refresh there made the chain's energy rise by 1.6 %.
void Solver::refresh_curvature() {
  if (!rigid_factor_.valid || tree_rows_.empty()) return;
  std::size_t next = 0;
  for (const JointRef& joint : *joints_) {
    const std::size_t count = static_cast<std::size_t>(joint.constraint->row_count());
    const Row& first = rows_[next];
    if (count > 0 && first.tree) {
      const Body* b = joint.b == no_body ? nullptr : &(*bodies_in_)[joint.b];
      ahead_.resize(count);
      build_rows_ahead(*joint.constraint, (*bodies_in_)[joint.a], b, first.a, first.b);
      for (std::size_t k = 0; k < count; ++k) {
        Row& r = rows_[next + k];
        if (r.tree)
          r.bias = (ahead_[k].error - r.error) / h_ - row_velocity(r.row, bodies_[r.a], bodies_[r.b]);
      }
    }
    next += count;
  }
}

// ---- spring and motor rows ----------------------------------------------------------------------
//
// A spring row is the damped oscillator C'' + 2ζω C' + ω² C = 0 of its coordinate, per unit
// effective mass m = 1/(J W Jᵀ) (Box2D's soft joint spring); a motor row is document 000's
// PD controller, m C'' = −kp C + kv (θ̇d − C') with C = θ − θd, i.e. the same oscillator
// with ω² = kp/m, 2ζω = kv/m, driven by (kv/m) θ̇d. Both are integrated EXACTLY over the
// substep, not to first order: from the row's coordinate C0 and its rate at the start of the
// substep (the free velocity less h times the free acceleration J a, which also drives the
// oscillator as a constant force) damped_oscillator_step gives C(h) and C'(h). The velocity
// sweeps then drive J v to C'(h) (a rigid row toward that target, its impulse bounded by
// max_force·h), and a push row on the push velocities (engine/solver.hpp) adds
// (C(h) − C0)/h − C'(h), so that the positions, which move by h (v + v_push), reach C(h):
// velocity and position of a lone spring follow the continuous solution to rounding, where
// a first-order soft row (Box2D's implicit Euler) lags by a phase of O(ωh) per period.
// A bounded motor is the same oscillator while its impulse stays inside ±max_force·h (it then
// moves exactly as the unbounded one). One that saturates applies exactly ±max_force over the
// substep: a constant acceleration a, for which x(h) = x0 + h C'0 + ½ h² a and C'(h) = C'0 + h a,
// so its push is (x(h) − x0)/h − C'(h) = −½ (C'(h) − C'0) (push_joints decides which, from the
// impulse the velocity sweeps left).
void Solver::prepare_oscillator(Row& r, const JointRow& spec) const {
  r.soft = rigid_softness;
  r.push_target = 0.0;
  r.start_rate = 0.0;
  r.pushes = false;
  r.bias = 0.0;
  if (!(r.row.mass > 0.0)) return;  // neither body can move along the row
  const double bound = spec.max_force * h_;
  if (spec.kind == JointRow::Kind::motor) r.row.lower = -bound, r.row.upper = bound;
  const double inverse_mass = 1.0 / r.row.mass;
  double k = 0.0, c = 0.0, f = 0.0;
  if (spec.kind == JointRow::Kind::spring) {
    const double omega = 2.0 * M_PI * spec.hertz;
    k = omega * omega, c = 2.0 * spec.damping_ratio * omega;
  } else {
    k = spec.kp * inverse_mass, c = spec.kv * inverse_mass;
    f = c * spec.target_velocity;
  }
  const Jacobian& j = r.row.jacobian;
  const Acceleration& aa = accelerations_[r.a];
  const Acceleration& ab = accelerations_[r.b];
  const double free_acceleration = j.linear.dot(ab.linear - aa.linear) +
                                   j.angular_b.dot(ab.angular) - j.angular_a.dot(aa.angular);
  const double v0 = row_velocity(r.row, bodies_[r.a], bodies_[r.b]) - h_ * free_acceleration;
  const OscillatorState end =
      damped_oscillator_step(spec.error, v0, k, c, f + free_acceleration, h_);
  if (!std::isfinite(end.x) || !std::isfinite(end.v)) return;
  r.bias = -end.v;
  r.push_target = (end.x - spec.error) / h_ - end.v;
  r.start_rate = v0;
  r.pushes = true;
}

// ---- warm start, solve, relax ------------------------------------------------------------------

void Solver::warm_start() {
  contacts_.warm_start(bodies_.data());
  for (Row& r : rows_) {  // the impulses prepare took from the joints
    apply_row(r.row, bodies_[r.a], bodies_[r.b], r.row.impulse);
    impulse(r, false) = r.row.impulse;
  }
}

// The velocity bias of a joint row and its softness in the velocity sweeps (engine/constraint.hpp,
// the row kinds): equality rows rigid, with their curvature; limits speculative while C > 0, else rigid; springs and
// motors their oscillator's end velocity (above).
double Solver::joint_bias(const Row& r) const {
  switch (r.kind) {
    case JointRow::Kind::equality:
      return r.bias;  // R/h, the curvature (above)
    case JointRow::Kind::limit:
      return r.error > 0.0 ? r.error / h_ : 0.0;  // may close within the substep, no more
    case JointRow::Kind::spring:
    case JointRow::Kind::motor:
      return r.bias;
  }
  return 0.0;
}

// The largest velocity error of the sweep: |J v + bias| before each update, except for a row
// that stays at a bound of its impulse (an inactive limit, a saturated motor): that row is
// satisfied. With `push`, each group's push rows are swept right after its velocity rows, in
// the same pass over the rows (push_joints with feedback, in one read of the rows instead of
// two): the velocity rows touch only the body velocities and the push rows only the push
// velocities, so the result is that of the two sweeps one after the other, as long as no push
// row reads the body velocities (a saturated motor's does: solve() fuses without motors only).
double Solver::sweep_joints(bool forward, bool push) {
  const bool tree = rigid_factor_.valid;
  const bool push_tree = push && soft_factor_.valid;
  double largest = tree && forward ? solve_tree(rigid_factor_, false) : 0.0;
  if (push_tree && forward) solve_tree(soft_factor_, true);
  const std::size_t n = groups_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Group& g = groups_[forward ? k : n - 1 - k];
    if (!(g.tree && tree)) largest = std::max(largest, sweep_group(g));
    if (push && !(g.tree && push_tree)) push_group(g, true);
  }
  if (tree && !forward) largest = std::max(largest, solve_tree(rigid_factor_, false));
  if (push_tree && !forward) solve_tree(soft_factor_, true);
  return largest;
}

// One group's velocity rows; its velocity error as sweep_joints counts it. The equality rows of
// a joint that constrain one point or one orientation together (3 point rows, 2 or 3 angular
// rows) are a block, as Box2D's revolute joint and Jolt's PointConstraintPart do, updated at
// once (engine/joint_blocks.hpp): exact for the block in one update where row-by-row
// Gauss-Seidel converges slowly: a bob on a 1 m arm has lever-arm terms 1000 times its 1/m, and
// 10 row-by-row sweeps left a hinged pendulum's period 1.5 % long at 80°.
double Solver::sweep_group(const Group& g) {
  if (g.size > 1) return blocks_.solve(g.block, bodies_.data(), false);
  Row& r = rows_[g.first];
  const double before = r.row.impulse;
  const double error = solve_row(r.row, bodies_[r.a], bodies_[r.b], joint_bias(r), rigid_softness);
  const bool saturated = r.row.impulse == before &&
                         (r.row.impulse == r.row.lower || r.row.impulse == r.row.upper);
  return saturated ? 0.0 : error;
}

// The forest's rows in one exact solve (engine/joint_tree.hpp): the rigid velocity rows with
// their curvature bias, or soft_step's soft position rows on the push velocities.
double Solver::solve_tree(const JointTree::Factor& f, bool push) {
  for (std::size_t i = 0; i < tree_rows_.size(); ++i) {
    Row& r = rows_[tree_rows_[i]];
    tree_bias_[i] = push ? r.soft.bias_rate * r.error : r.bias;
    tree_impulse_[i] = impulse(r, push);
  }
  const double largest =
      tree_.solve(f, push ? pushes_.data() : bodies_.data(), tree_bias_.data(), tree_impulse_.data());
  for (std::size_t i = 0; i < tree_rows_.size(); ++i) impulse(rows_[tree_rows_[i]], push) = tree_impulse_[i];
  return largest;
}

// The joints' rows on the push velocities (see the header). soft_step: the position feedback
// of the equality rows and violated limits, Box2D's soft joint row with joint_hertz and
// joint_damping_ratio. Both solvers: the springs' and motors' position part (above).
void Solver::push_joints(bool forward, bool feedback) {
  const bool tree = feedback && soft_factor_.valid;
  if (tree && forward) solve_tree(soft_factor_, true);
  const std::size_t n = groups_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Group& g = groups_[forward ? k : n - 1 - k];
    if (!(g.tree && tree)) push_group(g, feedback);
  }
  if (tree && !forward) solve_tree(soft_factor_, true);
}

// One group's push rows.
void Solver::push_group(const Group& g, bool feedback) {
  if (g.size > 1) {
    if (feedback) blocks_.solve(g.block, pushes_.data(), true);
    return;
  }
  Row& r = rows_[g.first];
  double bias = 0.0;
  Softness soft = rigid_softness;
  if (r.kind == JointRow::Kind::spring || r.kind == JointRow::Kind::motor) {
    if (!r.pushes) return;
    const bool saturated = r.kind == JointRow::Kind::motor &&
                           (r.row.impulse == r.row.lower || r.row.impulse == r.row.upper);
    // A saturated motor: −½ of the rate change its constant force made (above).
    bias = saturated ? 0.5 * (row_velocity(r.row, bodies_[r.a], bodies_[r.b]) - r.start_rate)
                     : -r.push_target;
  } else {
    const bool holds = r.kind == JointRow::Kind::equality ||
                       (r.kind == JointRow::Kind::limit && r.error <= 0.0);
    if (!feedback || !holds) return;
    soft = r.soft;
    bias = soft.mass_scale * soft.bias_rate * r.error;
  }
  ConstraintRow row = r.row;
  row.lower = -unbounded, row.upper = unbounded;
  if (r.kind == JointRow::Kind::limit) row.lower = 0.0;
  row.impulse = r.push_impulse;
  solve_row(row, pushes_[r.a], pushes_[r.b], bias, soft);
  r.push_impulse = row.impulse;
}

// Joints first, then contacts, as Box2D v3's stages; sweeps alternate direction (symmetric
// Gauss-Seidel). soft_step sweeps its position feedback too, on the push velocities.
void Solver::solve() {
  const bool soft = kind == SolverKind::soft_step;
  report_.clear();
  // A step where contacts begin has no warm start for them, and `iterations` sweeps carry a
  // load only about as many bodies down a stack (Gauss-Seidel on a chain of n converges in ~n²
  // sweeps): the rest of the stack falls through its supports for the first steps, until the
  // warm start has caught up. So on such a step the sweeps go on while they pay: until the
  // largest velocity error is a millionth of the first sweep's, or the last 10 (or
  // `iterations`) sweeps took less than 1 % off it (a heap's contacts can stall), at most
  // max_iterations in all. The warm steps after keep `iterations`. Which steps:
  // - sequential_impulses: every step where a point begins. Each layer stays sunk by what the
  //   first steps lose (under the slop, which the position sweeps leave alone: 2.8 mm for 5
  //   boxes, 57 mm for a column of 20, 30 mm for the pyramid of 210), and an impact's new
  //   point (a gap) must reach down a resting column in its step too: with the soft_step rule
  //   below, a column of 3 boxes still swayed at 3.6 cm/s (0.5 with this one) 20 steps after a
  //   ball bounced on it (tests/engine/bounce_on_stack_test.cpp).
  // - soft_step: the steps whose new touching points form a chain longer than the sweeps carry
  //   a load down, n² > iterations (ContactConstraints::cold_chain: the pyramid of 210 on its
  //   first step, n = 20). Its push-out lifts a sunk stack back, but not from everything:
  //   without this, the pyramid's top sank 43-72 mm in its first 10 steps (0.05 mm with it),
  //   and 10 of the add orders shuffled by mt19937 seeds 1 to 40 fell apart (the top 1.8-7.0
  //   m away after 10 s; tests/engine/pyramid_creep_test.cpp). New points that land on
  //   something held (a box on the floor or on a resting stack: n = 1; a settling heap:
  //   n <= 2) or have a gap (no load yet) keep `iterations`: the rule of sequential_impulses
  //   cost soft_step's settle/1024 5.8 times its time per step (bench/contacts_bench.cpp:
  //   21.5 ms against 3.73; a heap has new points every step).
  const std::size_t chain = contacts_.cold_chain();
  const bool converge = soft ? chain * chain > static_cast<std::size_t>(settings.iterations)
                             : contacts_.cold_points() > 0;
  const int most = converge ? ContactSettings::max_iterations : settings.iterations;
  const std::size_t window = static_cast<std::size_t>(std::max(settings.iterations, 10));
  // soft_step stops before `iterations` once the sweeps have converged: see settled().
  const bool may_settle = soft && !converge && rows_.empty();
  for (int sweep = 0; sweep < most; ++sweep) {
    if (may_settle && sweep >= 2 && settled()) break;
    const bool extra = sweep >= settings.iterations;
    if (extra) {
      const std::size_t done = report_.size();
      if (!(report_.back() > 1e-6 * report_.front())) break;
      if (done % window == 0 && done >= 2 * window &&
          report_.back() > 0.99 * report_[done - 1 - window])
        break;
    }
    if (poll != nullptr) poll->tick(contacts_.point_count() + rows_.size());
    const bool forward = sweep % 2 == 0;
    // The joints' push rows before the contacts' (the order of two sweeps), the contacts'
    // velocity and push rows in one pass (ContactConstraints::sweep): the joints' push rows
    // touch only the push velocities, the contacts' velocity rows only the body velocities.
    const bool fuse = soft && fuse_pushes_;
    const double joints = sweep_joints(forward, fuse);
    if (!fuse && !extra) push_joints(forward, soft);
    const double contacts = contacts_.sweep(bodies_.data(), NormalMode::velocity, forward,
                                            soft ? pushes_.data() : nullptr);
    report_.push_back(std::max(joints, contacts));
    if (sweep == 0) refresh_curvature();
  }
}

// Whether soft_step's velocity sweeps have converged, so that the rest of its `iterations`
// would change nothing worth a sweep: the last sweep's largest velocity error would move no
// point by a ten-millionth of the slop in the substep (3e-8 m/s at the defaults), and no point
// is sunk beyond the push's slop (the push rows, swept in the same passes, have nothing to do).
// A resting stack gets there in two sweeps (the pyramid of 210 at rest: 1.6e-5 m/s in the
// first, 2.2e-9 m/s from the second on; an aligned column: rounding, 7e-17), anything still
// moving or landing keeps its `iterations`. Not with joints (their push rows are not
// measured), nor for sequential_impulses (the lessons show its fixed sweeps converging).
// MuJoCo's solver stops on a tolerance the same way (mjOption.tolerance).
bool Solver::settled() {
  return report_.back() * h_ <= 1e-7 * settings.linear_slop && contacts_.push_idle();
}

void Solver::integrate_positions() {
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
  contacts_.restitution(bodies_.data(), accelerations_.data(), poll);
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
// b2Joint::SolvePositionConstraints): each joint's rows rebuilt at the present poses, then a
// position impulse λ moves both bodies along W Jᵀ. A block of equality rows (a point, an
// orientation: JointRow::block) is corrected as one, λ = −K⁻¹ C with K_ij = J_i W J_jᵀ, fully,
// as Box2D v2.4's revolute and spherical joints do; other rows by −β C/K (β = baumgarte).
// Measured on issue 14's chain of 10 boxes (sequential_impulses, defaults): the worst joint
// error over 10 s 2.75 mm with every row by −β C/K, 1.53 mm with the blocks (the rest is the
// velocity sweeps' convergence: 0.75 mm at 50 iterations).
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
      for (std::size_t k = 0; k < scratch_.size();) {
        const int size = std::clamp<int>(scratch_[k].block, 1, max_block);
        if (size > 1 && k + static_cast<std::size_t>(size) <= scratch_.size()) {
          correct_block(&scratch_[k], size, a, b, sa, sb);
          k += static_cast<std::size_t>(size);
          continue;
        }
        const JointRow& row = scratch_[k++];
        const bool holds = row.kind == JointRow::Kind::equality ||
                           (row.kind == JointRow::Kind::limit && row.error < 0.0);
        if (!holds) continue;
        const double kk = coupling(row.jacobian, row.jacobian, sa, sb);
        if (!(kk > 0.0)) continue;
        const double c = std::clamp(row.error, -settings.max_correction, settings.max_correction);
        move_apart(row.jacobian, -settings.baumgarte * c / kk, a, b, sa, sb);
      }
    }
  }
}

// One block of equality rows at the present poses: λ = −K⁻¹ C (each C clamped to
// max_correction), skipped when K cannot be factored (neither body can move along a row).
void Solver::correct_block(const JointRow* rows, int size, Body& a, Body* b, const SolverBody& sa,
                           const SolverBody& sb) const {
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, max_block, max_block>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_block, 1>;
  Small K(size, size);
  SmallVector c(size);
  for (int i = 0; i < size; ++i) {
    c[i] = std::clamp(rows[i].error, -settings.max_correction, settings.max_correction);
    for (int j = 0; j < size; ++j) K(i, j) = coupling(rows[i].jacobian, rows[j].jacobian, sa, sb);
  }
  const Eigen::LLT<Small> llt(K);
  if (llt.info() != Eigen::Success) return;
  const SmallVector lambda = -llt.solve(c);
  if (!lambda.allFinite()) return;
  Jacobian sum;
  for (int i = 0; i < size; ++i) {
    sum.linear += lambda[i] * rows[i].jacobian.linear;
    sum.angular_a += lambda[i] * rows[i].jacobian.angular_a;
    sum.angular_b += lambda[i] * rows[i].jacobian.angular_b;
  }
  move_apart(sum, 1.0, a, b, sa, sb);
}

// The position impulse λ J: a moves by −λ W_a J_a, b by +λ W_b J_b (translation and rotation).
void Solver::move_apart(const Jacobian& j, double lambda, Body& a, Body* b, const SolverBody& sa,
                        const SolverBody& sb) {
  if (sa.inverse_mass > 0.0) {
    a.position -= sa.inverse_mass * lambda * j.linear;
    a.orientation = rotate_by(a.orientation, -lambda * (sa.inverse_inertia * j.angular_a), 1.0);
  }
  if (b != nullptr && sb.inverse_mass > 0.0) {
    b->position += sb.inverse_mass * lambda * j.linear;
    b->orientation = rotate_by(b->orientation, lambda * (sb.inverse_inertia * j.angular_b), 1.0);
  }
}

// ---- sequential_impulses' velocity projection -----------------------------------------------------
//
// The velocity sweeps aim at the END of the substep (build_rows_ahead: J v' = −R/h at the start
// pose), so the velocities they leave carry the constraint's curvature and do not satisfy the
// rows at the start pose; after the positions moved, neither do they at the end pose, by
// O(h |v|²/L). sequential_impulses is document 000's solver, whose velocities satisfy the
// constraints: so at the end of each substep the joints' rows are rebuilt at the final
// (position-corrected) poses and the velocities projected on them, J(x_end) v = 0 (limits:
// not approaching past the bound; springs and motors are not constraints and are left out),
// by the same rigid sweeps. With the look-ahead sweep this is RATTLE (Andersen 1983: SHAKE's
// position half, then the velocity half on the constraint's tangent at the new position),
// symplectic like SHAKE; the projection does not change the motion, as the next substep's
// sweeps project the velocities on the same rows again (a projection of a projection), but
// what a user reads after a step is a velocity the joints allow, at the pose they see. A
// pendulum with plain rows at the start pose instead (J v' = 0 there, then the positions move
// on the tangent and are corrected back) loses a fraction (h ω)² of its energy per substep:
// measured, its period at 80° came out 1.8 % short at 60 Hz with 4 substeps.
void Solver::project_velocities(std::vector<Body>& bodies) {
  if (kind != SolverKind::sequential_impulses || joints_ == nullptr || joints_->empty()) return;
  auto load = [&](std::size_t i) {
    const Body& body = bodies[i];
    SolverBody& s = bodies_[i];
    s = SolverBody{};
    if (body.inverse_mass == 0.0) return;
    const Mat3 r = body.orientation.toRotationMatrix();
    s.velocity = body.velocity;
    s.angular_velocity = body.angular_velocity;
    s.inverse_mass = body.inverse_mass;
    s.inverse_inertia = r * body.inverse_inertia * r.transpose();
  };
  for (const JointRef& joint : *joints_) {
    load(joint.a);
    if (joint.b != no_body) load(joint.b);
  }
  rows_.clear();
  groups_.clear();
  blocks_.clear();
  for (const JointRef& joint : *joints_) {
    const Body* b = joint.b == no_body ? nullptr : &bodies[joint.b];
    scratch_.resize(static_cast<std::size_t>(joint.constraint->row_count()));
    joint.constraint->build_rows(bodies[joint.a], b, scratch_.data());
    const std::uint32_t a_slot = static_cast<std::uint32_t>(joint.a);
    const std::uint32_t b_slot = static_cast<std::uint32_t>(b == nullptr ? ground() : joint.b);
    for (const JointRow& spec : scratch_) {
      Row r = make_row(spec, a_slot, b_slot);
      if (spec.kind == JointRow::Kind::spring || spec.kind == JointRow::Kind::motor)
        r.row.lower = r.row.upper = 0.0;  // no constraint: never moves
      rows_.push_back(r);
    }
    group_rows(rows_.size() - scratch_.size());
  }
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    if (poll != nullptr) poll->tick(rows_.size());
    sweep_joints(sweep % 2 == 0);
  }
  for (const JointRef& joint : *joints_)
    for (std::size_t i : {joint.a, joint.b}) {
      if (i == no_body || bodies[i].inverse_mass == 0.0) continue;
      bodies[i].velocity = bodies_[i].velocity;
      bodies[i].angular_velocity = bodies_[i].angular_velocity;
    }
}

// ---- store -------------------------------------------------------------------------------------

void Solver::store() {
  contacts_.store(h_);
  std::size_t next = 0;
  for (const JointRef& joint : *joints_) {
    Constraint& c = *joint.constraint;
    std::vector<double>& kept = c.impulses_;
    const std::size_t count = static_cast<std::size_t>(c.row_count());
    kept.resize(count);
    c.motor_force_ = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      Row& r = rows_[next + k];
      r.row.impulse = impulse(r, false);
      kept[k] = r.row.impulse;
      // What b received: λ J's linear part; angular rows (no linear part) add λ k.
      c.step_impulse_ += r.row.impulse * r.row.jacobian.linear;
      if (r.row.jacobian.linear.isZero())
        c.step_angular_impulse_ += r.row.impulse * r.row.jacobian.angular_b;
      if (r.kind == JointRow::Kind::motor) c.motor_force_ = r.row.impulse / h_;
    }
    next += count;
  }
  last_h_ = h_;
}

}  // namespace rigidlab
