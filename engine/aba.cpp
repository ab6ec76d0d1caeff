#include "engine/aba.hpp"

#include <Eigen/Cholesky>
#include <stdexcept>
#include <string>

#include "engine/format.hpp"

// Notation. The document (000 "Featherstone's Algorithm") writes the three loops with
//   v_i velocity, c_i = v_i × s_i q̇_i, p_i = v_i × I_i v_i − F_ext,i (bias force),
//   I_i^accu, p_i^accu (articulated inertia and bias force), h_i = I_i^accu s_i,
//   d_i = s_iᵀ h_i, u_i = τ_i − h_iᵀ c_i − s_iᵀ p_i^accu, R_i^j (coordinate transforms).
// Featherstone's Table 7.1 names the same quantities v, c, p^A, I^A, U, D and uses
// u_F = τ − Sᵀ p^A; his p^a = p^A + I^a c + U D⁻¹ u_F with I^a = I^A − U D⁻¹ Uᵀ equals the
// document's p^accu + I^accu c + h u / d (expand I^a: the −h hᵀc/d term is the one the document
// folds into u). The code follows the document's form; the workspace names follow Featherstone
// (IA, pA, U, D) with the document's in comments.
namespace rigidlab {
namespace {

// A joint whose articulated inertia about its own axis is this small a fraction of the
// largest entry of I^A is singular: nothing it carries resists its motion.
constexpr double singular_fraction = 1e-12;

std::string link_label(const ArticulationModel& model, int link) {
  const std::string& name = model.links()[link].spec.name;
  return "link " + std::to_string(link + 1) + (name.empty() ? "" : " ('" + name + "')");
}

[[noreturn]] void singular_joint(const ArticulationModel& model, int link, double d) {
  const char* kind = joint_type_names[static_cast<int>(model.links()[link].spec.joint)];
  throw std::domain_error(
      link_label(model, link) + " has no inertia about its " + kind +
      " joint (d = sᵀ I^A s = " + format_number(d) +
      "): the links it carries have no mass or inertia that its joint would move, so any "
      "torque would accelerate it without bound; give them mass");
}

// Loop 1 (document: "compute velocities for all links"): v_i, c_i, then each link's own
// inertia and bias force start the accumulation, I_i^accu = I_i, p_i^accu = p_i.
void velocity_loop(const ArticulationModel& model, const Eigen::VectorXd& q,
                   const Eigen::VectorXd& v, ArticulationWorkspace& ws) {
  forward_kinematics(model, q, ws);
  forward_velocities(model, v, ws);
  ws.IA[0].setZero();  // the base frame itself is massless; a free base's mass is its links'
  ws.pA[0].setZero();
  for (int i = 1; i <= model.link_count(); ++i) {
    const Mat6& inertia = model.links()[i - 1].inertia;
    ws.p[i] = crf(ws.v[i], inertia * ws.v[i]) - gravity_force(model, ws, i);  // v × I v − F_ext
    ws.IA[i] = inertia;
    ws.pA[i] = ws.p[i];
  }
}

// Loop 2 (document: "compute inertia and bias force"), leaves to root: each link hands its
// articulated inertia and bias force, as seen through its joint, to its parent.
void inertia_loop(const ArticulationModel& model, const Eigen::VectorXd& tau,
                  ArticulationWorkspace& ws) {
  for (int i = model.link_count(); i >= 1; --i) {
    const Link& link = model.links()[i - 1];
    const int parent = link.spec.parent + 1;
    Mat6 handed_inertia = ws.IA[i];  // I^a: what the parent feels of this subtree
    Vec6 handed_bias = ws.pA[i] + ws.IA[i] * ws.c[i];
    if (link.v_index >= 0) {
      ws.U[i] = ws.IA[i] * ws.S[i];                                    // h_i = I^accu s_i
      ws.D[i] = ws.S[i].dot(ws.U[i]);                                  // d_i = s_iᵀ h_i
      if (!(ws.D[i] > singular_fraction * ws.IA[i].cwiseAbs().maxCoeff()))
        singular_joint(model, i - 1, ws.D[i]);
      ws.u[i] = tau[link.v_index] - ws.U[i].dot(ws.c[i]) - ws.S[i].dot(ws.pA[i]);
      handed_inertia -= ws.U[i] * ws.U[i].transpose() / ws.D[i];      // I^accu − h hᵀ / d
      handed_bias += ws.U[i] * (ws.u[i] / ws.D[i]);                    // + (u / d) h
    }
    if (parent == 0 && !model.free_base()) continue;  // a fixed base absorbs it
    ws.IA[parent] += inertia_to_parent(ws.X_up[i], handed_inertia);
    ws.pA[parent] += ws.X_up[i].transpose_force(handed_bias);
  }
}

// A free base: its six coordinates have an invertible S, so its acceleration follows from the
// whole articulation's inertia, I^A_0 a_0 + p^A_0 = S⁻ᵀ τ_base (RBDA 9.4, floating base).
void free_base_acceleration(const Eigen::VectorXd& tau, ArticulationWorkspace& ws,
                            Eigen::VectorXd& qdd) {
  const Eigen::Matrix<double, 6, 6> inertia = ws.IA[0];
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(inertia);
  const auto pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success ||
      !(pivots.minCoeff() > singular_fraction * pivots.cwiseAbs().maxCoeff()))
    throw std::domain_error(
        "the free base has no inertia in some direction: a free base is a massless frame, so "
        "attach links with mass to it (with a fixed joint for a rigid base body)");
  // S_base⁻ᵀ (F, n) = [Rᵀ n; Rᵀ F] = S_base (F, n): the world wrench in base coordinates.
  const Eigen::Matrix<double, 6, 1> wrench = ws.S_base * tau.head<6>() - ws.pA[0];
  ws.a[0] = ldlt.solve(wrench);
  const Vec6 joint_part = ws.a[0] - ws.c[0];  // a_0 = S q̈_base + c_0
  const Mat3& R = ws.rotation[0];
  qdd.head<3>() = R * bottom(joint_part);
  qdd.segment<3>(3) = R * top(joint_part);
}

// Loop 3 (document: "compute acceleration for all joints"), root to leaves:
//   q̈_i = (u_i − h_iᵀ R a_j) / d_i,   a_i = R a_j + c_i + s_i q̈_i.
void acceleration_loop(const ArticulationModel& model, ArticulationWorkspace& ws,
                       Eigen::VectorXd& qdd) {
  for (int i = 1; i <= model.link_count(); ++i) {
    const Link& link = model.links()[i - 1];
    const Vec6 a_parent = ws.X_up[i].apply_motion(ws.a[link.spec.parent + 1]);
    ws.a[i] = a_parent + ws.c[i];
    if (link.v_index >= 0) {
      const double qdd_i = (ws.u[i] - ws.U[i].dot(a_parent)) / ws.D[i];
      qdd[link.v_index] = qdd_i;
      ws.a[i] += ws.S[i] * qdd_i;
    }
  }
}

}  // namespace

void articulated_body_algorithm(const ArticulationModel& model, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v, const Eigen::VectorXd& tau,
                                ArticulationWorkspace& ws, Eigen::VectorXd& qdd) {
  qdd.resize(model.nv());
  velocity_loop(model, q, v, ws);
  inertia_loop(model, tau, ws);
  if (model.free_base())
    free_base_acceleration(tau, ws, qdd);
  else
    ws.a[0].setZero();  // gravity is a force on each link (F_ext), not a base acceleration
  acceleration_loop(model, ws, qdd);
}

}  // namespace rigidlab
