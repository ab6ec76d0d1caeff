#include "engine/articulation.hpp"
#include "engine/format.hpp"

#include <string>
#include <utility>

#include "engine/aba.hpp"
#include "engine/crba.hpp"
#include "engine/rnea.hpp"

namespace rigidlab {
namespace {

std::string vector_problem(const Eigen::VectorXd& x, Eigen::Index size, const char* name) {
  if (x.size() != size)
    return std::string(name) + " must have " + std::to_string(size) +
           " entries (one per velocity coordinate), got " + std::to_string(x.size());
  for (Eigen::Index k = 0; k < size; ++k)
    if (!std::isfinite(x[k]))
      return std::string(name) + "[" + std::to_string(k + 1) + "] must be finite, got " +
             format_number(x[k]);
  return {};
}

}  // namespace

Articulation::Articulation(BaseType base, const Vec3& base_position, const Quat& base_orientation)
    : model_(base, base_position, base_orientation) {
  ws_.resize(model_);
  q_ = model_.neutral_q();
  v_ = tau_ = Eigen::VectorXd::Zero(model_.nv());
  applied_ = qdd_ = v0_ = v_;
  q0_ = q_;
  q_slopes_.fill(q_);
  v_slopes_.fill(v_);
}

void Articulation::check_not_stepping(const char* what) const {
  if (stepping_)
    throw std::invalid_argument(std::string("the articulation is stepping: cannot ") + what +
                                " until step returns (a control may only return torques)");
}

void Articulation::check_link(int link) const {
  if (link < 0 || link >= model_.link_count())
    throw std::invalid_argument("link must be one of the links 1 to " +
                                std::to_string(model_.link_count()) + ", got " +
                                std::to_string(link + 1));
}

// Built on copies and committed by swaps (which cannot throw), so that a std::bad_alloc while
// growing the workspace or the state leaves the articulation as it was.
int Articulation::add_link(const LinkSpec& spec) {
  check_not_stepping("add a link");
  ArticulationModel model = model_;
  const int link = model.add_link(spec);  // throws before anything changes
  ArticulationWorkspace ws;
  ws.resize(model);
  Eigen::VectorXd q = q_, v = v_, tau = tau_;
  if (model.nv() > model_.nv()) {  // the new joint's entries are the last ones of q, q̇ and τ
    q.conservativeResize(model.nq());
    v.conservativeResize(model.nv());
    tau.conservativeResize(model.nv());
    q[model.nq() - 1] = v[model.nv() - 1] = tau[model.nv() - 1] = 0.0;
  }
  Eigen::VectorXd applied = v, qdd = v, v0 = v, q0 = q;
  std::array<Eigen::VectorXd, 4> q_slopes, v_slopes;
  q_slopes.fill(q);
  v_slopes.fill(v);
  std::swap(model_, model);
  std::swap(ws_, ws);
  q_.swap(q);
  v_.swap(v);
  tau_.swap(tau);
  applied_.swap(applied);
  qdd_.swap(qdd);
  v0_.swap(v0);
  q0_.swap(q0);
  q_slopes_.swap(q_slopes);
  v_slopes_.swap(v_slopes);
  return link;
}

void Articulation::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  check_not_stepping("set the state");
  const std::string problem = model_.state_problem(q, v);
  if (!problem.empty()) throw std::invalid_argument(problem);
  q_ = q;
  v_ = v;
  if (model_.free_base()) q_.segment<4>(3).normalize();
}

void Articulation::save_state(ArticulationState& to) const {
  to.q = q_;
  to.v = v_;
  to.tau = tau_;
  to.time = time_;
  to.links = model_.link_count();
}

void Articulation::restore_state(const ArticulationState& from) {
  check_not_stepping("restore a state");
  if (from.links != model_.link_count())
    throw std::invalid_argument("the state is of an articulation with " +
                                std::to_string(from.links) + " links, this one has " +
                                std::to_string(model_.link_count()));
  q_ = from.q;  // the same sizes as q_, v_, tau_: no allocation
  v_ = from.v;
  tau_ = from.tau;
  time_ = from.time;
}

void Articulation::set_torques(const Eigen::VectorXd& tau) {
  check_not_stepping("set the torques");
  const std::string problem = vector_problem(tau, model_.nv(), "tau");
  if (!problem.empty()) throw std::invalid_argument(problem);
  tau_ = tau;
}

void Articulation::add_control(Control control) {
  check_not_stepping("add a control");
  controls_.push_back(std::move(control));
}

