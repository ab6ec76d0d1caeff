// The contact constraints, part 3: restitution at the end of the step, impact by impact.
// See engine/contact_constraints.hpp ("Restitution").
#include <algorithm>
#include <cmath>

#include "engine/contact_helpers.hpp"

namespace rigidlab {

using namespace contact_detail;

namespace {

double square(double x) { return x * x; }

// Point flags of the restitution stage.
constexpr std::uint8_t touched_start = 1;  // touching when the substep began
constexpr std::uint8_t touching_end = 2;   // touching after the positions moved
constexpr std::uint8_t event = 4;          // impacts in the present round
constexpr std::uint8_t fired = 8;          // impacted in an earlier round
constexpr std::uint8_t took_part = ContactConstraints::took_part_flag;  // in some round
constexpr std::uint8_t opened = 32;        // resting when the substep began, a gap now

// A round solves its events with every point that touches at the end and touched already at
// the start (resting contacts: they hold what the impact pushes against) or has impacted, and
// the resting contacts that opened a little in the step (restitution, below).
bool in_round(std::uint8_t flags) {
  return (flags & (event | opened)) ||
         ((flags & touching_end) && (flags & (touched_start | fired)));
}

// At most this many rounds of impacts per step: each round is one impact of the chain a push
// can travel along (a row of n balls needs n − 1).
constexpr int max_rounds = 32;

// The manifold solves a round with a bounce may spend converging: a small round (a row of
// balls, Newton's cradle, a ball on a stack of a dozen boxes: up to 16 manifolds) gets every
// sweep up to ContactSettings::max_iterations; a round spanning a heap gets fewer, but never
// fewer than the velocity stage's `iterations`. Measured: in 1,024 spheres settling with
// e = 0.5 each step's bounce round spans ~80 % of the manifolds (touching ones hold what the
// impacts push against) and converged to 1e-12 in 200-380 sweeps of 600-1,250 manifolds,
// 5x the cost of the whole step without restitution.
constexpr long round_work = 16L * ContactSettings::max_iterations;

}  // namespace

// A body held by a resting contact does not fall freely: its acceleration over the step is
// taken as 0, and its velocity as the one it had at the start of the step (a box on the floor
// under a bouncing ball). A resting contact touched at the start of the step, carried load and
// did not come in fast; it holds a body when the body's free acceleration presses it into a
// support: the ground, a static body, a body held already (a column of boxes on the floor, held
// box by box from the floor up), or another free body pressing back (two bodies forced into
// each other). Without a force pressing them together (no gravity) touching bodies are free: a
// struck row of touching balls moves as one block. The search from the supports needs each
// body's manifolds (link_bodies).
void ContactConstraints::mark_supported(const Acceleration* acceleration) {
  acceleration_ = acceleration;
  supported_.assign(ground_ + 1, 0);
  link_bodies();
  const double tolerance = touch_tolerance();
  auto fixed = [&](std::uint32_t slot) {
    return slot == ground_ || solver_[slot].inverse_mass == 0.0;
  };
  // Whether the points of m that rest press b into a (n·(a_b − a_a) < 0, the accelerations of
  // the bodies' points; a support's is 0): the slightest tolerance keeps two free bodies that
  // fall side by side (equal accelerations, a difference of rounding) apart.
  auto presses = [&](const Manifold& m, bool seeding) {
    auto of = [&](std::uint32_t slot, const Vec3& r) -> Vec3 {
      if (fixed(slot) || (!seeding && supported_[slot])) return Vec3::Zero();
      return acceleration[slot].linear + acceleration[slot].angular.cross(r);
    };
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      const Point& p = points_[k];
      if (!(p.separation <= tolerance && normals_[k].impulse > 0.0 &&
            p.approach >= -settings_->restitution_threshold))
        continue;
      const Vec3 acc_a = of(m.a, p.r_a), acc_b = of(m.b, p.r_b);
      if (m.normal.dot(acc_b - acc_a) < -1e-9 * (acc_a.norm() + acc_b.norm())) return true;
    }
    return false;
  };
  frontier_.clear();
  auto hold = [&](std::uint32_t slot) {
    if (fixed(slot) || supported_[slot]) return;
    supported_[slot] = 1;
    frontier_.push_back(slot);
  };
  for (const Manifold& m : manifolds_)
    if (presses(m, true)) hold(m.a), hold(m.b);
  while (!frontier_.empty()) {  // up from the supports, contact by contact
    const std::uint32_t slot = frontier_.back();
    frontier_.pop_back();
    for (std::uint32_t j = body_first_[slot]; j < body_first_[slot + 1]; ++j) {
      const Manifold& m = manifolds_[body_manifolds_[j]];
      const std::uint32_t other = m.a == slot ? m.b : m.a;
      if (!fixed(other) && !supported_[other] && presses(m, false)) hold(other);
    }
  }
  for (std::uint32_t slot = 0; slot <= ground_; ++slot)
    if (fixed(slot)) supported_[slot] = 1;
}

