#include "engine/world.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/format.hpp"

namespace rigidlab {

namespace {

void require_not_stepping(const World& w, const char* what) {
  if (w.stepping())
    throw std::logic_error(std::string("cannot ") + what +
                           " during a step (force callbacks may only apply forces)");
}

}  // namespace

// Marks the world as stepping for one step; unless commit() is called, the destructor (reached
// by a normal return or by any exception, a Lua error included) puts the bodies, the time and
// the solver's memory back as they were before the step. RAII rather than catch-and-rethrow,
// so nothing is swallowed. The bodies' snapshot is taken here when `take_snapshot`, otherwise
// the first integrator pass writes it (no force element can run, and throw, before that pass)
// and the world calls snapshot_taken().
class World::StepGuard {
 public:
  StepGuard(World& w, bool take_snapshot) : world_(w), time_(w.time_) {
    world_.store_->stepping_ = true;
    world_.save_step(take_snapshot);
    has_snapshot_ = take_snapshot;
  }
  ~StepGuard() {
    world_.store_->stepping_ = false;
    if (committed_) return;
    world_.time_ = time_;
    if (has_snapshot_) world_.restore_step();
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

// ---- settings ----------------------------------------------------------------------------------

void World::set_gravity(const Vec3& g) {
  if (!is_finite(g)) throw std::invalid_argument("gravity must be finite");
  if (g != gravity_ && !stepping()) wake_all();
  gravity_ = g;
}

void World::set_solver(SolverKind kind) {
  require_not_stepping(*this, "change the solver");
  solver_.kind = kind;
}

void World::set_substeps(int n) {
  if (n < 1 || n > max_substeps)
    throw std::invalid_argument("substeps must be an integer from 1 to " +
                                std::to_string(max_substeps) + ", got " + std::to_string(n));
  substeps_ = n;
}

void World::set_contact_settings(const ContactSettings& s) {
  require_not_stepping(*this, "change the contact settings");
  const std::string problem = contact_settings_problem(s);
  if (!problem.empty()) throw std::invalid_argument(problem);
  solver_.settings = s;
  wake_all();
}

// ---- bodies and what is attached to them ---------------------------------------------------

BodyId World::add(const Body& b) {
  require_not_stepping(*this, "add a body");
  if (!state_is_finite(b) || !is_finite(b.force) || !is_finite(b.torque))
    throw std::invalid_argument("the body's state must be finite");
  const BodyId id = store_->insert(b);
  Body& added = store_->get(id);
  added.sleeping = false;
  added.sleep_time = 0.0;
  if (b.shape.kind != ShapeKind::none) ++shaped_bodies_;
  return id;
}

// Nothing is renumbered: what stays attached to other bodies keeps their ids.
Body World::remove(BodyId id) {
  require_not_stepping(*this, "remove a body");
  if (!store_->contains(id)) throw std::invalid_argument("the body is not in this world");
  wake(id);  // its island loses a body (and what linked the others through it)
  auto attached = [id](BodyId a, BodyId b) { return a == id || b == id; };
  springs_.erase(std::remove_if(springs_.begin(), springs_.end(),
                                [&](const Spring& s) { return attached(s.a, s.b); }),
                 springs_.end());
  drags_.erase(std::remove_if(drags_.begin(), drags_.end(),
                              [&](const Drag& d) { return d.body == id; }),
               drags_.end());
  joints_.erase(std::remove_if(joints_.begin(), joints_.end(),
                               [&](const std::unique_ptr<Constraint>& j) {
                                 return attached(j->body_a(), j->body_b());
                               }),
                joints_.end());
  solver_.contact_constraints().body_removed(id);
  if (store_->get(id).shape.kind != ShapeKind::none) --shaped_bodies_;
  return store_->erase(id);
}

std::size_t World::add_plane(const Plane& p) {
  require_not_stepping(*this, "add a plane");
  // Re-validate through make_plane: the normal must be unit for the contact code.
  planes_.push_back(make_plane(p.normal, p.offset, p.restitution, p.friction));
  wake_all();  // sleeping bodies do not meet planes: the new one must find them awake
  return planes_.size() - 1;
}

void World::add_spring(const Spring& s) {
  require_not_stepping(*this, "add a spring");
  if (!store_->contains(s.a) || (s.b.valid() && !store_->contains(s.b)))
    throw std::invalid_argument("spring attached to a body that is not in this world");
  const std::string problem = spring_problem(s);
  if (!problem.empty()) throw std::invalid_argument(problem);
  springs_.push_back(s);
  wake(s.a);
  if (s.b.valid()) wake(s.b);
}

void World::add_drag(const Drag& d) {
  require_not_stepping(*this, "add drag");
  if (!store_->contains(d.body))
    throw std::invalid_argument("drag on a body that is not in this world");
  const std::string problem = drag_problem(d);
  if (!problem.empty()) throw std::invalid_argument(problem);
  drags_.push_back(d);
  wake(d.body);
}

void World::add_force(ForceCallback callback) {
  require_not_stepping(*this, "add a force");
  if (!callback) throw std::invalid_argument("the force callback is empty");
  callbacks_.push_back(std::move(callback));
  wake_all();  // a force callback may push any body at any time: nothing sleeps with one
}

Constraint& World::add_constraint(std::unique_ptr<Constraint> joint) {
  require_not_stepping(*this, "add a joint");
  if (!joint) throw std::invalid_argument("the joint is empty");
  if (!store_->contains(joint->body_a()) ||
      (joint->body_b().valid() && !store_->contains(joint->body_b())))
    throw std::invalid_argument("joint attached to a body that is not in this world");
  if (joint->body_a() == joint->body_b())
    throw std::invalid_argument("a joint needs two different bodies");
  if (joint->row_count() < 0) throw std::invalid_argument("a joint has no negative row count");
  joint->serial_ = ++last_joint_serial_;
  wake(joint->body_a());
  if (joint->body_b().valid()) wake(joint->body_b());
  joints_.push_back(std::move(joint));
  return *joints_.back();
}

void World::remove_constraint(const Constraint& joint) {
  require_not_stepping(*this, "remove a joint");
  const auto it = std::find_if(joints_.begin(), joints_.end(),
                               [&](const std::unique_ptr<Constraint>& j) { return j.get() == &joint; });
  if (it == joints_.end()) throw std::invalid_argument("the joint is not in this world");
  wake((*it)->body_a());
  if ((*it)->body_b().valid()) wake((*it)->body_b());
  joints_.erase(it);
}

// Joints stay in the order added, so by serial number.
Constraint* World::find_constraint(std::uint64_t serial) {
  const auto it = std::lower_bound(
      joints_.begin(), joints_.end(), serial,
      [](const std::unique_ptr<Constraint>& j, std::uint64_t s) { return j->serial() < s; });
  return it != joints_.end() && (*it)->serial() == serial ? it->get() : nullptr;
}

bool World::has_force_elements() const {
  return !springs_.empty() || !drags_.empty() || !callbacks_.empty();
}

// Ids to indices, once per call of step(): bodies are neither added nor removed during it.
void World::resolve_ids() {
  const BodyStore& store = *store_;
  auto index = [&store](BodyId id) { return id.valid() ? store.index_of(id) : no_body; };
  spring_refs_.clear();
  for (const Spring& s : springs_) spring_refs_.push_back({index(s.a), index(s.b)});
  drag_refs_.clear();
  for (const Drag& d : drags_) drag_refs_.push_back(index(d.body));
  joint_refs_.clear();
  for (const auto& j : joints_)
    joint_refs_.push_back({j.get(), index(j->body_a()), index(j->body_b())});
  // Bodies joined by a joint without `collide` do not collide: the pairs to skip, made again
  // only when a joint was added or removed (allocation then, none per step).
  const std::pair<std::size_t, std::uint64_t> joints_now{joints_.size(), last_joint_serial_};
  if (joints_now == excluded_for_) return;
  auto& excluded = solver_.contact_constraints().excluded_pairs();
  excluded.clear();
  for (const auto& j : joints_) {
    if (j->collide() || !j->body_b().valid()) continue;
    const std::uint64_t a = ContactPairs::key_of(j->body_a()), b = ContactPairs::key_of(j->body_b());
    excluded.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(excluded.begin(), excluded.end());
  excluded_for_ = joints_now;
}

// 000_* "Particle system": at each evaluation sum every force acting on each body. The
// accumulators already hold what was applied before the step.
void World::evaluate_forces(double t) {
  time_ = t;
  std::vector<Body>& b = bodies();
  for (std::size_t i = 0; i < springs_.size(); ++i) {
    const SpringRef& r = spring_refs_[i];
    apply_spring(b[r.a], r.b == no_body ? nullptr : &b[r.b], springs_[i]);
  }
  for (std::size_t i = 0; i < drags_.size(); ++i) apply_drag(b[drag_refs_[i]], drags_[i]);
  // By index: a callback cannot add callbacks (add_force refuses during a step), but a
  // reference into the vector must not be held across a call that might throw.
  for (std::size_t i = 0; i < callbacks_.size(); ++i) callbacks_[i](*this, t);
}

// ---- the step pipeline (docs/architecture.md) -----------------------------------------------------

// A substep without constraints: each integrator in one pass over the bodies (STYLE.md 7: a
// switch on the enum), writing the undo snapshot on the way when asked.
std::size_t World::free_substep(double t, double h, BodyState* save_to) {
  if (integrator_ != Integrator::rk4 && has_force_elements()) evaluate_forces(t);
  switch (integrator_) {
    case Integrator::euler:
      return euler_step(bodies(), gravity_, gyroscopic_, h, save_to);
    case Integrator::semi_implicit:
      return semi_implicit_euler_step(bodies(), gravity_, gyroscopic_, h, save_to);
    case Integrator::rk4:
      break;
  }
  static const std::function<void(double)> no_forces;
  return rk4_step(bodies(), gravity_, t, h, rk4_, has_force_elements() ? stage_forces_ : no_forces,
                  save_to);
}

// One substep of the pipeline (000_* "Sequential impulses": forces into tentative velocities,
// impulses, positions from the new velocities), each stage in its file:
//   1 forces (Euler family; RK4 at its stages)        engine/forces.cpp, callbacks
//   2 velocity stage of the integrator                engine/integrators.cpp
//   3 prepare: contacts found, joint rows built       engine/solver.cpp, contact_finder.cpp
//   4 warm start, 5 solve                             engine/solver.cpp, contact_constraints.cpp
//   6 position stage of the integrator                engine/integrators.cpp
//   7 relax (soft_step), 8 restitution                engine/solver.cpp, contact_restitution.cpp
//   9 position correction (sequential_impulses)       engine/contact_positions.cpp
//  10 store impulses, 11 end-of-step velocities       engine/solver.cpp, integrators.cpp
//  12 joint velocity projection (sequential_impulses) engine/solver.cpp
std::size_t World::substep(double t, double h, BodyState* save_to) {
  if (!has_constraints()) return free_substep(t, h, save_to);
  std::vector<Body>& bodies = this->bodies();
  // The sleep stage: a contact found between an awake body and a sleeping one wakes the
  // sleeping island, and the substep starts again from its accumulators with that island's
  // masses (engine/islands.hpp, "Waking").
  const bool may_wake = islands_.any_frozen();
  if (may_wake) {
    accumulators_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
      accumulators_[i] = {bodies[i].force, bodies[i].torque};
  }
  for (;;) {
    if (integrator_ != Integrator::rk4 && has_force_elements()) evaluate_forces(t);
    solver_.begin(bodies.size());
    velocity_stage(integrator_, gyroscopic_, bodies, gravity_, h, solver_.bodies(),
                   solver_.accelerations(), stages_);
    solver_.stages = &stages_;
    solver_.prepare(bodies, store_->ids(), planes_, may_wake ? awake_joints() : joint_refs_, h);
    if (!may_wake || !wake_touched()) break;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      std::tie(bodies[i].force, bodies[i].torque) = accumulators_[i];
  }
  solver_.warm_start();
  solver_.solve();
  solver_.integrate_positions();
  static const std::function<void(double)> no_forces;
  std::size_t bad =
      position_stage(integrator_, gyroscopic_, bodies, gravity_, t, h, solver_.bodies(),
                     solver_.pushes(), stages_, rk4_,
                     has_force_elements() ? stage_forces_ : no_forces);
  if (bad != all_finite) return bad;
  solver_.relax();
  solver_.restitution();
  bad = solver_.correct_positions(bodies);
  solver_.store();
  const std::size_t finish = finish_stage(bodies, solver_.bodies(), stages_);
  if (bad == all_finite && finish == all_finite) solver_.project_velocities(bodies);
  return std::min(bad, finish);
}

// The undo of one step: the bodies' states (unless the first integrator pass writes them),
// the solver's memory and the joints' impulses.
void World::save_step(bool with_bodies) {
  const std::vector<Body>& b = bodies();
  snapshot_.resize(b.size());
  if (with_bodies)
    for (std::size_t i = 0; i < b.size(); ++i) snapshot_[i] = state_of(b[i]);
  solver_.begin_step();  // the contacts are kept aside by the step itself, not copied
  Solver::save_impulses(joints_, undo_impulses_);
}

void World::restore_step() {
  std::vector<Body>& b = bodies();
  for (std::size_t i = 0; i < b.size(); ++i) set_state(b[i], snapshot_[i]);
  solver_.undo_step();
  Solver::restore_impulses(joints_, undo_impulses_);
}

void World::step(double dt, long count, const std::function<void()>& poll) {
  if (!std::isfinite(dt) || !(dt > 0.0))
    throw std::invalid_argument("dt must be finite and > 0, got " + format_number(dt));
  if (count < 1) throw std::invalid_argument("the number of steps must be >= 1");
  require_not_stepping(*this, "step the world");
  steps_completed_ = 0;
  resolve_ids();
  StepPoll poller(poll);
  solver_.poll = &poller;
  struct ClearPoll {
    Solver& solver;
    ~ClearPoll() { solver.poll = nullptr; }
  } clear_poll{solver_};
  // Without force elements or constraints the first integrator pass writes the snapshot;
  // otherwise forces are evaluated (and callbacks may throw) or impulses change velocities
  // before it, so the snapshot comes first.
  const bool snapshot_in_pass = !has_force_elements() && !has_constraints();
  const double h = dt / substeps_;
  std::vector<Body>& bodies = this->bodies();
  // Gives the bodies frozen by the sleep stage their mass properties back, however the step
  // ends.
  struct Thaw {
    Islands& islands;
    std::vector<Body>& bodies;
    ~Thaw() { islands.thaw(bodies); }
  };
  for (long k = 0; k < count; ++k) {
    StepGuard guard(*this, !snapshot_in_pass);
    if (sleeping_) islands_.freeze(bodies);
    Thaw thaw{islands_, bodies};
    const double t = time_;
    for (const auto& j : joints_) j->step_impulse_ = j->step_angular_impulse_ = Vec3::Zero();
    for (int s = 0; s < substeps_; ++s) {
      // The integrators consume the accumulators; forces applied before the call act during
      // every substep of the first step.
      if (k == 0 && s > 0) {
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          bodies[i].force = snapshot_[i].force;
          bodies[i].torque = snapshot_[i].torque;
        }
      }
      const bool first_pass = s == 0 && snapshot_in_pass;
      const std::size_t bad = substep(t + s * h, h, first_pass ? snapshot_.data() : nullptr);
      if (first_pass) guard.snapshot_taken();
      if (bad != all_finite) throw_non_finite(bad, t, t + dt, count);
      poller.tick(bodies.size() + 1);
    }
    islands_.thaw(bodies);
    time_ = t + dt;
    guard.commit();
    ++steps_completed_;
    if (sleeping_) sleep_stage(dt);
    for (const std::shared_ptr<StepObserver>& o : observers_) o->after_step(*this);
  }
}

// ---- the sleep stage (engine/islands.hpp) ------------------------------------------------------

void World::set_sleeping(bool on) {
  require_not_stepping(*this, "change sleeping");
  if (!on) wake_all();
  sleeping_ = on;
}

void World::set_sleep_settings(const SleepSettings& s) {
  require_not_stepping(*this, "change the sleep settings");
  const std::string problem = sleep_settings_problem(s);
  if (!problem.empty()) throw std::invalid_argument(problem);
  sleep_settings_ = s;
}

void World::wake(BodyId id) {
  require_not_stepping(*this, "wake a body");
  if (!store_->contains(id)) throw std::invalid_argument("the body is not in this world");
  const Body& b = store_->get(id);
  if (b.sleeping) Islands::wake_island(bodies(), b.island);
}

void World::wake_all() { Islands::wake_all(bodies()); }

std::size_t World::sleeping_count() const {
  return static_cast<std::size_t>(std::count_if(bodies().begin(), bodies().end(),
                                                [](const Body& b) { return b.sleeping; }));
}

// The joints the solver sees while islands sleep: those with no frozen body (a joint inside a
// sleeping island keeps its impulses for the warm start when the island wakes).
const std::vector<Solver::JointRef>& World::awake_joints() {
  awake_joint_refs_.clear();
  for (const Solver::JointRef& j : joint_refs_)
    if (!islands_.frozen(j.a) && (j.b == no_body || !islands_.frozen(j.b)))
      awake_joint_refs_.push_back(j);
  return awake_joint_refs_;
}

// After the contacts of a substep are found: wakes the sleeping islands an awake dynamic
// body has a contact with. True when one woke (the substep is then prepared again).
bool World::wake_touched() {
  std::vector<Body>& b = bodies();
  const ContactConstraints& contacts = solver_.contact_constraints();
  const std::size_t n = b.size();
  auto awake_dynamic = [&](std::size_t i) {
    return i < n && !islands_.frozen(i) && !is_static(b[i]);
  };
  bool woke = false;
  for (std::size_t m = 0; m < contacts.manifold_count(); ++m) {
    const auto [x, y] = contacts.manifold_slots(m);
    for (const auto& [sleeper, other] : {std::pair{x, y}, std::pair{y, x}}) {
      if (!islands_.frozen(sleeper) || !awake_dynamic(other)) continue;
      islands_.wake_in_step(b, sleeper);
      woke = true;
    }
  }
  return woke;
}

// After a committed step: the islands through joints, springs and contacts (speculative ones
// too: they are what wakes a sleeping island, engine/islands.hpp), the timers, and the
// islands that fall asleep.
void World::sleep_stage(double dt) {
  std::vector<Body>& b = bodies();
  const BodyStore& store = *store_;
  islands_.begin_links(b.size());
  for (const Solver::JointRef& j : joint_refs_) islands_.link(b, j.a, j.b);
  for (const SpringRef& s : spring_refs_) islands_.link(b, s.a, s.b);
  if (has_constraints())
    for (const ContactInfo& c : solver_.contacts())
      if (store.contains(c.a) && store.contains(c.b))
        islands_.link(b, store.index_of(c.a), store.index_of(c.b));
  islands_.finish(b, store.ids(), dt, sleep_settings_, callbacks_.empty());
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

void World::throw_non_finite(std::size_t index, double t0, double t1, long count) const {
  const Body& b = bodies()[index];
  // Rates first: a non-finite velocity makes the position non-finite too.
  const char* what = !is_finite(b.velocity)           ? "velocity"
                     : !is_finite(b.angular_velocity) ? "angular velocity"
                     : !is_finite(b.position)         ? "position"
                                                      : "orientation";
  std::string message = "body " + std::to_string(index + 1) + " of " +
                        std::to_string(bodies().size()) + " would get a non-finite " + what +
                        " in the step from t = " + format_number(t0) +
                        " s to t = " + format_number(t1) + " s; ";
  if (count == 1)
    message += "nothing was changed (the world is still at t = " + format_number(t0) + " s)";
  else
    message += "that step was undone: " + std::to_string(steps_completed_) + " of " +
               std::to_string(count) + " steps completed (the world is at t = " +
               format_number(t0) + " s)";
  throw StepError(message, index, t0);
}

// ---- saved states ----------------------------------------------------------------------------------

void World::save_state(WorldState& to) const {
  require_not_stepping(*this, "save the state");
  to.ids = store_->ids();
  to.bodies = bodies();
  to.time = time_;
  solver_.save(to.contacts, to.last_substep);
  Solver::save_impulses(joints_, to.joint_impulses);
}

void World::restore_state(const WorldState& from) {
  require_not_stepping(*this, "restore a state");
  if (from.ids != store_->ids())
    throw std::invalid_argument("the state was saved with other bodies than the world has now");
  // The flattened impulses hold each joint's row count, its tracked state, then its impulses.
  std::size_t next = 0;
  for (std::size_t k = 0; k < joints_.size() && next <= from.joint_impulses.size(); ++k)
    next = next < from.joint_impulses.size()
               ? next + 2 + static_cast<std::size_t>(from.joint_impulses[next])
               : from.joint_impulses.size() + 1;
  if (next != from.joint_impulses.size())
    throw std::invalid_argument("the state was saved with other joints than the world has now");
  bodies() = from.bodies;
  time_ = from.time;
  solver_.restore(from.contacts, from.last_substep);
  Solver::restore_impulses(joints_, from.joint_impulses);
}

// ---- totals ------------------------------------------------------------------------------------

double World::kinetic_energy() const {
  double sum = 0.0;
  for (const Body& b : bodies()) sum += rigidlab::kinetic_energy(b);
  return sum;
}

double World::potential_energy() const {
  double sum = 0.0;
  for (const Body& b : bodies()) sum += gravity_potential_energy(b, gravity_);
  const BodyStore& store = *store_;
  for (const Spring& s : springs_)
    sum += spring_potential_energy(store.get(s.a), s.b.valid() ? &store.get(s.b) : nullptr, s);
  for (const auto& j : joints_)
    sum += j->potential_energy(store.get(j->body_a()),
                               j->body_b().valid() ? &store.get(j->body_b()) : nullptr);
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
