#include "engine/joint_blocks.hpp"

#include <algorithm>
#include <cmath>

namespace rigidlab {
namespace {

// m v with the products written out (Eigen's 3 x 3 product is an out-of-line call at -O2, a
// tenth of the sweep's time in bench/joint_bench.cpp's profile).
inline Vec3 times(const Mat3& m, const Vec3& v) {
  return Vec3(m(0, 0) * v.x() + m(0, 1) * v.y() + m(0, 2) * v.z(),
              m(1, 0) * v.x() + m(1, 1) * v.y() + m(1, 2) * v.z(),
              m(2, 0) * v.x() + m(2, 1) * v.y() + m(2, 2) * v.z());
}

// K⁻¹ of a block of S rows as its packed lower triangle (row i: entries 0..i), or false when K
// is not safely invertible: K is symmetric positive semi-definite, and a Cholesky pivot far
// below the largest diagonal entry means two rows ask nearly the same of the bodies (or neither
// can move along one). K = L Lᵀ, then K⁻¹ = L⁻ᵀ L⁻¹ with L⁻¹ by forward substitution: a few
// hundred flops, where Eigen's LLT::solve of the identity goes through its general
// triangular-matrix kernels (a tenth of a 100 x 100 joint grid's step).
template <int S>
bool packed_inverse(const Jacobian* rows, const SolverBody& a, const SolverBody& b, double* out) {
  Vec3 weighted_a[S], weighted_b[S];
  for (int j = 0; j < S; ++j) {
    weighted_a[j] = times(a.inverse_inertia, rows[j].angular_a);
    weighted_b[j] = times(b.inverse_inertia, rows[j].angular_b);
  }
  double l[S][S] = {};  // K's lower triangle, then L's
  double largest = 0.0;
  for (int i = 0; i < S; ++i) {
    for (int j = 0; j <= i; ++j)
      l[i][j] = coupling_weighted(rows[i], rows[j], a.inverse_mass, weighted_a[j], b.inverse_mass,
                                  weighted_b[j]);
    largest = std::max(largest, l[i][i]);
  }
  for (int j = 0; j < S; ++j) {
    double pivot = l[j][j];
    for (int k = 0; k < j; ++k) pivot -= l[j][k] * l[j][k];
    if (!(pivot > 1e-12 * largest)) return false;  // L_jj² against the largest diagonal entry
    l[j][j] = std::sqrt(pivot);
    for (int i = j + 1; i < S; ++i) {
      double sum = l[i][j];
      for (int k = 0; k < j; ++k) sum -= l[i][k] * l[j][k];
      l[i][j] = sum / l[j][j];
    }
  }
  double inverse_l[S][S] = {};  // L⁻¹, lower triangular
  for (int j = 0; j < S; ++j) {
    inverse_l[j][j] = 1.0 / l[j][j];
    for (int i = j + 1; i < S; ++i) {
      double sum = 0.0;
      for (int k = j; k < i; ++k) sum -= l[i][k] * inverse_l[k][j];
      inverse_l[i][j] = sum / l[i][i];
    }
  }
  for (int i = 0; i < S; ++i)  // (L⁻ᵀ L⁻¹)_ij = Σ_{k >= i} L⁻¹_ki L⁻¹_kj, j <= i
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (int k = i; k < S; ++k) sum += inverse_l[k][i] * inverse_l[k][j];
      *out++ = sum;
    }
  return true;
}

bool packed_inverse(const Jacobian* rows, int size, const SolverBody& a, const SolverBody& b,
                    double* out) {
  switch (size) {
    case 2: return packed_inverse<2>(rows, a, b, out);
    case 3: return packed_inverse<3>(rows, a, b, out);
    case 4: return packed_inverse<4>(rows, a, b, out);
    case 5: return packed_inverse<5>(rows, a, b, out);
    case 6: return packed_inverse<6>(rows, a, b, out);
  }
  return false;
}

// Whether rows 0 to 2 are point_jacobian(e_k, r_a, r_b) for the world axes e_k (compared
// exactly: r × e_k only copies and negates components of r); r_a and r_b if so.
bool point_rows(const Jacobian* rows, Vec3& r_a, Vec3& r_b) {
  r_a = Vec3(rows[1].angular_a.z(), -rows[0].angular_a.z(), rows[0].angular_a.y());
  r_b = Vec3(rows[1].angular_b.z(), -rows[0].angular_b.z(), rows[0].angular_b.y());
  for (int k = 0; k < 3; ++k) {
    const Jacobian expected = point_jacobian(Vec3::Unit(k), r_a, r_b);
    if (rows[k].linear != expected.linear || rows[k].angular_a != expected.angular_a ||
        rows[k].angular_b != expected.angular_b)
      return false;
  }
  return true;
}

bool angular_row(const Jacobian& row) {
  return row.linear == Vec3::Zero() && row.angular_a == row.angular_b;
}

void put(std::vector<double>& data, const Vec3& v) { data.insert(data.end(), {v.x(), v.y(), v.z()}); }
Vec3 get(const double* p) { return Vec3(p[0], p[1], p[2]); }

}  // namespace

void JointBlocks::clear() {
  heads_.clear();
  data_.clear();
  bias_.clear();
  push_bias_.clear();
  impulse_.clear();
  push_impulse_.clear();
}