// a_n: the relative normal acceleration of the point's material points (m/s²), each body free
// or, when supported, at rest.
double ContactConstraints::normal_acceleration(const Manifold& m, const Point& p) const {
  auto of = [&](std::uint32_t slot, const Vec3& r) -> Vec3 {
    if (supported_[slot]) return Vec3::Zero();
    return acceleration_[slot].linear + acceleration_[slot].angular.cross(r);
  };
  return m.start_normal.dot(of(m.b, p.start_r_b) - of(m.a, p.start_r_a));
}

// w (m/s, ≤ 0): the normal velocity with which p met the surface in this step (along the normal
// and at the arms it was found with), on the parabola
// its positions follow: with w₀ its normal velocity at the start of the step (u − a Δt/2 per
// body, u the velocity before the sweeps; a supported body's u − a Δt, the velocity it had
// before the step's forces: not what the sweeps left, which a soft column still giving way
// under the ball's speculative impulse made 0.85 m/s downward, and the ball's w that much
// slower) and s its gap then, the gap s + w₀ t + ½ a_n t² first closes at w = −√(w₀² − 2 a_n s) (however small s is:
// the last 0.1 mm of a 4 m/s fall at 1 kHz changes w by 2e-4 m/s). A point overlapping at the
// start meets the surface at once, at w₀. 0 when it does not come in within the step.
double ContactConstraints::impact_velocity(const Manifold& m, const Point& p) const {
  auto start = [&](std::uint32_t slot, const Vec3& r) -> Vec3 {
    const double back = supported_[slot] ? 1.0 : 0.5;  // to the start of the step, or its middle
    const Vec3 v = start_velocity_[slot] - back * h_ * acceleration_[slot].linear;
    const Vec3 w = start_angular_velocity_[slot] - back * h_ * acceleration_[slot].angular;
    return v + w.cross(r);
  };
  const double w0 = m.start_normal.dot(start(m.b, p.start_r_b) - start(m.a, p.start_r_a));
  const double a = normal_acceleration(m, p);
  const double s = p.separation;
  if (s <= 0.0) return std::min(w0, 0.0);
  // A sphere pair taken at the end poses: it did meet in the step (it touches now).
  if (p.turned) return w0 < 0.0 ? -std::sqrt(std::max(w0 * w0 - 2.0 * a * s, 0.0)) : 0.0;
  const double square = w0 * w0 - 2.0 * a * s;
  if (!(square >= 0.0)) return 0.0;  // turns back before reaching the surface
  const double w = -std::sqrt(square);
  // The time of that velocity, w = w₀ + a_n t, must lie within the step (and after w₀ < 0
  // when a_n = 0, the gap closing at the constant rate −w₀).
  const double t = a != 0.0 ? (w - w0) / a : (w0 < 0.0 ? s / -w0 : -1.0);
  return t >= 0.0 && t <= h_ * (1.0 + 1e-9) ? w : 0.0;
}

// The bounce target of a sphere pair taken at the end poses (turn_to_centres): the sweeps
// stopped it along the normal of the start, which is not the normal of the end, so reflecting
// the impact velocity there would not give the pair's energy back. The target is the normal
// velocity that does: the relative velocity of the centres leaves with |v|² = |v₀|² −
// (1 − e²) w², v₀ the relative velocity before the step and w the impact velocity along the
// normal, keeping what the bounce leaves alone across the normal now (the centres' relative
// velocity is the normal velocity of the point up to the spins, which a central impulse
// leaves alone).
double ContactConstraints::turned_target(const Manifold& m, double w,
                                         double a_n) const {
  // The centres' relative velocity: central impulses change only it (and the pair's kinetic
  // energy is that of the centre of mass plus ½ m_eff |v|² plus the unchanged spins).
  const Vec3 before = start_velocity_[m.b] - start_velocity_[m.a];
  const Vec3 now = solver_[m.b].velocity - solver_[m.a].velocity;
  const double across = now.squaredNorm() - square(now.dot(m.normal));
  const double e = m.restitution;
  const double along = before.squaredNorm() - (1.0 - e * e) * w * w - across;
  double target = std::sqrt(std::max(along, 0.0));
  // With friction part of what left the relative velocity across the normal went into heat
  // (and spins), not into the mismatch of the normals: it is not given back, and the bounce
  // is no more than the reflection e |w|.
  if (m.friction > 0.0) target = std::min(target, -e * w);
  return std::max(target - 0.5 * a_n * h_, 0.0);
}

