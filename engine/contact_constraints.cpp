// The contact constraints, part 2: settings, warm starting, the sweeps (friction, normals one
// by one or as a block: engine/contact_blocks.cpp) and the bookkeeping between steps. See
// engine/contact_constraints.hpp.
#include "engine/contact_constraints.hpp"

#include <algorithm>
#include <cmath>

#include "engine/contact_helpers.hpp"
#include "engine/format.hpp"

namespace rigidlab {

using namespace contact_detail;

std::optional<SolverKind> parse_solver(std::string_view name) {
  for (std::size_t i = 0; i < std::size(solver_names); ++i)
    if (name == solver_names[i]) return static_cast<SolverKind>(i);
  return std::nullopt;
}

std::string contact_settings_problem(const ContactSettings& s) {
  const struct {
    const char* name;
    int value, min;
  } counts[] = {{"iterations", s.iterations, 1},
                {"relax_iterations", s.relax_iterations, 0},
                {"position_iterations", s.position_iterations, 0}};
  for (const auto& field : counts)
    if (field.value < field.min || field.value > ContactSettings::max_iterations)
      return std::string(field.name) + " must be an integer from " + std::to_string(field.min) +
             " to " + std::to_string(ContactSettings::max_iterations) + ", got " +
             std::to_string(field.value);
  const struct {
    const char* name;
    double value;
  } nonnegative[] = {{"restitution_threshold", s.restitution_threshold},
                     {"linear_slop", s.linear_slop},
                     {"max_correction", s.max_correction},
                     {"speculative_distance", s.speculative_distance},
                     {"match_distance", s.match_distance},
                     {"contact_hertz", s.contact_hertz},
                     {"contact_damping_ratio", s.contact_damping_ratio},
                     {"joint_hertz", s.joint_hertz},
                     {"joint_damping_ratio", s.joint_damping_ratio},
                     {"contact_push_speed", s.contact_push_speed}};
  for (const auto& field : nonnegative)
    if (!std::isfinite(field.value) || !(field.value >= 0.0))
      return std::string(field.name) + " must be finite and >= 0, got " +
             format_number(field.value);
  if (!(s.baumgarte >= 0.0 && s.baumgarte <= 1.0))
    return "baumgarte must be in [0, 1], got " + format_number(s.baumgarte);
  return "";
}

// ---- warm starting -----------------------------------------------------------------------------

// The previous step's points of manifold m's pair (same bodies or plane): [first, last) of
// contacts_, found once per manifold. `hint` is where the pair's points would be if they
// followed the previous manifold's (the manifolds of a body's pairs come in the order of
// contacts_): checked first; when they do not start there, searched from it. The manifolds
// come as two runs in the order of contacts_ (find: the plane manifolds body by body, then
// the pairs), but contacts_ puts a body's plane points after its pairs' points, so the hint
// misses for every plane manifold and for each body's first pair: a binary search over all of
// contacts_ then cost log₂ of the points in cache misses (settle/4096: 12k points, 1.8 MB).
// Forward of the hint the search gallops (1, 2, 4, ... points on, then a binary search in the
// last stride): a few points, in cache. The same point as std::lower_bound over all.
std::pair<const ContactInfo*, const ContactInfo*> ContactConstraints::previous_points(
    const Manifold& m, const ContactInfo* hint) const {
  const ContactInfo* begin = contacts_.data();
  const ContactInfo* end = begin + contacts_.size();
  auto same_pair = [&m](const ContactInfo& info) {
    return info.a == m.id_a && info.b == m.id_b && info.plane == m.plane;
  };
  const ContactInfo* first = hint;
  if (!(hint != end && same_pair(*hint) && (hint == begin || !same_pair(hint[-1])))) {
    const auto key = sort_key(m.id_a, m.id_b, m.plane, 0);
    auto less = [](const ContactInfo& info, const auto& k) { return sort_key(info) < k; };
    const ContactInfo* from = begin;
    const ContactInfo* to = end;
    if (hint != end && less(*hint, key)) {  // after the hint: gallop
      std::size_t stride = 1;
      from = hint;  // less than key
      while (static_cast<std::size_t>(end - from) > stride && less(from[stride], key))
        from += stride, stride *= 2;
      to = static_cast<std::size_t>(end - from) > stride ? from + stride : end;
      ++from;
    } else if (hint != end) {  // at or before the hint
      to = hint + 1;
    }
    first = std::lower_bound(from, to, key, less);
  }
  const ContactInfo* last = first;
  while (last != end && same_pair(*last)) ++last;
  return {first, last};
}

// The previous step's point that p continues, among its pair's [first, last): the same
// feature, or else the nearest point of the pair within match_distance (features of clipped
// faces change when a corner of one box lies exactly on a side of the other). nullptr when p
// is new.
const ContactInfo* ContactConstraints::previous_point(const Point& p, const ContactInfo* first,
                                                      const ContactInfo* last) const {
  for (const ContactInfo* it = first; it != last; ++it)
    if (it->feature == p.feature) return it;
  const ContactInfo* nearest = nullptr;
  double best = settings_->match_distance * settings_->match_distance;
  for (const ContactInfo* it = first; it != last; ++it) {
    const double d2 = (it->point - p.point).squaredNorm();
    if (d2 <= best) best = d2, nearest = it;
  }
  return nearest;
}

// Starts every point from the impulses its point ended the previous step's sweeps with. The
// velocities before that are kept for the restitution stage.
void ContactConstraints::warm_start(SolverBody* solver) {
  solver_ = solver;
  start_velocity_.resize(ground_ + 1);
  start_angular_velocity_.resize(ground_ + 1);
  for (std::size_t i = 0; i <= ground_; ++i) {
    start_velocity_[i] = solver[i].velocity;
    start_angular_velocity_[i] = solver[i].angular_velocity;
  }
  // Impulses scale with the step: a resting contact carries m g Δt.
  const double scale = last_dt_ > 0.0 ? h_ / last_dt_ : 1.0;
  cold_points_ = 0;
  // The chains of new points (measure_cold_chain) start at the fixed bodies and the ground.
  chain_.resize(ground_ + 1);
  for (std::size_t i = 0; i <= ground_; ++i)
    chain_[i] = i == ground_ || solver[i].inverse_mass == 0.0 ? 0 : unreached;
  cold_manifolds_.clear();
  const ContactInfo* hint = contacts_.data();
  patches_.resize(manifolds_.size());
  for (Manifold& m : manifolds_) {
    SolverBody& a = solver[m.a];
    SolverBody& b = solver[m.b];
    const std::size_t index = static_cast<std::size_t>(&m - manifolds_.data());
    prepare_patch(index, a, b);  // contact_friction.cpp
    const bool patch = m.patch;
    if (!patch && may_be_patch(m)) prepare_friction(m, a, b);  // add_manifold left them
    const auto [first, last] = previous_points(m, hint);
    hint = last;
    bool cold_touching = false;
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      const ContactInfo* found = previous_point(points_[k], first, last);
      const bool touches = points_[k].separation <= touch_tolerance();
      if (found == nullptr) {
        ++cold_points_;
        cold_touching = cold_touching || touches;
        continue;
      }
      if (touches) chain_[m.a] = chain_[m.b] = 0;  // held by a warm-started point
      NormalRow& normal = normals_[k];
      FrictionRows& f = frictions_[k];
      normal.impulse = scale * found->sweep_impulse;
      f.tangent1.impulse = scale * found->friction_impulse.dot(f.tangent1.jacobian.linear);
      f.tangent2.impulse = scale * found->friction_impulse.dot(f.tangent2.jacobian.linear);
      apply_normal(m.normal, k, a, b, normal.impulse);
      if (patch) continue;
      apply_row(f.tangent1, a, b, f.tangent1.impulse);
      apply_row(f.tangent2, a, b, f.tangent2.impulse);
    }
    if (patch) warm_start_patch(index);
    if (cold_touching) cold_manifolds_.push_back(static_cast<std::uint32_t>(index));
  }
  measure_cold_chain();
}

