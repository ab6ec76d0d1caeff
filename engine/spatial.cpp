#include "engine/spatial.hpp"

namespace rigidlab {

// crm(m) = [ ω̂  0 ]      crf(m) = −crm(m)ᵀ = [ ω̂  v̂ ]      (RBDA eqs. 2.31, 2.32)
//          [ v̂  ω̂ ]                          [ 0   ω̂ ]
Mat6 crm_matrix(const Vec6& m) {
  Mat6 x = Mat6::Zero();
  x.topLeftCorner<3, 3>() = skew(top(m));
  x.bottomLeftCorner<3, 3>() = skew(bottom(m));
  x.bottomRightCorner<3, 3>() = skew(top(m));
  return x;
}

Mat6 crf_matrix(const Vec6& m) { return -crm_matrix(m).transpose(); }

Mat6 PluckerTransform::matrix() const {
  Mat6 x = Mat6::Zero();
  x.topLeftCorner<3, 3>() = E;
  x.bottomLeftCorner<3, 3>() = -E * skew(r);
  x.bottomRightCorner<3, 3>() = E;
  return x;
}

Mat6 rigid_body_inertia(double mass, const Vec3& com, const Mat3& inertia_about_com) {
  const Mat3 c = skew(com);
  Mat6 inertia;
  inertia.topLeftCorner<3, 3>() = inertia_about_com + mass * c * c.transpose();
  inertia.topRightCorner<3, 3>() = mass * c;
  inertia.bottomLeftCorner<3, 3>() = mass * c.transpose();
  inertia.bottomRightCorner<3, 3>() = mass * Mat3::Identity();
  return inertia;
}

// Xᵀ I X by 3x3 blocks, X = [E 0; −E r̂ E]: with I = [A B; Bᵀ C] in B coordinates, first
// rotate, A' = EᵀAE, B' = EᵀBE, C' = EᵀCE, then shift the reference point by r:
//   [ A' + r̂ B'ᵀ − B' r̂ − r̂ C' r̂    B' + r̂ C' ]
//   [ (B' + r̂ C')ᵀ                  C'        ]
// (RBDA 2.66 written out; the shift is the parallel-axis theorem of the spatial inertia). About
// a third of the work of two dense 6x6 products, and exactly symmetric.
Mat6 inertia_to_parent(const PluckerTransform& child_x_parent, const Mat6& inertia) {
  const Mat3& E = child_x_parent.E;
  const Mat3 a = E.transpose() * inertia.topLeftCorner<3, 3>() * E;
  const Mat3 b = E.transpose() * inertia.topRightCorner<3, 3>() * E;
  const Mat3 c = E.transpose() * inertia.bottomRightCorner<3, 3>() * E;
  const Mat3 r = skew(child_x_parent.r);
  const Mat3 b_shifted = b + r * c;
  const Mat3 a_shifted = a + r * b.transpose() - b * r - r * c * r;
  Mat6 result;
  result.topLeftCorner<3, 3>() = 0.5 * (a_shifted + a_shifted.transpose());
  result.topRightCorner<3, 3>() = b_shifted;
  result.bottomLeftCorner<3, 3>() = b_shifted.transpose();
  result.bottomRightCorner<3, 3>() = 0.5 * (c + c.transpose());
  return result;
}

Mat3 rotation_coordinates(const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * Mat3::Identity() - s * skew(axis) + (1.0 - c) * axis * axis.transpose();
}

}  // namespace rigidlab
