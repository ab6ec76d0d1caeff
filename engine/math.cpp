#include "engine/math.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace rigidlab {

Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(),
       a.z(), 0.0, -a.x(),
       -a.y(), a.x(), 0.0;
  return m;
}

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

Quat quat_from_axis_angle(const Vec3& axis, double angle) {
  const double length = axis.norm();
  if (!is_finite(axis) || !(length > 0.0))
    throw std::invalid_argument("axis must be a finite non-zero vector");
  if (!std::isfinite(angle)) throw std::invalid_argument("angle must be finite");
  const double half = 0.5 * angle;
  const Vec3 v = axis / length * std::sin(half);
  return Quat(std::cos(half), v.x(), v.y(), v.z());
}

void quat_to_axis_angle(const Quat& q_in, Vec3& axis, double& angle) {
  Quat q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() *= -1.0;  // same rotation, angle in [0, pi]
  const double s = q.vec().norm();
  angle = 2.0 * std::atan2(s, q.w());
  axis = s > 0.0 ? Vec3(q.vec() / s) : Vec3::UnitX();
}

double asymmetry(const Mat3& m) { return (m - m.transpose()).cwiseAbs().maxCoeff(); }

}  // namespace rigidlab
