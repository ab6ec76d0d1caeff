// Math helpers shared by the whole engine: the vector, matrix and quaternion types, the hat
// operator, symmetric eigen-decomposition and finiteness checks.
//
// Every type is plain doubles with no alignment requirement (Vector3d and Matrix3d are not
// vectorised by Eigen; the quaternion is declared DontAlign), so values can live anywhere,
// including inside Lua userdata, which is only 8-byte aligned.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace rigidlab {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaternion<double, Eigen::DontAlign>;

// x with A x = b for an invertible 3x3 A, by Cramer's rule written with the columns a1, a2,
// a3 of A: x = (b·(a2×a3), b·(a3×a1), b·(a1×a2)) / det A, det A = a1·(a2×a3). Cheaper than
// forming A⁻¹ and as accurate for the well-conditioned systems of the integrators.
inline Vec3 solve3(const Mat3& a, const Vec3& b) {
  const Vec3 c23 = a.col(1).cross(a.col(2));
  const Vec3 c31 = a.col(2).cross(a.col(0));
  const Vec3 c12 = a.col(0).cross(a.col(1));
  return Vec3(b.dot(c23), b.dot(c31), b.dot(c12)) / a.col(0).dot(c23);
}

// The hat operator: skew(a) * b == a.cross(b). Inline: the integrators' body loops use it.
inline Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(),
       a.z(), 0.0, -a.x(),
       -a.y(), a.x(), 0.0;
  return m;
}

// Eigen-decomposition of a symmetric matrix: values ascending, axes the matching unit
// eigenvectors as columns, right-handed (det = +1). Each axis is given the sign that makes its
// largest-magnitude component positive (the third then flips if needed for det = +1), so the
// result is the same for the same input.
struct SymmetricEigen {
  Vec3 values;
  Mat3 axes;
};
SymmetricEigen symmetric_eigen(const Mat3& symmetric);
// The symmetric part ½(M + Mᵀ), halved before adding so that it is finite for every finite M:
// M + Mᵀ overflows for entries near the largest double (mat3.diag(1e308, 1, 1) gave NaN).
inline Mat3 symmetric_part(const Mat3& m) { return 0.5 * m + 0.5 * m.transpose(); }

// Euclidean length and direction without overflow or underflow in the squares: the plain
// v / sqrt(v·v) turns (1e300, 1e300, 0) into (0, 0, 0) (v·v overflows to inf) and
// (1e-320, 0, 0) into NaN (v·v underflows to 0). When v·v is not a comfortable normal number
// these divide by the largest |component| first, as LAPACK's dnrm2 and Eigen's stableNorm do
// (Blue, "A Portable Fortran Program to Find the Euclidean Norm of a Vector", ACM TOMS 4(1),
// 1978); otherwise they compute exactly what Eigen's norm() and normalized() compute.
// Every normalisation in the engine and the bindings goes through these. Inline, with the
// rescaling out of line: the integrators normalise every body's quaternion at every stage.
namespace detail {
// Sums of squares in this range are computed without harm (well inside DBL_MIN .. DBL_MAX, so
// no component's square overflowed and the ones that underflowed do not matter).
inline bool safe_squares(double squares) { return squares >= 1e-280 && squares <= 1e280; }
double rescaled_norm(const Vec3& v);
double rescaled_norm(const Quat& q);
Vec3 rescaled_unit(const Vec3& v);
Quat rescaled_unit(const Quat& q);
}  // namespace detail

inline double stable_norm(const Vec3& v) {
  const double squares = v.squaredNorm();
  return detail::safe_squares(squares) ? std::sqrt(squares) : detail::rescaled_norm(v);
}
inline double stable_norm(const Quat& q) {  // of the four coefficients
  const double squares = q.squaredNorm();
  return detail::safe_squares(squares) ? std::sqrt(squares) : detail::rescaled_norm(q);
}
// v / |v|. v must be finite and non-zero (test with is_finite and is_zero first); otherwise
// the result is not finite.
inline Vec3 unit(const Vec3& v) {
  const double squares = v.squaredNorm();
  return detail::safe_squares(squares) ? Vec3(v / std::sqrt(squares)) : detail::rescaled_unit(v);
}
inline Quat unit(const Quat& q) {
  const double squares = q.squaredNorm();
  return detail::safe_squares(squares) ? Quat(q.coeffs() / std::sqrt(squares))
                                       : detail::rescaled_unit(q);
}

// Rotation of `angle` radians about `axis` (any non-zero length). Throws std::invalid_argument
// for a zero or non-finite axis.
Quat quat_from_axis_angle(const Vec3& axis, double angle);

// The axis (unit) and angle in [0, pi] of a rotation quaternion (normalised first). For the
// identity the axis is +x and the angle 0.
void quat_to_axis_angle(const Quat& q, Vec3& axis, double& angle);

// Inline: the bindings call these on every arithmetic result. x - x is 0 for finite x and NaN
// otherwise, so one comparison tests a whole vector without branches.
inline bool is_finite(double x) { return x - x == 0.0; }
inline bool is_finite(const Vec3& v) { return (v - v).squaredNorm() == 0.0; }
inline bool is_finite(const Mat3& m) { return (m - m).squaredNorm() == 0.0; }
inline bool is_finite(const Quat& q) { return (q.coeffs() - q.coeffs()).squaredNorm() == 0.0; }

// Exactly zero (every component 0): a vector of any tiny length, even 1e-320, is non-zero.
inline bool is_zero(const Vec3& v) { return (v.array() == 0.0).all(); }
inline bool is_zero(const Quat& q) { return (q.coeffs().array() == 0.0).all(); }

// Largest |a_ij - a_ji| over the off-diagonal pairs: 0 for an exactly symmetric matrix.
double asymmetry(const Mat3& m);

}  // namespace rigidlab
