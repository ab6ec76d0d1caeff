#include "engine/world.hpp"

#include <algorithm>
#include <cmath>

#include "engine/format.hpp"

namespace rigidlab {

// ---- BodyStore ------------------------------------------------------------------------------

BodyStore::Id BodyStore::insert(const Body& b) {
  Id id;
  if (!free_ids_.empty()) {
    id = free_ids_.back();
    free_ids_.pop_back();
  } else {
    id = static_cast<Id>(index_of_.size());
    index_of_.push_back(npos);
  }
  index_of_[id] = static_cast<std::uint32_t>(bodies_.size());
  bodies_.push_back(b);
  ids_.push_back(id);
  return id;
}

Body BodyStore::erase(Id id) {
  const std::size_t index = index_of_[id];
  Body b = bodies_[index];
  bodies_.erase(bodies_.begin() + static_cast<std::ptrdiff_t>(index));
  ids_.erase(ids_.begin() + static_cast<std::ptrdiff_t>(index));
  for (std::size_t i = index; i < ids_.size(); ++i) index_of_[ids_[i]] = static_cast<std::uint32_t>(i);
  index_of_[id] = npos;
  free_ids_.push_back(id);
  return b;
}

// ---- World ----------------------------------------------------------------------------------

namespace {

// The velocities that move the positions in each integrator's step (engine/contact_solver.hpp).
ContactVelocities contact_velocities(Integrator integrator) {
  switch (integrator) {
    case Integrator::euler: return ContactVelocities::current;
    case Integrator::semi_implicit: return ContactVelocities::after_forces;
    case Integrator::rk4: break;
  }
  return ContactVelocities::mid_step;
}

void require_not_stepping(const World& w, const char* what) {
  if (w.stepping())
    throw std::logic_error(std::string("cannot ") + what +
                           " during a step (force callbacks may only apply forces)");
}

}  // namespace

// Marks the world as stepping; unless commit() is called, the destructor (reached by a normal
// return or by any exception, a Lua error included) puts the bodies back as in the snapshot
// and the time back. RAII rather than catch-and-rethrow, so nothing is swallowed. The snapshot
// is taken here when `take_snapshot`, otherwise the first integrator pass writes it (no force
// element can run, and throw, before that pass) and the world calls snapshot_taken().
class World::StepGuard {
 public:
  StepGuard(World& w, bool take_snapshot) : world_(w), time_(w.time_) {
    world_.store_->stepping_ = true;
    world_.contacts_.save();
    world_.snapshot_.resize(world_.bodies().size());
    if (!take_snapshot) return;
    const std::vector<Body>& bodies = world_.bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) world_.snapshot_[i] = state_of(bodies[i]);
    has_snapshot_ = true;
  }
  ~StepGuard() {
    world_.store_->stepping_ = false;
    world_.contacts_.poll = nullptr;
    if (committed_) return;
    world_.time_ = time_;
    world_.contacts_.restore();
    if (!has_snapshot_) return;
    std::vector<Body>& bodies = world_.bodies();
    for (std::size_t i = 0; i < bodies.size(); ++i) set_state(bodies[i], world_.snapshot_[i]);
  }
  StepGuard(const StepGuard&) = delete;
  StepGuard& operator=(const StepGuard&) = delete;
  void snapshot_taken() { has_snapshot_ = true; }
  void commit() { committed_ = true; }

 private:
  World& world_;
  double time_;
  bool has_snapshot_ = false;
  bool committed_ = false;
};

World::World()
    : store_(std::make_shared<BodyStore>()),
      gravity_(0.0, -9.81, 0.0),
      stage_forces_([this](double t) { evaluate_forces(t); }) {
  store_->world_ = this;
}

World::~World() { store_->world_ = nullptr; }

void World::set_gravity(const Vec3& g) {
  if (!is_finite(g)) throw std::invalid_argument("gravity must be finite");
  gravity_ = g;
}

void World::set_substeps(int n) {
  if (n < 1 || n > max_substeps)
    throw std::invalid_argument("substeps must be an integer from 1 to " +
                                std::to_string(max_substeps) + ", got " + std::to_string(n));
  substeps_ = n;
}