// The longest chain of new touching contacts (cold_chain): each body's fewest new contacts in
// series down to what holds it (a fixed body, the ground, or a body with a warm-started point
// that touches), by relaxing the manifolds of new touching points until nothing changes
// (Bellman-Ford: as many passes as the chain is long, over those manifolds only). A body that
// no chain reaches rests on nothing held (it is free, or on other new contacts only that reach
// no support): it carries no load to a support and is left out.
void ContactConstraints::measure_cold_chain() {
  cold_chain_ = 0;
  if (cold_manifolds_.empty()) return;
  for (bool changed = true; changed;) {
    changed = false;
    for (const std::uint32_t mi : cold_manifolds_) {
      std::uint32_t& a = chain_[manifolds_[mi].a];
      std::uint32_t& b = chain_[manifolds_[mi].b];
      if (a + 1 < b) b = a + 1, changed = true;
      if (b + 1 < a) a = b + 1, changed = true;
    }
  }
  for (const std::uint32_t mi : cold_manifolds_)
    for (const std::uint32_t links : {chain_[manifolds_[mi].a], chain_[manifolds_[mi].b]})
      if (links != unreached) cold_chain_ = std::max<std::size_t>(cold_chain_, links);
}

// An impact of this step with e > 0 (a gap at the start, touching after the positions moved)
// was stopped by the velocity sweeps as a speculative contact, v_n ≥ −s/Δt: an inelastic push,
// which a chain of gaps closed within the step passes on inelastically too (a struck row of
// five balls 1 mm apart at 60 Hz: about 0.6 m/s each after the sweeps, of which the
// restitution stage could only reflect what was left: 32 % of the striker's energy lost). So
// its sweep impulse is taken back before the restitution stage, which then resolves the
// impact from the velocities the bodies met with, impact by impact. It is taken back along
// the row at the end poses (positions_moved brought the arms to one point again), so that
// momentum and angular momentum stay exact; the positions keep the move the sweeps gave
// them (the bodies landed on the surface, not through it).
// Only where the push went no further than such impacts: a body that some other contact
// pushed in the sweeps (a box on the floor under a bouncing ball: the floor's reaction to the
// ball's push) is held, and its impacts keep their sweep impulse, as the restitution rounds
// can add to the floor's impulse but not take it back.
void ContactConstraints::take_back_speculative() {
  const double touching = touch_tolerance(), landed = landed_tolerance();
  auto candidate = [&](const Manifold& m, const Point& p) {
    return m.restitution > 0.0 && p.separation > touching && p.end_separation <= landed;
  };
  held_.assign(ground_ + 1, 0);
  auto hold = [&](std::uint32_t slot) {
    if (solver_[slot].inverse_mass > 0.0 && !held_[slot]) return held_[slot] = 1, true;
    return false;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (const Manifold& m : manifolds_)
      for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
        if (!(normals_[k].impulse > 0.0)) continue;
        if (candidate(m, points_[k]) && !held_[m.a] && !held_[m.b]) continue;
        changed = hold(m.a) || changed;
        changed = hold(m.b) || changed;
      }
  }
  for (const Manifold& m : manifolds_) {
    if (held_[m.a] || held_[m.b]) continue;
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      NormalRow& normal = normals_[k];
      if (!(normal.impulse > 0.0) || !candidate(m, points_[k])) continue;
      apply_normal(m.normal, k, solver_[m.a], solver_[m.b], -normal.impulse);
      normal.impulse = 0.0;
    }
  }
}

