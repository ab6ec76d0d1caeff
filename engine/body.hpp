// A rigid body as a plain value: mass properties, state (position and orientation of the
// centre of mass, linear and angular velocity), the force and torque accumulated for the next
// step, and a collision shape. Free functions compute the derived quantities.
//
// Frames: `inertia` and `inverse_inertia` are in the body frame, about the COM; everything
// else (position, velocity, angular_velocity, force, torque) is in the world frame. The
// orientation q maps body coordinates to world coordinates: x_world = position + q x_body.
//
// Source: /work/shared/seeds/002_* "Rigid Body Dynamics" (Rotenberg, CSE169): the rotated
// inertia I' = R I Rᵀ, angular momentum L = I ω, point velocity v + ω × r, torque r × f.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "engine/math.hpp"
#include "engine/plane.hpp"

namespace rigidlab {

enum class ShapeKind { none, sphere, box };

// The collision shape, centred on the COM and aligned with the body frame.
struct Shape {
  ShapeKind kind = ShapeKind::none;
  double radius = 0.0;                     // sphere, m
  Vec3 half_extents = Vec3::Zero();        // box, m (half of width, height, depth)
};

struct Body {
  double mass = 0.0;                       // kg; +inf for a static body
  double inverse_mass = 0.0;               // 1/kg; 0 for a static body
  Mat3 inertia = Mat3::Zero();             // kg m², body frame, about the COM
  Mat3 inverse_inertia = Mat3::Zero();     // 1/(kg m²), body frame; 0 for a static body
  Vec3 position = Vec3::Zero();            // m, COM in the world
  Quat orientation = Quat::Identity();     // unit, body -> world
  Vec3 velocity = Vec3::Zero();            // m/s, of the COM, world
  Vec3 angular_velocity = Vec3::Zero();    // rad/s, world
  Vec3 force = Vec3::Zero();               // N, world, accumulated until the next step
  Vec3 torque = Vec3::Zero();              // N m, world, about the COM, accumulated
  Shape shape;
  // Surface material for contacts (engine/plane.hpp: mixing rules and defaults).
  double restitution = default_restitution;  // e in [0, 1]
  double friction = default_friction;        // Coulomb μ >= 0
  // Sleep state, kept by a world with sleeping on (engine/islands.hpp): a sleeping body is at
  // rest and skipped by the step until its island wakes.
  bool sleeping = false;
  double sleep_time = 0.0;     // s the body has been slower than the sleep tolerances
  std::uint32_t island = 0;    // while sleeping: its island's label
};

// Why `mass` (kg) cannot be a dynamic body's mass, or empty: it must be finite, > 0, and not
// so small (below about 5.6e-309 kg, a subnormal) that 1/mass overflows. The message names no
// field ("must be > 0, got -1", "is too small: 1/mass overflows, got 1e-320"); callers prefix
// "mass " or "field 'mass' ".
std::string mass_problem(double mass);
// A dynamic body of `mass` (mass_problem empty) and body-frame `inertia` (inertia_tensor_problem
// with InertiaRules::body empty: symmetric positive definite with a finite inverse, satisfying
// the triangle inequalities). Throws std::invalid_argument naming the rule broken.
// Position zero, orientation identity, at rest.
Body make_body(double mass, const Mat3& inertia);
// An immovable body: mass +inf, inverse mass and inverse inertia 0 (impulses and forces do
// nothing to it). `inertia` is reported as +inf on the diagonal.
Body make_static_body();
// A solid sphere / box of uniform density (inertia from engine/inertia.hpp) with its shape.
Body make_sphere_body(double mass, double radius);
Body make_box_body(double mass, const Vec3& size);  // size = full width, height, depth (m)
// Makes an existing body static, keeping its state and shape (velocities set to zero).
void make_static(Body& b);

inline bool is_static(const Body& b) { return b.inverse_mass == 0.0; }

// The rotation matrix R of the orientation (body -> world).
inline Mat3 rotation(const Body& b) { return b.orientation.toRotationMatrix(); }
// R I Rᵀ: the inertia tensor in world axes, about the COM (kg m²). 002_* "Rotational Inertia".
Mat3 world_inertia(const Body& b);
// R I⁻¹ Rᵀ: its inverse (0 for a static body).
Mat3 inverse_world_inertia(const Body& b);

// World coordinates of a point given in body coordinates, and back (m).
inline Vec3 to_world(const Body& b, const Vec3& p_local) {
  return b.position + b.orientation * p_local;
}
inline Vec3 to_local(const Body& b, const Vec3& p_world) {
  return b.orientation.conjugate() * (p_world - b.position);
}
// Velocity of the material point at world position p: v + ω × (p − x) (m/s).
inline Vec3 point_velocity(const Body& b, const Vec3& p_world) {
  return b.velocity + b.angular_velocity.cross(p_world - b.position);
}

// Force f (N, world) at world point p: adds f to the force and (p − x) × f to the torque.
// Accumulated until the next step. A static body accumulates nothing.
void apply_force(Body& b, const Vec3& f, const Vec3& p_world);
void apply_force(Body& b, const Vec3& f);          // at the COM
void apply_torque(Body& b, const Vec3& torque);    // N m, world
// Impulse j (N s, world) at world point p: changes the velocities now,
// Δv = j/m, Δω = I_world⁻¹ ((p − x) × j). Nothing happens to a static body.
void apply_impulse(Body& b, const Vec3& j, const Vec3& p_world);
void apply_impulse(Body& b, const Vec3& j);        // at the COM
void apply_angular_impulse(Body& b, const Vec3& h);  // N m s, world: Δω = I_world⁻¹ h

// Momenta and energy. For a static body they are zero (it never moves).
inline Vec3 linear_momentum(const Body& b) {       // kg m/s
  return is_static(b) ? Vec3::Zero() : Vec3(b.mass * b.velocity);
}
Vec3 angular_momentum(const Body& b);              // kg m²/s, world, about the COM: I_world ω
double kinetic_energy(const Body& b);              // J: ½ m v² + ½ ω·I_world ω

}  // namespace rigidlab
