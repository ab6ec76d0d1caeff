// When two moving shapes first touch within a step: conservative advancement (B. Mirtich,
// "Impulse-based Dynamic Simulation of Rigid Body Systems", PhD thesis, Berkeley 1996, 3.4;
// E. Catto, "Continuous Collision", GDC 2013). Each body moves with constant velocity v and
// angular velocity ω (world) over the step. From t = 0, with d a lower bound on the distance
// at t (engine/narrow_phase.hpp separation) and s a bound on how fast it can shrink,
//   s = |v_b − v_a| + |ω_a| R_a + |ω_b| R_b   (R the bounding radius about the centre),
// the shapes cannot touch before t + d/s, so t advances by d/s until d is within the
// tolerance (a touch) or t passes the end of the step (a miss). Used by the contact solver to
// keep only the speculative contacts of bodies that really meet in the step: the contact of a
// body flying past a corner is then no contact at all (no "ghost" hit).
#pragma once

#include "engine/body.hpp"
#include "engine/narrow_phase.hpp"
#include "engine/plane.hpp"

namespace rigidlab {

// How a shape moves during a step: constant velocity and angular velocity (world, m/s, rad/s).
struct Motion {
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
};

// The pose after time t (s): translated by v t, turned by the angle |ω| t about ω.
Pose advance(const Pose& pose, const Motion& motion, double t);

// The first time in [0, dt] at which the shapes are within `tolerance` (m) of touching, or a
// negative number when they do not come that close in the step. 0 when they already do.
// After `max_iterations` advances without deciding, the time reached is returned (a possible
// touch: the caller then looks at the shapes there).
double time_of_impact(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                      const Pose& pose_b, const Motion& motion_b, double dt, double tolerance);
double time_of_impact(const Shape& shape, const Pose& pose, const Motion& motion,
                      const Plane& plane, double dt, double tolerance);

}  // namespace rigidlab