// One Gauss-Seidel sweep of a restitution round over its points, on the round's increments
// (≥ 0). Whole manifolds in the round go as a block (a box landing flat leaves without a
// spin). Returns the largest change of an increment, and the largest increment in `peak`
// (measured here, as the points are in cache: a pass of its own over the round's points after
// each sweep read them from memory again, a tenth of the stage's misses at 4,096 spheres).
double ContactConstraints::round_sweep(bool forward, double& peak) {
  const std::size_t n = round_manifolds_.size();
  double largest = 0.0;
  // The round's manifolds are scattered over the arrays (gather_round): each is asked for
  // twice the prefetch distance ahead, its points and bodies once the distance ahead (as the
  // sweeps do: sweep_as).
  auto at = [&](std::size_t j) { return round_manifolds_[forward ? j : n - 1 - j]; };
  for (std::size_t k = 0; k < n; ++k) {
    if (k + 2 * prefetch_distance < n)
      __builtin_prefetch(&manifolds_[at(k + 2 * prefetch_distance)]);
    if (k + prefetch_distance < n) {
      const Manifold& next = manifolds_[at(k + prefetch_distance)];
      prefetch_bodies(solver_, next);
      if (next.count > 0) {
        __builtin_prefetch(&points_[next.first].round_impulse, 1);
        __builtin_prefetch(&normals_[next.first]);
      }
    }
    const std::size_t mi = at(k);
    Manifold& m = manifolds_[mi];
    SolverBody& a = solver_[m.a];
    SolverBody& b = solver_[m.b];
    bool all = true, any = false;
    bool member[max_manifold_points];
    double residual[max_manifold_points], before[max_manifold_points];
    const double gamma[max_manifold_points] = {0.0, 0.0, 0.0, 0.0};
    for (std::uint32_t i = 0; i < m.count; ++i) {
      const Point& p = points_[m.first + i];
      member[i] = in_round(p.flags);
      all = all && member[i], any = any || member[i];
      residual[i] = member[i] ? normal_velocity(m.normal, m.first + i, a, b) - p.target : 0.0;
      before[i] = p.round_impulse;
    }
    if (!any) continue;
    ++round_solves_;
    Vec4 start;
    const bool block =
        block_usable(mi) && (all ? solve_block(mi, blocks_[mi].rigid_inverse, 0.0,
                                      residual, nullptr, Impulse::round, &start) ||
                              solve_subset(mi, member, residual, gamma, nullptr, Impulse::round,
                                           &start)
                        : solve_subset(mi, member, residual, gamma, nullptr, Impulse::round,
                                       nullptr));
    if (!block) {
      for (std::uint32_t i = 0; i < m.count; ++i) {
        Point& p = points_[m.first + i];
        if (!in_round(p.flags)) continue;
        const double v = normal_velocity(m.normal, m.first + i, a, b);
        const double total =
            std::max(p.round_impulse - normals_[m.first + i].mass * (v - p.target), 0.0);
        apply_normal(m.normal, m.first + i, a, b, total - p.round_impulse);
        p.round_impulse = total;
      }
    }
    for (std::uint32_t i = 0; i < m.count; ++i) {
      const double impulse = points_[m.first + i].round_impulse;
      largest = std::max(largest, std::abs(impulse - before[i]));
      peak = std::max(peak, impulse);
    }
  }
  return largest;
}

// Closes a round at a point: its increment joins the restitution impulse, and it took part.
void ContactConstraints::end_round(Point& p) {
  p.restitution_impulse += p.round_impulse;
  if (in_round(p.flags)) p.flags |= took_part;
}

