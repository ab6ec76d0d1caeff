// Force elements of a world: uniform gravity, damped springs between two bodies or a body and
// a world anchor, and linear drag. Each adds to the force and torque accumulators of the bodies
// it acts on (apply_force in engine/body.hpp), so it works at any integrator stage.
//
// Sources: /work/shared/seeds/000_* "Particle system" (forces: constant like gravity, position
// dependent, velocity dependent like drag; sum them, then integrate); 001_* "Springs" (Hooke's
// law F = k x between a point of the body, given in body coordinates, and a target point).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "engine/body.hpp"
#include "engine/body_store.hpp"

namespace rigidlab {


// A Hooke spring with a damper along its line, from a point of body a to a point of body b or
// to a fixed world anchor (b == no_body). With d = p_b − p_a, L = |d|, u = d/L and the relative
// velocity of the two points w = v_b(p_b) − v_a(p_a), the force on a is
//   F_a = (k (L − L₀) + c (w·u)) u,   F_b = −F_a,
// applied at the attachment points (so it also gives torques). This is the damped spring of
// Baraff & Witkin, "Physically Based Modeling" (SIGGRAPH 2001), "Particle System Dynamics" 4.3;
// with L₀ = 0 its elastic part is 001_*'s F = k x. When L = 0 the direction is undefined and
// the spring exerts no force (with L₀ = 0 the elastic force is k d = 0 there anyway).
struct Spring {
  BodyId a;                         // body a (engine/body_store.hpp)
  BodyId b;                         // body b, or no_body_id for a world anchor
  Vec3 a_point = Vec3::Zero();      // m, body-a coordinates (relative to its COM)
  Vec3 b_point = Vec3::Zero();      // m, body-b coordinates
  Vec3 anchor = Vec3::Zero();       // m, world, used when b == no_body
  double stiffness = 0.0;           // k, N/m, >= 0
  double damping = 0.0;             // c, N s/m, >= 0
  double rest_length = 0.0;         // L₀, m, >= 0
};

// Linear drag on one body at its COM: F = −linear · v, τ = −angular · ω (a velocity-dependent
// force, 000_* "Particle system"). Coefficients in N s/m and N m s, >= 0.
struct Drag {
  BodyId body;
  double linear = 0.0;
  double angular = 0.0;
};

// Empty when the coefficients are admissible (finite, stiffness/damping/rest length >= 0,
// points finite), otherwise the rule broken: "stiffness must be >= 0, got -1".
std::string spring_problem(const Spring& s);
std::string drag_problem(const Drag& d);

// The functions below take the bodies the spring's ids name (the world resolves them once per
// step): `a`, and `b` or nullptr for a world anchor.
// World positions of the two ends of the spring (m).
Vec3 spring_end_a(const Body& a, const Spring& s);
Vec3 spring_end_b(const Body* b, const Spring& s);
// The force on body a (N, world); the force on b is its opposite.
Vec3 spring_force(const Body& a, const Body* b, const Spring& s);
// Adds the spring force to both bodies at their attachment points.
void apply_spring(Body& a, Body* b, const Spring& s);
// Elastic energy ½ k (L − L₀)² (J).
double spring_potential_energy(const Body& a, const Body* b, const Spring& s);

void apply_drag(Body& body, const Drag& d);

// Weight m g (N) of a dynamic body, zero for a static one; g in m/s².
inline Vec3 gravity_force(const Body& b, const Vec3& gravity) {
  return is_static(b) ? Vec3::Zero() : Vec3(b.mass * gravity);
}
// Potential energy in uniform gravity, −m g·x (J), zero at the world origin; 0 for a static body.
inline double gravity_potential_energy(const Body& b, const Vec3& gravity) {
  return is_static(b) ? 0.0 : -b.mass * gravity.dot(b.position);
}

}  // namespace rigidlab
