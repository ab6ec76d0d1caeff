// Forward dynamics by the articulated-body algorithm (ABA): the joint accelerations q̈ of an
// articulation at state (q, q̇) under generalised forces τ and gravity, in O(n) — document 000
// "Featherstone's Algorithm" (three loops over the links; "f + F_ext = I a + p": the force on
// a subtree is linear in its acceleration, through its articulated inertia I and bias force
// p) and R. Featherstone, "Rigid Body Dynamics Algorithms" (2008), section 7.3 and Table 7.1.
// No mass matrix is formed and nothing is solved except a 6x6 system for a free base.
#pragma once

#include <Eigen/Core>

#include "engine/articulation_kinematics.hpp"

namespace rigidlab {

// q̈ (length nv) for q (nq), q̇ (nv) and τ (nv): τ's entries are joint torques (N·m) and
// forces (N); a free base's first six are the world force and torque on it. Sizes must match
// the model (the caller checks). Leaves every loop's quantities in `ws` (v, c, p, IA, pA, U,
// D, u, a) for display. Throws std::domain_error when the dynamics are singular: a joint whose
// subtree has no inertia about its axis (a massless last link), or a free base that carries
// no mass; `qdd` is then unspecified.
void articulated_body_algorithm(const ArticulationModel& model, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v, const Eigen::VectorXd& tau,
                                ArticulationWorkspace& ws, Eigen::VectorXd& qdd);

}  // namespace rigidlab
