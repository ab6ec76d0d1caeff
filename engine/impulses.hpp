// Collision impulses on their own: the 1-D impulse between two particles, the inverse mass
// matrix of a rigid body, the effective mass of a contact, and the resolution of one contact
// between two bodies (normal impulse with restitution, then Coulomb friction).
//
// Sources:
//   /work/shared/seeds/001_* "System Of Particles" (J = −2(v_b − v_a)/(m_a⁻¹ + m_b⁻¹), the
//     worked numbers J = 2 and J = 3.2), "Collisions" (the sphere on the floor: normal impulse,
//     then a friction impulse along the tangential relative velocity), Appendix C (the impulse
//     from the conservation laws, restitution e, inverse masses so that an infinite mass is
//     m⁻¹ = 0, the rotational denominator), Appendix D (the same impulse as a constraint:
//     λ = −J v / (J W Jᵀ) with the Jacobian J = [−n, −r_a × n, n, r_b × n]).
//   /work/shared/seeds/002_* "Inverse Mass Matrix" (M⁻¹ = (1/m) E − r̂₂ I⁻¹ r̂₁: the velocity
//     change at offset r₂ caused by an impulse at offset r₁), "Collisions".
//   /work/shared/seeds/003_* "Collision Response" (momentum conservation, the coefficient of
//     restitution (v₂' − v₁')·n = −ε (v₂ − v₁)·n, an immovable body).
//
// Conventions: world frame; offsets r are from the body's centre of mass (m); the contact
// normal points from body a to body b; the impulse J n acts on b and −J n on a (N s).
// Immovable bodies (inverse mass 0, inverse inertia 0) are allowed everywhere.
#pragma once

#include <string>

#include "engine/body.hpp"

namespace rigidlab {

// ---- one dimension -------------------------------------------------------------------------

struct Impulse1D {
  double impulse = 0.0;     // J, N s: b receives +J, a receives −J
  double velocity_a = 0.0;  // v_a' = v_a − J/m_a, m/s
  double velocity_b = 0.0;  // v_b' = v_b + J/m_b, m/s
};

// J = −(1 + e)(v_b − v_a)/(m_a⁻¹ + m_b⁻¹) (001_* "System Of Particles" and Appendix C), with b
// ahead of a on the axis. The formula is applied as written: when v_b > v_a (separating) J is
// negative. Inverse masses ≥ 0 (0 = immovable), finite, not both 0; e in [0, 1]. Throws
// std::invalid_argument otherwise, and when the impulse or a velocity overflows.
Impulse1D impulse_1d(double inverse_mass_a, double velocity_a, double inverse_mass_b,
                     double velocity_b, double restitution);

// ---- rigid bodies --------------------------------------------------------------------------

// 002_* "Inverse Mass Matrix": M⁻¹ = (1/m) E − r̂₂ I_world⁻¹ r̂₁ (1/kg). An impulse j applied at
// offset r1 changes the velocity of the material point at offset r2 by M⁻¹ j. Zero for an
// immovable body.
Mat3 inverse_mass_matrix(const Body& b, const Vec3& r1, const Vec3& r2);

// The inverse mass matrix of a contact at world point p between a and b: the change of the
// relative velocity v_b(p) − v_a(p) per unit impulse applied to b (and its opposite to a),
// K = M_a⁻¹(r_a, r_a) + M_b⁻¹(r_b, r_b) (1/kg).
Mat3 contact_inverse_mass(const Body& a, const Body& b, const Vec3& point);

// 001_* Appendix D: 1/(J W Jᵀ) with J = [−n, −r_a × n, n, r_b × n] and W the block-diagonal
// inverse mass of both bodies (kg): the mass the contact "feels" along the unit normal n
// (normalised here). J W Jᵀ = m_a⁻¹ + m_b⁻¹ + (r_a×n)·I_a⁻¹(r_a×n) + (r_b×n)·I_b⁻¹(r_b×n).
// Throws std::invalid_argument when both bodies are immovable (J W Jᵀ = 0), for a zero or
// non-finite normal ("normal ...") and when J W Jᵀ overflows ("point ... too far").
double effective_mass(const Body& a, const Body& b, const Vec3& point, const Vec3& normal);

struct Contact {
  Vec3 point = Vec3::Zero();   // m, world
  Vec3 normal = Vec3::UnitY(); // from a to b, any non-zero length (normalised)
  double restitution = 0.0;    // e in [0, 1]
  double friction = 0.0;       // Coulomb coefficient μ ≥ 0
};

struct ContactImpulse {
  double normal_impulse = 0.0;                // J ≥ 0, N s, along n on b
  Vec3 friction_impulse = Vec3::Zero();       // N s, tangential, on b (a gets the opposite)
};

// "" when the contact can be resolved between a and b, else what is wrong, starting with the
// name of the field or argument ("normal must not be zero", "restitution must be in [0, 1],
// got 2", "friction must be >= 0, got -1", "a and b are the same body", "both bodies are
// immovable").
std::string contact_problem(const Body& a, const Body& b, const Contact& contact);

// Resolves one contact (001_* Appendix C and "Collisions"; friction as an impulse with a
// sticking and a sliding case, R. M. Brach, "Rigid Body Collisions", J. Appl. Mech. 56, 1989;
// B. Mirtich, "Impulse-based Dynamic Simulation of Rigid Body Systems", PhD thesis, 1996).
// With v = v_b(p) − v_a(p), v_n = v·n and K = contact_inverse_mass (v' = v + K P for an
// impulse P on b, −P on a):
//  1. v_n ≥ 0: the bodies are separating or resting; nothing happens, the result is zero.
//  2. Compression (e = 0): the impulse that stops the contact point, P_s = −K⁻¹v (sticking),
//     if it lies in Coulomb's cone |P_t| ≤ μ P_n; otherwise the point where the segment from
//     the frictionless impulse P_f = −v_n/(n·K n) n to P_s leaves the cone (sliding at the
//     Coulomb limit |P_t| = μ P_n). Every point of that segment gives v_n' = 0, and the
//     energy, a convex function on it, is highest at P_f: the contact loses at least the
//     frictionless ½ v_n²/(n·K n).
//  3. Restitution: the further normal impulse that makes v_n' = −e v_n exactly (Newton's law,
//     003_* "Collision Response"), again moved from the frictionless one toward the impulse
//     that leaves the point sticking (v' = −e v_n n), as far as the cone allows and as long
//     as the kinetic energy does not increase: with e > 0 and a point whose normal and
//     tangential motions are coupled (n·K t ≠ 0), sticking after the rebound can need more
//     energy than the impact had (Kane's paradox, W. J. Stronge, Proc. R. Soc. A 431, 1990),
//     and then the contact leaves slipping.
// So v_n' = −e v_n, |friction| ≤ μ·(normal impulse), linear and angular momentum about any
// point are conserved (equal and opposite impulses at one point), the kinetic energy never
// increases (kept for e = 1, μ = 0), and a point that friction can stop (μ large) ends
// sticking when e = 0 or when n·K t = 0 (a sphere).
// Throws std::invalid_argument with contact_problem's message for a bad contact, and when the
// point is so far from the centres of mass that the impulse or the velocities overflow; the
// bodies are then unchanged.
ContactImpulse resolve_contact(Body& a, Body& b, const Contact& contact);

}  // namespace rigidlab
