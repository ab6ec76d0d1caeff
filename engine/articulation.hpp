// An articulated body simulated in reduced coordinates (document 000 "Coordinate simulation",
// "Featherstone's Algorithm"): a model (engine/articulation_model.hpp), its state q, q̇ and
// time, the joint torques held by set_torques, control functions evaluated at every stage of
// a step (document 000 "Joint torques", "PD controller", "Muscle forces"), and a time step with
// the world's three integrators (engine/integrators.hpp: euler, semi_implicit, rk4), stepped by
// the engine's one integration core (engine/runge_kutta.hpp).
//
// Each query runs one algorithm in its own file: forward dynamics by the articulated-body
// algorithm (engine/aba), inverse dynamics and bias forces by recursive Newton-Euler
// (engine/rnea), the mass matrix by the composite-rigid-body algorithm (engine/crba), the
// Jacobian, virtual forces, energies and momentum by forward kinematics
// (engine/articulation_kinematics). Queries use preallocated storage: a step allocates nothing.
//
// Errors: bad arguments throw std::invalid_argument naming the rule (nothing changes); a step
// that meets singular dynamics or a state that is not finite throws ArticulationStepError and
// leaves q, q̇ and the time exactly as before; exceptions from a control are rethrown after the
// same restore.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/articulation_kinematics.hpp"
#include "engine/integrators.hpp"

namespace rigidlab {

class ArticulationStepError : public std::runtime_error {
 public:
  ArticulationStepError(const std::string& message, double time)
      : std::runtime_error(message), time(time) {}
  double time;  // s, the start of the step that failed
};

class Articulation;

// What a step reads and writes of an articulation, saved and put back exactly (the live view's
// rewind): q, q̇, the held torques and the time, for a model of `links` links. The model,
// gravity, the integrator and the controls are not part of it.
struct ArticulationState {
  Eigen::VectorXd q, v, tau;
  double time = 0.0;
  int links = 0;
};

// Something that watches an articulation's motion (a recorder): told after every completed
// step, with the articulation in the state that step left. It may query it (kinematics,
// energies) but neither change it nor throw.
class ArticulationObserver {
 public:
  virtual ~ArticulationObserver() = default;
  virtual void after_step(Articulation& art) noexcept = 0;
};

class Articulation {
 public:
  // A control adds its generalised forces (length nv) to `tau` at time t (s). It reads the
  // state being evaluated from the articulation (q(), v(), time(), link queries): during a
  // step that is the stage state.
  using Control = std::function<void(double t, Eigen::VectorXd& tau)>;

  explicit Articulation(BaseType base = BaseType::fixed, const Vec3& base_position = Vec3::Zero(),
                        const Quat& base_orientation = Quat::Identity());

  // ---- model ----
  const ArticulationModel& model() const { return model_; }
  // Adds a link (see ArticulationModel::add_link); its joint coordinate, rate and held torque
  // start at 0. Throws std::invalid_argument (nothing changes) or while stepping.
  int add_link(const LinkSpec& spec);
  const Vec3& gravity() const { return model_.gravity(); }
  void set_gravity(const Vec3& g);  // throws while stepping or for a non-finite g
  Integrator integrator() const { return integrator_; }
  void set_integrator(Integrator integrator) { integrator_ = integrator; }

  // ---- state ----
  const Eigen::VectorXd& q() const { return q_; }
  const Eigen::VectorXd& v() const { return v_; }  // q̇
  double time() const { return time_; }  // s; during a step, the time of the current stage
  // Throws std::invalid_argument (wrong length, not finite, a free base's quaternion not of
  // unit length within 1e-6, which is then normalised).
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& v);
  // A copy of the state (allocates only when `to` is smaller than this model's), and back:
  // restore_state throws std::invalid_argument (nothing changes) when the state is of a model
  // with another number of links, or while stepping.
  void save_state(ArticulationState& to) const;
  void restore_state(const ArticulationState& from);
  // Held generalised forces (length nv), added at every evaluation until changed.
  const Eigen::VectorXd& torques() const { return tau_; }
  void set_torques(const Eigen::VectorXd& tau);
  void add_control(Control control);
  void clear_controls() { controls_.clear(); }
  int control_count() const { return static_cast<int>(controls_.size()); }
  bool stepping() const { return stepping_; }

