// Inverse dynamics by the recursive Newton-Euler algorithm (RNEA): the generalised forces
//   τ = M(q) q̈ + C(q, q̇) q̇ + g(q)
// that produce accelerations q̈ at state (q, q̇) under gravity, in O(n) (R. Featherstone, "Rigid
// Body Dynamics Algorithms" (2008), section 5.3 and Table 5.1). Two passes: velocities and
// accelerations outwards, then each link's net force f_i = I_i a_i + v_i × I_i v_i − f_g,i
// inwards, τ_i = S_iᵀ f_i (the part of the joint force its motion subspace feels).
//
// The bias forces C(q, q̇) q̇ + g(q) are the RNEA with q̈ = 0 (RBDA 6.1), and g(q) alone, the
// torques that hold a pose against gravity, is the RNEA at rest: gravity compensation.
#pragma once

#include <Eigen/Core>

#include "engine/articulation_kinematics.hpp"

namespace rigidlab {

// τ (length nv) for q (nq), q̇ (nv), q̈ (nv); sizes must match the model (the caller checks).
// A free base's first six entries are the world force and torque the base would need.
void recursive_newton_euler(const ArticulationModel& model, const Eigen::VectorXd& q,
                            const Eigen::VectorXd& v, const Eigen::VectorXd& qdd,
                            ArticulationWorkspace& ws, Eigen::VectorXd& tau);

// C(q, q̇) q̇ + g(q): recursive_newton_euler with q̈ = 0.
void bias_forces(const ArticulationModel& model, const Eigen::VectorXd& q,
                 const Eigen::VectorXd& v, ArticulationWorkspace& ws, Eigen::VectorXd& tau);

}  // namespace rigidlab