// See the header ("Lever arms after the positions moved").
void ContactConstraints::positions_moved(SolverBody* solver) {
  solver_ = solver;
  relax_rows_.ready = false;
  const double tolerance = landed_tolerance();
  for (std::size_t mi = 0; mi < manifolds_.size(); ++mi) {
    Manifold& m = manifolds_[mi];
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = points_[k];
      p.end_separation = current_separation(m, p);
      normals_[k].relax_cap = p.end_separation <= tolerance ? unbounded : normals_[k].impulse;
    }
    const SolverBody& a = solver[m.a];
    const SolverBody& b = solver[m.b];
    const Vec3 apart = b.delta_position - a.delta_position;
    if (!(apart.squaredNorm() > tolerance * tolerance)) continue;
    if (m.radius_a > 0.0 && m.radius_b > 0.0) {
      turn_to_centres(m, apart);
      continue;
    }
    const double w = a.inverse_mass / (a.inverse_mass + b.inverse_mass);
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = points_[k];
      p.r_a += (1.0 - w) * apart;
      p.r_b -= w * apart;
      prepare_normal(k, m.normal, p.r_a, p.r_b, a, b);
    }
    Patch& patch = patches_[mi];
    if (m.patch) {
      // The patch keeps its impulses at the new arms. Only if it cannot be prepared there do
      // its points take them (spread at the patch's old centre and spread, as before the
      // move) and solve their own rows; else store() spreads them at the end of the step.
      const Vec3 centre = patch.r_b;
      const double spread = patch.spread;
      prepare_patch(mi, a, b);
      if (!m.patch) {
        patch.r_b = centre, patch.spread = spread, m.patch = true;
        spread_patch(mi);
        m.patch = false;
        prepare_friction(m, a, b);
      }
    } else {
      prepare_friction(m, a, b);
    }
    if (m.block_state == prepared) prepare_block(mi, false);
    else m.block_state = rigid_only;
  }
}

