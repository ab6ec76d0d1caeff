// A world: bodies with stable ids (engine/body_store.hpp), uniform gravity, force elements
// (springs, drag, user callbacks), static planes, joints (engine/constraint.hpp), a time
// integrator and a constraint solver (engine/solver.hpp), run as one step pipeline
// (docs/architecture.md). step(dt, n) advances n steps; a step that would leave a NaN or an
// infinity anywhere is refused and undone (STYLE.md 5, MuJoCo's mj_checkPos idea), and so is
// a step a callback or the stop check throws from: the steps before it are kept.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/body.hpp"
#include "engine/body_store.hpp"
#include "engine/constraint.hpp"
#include "engine/contact_constraints.hpp"
#include "engine/forces.hpp"
#include "engine/integrators.hpp"
#include "engine/islands.hpp"
#include "engine/plane.hpp"
#include "engine/solver.hpp"

namespace rigidlab {

// Raised by World::step when the new state of a body is not finite. The world is then as it
// was after the last completed step. body_index is 0-based; the message counts from 1, as Lua
// does.
class StepError : public std::runtime_error {
 public:
  StepError(const std::string& message, std::size_t body_index, double time)
      : std::runtime_error(message), body_index(body_index), time(time) {}
  std::size_t body_index;
  double time;  // s, the start of the step that failed
};

// A user force: called with the world and the time t (s) at every force evaluation (once per
// substep for the Euler family, at each of the four stages of RK4, with the bodies holding the
// stage's state); it applies forces with apply_force / apply_torque.
using ForceCallback = std::function<void(World&, double t)>;

// Something that watches a world's motion (a recorder): told after every completed step, with
// the world in the state that step left. It must neither change the world nor throw.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void after_step(const World& world) noexcept = 0;
};

// Everything a step reads that changes as the world runs: the bodies (all of each Body), the
// time, the contacts and joint impulses the next step is warm started from. World::save_state
// and restore_state (the viewer's rewind): restoring and stepping again gives the same states
// bit for bit.
struct WorldState {
  std::vector<BodyId> ids;
  std::vector<Body> bodies;
  double time = 0.0;
  ContactConstraints::Cache contacts;
  double last_substep = 0.0;
  std::vector<double> joint_impulses;  // of each joint's rows, in the world's joint order
};

class World {
 public:
  static constexpr int max_substeps = 10000;

  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // ---- settings (throw std::invalid_argument for bad values, std::logic_error in a step) ----
  const Vec3& gravity() const { return gravity_; }  // m/s², default (0, −9.81, 0)
  void set_gravity(const Vec3& g);
  Integrator integrator() const { return integrator_; }
  void set_integrator(Integrator i) { integrator_ = i; }
  GyroscopicTerm gyroscopic() const { return gyroscopic_; }
  void set_gyroscopic(GyroscopicTerm g) { gyroscopic_ = g; }
  SolverKind solver() const { return solver_.kind; }
  void set_solver(SolverKind kind);
  int substeps() const { return substeps_; }
  void set_substeps(int n);  // 1 .. max_substeps

  // ---- sleeping islands (engine/islands.hpp; off by default) ----
  bool sleeping() const { return sleeping_; }
  void set_sleeping(bool on);  // off wakes every body
  const SleepSettings& sleep_settings() const { return sleep_settings_; }
  void set_sleep_settings(const SleepSettings& s);  // std::invalid_argument if bad
  // Wakes the island of the body (its id must be in this world); nothing if it is awake.
  void wake(BodyId id);
  std::size_t sleeping_count() const;

  // ---- bodies (std::logic_error during a step) ----
  // Adds a copy of b (its state must be finite); returns its id.
  BodyId add(const Body& b);
  // Removes the body (its id must be in this world) and every spring, drag, joint and
  // remembered contact attached to it; returns the body. The other bodies keep their ids.
  Body remove(BodyId id);
  bool contains(BodyId id) const { return store_->contains(id); }
  std::vector<Body>& bodies() { return store_->bodies(); }
  const std::vector<Body>& bodies() const { return store_->bodies(); }
  BodyStore& store() { return *store_; }
  const BodyStore& store() const { return *store_; }
  const std::shared_ptr<BodyStore>& shared_store() const { return store_; }

  // ---- force elements (std::invalid_argument when invalid or not attached to this world) ----
  void add_spring(const Spring& s);
  void add_drag(const Drag& d);
  void add_force(ForceCallback callback);
  const std::vector<Spring>& springs() const { return springs_; }
  const std::vector<Drag>& drags() const { return drags_; }

  // ---- joints (engine/constraint.hpp) ----
  // Takes ownership; its bodies must be in this world (b may be no_body_id: the world) and
  // differ. Returns the joint, which lives until remove_constraint or its bodies' removal.
  Constraint& add_constraint(std::unique_ptr<Constraint> joint);
  void remove_constraint(const Constraint& joint);
  std::size_t constraint_count() const { return joints_.size(); }
  Constraint& constraint(std::size_t i) { return *joints_[i]; }
  const Constraint& constraint(std::size_t i) const { return *joints_[i]; }
  // The joint of serial number `serial` (Constraint::serial), or nullptr once removed.
  Constraint* find_constraint(std::uint64_t serial);
  // The serial number the next joint added will get.
  std::uint64_t next_joint_serial() const { return last_joint_serial_ + 1; }

