#include "engine/rnea.hpp"

namespace rigidlab {
namespace {

// Pass 1 (RBDA Table 5.1, outward): a_i = i_X_λ a_λ + S_i q̈_i + c_i and the net force
// f_i = I_i a_i + v_i ×* I_i v_i − f_g,i each link needs for that motion.
template <class Accelerations>
void outward_pass(const ArticulationModel& model, const Accelerations& qdd,
                  ArticulationWorkspace& ws) {
  if (model.free_base())
    ws.a[0] = ws.S_base * qdd.template head<6>() + ws.c[0];  // a_0 = S q̈_base + c_0
  else
    ws.a[0].setZero();  // gravity enters as a force on each link
  ws.f[0].setZero();    // the base frame is massless
  for (int i = 1; i <= model.link_count(); ++i) {
    const Link& link = model.links()[i - 1];
    ws.a[i] = ws.X_up[i].apply_motion(ws.a[link.spec.parent + 1]) + ws.c[i];
    if (link.v_index >= 0) ws.a[i] += ws.S[i] * qdd[link.v_index];
    const Vec6 momentum = link.inertia * ws.v[i];
    ws.f[i] = link.inertia * ws.a[i] + crf(ws.v[i], momentum) - gravity_force(model, ws, i);
  }
}

// Pass 2 (inward): τ_i = S_iᵀ f_i, then f_λ += λ_X_i* f_i.
void inward_pass(const ArticulationModel& model, ArticulationWorkspace& ws,
                 Eigen::VectorXd& tau) {
  for (int i = model.link_count(); i >= 1; --i) {
    const Link& link = model.links()[i - 1];
    if (link.v_index >= 0) tau[link.v_index] = ws.S[i].dot(ws.f[i]);
    ws.f[link.spec.parent + 1] += ws.X_up[i].transpose_force(ws.f[i]);
  }
  if (model.free_base()) {  // S_baseᵀ f_0 = (R f, R n): the world force and torque
    tau.head<3>() = ws.rotation[0] * bottom(ws.f[0]);
    tau.segment<3>(3) = ws.rotation[0] * top(ws.f[0]);
  }
}

}  // namespace

void recursive_newton_euler(const ArticulationModel& model, const Eigen::VectorXd& q,
                            const Eigen::VectorXd& v, const Eigen::VectorXd& qdd,
                            ArticulationWorkspace& ws, Eigen::VectorXd& tau) {
  forward_kinematics(model, q, ws);
  forward_velocities(model, v, ws);
  tau.resize(model.nv());
  outward_pass(model, qdd, ws);
  inward_pass(model, ws, tau);
}

void bias_forces(const ArticulationModel& model, const Eigen::VectorXd& q,
                 const Eigen::VectorXd& v, ArticulationWorkspace& ws, Eigen::VectorXd& tau) {
  forward_kinematics(model, q, ws);
  forward_velocities(model, v, ws);
  tau.resize(model.nv());
  outward_pass(model, Eigen::VectorXd::Zero(model.nv()), ws);
  inward_pass(model, ws, tau);
}

}  // namespace rigidlab