BodyStore::Id World::add(const Body& b) {
  require_not_stepping(*this, "add a body");
  if (!state_is_finite(b) || !is_finite(b.force) || !is_finite(b.torque))
    throw std::invalid_argument("the body's state must be finite");
  if (b.shape.kind != ShapeKind::none) ++shaped_bodies_;
  return store_->insert(b);
}

Body World::remove(BodyStore::Id id) {
  require_not_stepping(*this, "remove a body");
  const std::size_t index = store_->index_of(id);
  auto renumber = [index](std::size_t& i) {
    if (i != no_body && i > index) --i;
  };
  std::vector<Spring> springs;
  for (Spring s : springs_) {
    if (s.a == index || s.b == index) continue;
    renumber(s.a);
    renumber(s.b);
    springs.push_back(s);
  }
  springs_.swap(springs);
  std::vector<Drag> drags;
  for (Drag d : drags_) {
    if (d.body == index) continue;
    renumber(d.body);
    drags.push_back(d);
  }
  drags_.swap(drags);
  contacts_.body_removed(index);
  if (store_->get(id).shape.kind != ShapeKind::none) --shaped_bodies_;
  return store_->erase(id);
}

std::size_t World::add_plane(const Plane& p) {
  require_not_stepping(*this, "add a plane");
  // Re-validate through make_plane: the normal must be unit for the contact code.
  planes_.push_back(make_plane(p.normal, p.offset, p.restitution, p.friction));
  return planes_.size() - 1;
}

void World::set_contact_settings(const ContactSettings& s) {
  require_not_stepping(*this, "change the contact settings");
  const std::string problem = contact_settings_problem(s);
  if (!problem.empty()) throw std::invalid_argument(problem);
  contacts_.settings = s;
}

void World::add_spring(const Spring& s) {
  require_not_stepping(*this, "add a spring");
  const std::size_t n = bodies().size();
  if (s.a >= n || (s.b != no_body && s.b >= n))
    throw std::invalid_argument("spring attached to a body that is not in this world");
  const std::string problem = spring_problem(s);
  if (!problem.empty()) throw std::invalid_argument(problem);
  springs_.push_back(s);
}

void World::add_drag(const Drag& d) {
  require_not_stepping(*this, "add drag");
  if (d.body >= bodies().size())
    throw std::invalid_argument("drag on a body that is not in this world");
  const std::string problem = drag_problem(d);
  if (!problem.empty()) throw std::invalid_argument(problem);
  drags_.push_back(d);
}

void World::add_force(ForceCallback callback) {
  require_not_stepping(*this, "add a force");
  if (!callback) throw std::invalid_argument("the force callback is empty");
  callbacks_.push_back(std::move(callback));
}

bool World::has_force_elements() const {
  return !springs_.empty() || !drags_.empty() || !callbacks_.empty();
}

// 000_* "Particle system": at each evaluation sum every force acting on each body. The
// accumulators already hold what was applied before the step.
void World::evaluate_forces(double t) {
  time_ = t;
  std::vector<Body>& b = bodies();
  for (const Spring& s : springs_) apply_spring(b, s);
  for (const Drag& d : drags_) apply_drag(b, d);
  // By index: a callback cannot add callbacks (add_force refuses during a step), but a
  // reference into the vector must not be held across a call that might throw.
  for (std::size_t i = 0; i < callbacks_.size(); ++i) callbacks_[i](*this, t);
}

// One substep from t to t + dt with the chosen integrator (STYLE.md 7: a switch on the enum),
// and the contact step around it (engine/contact_solver.hpp): contact impulses on the
// velocities that will move the positions, the integrator, then position correction.
std::size_t World::integrate(double t, double dt, BodyState* save_to) {
  // RK4 evaluates the force elements at each of its stages; the Euler methods once, first.
  if (integrator_ != Integrator::rk4 && has_force_elements()) evaluate_forces(t);
  const bool contacts = has_contacts();
  if (contacts)
    contacts_.solve_velocities(bodies(), planes_, gravity_, dt, contact_velocities(integrator_));
  std::size_t bad = all_finite;
  switch (integrator_) {
    case Integrator::euler:
      bad = euler_step(bodies(), gravity_, gyroscopic_, dt, save_to);
      break;
    case Integrator::semi_implicit:
      bad = semi_implicit_euler_step(bodies(), gravity_, gyroscopic_, dt, save_to);
      break;
    case Integrator::rk4: {
      static const std::function<void(double)> no_forces;
      bad = rk4_step(bodies(), gravity_, t, dt, rk4_,
                     has_force_elements() ? stage_forces_ : no_forces, save_to);
      break;
    }
  }
  if (contacts && bad == all_finite) bad = contacts_.correct_positions(bodies());
  return bad;
}