// Opens the next round (see the header), after closing the previous one (end_round). Its impacts: in the first round the points that came
// in by themselves during the step (their impact velocity w from the start of the step < 0):
// fast ones bounce, the others that had a gap at the start land; in a later round the points
// that had a gap at the start, touch now and come in, pushed by an earlier impact (w their
// present normal velocity at the end of the step, u + a_n Δt/2).
// Each impact's target: the bounce −e w − a_n Δt/2 when e > 0 and −w exceeds the threshold,
// else just no more approach (v_n ≥ 0). Returns whether there is any impact.
bool ContactConstraints::start_round(bool first) {
  const double threshold = settings_->restitution_threshold;
  bool any = false;
  bounces_ = false;
  for (const Manifold& m : manifolds_) {
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = points_[k];
      if (!first) end_round(p);
      p.round_impulse = 0.0;
      p.target = (p.flags & opened) ? -p.end_separation / h_ : 0.0;
      if (p.flags & event) p.flags = static_cast<std::uint8_t>((p.flags & ~event) | fired);
      if (!(p.flags & touching_end) || (p.flags & fired)) continue;
      const double a_n = normal_acceleration(m, p);
      const double v = normal_velocity(m.normal, k, solver_[m.a], solver_[m.b]);
      double w;
      if (first) {  // came in by itself, fast (a bounce) or not (a landing), or not at all
        w = impact_velocity(m, p);
        if (!(w < 0.0)) continue;
        if ((p.flags & touched_start) && !(m.restitution > 0.0 && -w > threshold)) continue;
      } else {  // pushed in by an earlier impact
        if (p.flags & touched_start) continue;
        w = v + 0.5 * a_n * h_;
        // Coming in by more than the landing tolerance over the step: two balls at rest
        // read v = −1e-16 from rounding, and taking that as an impact in the same round as
        // the blow that reaches them merged them into one body that the blow's reflection
        // then gave too much energy (a struck row, 1 cm apart at 30 Hz: +25 %).
        if (!(v < -landed_tolerance() / h_)) continue;
      }
      if (m.restitution > 0.0 && -w > threshold)
        p.target = p.turned && first ? turned_target(m, w, a_n)
                                     : std::max(-m.restitution * w - 0.5 * a_n * h_, 0.0);
      p.flags |= event;
      any = true;
      bounces_ = bounces_ || p.target > 0.0;
    }
  }
  return any;
}

// Each body's manifolds, for gather_round: body_manifolds_[body_first_[s] .. body_first_[s+1])
// are the manifolds of solver slot s (the ground's too; gather_round never walks through it).
void ContactConstraints::link_bodies() {
  const std::size_t slots = ground_ + 1;
  body_first_.assign(slots + 1, 0);
  for (const Manifold& m : manifolds_) ++body_first_[m.a + 1], ++body_first_[m.b + 1];
  for (std::size_t s = 0; s < slots; ++s) body_first_[s + 1] += body_first_[s];
  body_manifolds_.resize(2 * manifolds_.size());
  frontier_.assign(body_first_.begin(), body_first_.end() - 1);  // the next free place per slot
  for (std::size_t mi = 0; mi < manifolds_.size(); ++mi) {
    body_manifolds_[frontier_[manifolds_[mi].a]++] = static_cast<std::uint32_t>(mi);
    body_manifolds_[frontier_[manifolds_[mi].b]++] = static_cast<std::uint32_t>(mi);
  }
  body_reached_.assign(slots, 0);
  manifold_taken_.assign(manifolds_.size(), 0);
}

// The manifolds a later round of landings sweeps: those of its impacts and the round's
// manifolds up to `hops` contacts away from their bodies, through bodies that can move (not
// the ground or a static body), in manifold order. `hops` is the round's sweeps: a sweep
// carries a push about one contact further (as the velocity stage does), so the manifolds
// beyond are left to the next step's velocity stage as any resting contact is. Sweeping
// every touching manifold instead (the whole heap) made each impact anywhere cost the whole
// heap 10 sweeps, and a larger heap has more of them per step: 1.25 / 1.63 / 2.10 rounds
// per step at 256 / 1,024 / 4,096 settling spheres, the restitution stage's manifold solves
// per body-step 27.6 / 35.9 / 46.5 (bench/contacts_bench settle/N).
void ContactConstraints::gather_round(int hops) {
  round_manifolds_.clear();
  frontier_.clear();
  auto reach = [&](std::uint32_t slot, std::vector<std::uint32_t>& to) {
    if (slot == ground_ || body_reached_[slot] || solver_[slot].inverse_mass == 0.0) return;
    body_reached_[slot] = 1;
    to.push_back(slot);
  };
  auto take = [&](std::size_t mi) {
    manifold_taken_[mi] = 1;
    round_manifolds_.push_back(static_cast<std::uint32_t>(mi));
  };
  for (std::size_t mi = 0; mi < manifolds_.size(); ++mi) {
    const Manifold& m = manifolds_[mi];
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k)
      if (points_[k].flags & event) {
        take(mi);
        reach(m.a, frontier_), reach(m.b, frontier_);
        break;
      }
  }
  for (int hop = 0; hop < hops && !frontier_.empty(); ++hop) {
    next_frontier_.clear();
    for (const std::uint32_t slot : frontier_)
      for (std::uint32_t j = body_first_[slot]; j < body_first_[slot + 1]; ++j) {
        const std::uint32_t mi = body_manifolds_[j];
        if (manifold_taken_[mi]) continue;
        const Manifold& m = manifolds_[mi];
        bool member = false;
        for (std::uint32_t k = m.first; k < m.first + m.count && !member; ++k)
          member = in_round(points_[k].flags);
        if (!member) continue;
        take(mi);
        reach(m.a == slot ? m.b : m.a, next_frontier_);
      }
    frontier_.swap(next_frontier_);
  }
  std::sort(round_manifolds_.begin(), round_manifolds_.end());
  for (const std::uint32_t mi : round_manifolds_) {
    manifold_taken_[mi] = 0;
    body_reached_[manifolds_[mi].a] = body_reached_[manifolds_[mi].b] = 0;
  }
}