std::uint32_t JointBlocks::add(std::uint32_t a, std::uint32_t b, const Jacobian* rows, int size,
                               const SolverBody& body_a, const SolverBody& body_b,
                               const double* bias, const double* push_bias, const Softness& soft) {
  double inverse[max_size * (max_size + 1) / 2];
  if (size < 2 || size > max_size || !packed_inverse(rows, size, body_a, body_b, inverse))
    return none;
  Head h{a, b, static_cast<std::uint32_t>(data_.size()), static_cast<std::uint32_t>(bias_.size()),
         static_cast<std::uint8_t>(size), 0, 0};
  data_.insert(data_.end(), {soft.mass_scale, soft.impulse_scale});
  int i = 0;
  Vec3 r_a, r_b;
  if (size >= 3 && point_rows(rows, r_a, r_b)) {
    h.point = 1;
    put(data_, r_a);
    put(data_, r_b);
    i = 3;
  }
  for (; i < size; ++i) {
    if (angular_row(rows[i])) {
      h.angular |= static_cast<std::uint8_t>(1u << i);
      put(data_, rows[i].angular_a);
    } else {
      put(data_, rows[i].linear);
      put(data_, rows[i].angular_a);
      put(data_, rows[i].angular_b);
    }
  }
  data_.insert(data_.end(), inverse, inverse + size * (size + 1) / 2);
  bias_.insert(bias_.end(), bias, bias + size);
  push_bias_.insert(push_bias_.end(), push_bias, push_bias + size);
  impulse_.resize(impulse_.size() + static_cast<std::size_t>(size), 0.0);
  push_impulse_.resize(push_impulse_.size() + static_cast<std::size_t>(size), 0.0);
  heads_.push_back(h);
  return static_cast<std::uint32_t>(heads_.size() - 1);
}

// The size is a template argument so that the row loops unroll (a third of the sweep's time).
template <int size>
double JointBlocks::solve_sized(const Head& h, SolverBody* set, bool push) {
  SolverBody& a = set[h.a];
  SolverBody& b = set[h.b];
  const double* d = &data_[h.data];
  const double mass_scale = push ? d[0] : 1.0;
  const double impulse_scale = push ? d[1] : 0.0;
  d += 2;
  const double* bias = (push ? push_bias_ : bias_).data() + h.row;
  double* lambda = (push ? push_impulse_ : impulse_).data() + h.row;

  // J v, row by row in the form stored.
  double v[size];
  const double* j = d;
  int i = 0;
  if (size >= 3 && h.point) {
    const Vec3 dv = b.velocity + b.angular_velocity.cross(get(j + 3)) - a.velocity -
                    a.angular_velocity.cross(get(j));
    v[0] = dv.x(), v[1] = dv.y(), v[2] = dv.z();
    i = 3, j += 6;
  }
  for (; i < size; ++i) {
    if (h.angular >> i & 1u) {
      v[i] = get(j).dot(b.angular_velocity - a.angular_velocity);
      j += 3;
    } else {
      v[i] = get(j).dot(b.velocity - a.velocity) + get(j + 6).dot(b.angular_velocity) -
             get(j + 3).dot(a.angular_velocity);
      j += 9;
    }
  }
  const double* inverse = j;  // packed lower triangle

  // Δλ = −K⁻¹ (mass_scale J v + bias) − impulse_scale λ.
  double largest = 0.0, rhs[size], change[size];
  for (i = 0; i < size; ++i) {
    largest = std::max(largest, std::abs(v[i] + bias[i]));
    rhs[i] = mass_scale * v[i] + bias[i];
  }
  for (i = 0; i < size; ++i) {
    const double* row = inverse + i * (i + 1) / 2;
    double sum = 0.0;
    for (int c = 0; c <= i; ++c) sum += row[c] * rhs[c];
    for (int c = i + 1; c < size; ++c) sum += inverse[c * (c + 1) / 2 + i] * rhs[c];
    change[i] = -sum - impulse_scale * lambda[i];
    lambda[i] += change[i];
  }

  // Δv = W Jᵀ Δλ: the block's linear impulse and the angular impulses on a and b, then W.
  Vec3 p = Vec3::Zero(), l_a = Vec3::Zero(), l_b = Vec3::Zero();
  j = d, i = 0;
  if (size >= 3 && h.point) {
    const Vec3 q(change[0], change[1], change[2]);
    p = q;
    l_a = get(j).cross(q);
    l_b = get(j + 3).cross(q);
    i = 3, j += 6;
  }
  for (; i < size; ++i) {
    if (h.angular >> i & 1u) {
      const Vec3 axis = change[i] * get(j);
      l_a += axis, l_b += axis;
      j += 3;
    } else {
      p += change[i] * get(j);
      l_a += change[i] * get(j + 3);
      l_b += change[i] * get(j + 6);
      j += 9;
    }
  }
  a.velocity -= a.inverse_mass * p;
  a.angular_velocity -= times(a.inverse_inertia, l_a);
  b.velocity += b.inverse_mass * p;
  b.angular_velocity += times(b.inverse_inertia, l_b);
  return largest;
}

double JointBlocks::solve(std::uint32_t k, SolverBody* set, bool push) {
  const Head& h = heads_[k];
  switch (h.size) {
    case 2: return solve_sized<2>(h, set, push);
    case 3: return solve_sized<3>(h, set, push);
    case 4: return solve_sized<4>(h, set, push);
    case 5: return solve_sized<5>(h, set, push);
    default: return solve_sized<6>(h, set, push);
  }
}


}  // namespace rigidlab