// Two spheres (one point) that moved apart in the step: the impulses after the move (relax,
// restitution) are taken at the end poses (see the header): the normal turned to the line of
// the centres there, the arms along it through the centres (one point, midway between the
// surfaces), and the impact velocity measured along it. The accumulated impulses keep their
// world directions: the normal one goes on along the new normal, the friction impulse is
// projected on the new tangents.
void ContactConstraints::turn_to_centres(Manifold& m, const Vec3& apart) {
  Point& p = points_[m.first];
  FrictionRows& f = frictions_[m.first];
  const Vec3 centres = p.r_a - p.r_b + apart;  // x_b − x_a at the end (r_a − r_b at the start)
  const double length = centres.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return;
  const Vec3 friction = f.tangent1.impulse * f.tangent1.jacobian.linear +
                        f.tangent2.impulse * f.tangent2.jacobian.linear;
  m.normal = m.start_normal = centres / length;
  const double from_a = m.radius_a + 0.5 * (length - m.radius_a - m.radius_b);
  p.r_a = p.start_r_a = from_a * m.normal;
  p.r_b = p.start_r_b = (from_a - length) * m.normal;
  Vec3 t1 = in_plane(f.tangent1.jacobian.linear, m.normal);
  if (!(t1.norm() > 1e-9)) tangent_basis(m.normal, t1, t1);
  t1.normalize();
  const Vec3 t2 = m.normal.cross(t1);
  f.tangent1.jacobian = point_jacobian(t1, p.r_a, p.r_b);
  f.tangent2.jacobian = point_jacobian(t2, p.r_a, p.r_b);
  f.tangent1.impulse = friction.dot(t1);
  f.tangent2.impulse = friction.dot(t2);
  prepare_normal(m.first, m.normal, p.r_a, p.r_b, solver_[m.a], solver_[m.b]);
  for (ConstraintRow* row : {&f.tangent1, &f.tangent2})
    prepare_row(*row, solver_[m.a], solver_[m.b]);
  p.turned = true;
}

// ---- the sweeps ----------------------------------------------------------------------------------

// The gap of p now (Box2D v3 b2SolveContact, with the rotation linearised over the substep):
// s₀ plus how far the bodies moved along the normal at the point.
double ContactConstraints::current_separation(const Manifold& m, const Point& p) const {
  const SolverBody& a = solver_[m.a];
  const SolverBody& b = solver_[m.b];
  const Vec3 moved = b.delta_position + b.delta_rotation.cross(p.r_b) - a.delta_position -
                     a.delta_rotation.cross(p.r_a);
  return p.separation + m.normal.dot(moved);
}

