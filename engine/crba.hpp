// The joint-space mass matrix M(q) by the composite-rigid-body algorithm (CRBA): R.
// Featherstone, "Rigid Body Dynamics Algorithms" (2008), section 6.2 and Table 6.2. The
// kinetic energy is T = ½ q̇ᵀ M q̇; M is symmetric positive definite for a model whose every
// joint moves some mass.
//
// Inward, each link's composite inertia I^c_i (its subtree as one rigid body) is accumulated;
// then for each joint F = I^c_i S_i is the force that a unit acceleration of that joint alone
// needs, and carried towards the root it meets every ancestor joint j: M_ij = S_jᵀ F.
// O(n d) for depth d (O(n²) for a chain); solving M q̈ = τ − C q̇ − g adds O(n³), which is why
// the forward dynamics use the articulated-body algorithm instead (engine/aba.hpp) and this is
// for display, checking and the benchmark.
#pragma once

#include <Eigen/Core>

#include "engine/articulation_kinematics.hpp"

namespace rigidlab {

// M (nv x nv) at q (length nq, checked by the caller). A free base's block pairs with its
// world velocity and angular velocity.
void composite_rigid_body(const ArticulationModel& model, const Eigen::VectorXd& q,
                          ArticulationWorkspace& ws, Eigen::MatrixXd& mass_matrix);

}  // namespace rigidlab
