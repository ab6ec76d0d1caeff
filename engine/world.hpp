// A world: bodies stored contiguously, uniform gravity, force elements (springs, drag, user
// callbacks) and a time integrator. step(dt) advances every body; a step that would leave a
// NaN or an infinity anywhere is refused and undone (STYLE.md 5, MuJoCo's mj_checkPos idea).
//
// Bodies live in a BodyStore: a std::vector<Body> (the step loops run over it directly) with
// stable ids, because indices shift when a body is removed. The store is held by shared_ptr
// so handles to bodies (the Lua binding's body objects) can keep it alive after the world is
// gone: such bodies stay readable, and store.world() is then nullptr.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/body.hpp"
#include "engine/contact_solver.hpp"
#include "engine/forces.hpp"
#include "engine/integrators.hpp"
#include "engine/plane.hpp"

namespace rigidlab {

class World;

// Contiguous bodies with stable ids. Erasing keeps the order of the others (their indices
// above the erased one drop by 1); ids of erased bodies are reused by later inserts.
class BodyStore {
 public:
  using Id = std::uint32_t;

  Id insert(const Body& b);
  Body erase(Id id);  // the erased body
  bool contains(Id id) const {
    return id < index_of_.size() && index_of_[id] != npos;
  }
  Body& get(Id id) { return bodies_[index_of_[id]]; }
  const Body& get(Id id) const { return bodies_[index_of_[id]]; }
  std::size_t index_of(Id id) const { return index_of_[id]; }
  Id id_at(std::size_t index) const { return ids_[index]; }
  std::size_t size() const { return bodies_.size(); }
  std::vector<Body>& bodies() { return bodies_; }
  const std::vector<Body>& bodies() const { return bodies_; }

  // The world this store belongs to: nullptr for a store made for a lone body, and after the
  // world has been destroyed.
  World* world() const { return world_; }
  // True during World::step: only forces may then be applied to the bodies (see World::step).
  bool stepping() const { return stepping_; }

 private:
  friend class World;
  static constexpr std::uint32_t npos = static_cast<std::uint32_t>(-1);
  std::vector<Body> bodies_;
  std::vector<Id> ids_;                   // by index
  std::vector<std::uint32_t> index_of_;   // by id; npos when free
  std::vector<Id> free_ids_;
  World* world_ = nullptr;
  bool stepping_ = false;
};

// Raised by World::step when the new state of a body is not finite. The world is then exactly
// as it was before the call. body_index is 0-based; the message counts from 1, as Lua does.
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

class World {
 public:
  static constexpr int max_substeps = 10000;

  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // ---- settings (throw std::invalid_argument for bad values) ----
  const Vec3& gravity() const { return gravity_; }  // m/s², default (0, −9.81, 0)
  void set_gravity(const Vec3& g);
  Integrator integrator() const { return integrator_; }
  void set_integrator(Integrator i) { integrator_ = i; }
  GyroscopicTerm gyroscopic() const { return gyroscopic_; }
  void set_gyroscopic(GyroscopicTerm g) { gyroscopic_ = g; }
  int substeps() const { return substeps_; }
  void set_substeps(int n);  // 1 .. max_substeps

  // ---- bodies (std::logic_error during a step) ----
  // Adds a copy of b (its state must be finite); returns its id in store().
  BodyStore::Id add(const Body& b);
  // Removes the body and every spring and drag attached to it; returns the body.
  Body remove(BodyStore::Id id);
  std::vector<Body>& bodies() { return store_->bodies(); }
  const std::vector<Body>& bodies() const { return store_->bodies(); }
  BodyStore& store() { return *store_; }
  const std::shared_ptr<BodyStore>& shared_store() const { return store_; }

  // ---- force elements (indices into bodies(); std::invalid_argument when invalid) ----
  void add_spring(const Spring& s);
  void add_drag(const Drag& d);
  void add_force(ForceCallback callback);
  const std::vector<Spring>& springs() const { return springs_; }
  const std::vector<Drag>& drags() const { return drags_; }

  // ---- contacts (engine/contact_solver.hpp) ----
  // Bodies with a shape collide with each other and with the planes. A body's shape must not
  // change while it is in the world (the world counts the shaped bodies when they are added).
  std::size_t add_plane(const Plane& p);  // returns its index; std::invalid_argument if bad
  const std::vector<Plane>& planes() const { return planes_; }
  const ContactSettings& contact_settings() const { return contacts_.settings; }
  void set_contact_settings(const ContactSettings& s);  // std::invalid_argument if bad
  // The contact points of the last substep (ContactInfo::a, b index bodies()).
  const std::vector<ContactInfo>& contacts() const { return contacts_.contacts(); }

  // ---- time ----
  // Advances `count` steps of dt (s, finite and > 0), each in substeps() equal substeps with
  // the chosen integrator. Forces applied before the call act during the whole first step
  // (all its substeps and stages) and are then cleared, as if step(dt) were called `count`
  // times. `poll`, if given, is called about every millisecond of work at most (between
  // substeps and between sweeps of the contact solver; engine/step_poll.hpp): the embedding
  // program stops the step by throwing from it (Ctrl-C, a time limit). Throws StepError if
  // any body's state would become non-finite, std::logic_error when called during a step
  // (from a force callback), and propagates what a callback or the poll throws; after any
  // failure the bodies, their accumulators and
  // the time are exactly as before the call. While stepping, bodies hold intermediate (stage)
  // states and store().stepping() is true.
  void step(double dt, long count = 1, const std::function<void()>& poll = {});
  double time() const { return time_; }  // s; during a step, the time of the current stage
  // Observers of completed steps (recorders); the world shares their ownership. Adding or
  // removing one during a step is a std::logic_error.
  void add_step_observer(std::shared_ptr<StepObserver> observer);
  void remove_step_observer(const StepObserver* observer);
  bool stepping() const { return store_->stepping_; }

  // ---- totals (dynamic bodies; static ones have no momentum and no energy) ----
  double kinetic_energy() const;                   // J
  double potential_energy() const;                 // J: gravity (zero at the origin) + springs
  double energy() const { return kinetic_energy() + potential_energy(); }
  Vec3 linear_momentum() const;                    // kg m/s
  // kg m²/s about the world point `about`: Σ (x − about) × m v + I_world ω.
  Vec3 angular_momentum(const Vec3& about = Vec3::Zero()) const;

 private:
  class StepGuard;
  bool has_force_elements() const;
  bool has_contacts() const {
    return shaped_bodies_ >= (planes_.empty() ? 2u : 1u);
  }
  void evaluate_forces(double t);
  std::size_t integrate(double t, double dt, BodyState* save_to);
  [[noreturn]] void throw_non_finite(std::size_t index, double t0, double t1,
                                     double call_start) const;

  std::shared_ptr<BodyStore> store_;
  Vec3 gravity_;
  Integrator integrator_ = Integrator::semi_implicit;
  GyroscopicTerm gyroscopic_ = default_gyroscopic;
  int substeps_ = 1;
  double time_ = 0.0;
  std::vector<Spring> springs_;
  std::vector<Drag> drags_;
  std::vector<ForceCallback> callbacks_;
  std::vector<Plane> planes_;
  ContactSolver contacts_;
  std::size_t shaped_bodies_ = 0;  // bodies whose shape is not none
  std::vector<BodyState> snapshot_;  // the state before the current step, for undoing it
  Rk4Workspace rk4_;
  std::function<void(double)> stage_forces_;  // evaluate_forces, bound once for rk4_step
  std::vector<std::shared_ptr<StepObserver>> observers_;
};

}  // namespace rigidlab