void ContactConstraints::prepare_normal(std::uint32_t k, const Vec3& normal, const Vec3& r_a,
                                        const Vec3& r_b, const SolverBody& a,
                                        const SolverBody& b) {
  NormalRow& row = normals_[k];
  row.angular_a = r_a.cross(normal);
  row.angular_b = r_b.cross(normal);
  row.weighted_a = a.inverse_inertia * row.angular_a;
  row.weighted_b = b.inverse_inertia * row.angular_b;
  row.mass = inverse_or_zero(coupling_parts(normal.dot(normal), row.angular_a, row.angular_b,
                                            a.inverse_mass, row.weighted_a, b.inverse_mass,
                                            row.weighted_b));
}

// The velocity bias of p's normal row (solve_row drives J v toward −bias) and its softness,
// per mode (see NormalMode). False when the row is left alone.
bool ContactConstraints::normal_bias(const Manifold& m, std::uint32_t k, NormalMode mode,
                                     double& bias, Softness& soft) const {
  const Point& p = points_[k];
  soft = rigid_softness;
  bias = 0.0;
  switch (mode) {
    case NormalMode::velocity:  // before the positions move: a gap may close, no more
      if (p.separation > 0.0) bias = p.separation / h_;
      return true;
    case NormalMode::push:  // within the landing tolerance counts as touching, so that the
      // corners of a face resting flat (gaps of ±1e-16 m) all get the same soft row
      if (p.separation > landed_tolerance()) return false;
      soft = m.softness;
      // Pushed out to an overlap of push_slop_fraction of the point's slop, not to 0: see
      // push_slop_fraction.
      bias = std::max(soft.mass_scale * soft.bias_rate *
                          std::min(p.separation + push_slop_fraction * p.slop, 0.0),
                      -settings_->contact_push_speed);
      return true;
    case NormalMode::relax:
      // A point that had a gap at the start and touches now is an impact of this step: the
      // restitution stage takes it, in the order of the impacts (a row of balls).
      if (p.separation > touch_tolerance()) return false;
      if (p.end_separation <= landed_tolerance()) return true;
      bias = p.end_separation / h_;
      return normals_[k].relax_cap > 0.0;
  }
  return false;
}