void World::step(double dt, long count, const std::function<void()>& poll) {
  if (!std::isfinite(dt) || !(dt > 0.0))
    throw std::invalid_argument("dt must be finite and > 0, got " + format_number(dt));
  if (count < 1) throw std::invalid_argument("the number of steps must be >= 1");
  require_not_stepping(*this, "step the world");
  // With force elements, forces are evaluated (and callbacks may throw) before the first
  // integrator pass, and contact impulses change velocities before it, so the snapshot comes
  // first; without either, that pass writes it.
  const bool snapshot_in_pass = !has_force_elements() && !has_contacts();
  StepGuard guard(*this, !snapshot_in_pass);
  StepPoll poller(poll);
  contacts_.poll = &poller;  // reset by the guard
  const double call_start = time_;
  const double h = dt / substeps_;
  std::vector<Body>& bodies = this->bodies();
  double t = call_start;
  for (long k = 0; k < count; ++k) {
    for (int s = 0; s < substeps_; ++s) {
      // The integrators consume the accumulators; forces applied before the call act during
      // every substep of the first step.
      if (k == 0 && s > 0) {
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          bodies[i].force = snapshot_[i].force;
          bodies[i].torque = snapshot_[i].torque;
        }
      }
      const bool first_pass = k == 0 && s == 0;
      const std::size_t bad =
          integrate(t + s * h, h, first_pass && snapshot_in_pass ? snapshot_.data() : nullptr);
      if (first_pass && snapshot_in_pass) guard.snapshot_taken();
      if (bad != all_finite) throw_non_finite(bad, t, t + dt, call_start);
      poller.tick(bodies.size() + 1);
    }
    t += dt;
    time_ = t;
    for (const std::shared_ptr<StepObserver>& o : observers_) o->after_step(*this);
  }
  guard.commit();
}

void World::add_step_observer(std::shared_ptr<StepObserver> observer) {
  require_not_stepping(*this, "add an observer");
  observers_.push_back(std::move(observer));
}

void World::remove_step_observer(const StepObserver* observer) {
  require_not_stepping(*this, "remove an observer");
  observers_.erase(std::remove_if(observers_.begin(), observers_.end(),
                                  [&](const auto& o) { return o.get() == observer; }),
                   observers_.end());
}

void World::throw_non_finite(std::size_t index, double t0, double t1, double call_start) const {
  const Body& b = bodies()[index];
  // Rates first: a non-finite velocity makes the position non-finite too.
  const char* what = !is_finite(b.velocity)           ? "velocity"
                     : !is_finite(b.angular_velocity) ? "angular velocity"
                     : !is_finite(b.position)         ? "position"
                                                      : "orientation";
  throw StepError("body " + std::to_string(index + 1) + " of " +
                      std::to_string(bodies().size()) + " would get a non-finite " + what +
                      " in the step from t = " + format_number(t0) + " s to t = " + format_number(t1) +
                      " s; nothing was changed (the world is still at t = " +
                      format_number(call_start) + " s)",
                  index, t0);
}

double World::kinetic_energy() const {
  double sum = 0.0;
  for (const Body& b : bodies()) sum += rigidlab::kinetic_energy(b);
  return sum;
}

double World::potential_energy() const {
  double sum = 0.0;
  for (const Body& b : bodies()) sum += gravity_potential_energy(b, gravity_);
  for (const Spring& s : springs_) sum += spring_potential_energy(bodies(), s);
  return sum;
}

Vec3 World::linear_momentum() const {
  Vec3 sum = Vec3::Zero();
  for (const Body& b : bodies()) sum += rigidlab::linear_momentum(b);
  return sum;
}

// 002_* "Momentum and inertia": L about a point = Σ r × m v (orbital) + I ω (spin about COM).
Vec3 World::angular_momentum(const Vec3& about) const {
  Vec3 sum = Vec3::Zero();
  for (const Body& b : bodies())
    sum += (b.position - about).cross(rigidlab::linear_momentum(b)) + rigidlab::angular_momentum(b);
  return sum;
}

}  // namespace rigidlab