  // ---- contacts (engine/contact_constraints.hpp) ----
  // Bodies with a shape collide with each other and with the planes. A body's shape must not
  // change while it is in the world (the world counts the shaped bodies when they are added).
  std::size_t add_plane(const Plane& p);  // returns its index; std::invalid_argument if bad
  const std::vector<Plane>& planes() const { return planes_; }
  const ContactSettings& contact_settings() const { return solver_.settings; }
  void set_contact_settings(const ContactSettings& s);  // std::invalid_argument if bad
  // The contact points of the last substep (ContactInfo::a, b are body ids).
  const std::vector<ContactInfo>& contacts() const { return solver_.contacts(); }
  // The largest constraint velocity error after each solver sweep of the last substep.
  const std::vector<double>& solver_report() const { return solver_.report(); }
  // The restitution rounds of the last substep (engine/contact_constraints.hpp).
  const std::vector<RestitutionRound>& restitution_rounds() const {
    return solver_.contact_constraints().restitution_rounds();
  }

  // ---- time ----
  // Advances `count` steps of dt (s, finite and > 0), each in substeps() equal substeps of the
  // step pipeline. Forces applied before the call act during the whole first step (all its
  // substeps and stages) and are then cleared, as if step(dt) were called `count` times.
  // `poll`, if given, is called about every millisecond of work at most (between substeps
  // and between solver sweeps; engine/step_poll.hpp): the embedding program stops the step by
  // throwing from it (Ctrl-C, a time limit). Throws StepError if any body's state would
  // become non-finite, std::logic_error when called during a step (from a force callback),
  // and propagates what a callback or the poll throws. A failure undoes the step it happened
  // in (bodies, accumulators, time, contacts); the steps before it are kept, and
  // steps_completed() says how many. While stepping, bodies hold intermediate (stage) states
  // and store().stepping() is true.
  void step(double dt, long count = 1, const std::function<void()>& poll = {});
  // The number of steps the last call of step() completed (all of them when it returned).
  long steps_completed() const { return steps_completed_; }
  double time() const { return time_; }  // s; during a step, the time of the current stage
  // Observers of completed steps (recorders); the world shares their ownership. Adding or
  // removing one during a step is a std::logic_error.
  void add_step_observer(std::shared_ptr<StepObserver> observer);
  void remove_step_observer(const StepObserver* observer);
  bool stepping() const { return store_->stepping_; }

  // ---- saved states (not during a step: std::logic_error) ----
  void save_state(WorldState& to) const;
  // std::invalid_argument, changing nothing, when the world's bodies or joints are not the
  // ones the state was saved with.
  void restore_state(const WorldState& from);

  // ---- totals (dynamic bodies; static ones have no momentum and no energy) ----
  double kinetic_energy() const;                   // J
  double potential_energy() const;                 // J: gravity (zero at the origin),
                                                   // springs and joint springs
  double energy() const { return kinetic_energy() + potential_energy(); }
  Vec3 linear_momentum() const;                    // kg m/s
  // kg m²/s about the world point `about`: Σ (x − about) × m v + I_world ω.
  Vec3 angular_momentum(const Vec3& about = Vec3::Zero()) const;

 private:
  class StepGuard;
  struct SpringRef {
    std::size_t a, b;  // indices (no_body for an anchor)
  };
  bool has_force_elements() const;
  bool has_constraints() const {
    return !joints_.empty() || shaped_bodies_ >= (planes_.empty() ? 2u : 1u);
  }
  void resolve_ids();
  void evaluate_forces(double t);
  std::size_t substep(double t, double h, BodyState* save_to);
  std::size_t free_substep(double t, double h, BodyState* save_to);
  void save_step(bool with_bodies);
  void restore_step();
  // The sleep stage (engine/islands.hpp): wakes in a substep, islands after a step.
  const std::vector<Solver::JointRef>& awake_joints();
  bool wake_touched();
  void sleep_stage(double dt);
  void wake_all();
  [[noreturn]] void throw_non_finite(std::size_t index, double t0, double t1, long count) const;

  std::shared_ptr<BodyStore> store_;
  Vec3 gravity_;
  Integrator integrator_ = Integrator::semi_implicit;
  GyroscopicTerm gyroscopic_ = default_gyroscopic;
  int substeps_ = 1;
  double time_ = 0.0;
  long steps_completed_ = 0;
  std::vector<Spring> springs_;
  std::vector<Drag> drags_;
  std::vector<ForceCallback> callbacks_;
  std::vector<Plane> planes_;
  std::vector<std::unique_ptr<Constraint>> joints_;  // in the order added (serials rise)
  std::uint64_t last_joint_serial_ = 0;
  std::vector<std::shared_ptr<StepObserver>> observers_;
  std::size_t shaped_bodies_ = 0;  // bodies whose shape is not none
  Solver solver_;
  // Resolved once per call of step(): the bodies' indices of springs, drags and joints.
  std::vector<SpringRef> spring_refs_;
  std::vector<std::size_t> drag_refs_;
  std::vector<Solver::JointRef> joint_refs_;
  // The joints (count, last serial) the solver's excluded contact pairs were made for.
  std::pair<std::size_t, std::uint64_t> excluded_for_{0, 0};
  // The undo of the step being taken: the bodies' states before it, the solver's memory.
  std::vector<BodyState> snapshot_;
  std::vector<double> undo_impulses_;  // the joints' (the contacts: Solver::begin_step)
  StageWorkspace stages_;
  Rk4Workspace rk4_;
  std::function<void(double)> stage_forces_;  // evaluate_forces, bound once for rk4_step
  // Sleeping: the setting, the islands, the joints of awake bodies and the accumulators of a
  // substep that may be prepared again when a contact wakes an island.
  bool sleeping_ = false;
  SleepSettings sleep_settings_;
  Islands islands_;
  std::vector<Solver::JointRef> awake_joint_refs_;
  std::vector<std::pair<Vec3, Vec3>> accumulators_;
};

}  // namespace rigidlab