// Gauss-Seidel updates of each point's friction within the Coulomb disk of its current normal
// impulse (Catto 2005; Box2D v2.4 SolveVelocityConstraints): both tangents from the same
// velocities, the pair clamped to the disk, so sliding friction lies against the slip. The
// points are taken in the order of the sweep (forward, then backward: symmetric Gauss-Seidel),
// as the manifolds are: in one fixed order the first corner of every face always got its
// friction first, and a pyramid of 210 boxes, symmetric across its plane, rocked out of it
// (its top ±1 cm in z after 10 s; now 0.6 mm).
void ContactConstraints::solve_friction(Manifold& m, bool forward) {
  if (!(m.friction > 0.0)) return;
  const std::size_t index = static_cast<std::size_t>(&m - manifolds_.data());
  if (m.patch) return solve_patch(index);  // contact_friction.cpp
  SolverBody& a = solver_[m.a];
  SolverBody& b = solver_[m.b];
  // The velocities in locals for the manifold's points: the stores of the impulses could
  // alias them, and every point would read them back from memory.
  Vec3 va = a.velocity, wa = a.angular_velocity, vb = b.velocity, wb = b.angular_velocity;
  const double ma = a.inverse_mass, mb = b.inverse_mass;
  bool changed = false;
  for (std::uint32_t i = 0; i < m.count; ++i) {
    const std::uint32_t k = m.first + (forward ? i : m.count - 1 - i);
    FrictionRows& p = frictions_[k];
    const double limit = m.friction * normals_[k].impulse;
    // No normal load and no friction impulse: the disk is a point and nothing changes (side
    // by side boxes of a pyramid, spheres grazing in a heap).
    if (limit == 0.0 && p.tangent1.impulse == 0.0 && p.tangent2.impulse == 0.0) continue;
    const Vec3 dv = vb - va;
    const Jacobian& j1 = p.tangent1.jacobian;
    const Jacobian& j2 = p.tangent2.jacobian;
    double t1 = p.tangent1.impulse - p.tangent1.mass * jacobian_velocity(j1, dv, wa, wb);
    double t2 = p.tangent2.impulse - p.tangent2.mass * jacobian_velocity(j2, dv, wa, wb);
    // Squares first: std::hypot's care against overflow cost a fifth of a pyramid's step, so
    // it is kept for the impulses whose squares overflow; and a point that sticks (inside the
    // disk, the usual case at rest) needs no square root at all.
    const double length_squared = t1 * t1 + t2 * t2;
    if (!(length_squared <= limit * limit) || !std::isfinite(length_squared)) {
      const double length =
          std::isfinite(length_squared) ? std::sqrt(length_squared) : std::hypot(t1, t2);
      if (length > limit) {  // slipping: on the edge of the cone, against the slip
        const double scale = length > 0.0 ? limit / length : 0.0;
        t1 *= scale, t2 *= scale;
      }
    }
    // Both rows' changes applied at once (Δv = W Jᵀ Δλ of the pair).
    const double d1 = t1 - p.tangent1.impulse, d2 = t2 - p.tangent2.impulse;
    const Vec3 linear = d1 * j1.linear + d2 * j2.linear;
    va -= ma * linear;
    wa -= d1 * p.tangent1.weighted_a + d2 * p.tangent2.weighted_a;
    vb += mb * linear;
    wb += d1 * p.tangent1.weighted_b + d2 * p.tangent2.weighted_b;
    p.tangent1.impulse = t1, p.tangent2.impulse = t2;
    changed = true;
  }
  if (!changed) return;
  a.velocity = va, a.angular_velocity = wa;
  b.velocity = vb, b.angular_velocity = wb;
}

