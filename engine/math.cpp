#include "engine/math.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace rigidlab {

SymmetricEigen symmetric_eigen(const Mat3& symmetric) {
  // The iterative solver (not computeDirect) keeps A·V = V·D to ~1e-15 relative even for
  // nearly repeated eigenvalues, which principal moments of symmetric shapes often are.
  Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric, Eigen::ComputeEigenvectors);
  SymmetricEigen result;
  result.values = solver.eigenvalues();  // ascending
  result.axes = solver.eigenvectors();
  for (int j = 0; j < 3; ++j) {
    Eigen::Index largest = 0;
    result.axes.col(j).cwiseAbs().maxCoeff(&largest);
    if (result.axes(largest, j) < 0.0) result.axes.col(j) *= -1.0;
  }
  if (result.axes.determinant() < 0.0) result.axes.col(2) *= -1.0;
  return result;
}

namespace {

// The slow paths: divide by the largest |component| first, so the squares are of numbers in
// [0, 1] with at least one equal to 1.
template <class V>
double norm_by_largest(const V& v) {
  const double scale = v.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return scale;  // 0, inf or NaN as they are
  return scale * (v / scale).norm();
}

template <class V>
V unit_by_largest(const V& v) {
  const V scaled = v / v.cwiseAbs().maxCoeff();  // largest |component| exactly 1
  return scaled / scaled.norm();
}

}  // namespace

namespace detail {
double rescaled_norm(const Vec3& v) { return norm_by_largest(v); }
double rescaled_norm(const Quat& q) { return norm_by_largest(Eigen::Vector4d(q.coeffs())); }
Vec3 rescaled_unit(const Vec3& v) { return unit_by_largest(v); }
Quat rescaled_unit(const Quat& q) { return Quat(unit_by_largest(Eigen::Vector4d(q.coeffs()))); }
}  // namespace detail

Quat quat_from_axis_angle(const Vec3& axis, double angle) {
  if (!is_finite(axis) || is_zero(axis))
    throw std::invalid_argument("axis must be a finite non-zero vector");
  if (!std::isfinite(angle)) throw std::invalid_argument("angle must be finite");
  const double half = 0.5 * angle;
  const Vec3 v = unit(axis) * std::sin(half);
  return Quat(std::cos(half), v.x(), v.y(), v.z());
}

void quat_to_axis_angle(const Quat& q_in, Vec3& axis, double& angle) {
  Quat q = unit(q_in);
  if (q.w() < 0.0) q.coeffs() *= -1.0;  // same rotation, angle in [0, pi]
  const double s = q.vec().norm();
  angle = 2.0 * std::atan2(s, q.w());
  axis = s > 0.0 ? Vec3(q.vec() / s) : Vec3::UnitX();
}

double asymmetry(const Mat3& m) { return (m - m.transpose()).cwiseAbs().maxCoeff(); }

}  // namespace rigidlab
