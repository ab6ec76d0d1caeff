// Sleeping islands: see engine/islands.hpp.
#include "engine/islands.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/format.hpp"
#include "engine/narrow_phase.hpp"

namespace rigidlab {

std::string sleep_settings_problem(const SleepSettings& s) {
  const std::pair<const char*, double> values[] = {
      {"sleep_linear", s.linear}, {"sleep_angular", s.angular}, {"sleep_time", s.time}};
  for (const auto& [name, value] : values)
    if (!std::isfinite(value) || !(value > 0.0))
      return std::string(name) + " must be finite and > 0, got " + format_number(value);
  return "";
}

namespace {

// At rest for the sleep timer: the COM slower than `linear` and either the turning slower than
// `angular` or, for a body with a shape, no point of it faster than `linear` (|v| + R |ω| with R
// its bounding radius: Box2D v3's rule, b2FinalizeBodies). The second lets a ball that spins
// slowly about its contact normal sleep — nothing in the contact model stops that spin (a
// settled heap of 1,024 balls keeps 3 spinning at 0.099 rad/s forever) — while a body without
// a shape (a torque-free spinning top) stays awake while it turns faster than `angular`.
bool at_rest(const Body& b, const SleepSettings& s) {
  const double v = b.velocity.norm(), w = b.angular_velocity.norm();
  if (!(v < s.linear)) return false;
  if (w < s.angular) return true;
  return b.shape.kind != ShapeKind::none && v + bounding_radius(b.shape) * w < s.linear;
}

bool disturbed(const Body& b) {
  return b.velocity != Vec3::Zero() || b.angular_velocity != Vec3::Zero() ||
         b.force != Vec3::Zero() || b.torque != Vec3::Zero();
}

}  // namespace

// ---- during a step ---------------------------------------------------------------------------

void Islands::freeze(std::vector<Body>& bodies) {
  const std::size_t n = bodies.size();
  state_.assign(n, State::awake);
  // Sized here, before the step commits, so that finish() allocates nothing.
  parent_.resize(n);
  island_time_.resize(n);
  frozen_.clear();
  frozen_count_ = 0;
  disturbed_.clear();
  for (const Body& b : bodies)
    if (b.sleeping && disturbed(b)) disturbed_.push_back(b.island);
  std::sort(disturbed_.begin(), disturbed_.end());
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (!b.sleeping) continue;
    if (std::binary_search(disturbed_.begin(), disturbed_.end(), b.island)) {
      state_[i] = State::woken;
      continue;
    }
    state_[i] = State::frozen;
    frozen_.push_back({i, b.inverse_mass, b.inverse_inertia});
    ++frozen_count_;
    b.inverse_mass = 0.0;
    b.inverse_inertia.setZero();
  }
}

void Islands::restore(std::vector<Body>& bodies, const Frozen& f) {
  Body& b = bodies[f.index];
  b.inverse_mass = f.inverse_mass;
  b.inverse_inertia = f.inverse_inertia;
  state_[f.index] = State::woken;
  --frozen_count_;
}

// Frozen bodies are listed by index, so the island is found in one pass over them.
void Islands::wake_in_step(std::vector<Body>& bodies, std::size_t i) {
  if (!frozen(i)) return;
  const std::uint32_t label = bodies[i].island;
  for (const Frozen& f : frozen_)
    if (state_[f.index] == State::frozen && bodies[f.index].island == label)
      restore(bodies, f);
}

void Islands::thaw(std::vector<Body>& bodies) {
  for (const Frozen& f : frozen_)
    if (state_[f.index] == State::frozen) {
      restore(bodies, f);
      state_[f.index] = State::frozen;  // still asleep: only its mass properties are back
    }
  // Given back once: the list is of this step's bodies. Kept, a later thaw (the step's guard
  // after the committed step's own thaw, or any step once sleeping is off) would give its
  // mass properties to whatever body has that index by then, reading states finish() cleared.
  frozen_.clear();
  frozen_count_ = 0;
}

// ---- after a committed step ------------------------------------------------------------------

void Islands::begin_links(std::size_t body_count) {
  parent_.resize(body_count);
  std::iota(parent_.begin(), parent_.end(), std::size_t{0});
}

std::size_t Islands::find(std::size_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];  // path halving
    i = parent_[i];
  }
  return i;
}

void Islands::link(std::vector<Body>& bodies, std::size_t a, std::size_t b) {
  if (a == no_body || b == no_body) return;
  Body& x = bodies[a];
  Body& y = bodies[b];
  if (is_static(x) || is_static(y)) return;
  if (x.sleeping != y.sleeping) wake_island(bodies, x.sleeping ? x.island : y.island);
  if (x.sleeping) return;  // both asleep: already one island, or two kept apart
  // The larger index under the smaller: roots are each island's first body.
  const std::size_t ra = find(a), rb = find(b);
  if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
}

void Islands::finish(std::vector<Body>& bodies, const std::vector<BodyId>& ids, double dt,
                     const SleepSettings& settings, bool may_sleep) {
  const std::size_t n = bodies.size();
  for (std::size_t i = 0; i < n && i < state_.size(); ++i)
    if (state_[i] == State::woken) {
      bodies[i].sleeping = false;
      bodies[i].sleep_time = 0.0;
    }
  state_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    island_time_[i] = std::numeric_limits<double>::infinity();
    if (b.sleeping || is_static(b)) continue;
    b.sleep_time = may_sleep && at_rest(b, settings) ? b.sleep_time + dt : 0.0;
  }
  if (!may_sleep) return;
  for (std::size_t i = 0; i < n; ++i) {
    const Body& b = bodies[i];
    if (b.sleeping || is_static(b)) continue;
    double& t = island_time_[find(i)];
    t = std::min(t, b.sleep_time);
  }
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.sleeping || is_static(b)) continue;
    const std::size_t root = find(i);
    if (!(island_time_[root] >= settings.time)) continue;
    b.sleeping = true;
    b.island = ids[root].slot;  // a slot of one of its bodies: no other island has it
    b.velocity.setZero();
    b.angular_velocity.setZero();
  }
}

// ---- outside a step --------------------------------------------------------------------------

std::size_t Islands::wake_island(std::vector<Body>& bodies, std::uint32_t label) {
  std::size_t count = 0;
  for (Body& b : bodies) {
    if (!b.sleeping || b.island != label) continue;
    b.sleeping = false;
    b.sleep_time = 0.0;
    ++count;
  }
  return count;
}

void Islands::wake_all(std::vector<Body>& bodies) {
  for (Body& b : bodies) {
    b.sleeping = false;
    b.sleep_time = 0.0;
  }
}

}  // namespace rigidlab