// The normal rows of one manifold in `mode` (see the header): as the prepared block when all
// its points take part, as a smaller block when some do, point by point when a block cannot
// settle. Returns the largest velocity error before the update.
// Rows that carry no impulse and do not approach (r = J v + bias ≥ 0 on every active row, all
// λ = 0) are already solved: λ' = 0 meets every form's conditions (w = r ≥ 0, λ' = 0), so the
// manifold is left alone (a pyramid's boxes touching side by side, a heap's grazing spheres).
// A template on the mode: the sweeps call it some 24 times per manifold and step, and each
// mode's tests then fold away.
template <NormalMode mode>
double ContactConstraints::solve_normals(std::size_t manifold) {
  Manifold& m = manifolds_[manifold];
  SolverBody& a = solver_[m.a];
  SolverBody& b = solver_[m.b];
  constexpr Impulse which = mode == NormalMode::push ? Impulse::push : Impulse::sweep;
  double bias[max_manifold_points], residual[max_manifold_points];
  double gamma[max_manifold_points], cap[max_manifold_points];
  Softness soft[max_manifold_points];
  bool active[max_manifold_points];
  bool all_active = true, solved = true;
  double largest = 0.0;
  const ModeRow* rows = mode_rows(mode).rows.data() + m.first;
  // J v = n·(v_b − v_a) + (r_b × n)·ω_b − (r_a × n)·ω_a: the points share the first term.
  const double linear = m.normal.dot(b.velocity - a.velocity);
  for (std::uint32_t i = 0; i < m.count; ++i) {
    const NormalRow& p = normals_[m.first + i];
    active[i] = rows[i].active;
    cap[i] = mode == NormalMode::relax ? p.relax_cap : unbounded;
    if (!active[i]) {
      all_active = false;
      residual[i] = 0.0;
      continue;
    }
    const double velocity = linear + p.angular_b.dot(b.angular_velocity) -
                            p.angular_a.dot(a.angular_velocity);
    const double impulse = mode == NormalMode::push ? p.push_impulse : p.impulse;
    // The block form takes β C without the mass scale (which its matrix holds as Γ, the same
    // for all the points of a manifold: they share their softness): offset = bias/mass_scale.
    residual[i] = velocity + rows[i].offset;
    // The error, velocity + bias, is the residual for the rigid modes (mass_scale 1); the
    // push mode's is not reported (sweep).
    const double error = residual[i];
    largest = std::max(largest, impulse > 0.0 ? std::abs(error) : -std::min(error, 0.0));
    solved = solved && impulse == 0.0 && residual[i] >= 0.0;
  }
  if (solved) return largest;
  if (block_usable(manifold)) {
    // Γ: the same for all the points of a manifold (its compliance, made with the block).
    for (std::uint32_t i = 0; i < m.count; ++i)
      gamma[i] = mode == NormalMode::push ? m.compliance : 0.0;
    const Block& block = blocks_[manifold];
    constexpr bool push = mode == NormalMode::push;
    Vec4 start;
    if (all_active) {
      if (solve_block<which>(manifold, push ? block.soft_inverse : block.rigid_inverse,
                             push ? m.compliance : 0.0, residual,
                             mode == NormalMode::relax ? cap : nullptr, &start) ||
          solve_subset<which>(manifold, active, residual, gamma, cap, &start))
        return largest;
    } else if (solve_subset<which>(manifold, active, residual, gamma, cap, nullptr)) {
      return largest;
    }
  }
  for (std::uint32_t i = 0; i < m.count; ++i) {
    if (!active[i]) continue;
    const std::uint32_t k = m.first + i;
    normal_bias(m, k, mode, bias[i], soft[i]);
    // solve_row (engine/constraint_row.hpp) on this mode's impulse within [0, cap], without
    // copying the point's row into a ConstraintRow.
    double& impulse = impulse_of<which>(k);
    const double v = normal_velocity(m.normal, k, a, b);
    const double total =
        updated_impulse(normals_[k].mass, impulse, v, bias[i], soft[i], 0.0, cap[i]);
    apply_normal(m.normal, k, a, b, total - impulse);
    impulse = total;
  }
  return largest;
}

void ContactConstraints::prepare_mode(NormalMode mode) {
  std::vector<ModeRow>& rows = mode_rows(mode).rows;
  rows.resize(points_.size());
  bool idle = true;
  for (const Manifold& m : manifolds_)
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      double bias;
      Softness soft;
      rows[k].active = normal_bias(m, k, mode, bias, soft);
      rows[k].offset = rows[k].active ? bias / soft.mass_scale : 0.0;
      idle = idle && rows[k].offset == 0.0;
    }
  mode_rows(mode).ready = true;
  mode_rows(mode).idle = idle;
}

double ContactConstraints::sweep(SolverBody* solver, NormalMode mode, bool forward,
                                 SolverBody* push) {
  if (!mode_rows(mode).ready) prepare_mode(mode);
  if (push != nullptr && !push_rows_.ready) prepare_mode(NormalMode::push);
  switch (mode) {
    case NormalMode::velocity: return sweep_as<NormalMode::velocity>(solver, forward, push);
    case NormalMode::push: return sweep_as<NormalMode::push>(solver, forward, push);
    case NormalMode::relax: break;
  }
  return sweep_as<NormalMode::relax>(solver, forward, push);
}