  // ---- dynamics at the current state ----
  // q̈ for the held torques plus every control's at the current time (what a step would use
  // now), or for `tau` alone. After either, workspace() holds the three loops' quantities.
  // The first (and applied_torques) cannot be called from a control: it would call itself.
  const Eigen::VectorXd& forward_dynamics();
  const Eigen::VectorXd& forward_dynamics(const Eigen::VectorXd& tau);
  // τ = M q̈ + C q̇ + g for the given q̈ (length nv).
  Eigen::VectorXd inverse_dynamics(const Eigen::VectorXd& qdd);
  Eigen::MatrixXd mass_matrix();
  Eigen::VectorXd bias_forces();  // C(q, q̇) q̇ + g(q)
  // The generalised forces of the held torques and the controls at the current state.
  Eigen::VectorXd applied_torques();

  // ---- kinematics at the current state (link index 0-based, point in link coordinates) ----
  Eigen::MatrixXd jacobian(int link, const Vec3& point);
  Eigen::VectorXd virtual_force(int link, const Vec3& point, const Vec3& force,
                                const Vec3& torque = Vec3::Zero());
  Vec3 link_position(int link);  // the link frame's origin (the joint), world
  Vec3 link_com(int link);       // the link's centre of mass, world
  Mat3 link_rotation(int link);  // link to world
  Vec3 point_position(int link, const Vec3& point);
  Vec3 point_velocity(int link, const Vec3& point);
  Vec3 angular_velocity(int link);
  double kinetic_energy();
  double potential_energy();
  double energy() { return kinetic_energy() + potential_energy(); }
  void momentum(Vec3& linear, Vec3& angular);
  double center_of_mass(Vec3& com);
  // The workspace of the last algorithm run (for display of the loops' quantities).
  const ArticulationWorkspace& workspace() const { return ws_; }

  // ---- time ----
  // Advances by `count` steps of dt (s) with the integrator. `poll`, if given, is called before
  // every step and may throw to stop (the steps already taken stay). Throws
  // std::invalid_argument for dt not finite and > 0 and when called from a control.
  void step(double dt, int count = 1, const std::function<void()>& poll = {});

  // Observers of completed steps (recorders); the articulation shares their ownership.
  // Adding or removing one during a step is a std::logic_error.
  void add_step_observer(std::shared_ptr<ArticulationObserver> observer);
  void remove_step_observer(const ArticulationObserver* observer);

 private:
  void check_link(int link) const;
  void check_not_stepping(const char* what) const;
  void update_kinematics();  // forward kinematics and velocities at the current state
  // q̈ at (q_, v_, time_) for held torques + controls, into `qdd`.
  void evaluate(Eigen::VectorXd& qdd);
  void run_controls();  // applied_ = held torques + every control's
  void step_once(double dt);
  void integrate_step(double dt);  // one step of the integrator from (q_, v_, time_)
  friend class ArticulationSystem;  // the state as a system of the integration core

  ArticulationModel model_;
  ArticulationWorkspace ws_;
  Integrator integrator_ = Integrator::semi_implicit;
  Eigen::VectorXd q_, v_, tau_;
  double time_ = 0.0;
  std::vector<Control> controls_;
  bool stepping_ = false;
  bool in_controls_ = false;  // the controls are running: they may not evaluate themselves
  // Scratch, sized with the model: the total applied τ, q̈, the state at the start of a step
  // and the slopes of its stages (q̇ as coordinate rates, length nq; q̈, length nv).
  Eigen::VectorXd applied_, qdd_;
  Eigen::VectorXd q0_, v0_;
  std::array<Eigen::VectorXd, 4> q_slopes_, v_slopes_;
  std::vector<std::shared_ptr<ArticulationObserver>> observers_;
};

// q̇ as the derivative of q: the joint rates, and for a free base ẋ = v and the quaternion rate
// ½ (0, ω) ⊗ q (003 "Fourth-Order Runge-Kutta" integrates this 4-vector) — length nq.
void coordinate_rates(const ArticulationModel& model, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& v, Eigen::VectorXd& rates);
// q ⊕ dt v: every joint coordinate plus dt times its rate; a free base's position plus dt v,
// its orientation turned by the exact rotation of angle |ω| dt about ω (rotate_by), as the
// world's Euler integrators turn bodies.
void integrate_coordinates(const ArticulationModel& model, Eigen::VectorXd& q,
                           const Eigen::VectorXd& v, double dt);

}  // namespace rigidlab
