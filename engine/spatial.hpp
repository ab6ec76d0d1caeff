// Spatial (6-D) vector algebra for articulated bodies, in the notation of R. Featherstone,
// "Rigid Body Dynamics Algorithms" (Springer 2008), chapter 2 — the algebra behind document
// 000 "Featherstone's Algorithm", whose velocities v_i, bias forces p_i and inertias I_i are
// spatial quantities.
//
// Plücker coordinates in a frame with origin O (RBDA 2.3-2.4, angular part first):
//   motion vector  m = [ω; v_O]  — angular velocity and the velocity of the body point that is
//                                  passing through O at this instant (m/s, rad/s);
//   force vector   f = [n_O; f]  — moment about O and resultant force (N·m, N).
// The scalar product m·f is power (W). Both are Vec6 here; the function names say which kind
// an argument is (crm for motion, crf for force).
//
// A Plücker transform B_X_A (RBDA 2.8) changes coordinates of a motion vector from frame A to
// frame B: with E the rotation taking A coordinates to B coordinates and r the position of B's
// origin expressed in A,
//   B_X_A = [ E      0 ]        B_X_A* = [ E   −E r̂ ]   (for forces)
//           [ −E r̂   E ]                 [ 0    E   ]
// Every type is fixed-size with Eigen::DontAlign, so values may be stored in std::vector and in
// Lua userdata (only 8-byte aligned) without alignment requirements.
#pragma once

#include <Eigen/Core>

#include "engine/math.hpp"

namespace rigidlab {

using Vec6 = Eigen::Matrix<double, 6, 1, Eigen::DontAlign>;
using Mat6 = Eigen::Matrix<double, 6, 6, Eigen::DontAlign>;

// [top; bottom]: spatial(ω, v) for a motion vector, spatial(n, f) for a force.
inline Vec6 spatial(const Vec3& top, const Vec3& bottom) {
  Vec6 s;
  s << top, bottom;
  return s;
}
inline Vec3 top(const Vec6& s) { return s.head<3>(); }     // ω of a motion, n of a force
inline Vec3 bottom(const Vec6& s) { return s.tail<3>(); }  // v of a motion, f of a force

// The spatial cross products (RBDA 2.9, eqs. 2.31-2.33). For motion vectors m1 = [ω; v]:
//   m1 ×  m2 = [ω × ω2;  ω × v2 + v × ω2]              (crm: the derivative of a moving motion)
//   m1 ×* f  = [ω × n + v × f;  ω × f]                 (crf = −crmᵀ: the derivative of a force)
inline Vec6 crm(const Vec6& m1, const Vec6& m2) {
  const Vec3 w = top(m1), v = bottom(m1);
  return spatial(w.cross(top(m2)), w.cross(bottom(m2)) + v.cross(top(m2)));
}
inline Vec6 crf(const Vec6& m, const Vec6& f) {
  const Vec3 w = top(m), v = bottom(m);
  return spatial(w.cross(top(f)) + v.cross(bottom(f)), w.cross(bottom(f)));
}
// The 6x6 matrices of the two operators: crm_matrix(m) * x == crm(m, x).
Mat6 crm_matrix(const Vec6& m);
Mat6 crf_matrix(const Vec6& m);

// B_X_A as the pair (E, r) of RBDA 2.8; the identity by default.
struct PluckerTransform {
  Mat3 E = Mat3::Identity();  // rotation: A coordinates to B coordinates
  Vec3 r = Vec3::Zero();      // B's origin relative to A's, in A coordinates (m)

  // B_X_A m = [E ω; E (v − r × ω)]
  Vec6 apply_motion(const Vec6& m) const {
    const Vec3 w = top(m);
    return spatial(E * w, E * (bottom(m) - r.cross(w)));
  }
  // B_X_A* f = [E (n − r × f); E f]
  Vec6 apply_force(const Vec6& f) const {
    const Vec3 force = bottom(f);
    return spatial(E * (top(f) - r.cross(force)), E * force);
  }
  // A_X_B m = (B_X_A)⁻¹ m = [Eᵀ ω; Eᵀ v + r × Eᵀ ω]: a motion back from B to A.
  Vec6 inverse_motion(const Vec6& m) const {
    const Vec3 w = E.transpose() * top(m);
    return spatial(w, E.transpose() * bottom(m) + r.cross(w));
  }
  // A_X_B* f = (B_X_A)ᵀ f = [Eᵀ n + r × Eᵀ f; Eᵀ f]: a force back from B to A (RBDA 2.25).
  Vec6 transpose_force(const Vec6& f) const {
    const Vec3 force = E.transpose() * bottom(f);
    return spatial(E.transpose() * top(f) + r.cross(force), force);
  }
  // The 6x6 motion transform B_X_A.
  Mat6 matrix() const;
  // C_X_A = C_X_B * B_X_A (this = C_X_B).
  PluckerTransform operator*(const PluckerTransform& b_x_a) const {
    return {E * b_x_a.E, b_x_a.r + b_x_a.E.transpose() * r};
  }
  // A_X_B.
  PluckerTransform inverse() const { return {E.transpose(), -(E * r)}; }
};

// Featherstone's rot(E) and xlt(r) (RBDA 2.8): a pure rotation, a pure translation.
inline PluckerTransform plucker_rotation(const Mat3& E) { return {E, Vec3::Zero()}; }
inline PluckerTransform plucker_translation(const Vec3& r) { return {Mat3::Identity(), r}; }

// The spatial inertia about the frame origin of a rigid body of mass m (kg) with its COM at c
// (m) and rotational inertia I_c (kg·m²) about the COM, all in that frame (RBDA eq. 2.63):
//   I = [ I_c + m ĉ ĉᵀ   m ĉ ]
//       [ m ĉᵀ           m 1 ]
Mat6 rigid_body_inertia(double mass, const Vec3& com, const Mat3& inertia_about_com);

// An inertia (rigid or articulated) of frame B expressed in frame A: B_X_Aᵀ I B_X_A
// (RBDA eq. 2.66, I_A = A_X_B* I_B B_X_A). Used by ABA and CRBA to add a child's inertia to
// its parent's.
Mat6 inertia_to_parent(const PluckerTransform& child_x_parent, const Mat6& inertia);

// The unit rotation of `angle` rad about the unit `axis`, as the coordinate transform E of a
// frame turned by that rotation (E = R(axis, angle)ᵀ; RBDA's rotx/roty/rotz for the axes).
Mat3 rotation_coordinates(const Vec3& axis, double angle);

}  // namespace rigidlab