// The solver bodies of a manifold a few ahead in a sweep, asked for before they are needed: a
// sweep visits the manifolds in order, but their bodies are scattered over the solver array,
// and from settle/4096 on (786 KB of solver bodies, the contacts streaming past them) they
// come from L3 every sweep (bench/contacts_bench.cpp). A hint: results do not change.
template <NormalMode mode>
double ContactConstraints::sweep_as(SolverBody* solver, bool forward, SolverBody* push) {
  const std::size_t n = manifolds_.size();
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t m = forward ? k : n - 1 - k;
    if (k + prefetch_distance < n) {
      const Manifold& next = manifolds_[forward ? k + prefetch_distance : m - prefetch_distance];
      prefetch_bodies(solver, next);
      if (push != nullptr) prefetch_bodies(push, next);
    }
    solver_ = solver;
    if (mode != NormalMode::push) solve_friction(manifolds_[m], forward);
    largest = std::max(largest, solve_normals<mode>(m));
    if (push == nullptr) continue;
    solver_ = push;
    solve_normals<NormalMode::push>(m);
  }
  solver_ = solver;
  return largest;
}

// ---- bookkeeping -----------------------------------------------------------------------------

// The points go out in the order of contacts() (sort_key): the manifolds sorted by their
// pair (one manifold per pair), each one's points by feature, instead of sorting every point.
void ContactConstraints::store(double h) {
  for (std::size_t i = 0; i < manifolds_.size(); ++i) spread_patch(i);
  next_contacts_.clear();
  order_.resize(manifolds_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<std::uint32_t>(i);
  auto key = [this](std::uint32_t i) {
    const Manifold& m = manifolds_[i];
    return sort_key(m.id_a, m.id_b, m.plane, 0);
  };
  // find() makes the plane manifolds first, body by body, then the pairs in the order of
  // their ids: two sorted runs, merged in one pass (sorted when they are not).
  auto less = [&key](std::uint32_t x, std::uint32_t y) { return key(x) < key(y); };
  const auto middle = std::find_if(order_.begin(), order_.end(),
                                   [this](std::uint32_t i) { return manifolds_[i].plane == no_plane; });
  if (std::is_sorted(order_.begin(), middle, less) && std::is_sorted(middle, order_.end(), less)) {
    merged_.resize(order_.size());
    std::merge(order_.begin(), middle, middle, order_.end(), merged_.begin(), less);
    order_.swap(merged_);
  } else {
    std::sort(order_.begin(), order_.end(), less);
  }
  for (std::uint32_t index : order_) {
    const Manifold& m = manifolds_[index];
    const std::size_t first = next_contacts_.size();
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      const Point& p = points_[k];
      ContactInfo info;
      info.a = m.id_a, info.b = m.id_b, info.plane = m.plane, info.feature = p.feature;
      info.point = p.point;
      info.normal = m.normal;
      info.depth = -p.separation;
      // The next step is warm started with the load a point carried, not with an impact
      // (touching balls that a blow set apart at one speed would be pushed apart again).
      const double normal_impulse = normals_[k].impulse;
      const FrictionRows& f = frictions_[k];
      info.sweep_impulse = (p.flags & took_part_flag) ? 0.0 : normal_impulse;
      info.normal_impulse = normal_impulse + p.restitution_impulse;
      info.friction_impulse = f.tangent1.impulse * f.tangent1.jacobian.linear +
                              f.tangent2.impulse * f.tangent2.jacobian.linear;
      info.restitution = m.restitution;
      info.friction = m.friction;
      next_contacts_.push_back(info);
    }
    std::sort(next_contacts_.begin() + static_cast<std::ptrdiff_t>(first), next_contacts_.end(),
              [](const ContactInfo& x, const ContactInfo& y) { return x.feature < y.feature; });
  }
  contacts_.swap(next_contacts_);
  if (undo_open_) {  // the step's first store: keep the points it started from (begin_step)
    undo_contacts_.swap(next_contacts_);
    undo_open_ = false;
    undo_kept_ = true;
  }
  last_dt_ = h;
}

void ContactConstraints::body_removed(BodyId id) {
  auto involves = [id](const ContactInfo& c) { return c.a == id || c.b == id; };
  contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(), involves), contacts_.end());
  manifolds_.clear();
  points_.clear();
  normals_.clear();
  frictions_.clear();
  velocity_rows_.ready = push_rows_.ready = relax_rows_.ready = false;
}

}  // namespace rigidlab
