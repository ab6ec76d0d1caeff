// Forward kinematics of an articulation (RBDA 4.1 and Table 4.1; document 000 "Featherstone's
// Algorithm", first loop: v_i = R_i^j v_j + s_i q̇_i) and the quantities computed from it: the
// Jacobian of a link point, virtual forces τ = Jᵀ F (document 000 "Virtual forces"), kinetic
// and potential energy, momentum.
//
// The per-body arrays of every algorithm live in one ArticulationWorkspace, sized once per
// model, so no algorithm allocates. Body numbering as in articulation_model.hpp: body 0 is the
// base, link k is body k + 1.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "engine/articulation_model.hpp"

namespace rigidlab {

struct ArticulationWorkspace {
  // ---- kinematics (forward_kinematics, forward_velocities) ----
  std::vector<PluckerTransform> X_up;  // i_X_λ(i); body 0: base_X_world
  std::vector<Mat3> rotation;          // world from body coordinates
  std::vector<Vec3> position;          // body origin in the world (m)
  std::vector<Vec6> S;                 // motion subspace of a 1-dof joint (body coords)
  std::vector<Vec6> v;                 // spatial velocity (body coords), RBDA eq. 4.5
  std::vector<Vec6> c;                 // velocity-product acceleration c_i = v_i × S_i q̇_i
  Mat6 S_base = Mat6::Zero();          // a free base: [R^T ω; R^T v] = S_base (v, ω)
  // ---- articulated-body algorithm (engine/aba) ----
  std::vector<Vec6> p;                 // bias force of the link alone: v × I v − f_ext
  std::vector<Mat6> IA;                // articulated-body inertia I^A (document: I^accu)
  std::vector<Vec6> pA;                // articulated bias force p^A (document: p^accu)
  std::vector<Vec6> U;                 // U = I^A S (document: h)
  std::vector<double> D;               // D = Sᵀ U (document: d)
  std::vector<double> u;               // document's u = τ − hᵀc − sᵀp^A
  std::vector<Vec6> a;                 // spatial acceleration (body coords)
  // ---- recursive Newton-Euler and composite rigid body (engine/rnea, engine/crba) ----
  std::vector<Vec6> f;                 // force across each joint, from parent to body
  std::vector<Mat6> IC;                // composite inertia of each subtree

  void resize(const ArticulationModel& model);
};

// Every body's X_up, rotation, position and S at state q (length nq).
void forward_kinematics(const ArticulationModel& model, const Eigen::VectorXd& q,
                        ArticulationWorkspace& ws);
// Every body's v and c at rates v (length nv); forward_kinematics for the same q first.
void forward_velocities(const ArticulationModel& model, const Eigen::VectorXd& v,
                        ArticulationWorkspace& ws);

// The force of gravity on link body `body` in its own coordinates: I_i [0; Rᵢᵀ g] (the weight
// acting at the COM, as a spatial force about the link origin). forward_kinematics first.
Vec6 gravity_force(const ArticulationModel& model, const ArticulationWorkspace& ws, int body);

// ---- after forward_kinematics (and forward_velocities where velocities are used) ----

// The world position (m) and velocity (m/s) of point `point` fixed in link `link` (link
// coordinates), and the link's angular velocity (rad/s, world).
Vec3 link_point_position(const ArticulationWorkspace& ws, int link, const Vec3& point);
Vec3 link_point_velocity(const ArticulationWorkspace& ws, int link, const Vec3& point);
Vec3 link_angular_velocity(const ArticulationWorkspace& ws, int link);

// The 6 x nv Jacobian of point `point` of link `link` (link coordinates): rows 0-2 the point's
// world linear velocity and rows 3-5 the link's world angular velocity per unit q̇. Column of
// an ancestor joint with world axis â through world point o: revolute [â × (p − o); â],
// prismatic [â; 0]; a free base: [E; 0] for its velocity and [−(p − x_base)^; E] for its
// angular velocity; all other columns zero. Written from the geometry, not from the spatial
// algebra of the other algorithms, so each checks the other.
void point_jacobian(const ArticulationModel& model, const ArticulationWorkspace& ws, int link,
                    const Vec3& point, Eigen::MatrixXd& jacobian);

// τ = Jᵀ F: the generalised forces that act as a world force `force` (N) applied at point
// `point` of link `link` would (document 000 "Virtual forces"), and optionally a world torque
// (N·m) on that link. Walks the link's ancestors: O(depth), no Jacobian is formed.
void virtual_force(const ArticulationModel& model, const ArticulationWorkspace& ws, int link,
                   const Vec3& point, const Vec3& force, const Vec3& torque,
                   Eigen::VectorXd& tau);

// T = Σ ½ vᵢ · Iᵢ vᵢ (J).
double kinetic_energy(const ArticulationModel& model, const ArticulationWorkspace& ws);
// V = −Σ mᵢ g · x_com,i (J), zero with every COM at the world origin.
double potential_energy(const ArticulationModel& model, const ArticulationWorkspace& ws);
// Total linear momentum (kg·m/s) and angular momentum about the world origin (kg·m²/s).
void momentum(const ArticulationModel& model, const ArticulationWorkspace& ws, Vec3& linear,
              Vec3& angular);
// Total mass (kg) and the centre of mass (world, m); (0, base origin) for a massless model.
double center_of_mass(const ArticulationModel& model, const ArticulationWorkspace& ws,
                      Vec3& com);

}  // namespace rigidlab