void ContactConstraints::restitution(SolverBody* solver, const Acceleration* acceleration,
                                     StepPoll* poll) {
  solver_ = solver;
  acceleration_ = acceleration;
  take_back_speculative();
  rounds_.clear();
  rounds_.reserve(max_rounds);
  const double tolerance = touch_tolerance();
  bool landings = false;
  for (const Manifold& m : manifolds_)
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = points_[k];
      p.flags = 0;
      if (p.separation <= tolerance) p.flags |= touched_start;
      if (p.end_separation <= landed_tolerance()) p.flags |= touching_end;
      landings = landings || (p.flags == touching_end) || (p.flags && m.restitution > 0.0);
    }
  if (!landings) return;
  mark_supported(acceleration);
  // A resting contact of two held bodies that the sweeps opened by a little (the top box of a
  // column rocked by the ball's speculative impulse: 10-60 µm at one edge) still holds in the
  // event, as the step's speculative contacts do: it may close its gap s and no more,
  // v_n ≥ −s/Δt. (Without it the top box of 5 pivoted on its other edge under the ball.)
  // Only between held bodies: touching balls that a blow set apart keep apart.
  for (const Manifold& m : manifolds_) {
    if (!supported_[m.a] || !supported_[m.b]) continue;
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
      Point& p = points_[k];
      if ((p.flags & touched_start) && !(p.flags & touching_end)) p.flags |= opened;
    }
  }
  // A push travels one contact of a chain per sweep pair (a ball bouncing on a box on the
  // floor: the box's rebound error halves per pair; a struck row of touching balls), and
  // impacts are rare: a round runs over its own manifolds until its increments settle to
  // 1e-12 of the largest, up to max_iterations sweeps.
  for (int round = 0; round < max_rounds && start_round(round == 0); ++round) {
    if (round > 0 && !bounces_) {
      gather_round(settings_->iterations);
    } else {
      round_manifolds_.clear();
      for (std::size_t mi = 0; mi < manifolds_.size(); ++mi) {
        const Manifold& m = manifolds_[mi];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k)
          if (in_round(points_[k].flags)) {
            round_manifolds_.push_back(static_cast<std::uint32_t>(mi));
            break;
          }
      }
    }
    // A round of landings only (every target "no more approach") is solved like the velocity
    // stage, in `iterations` sweeps: in a settling heap every step has landings, and its
    // resting contacts converge to 1e-12 no faster than the heap's Gauss-Seidel does (1,000
    // sweeps a step made 1,000 spheres settling 4× slower than the rest of the step). A round
    // with a bounce converges, so that elastic impacts keep the energy exactly, within a
    // budget of round_work manifold solves (a bounce in a heap is solved like its landings).
    const long size = static_cast<long>(round_manifolds_.size());
    const int sweeps =
        bounces_ ? static_cast<int>(std::clamp<long>(round_work / std::max(size, 1L),
                                                     settings_->iterations,
                                                     ContactSettings::max_iterations))
                 : settings_->iterations;
    RestitutionRound record;
    record.manifolds = static_cast<std::uint32_t>(size);
    record.allowed_sweeps = sweeps;
    record.bounces = bounces_;
    round_solves_ = 0;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      if (poll != nullptr) poll->tick(round_manifolds_.size());
      ++record.sweeps;
      // The round's points outside the manifolds round_sweep solved keep the increment 0
      // start_round gave them: the largest is the same.
      double largest = 0.0;
      const double change = round_sweep(sweep % 2 == 0, largest);
      if (!(change > 1e-12 * largest)) break;
    }
    record.solves = round_solves_;
    rounds_.push_back(record);
  }
  // The next start_round closed each round (one pass over the points instead of two); the
  // last of max_rounds has none.
  if (rounds_.size() == static_cast<std::size_t>(max_rounds))
    for (Point& p : points_) end_round(p);
}

}  // namespace rigidlab