void Articulation::update_kinematics() {
  forward_kinematics(model_, q_, ws_);
  forward_velocities(model_, v_, ws_);
}

void Articulation::set_gravity(const Vec3& g) {
  check_not_stepping("change gravity");
  model_.set_gravity(g);
}

void Articulation::run_controls() {
  if (in_controls_)
    throw std::invalid_argument(
        "the controls are running: a control cannot ask for the controls' torques or the "
        "forward dynamics they give (pass tau explicitly)");
  applied_ = tau_;
  in_controls_ = true;
  try {
    for (const Control& control : controls_) control(time_, applied_);
  } catch (...) {
    in_controls_ = false;
    throw;
  }
  in_controls_ = false;
  const std::string problem = vector_problem(applied_, model_.nv(), "the controls' tau");
  if (!problem.empty()) throw std::invalid_argument(problem);
}

Eigen::VectorXd Articulation::applied_torques() {
  run_controls();
  return applied_;
}

void Articulation::evaluate(Eigen::VectorXd& qdd) {
  run_controls();
  articulated_body_algorithm(model_, q_, v_, applied_, ws_, qdd);
}

const Eigen::VectorXd& Articulation::forward_dynamics() {
  evaluate(qdd_);
  return qdd_;
}

const Eigen::VectorXd& Articulation::forward_dynamics(const Eigen::VectorXd& tau) {
  const std::string problem = vector_problem(tau, model_.nv(), "tau");
  if (!problem.empty()) throw std::invalid_argument(problem);
  articulated_body_algorithm(model_, q_, v_, tau, ws_, qdd_);
  return qdd_;
}

Eigen::VectorXd Articulation::inverse_dynamics(const Eigen::VectorXd& qdd) {
  const std::string problem = vector_problem(qdd, model_.nv(), "qdd");
  if (!problem.empty()) throw std::invalid_argument(problem);
  Eigen::VectorXd tau;
  recursive_newton_euler(model_, q_, v_, qdd, ws_, tau);
  return tau;
}

Eigen::MatrixXd Articulation::mass_matrix() {
  Eigen::MatrixXd M;
  composite_rigid_body(model_, q_, ws_, M);
  return M;
}

Eigen::VectorXd Articulation::bias_forces() {
  Eigen::VectorXd tau;
  rigidlab::bias_forces(model_, q_, v_, ws_, tau);
  return tau;
}

Eigen::MatrixXd Articulation::jacobian(int link, const Vec3& point) {
  check_link(link);
  update_kinematics();
  Eigen::MatrixXd J;
  point_jacobian(model_, ws_, link, point, J);
  return J;
}

Eigen::VectorXd Articulation::virtual_force(int link, const Vec3& point, const Vec3& force,
                                            const Vec3& torque) {
  check_link(link);
  update_kinematics();
  Eigen::VectorXd tau;
  rigidlab::virtual_force(model_, ws_, link, point, force, torque, tau);
  return tau;
}

Vec3 Articulation::link_position(int link) { return point_position(link, Vec3::Zero()); }

Vec3 Articulation::link_com(int link) {
  check_link(link);
  return point_position(link, model_.links()[static_cast<std::size_t>(link)].spec.com);
}

Mat3 Articulation::link_rotation(int link) {
  check_link(link);
  update_kinematics();
  return ws_.rotation[link + 1];
}

Vec3 Articulation::point_position(int link, const Vec3& point) {
  check_link(link);
  update_kinematics();
  return link_point_position(ws_, link, point);
}

Vec3 Articulation::point_velocity(int link, const Vec3& point) {
  check_link(link);
  update_kinematics();
  return link_point_velocity(ws_, link, point);
}

Vec3 Articulation::angular_velocity(int link) {
  check_link(link);
  update_kinematics();
  return link_angular_velocity(ws_, link);
}

double Articulation::kinetic_energy() {
  update_kinematics();
  return rigidlab::kinetic_energy(model_, ws_);
}

double Articulation::potential_energy() {
  update_kinematics();
  return rigidlab::potential_energy(model_, ws_);
}

void Articulation::momentum(Vec3& linear, Vec3& angular) {
  update_kinematics();
  rigidlab::momentum(model_, ws_, linear, angular);
}

double Articulation::center_of_mass(Vec3& com) {
  update_kinematics();
  return rigidlab::center_of_mass(model_, ws_, com);
}

}  // namespace rigidlab
