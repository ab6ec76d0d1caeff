// The contact constraints, part 6: a manifold's normal rows as one block — the block matrices
// (prepare_block), the block solve (solve_block) and the solve of a subset of its rows with
// bounds (solve_subset). See engine/contact_constraints.hpp ("The normal impulses of a manifold
// are solved as a block").
#include <algorithm>
#include <cmath>
#include <type_traits>

#include <Eigen/LU>

#include "engine/contact_constraints.hpp"
#include "engine/contact_helpers.hpp"

namespace rigidlab {

using namespace contact_detail;

namespace {

// m/s: below this a velocity error is rounding (a gap of 1e-14 m closed in a step of 1/60 s).
constexpr double velocity_rounding = 1e-12;

// f(std::integral_constant<Impulse, which>): the runtime `which` to the template's instance.
template <class Impulse, class F>
bool with_impulse(Impulse which, F&& f) {
  switch (which) {
    case Impulse::sweep: return f(std::integral_constant<Impulse, Impulse::sweep>{});
    case Impulse::round: return f(std::integral_constant<Impulse, Impulse::round>{});
    case Impulse::push: break;
  }
  return f(std::integral_constant<Impulse, Impulse::push>{});
}

}  // namespace

// ---- the block matrices ---------------------------------------------------------------------

namespace {

// The affine dependency of four points in the contact plane (coordinates x, y): the unit
// vector c with Σ cᵢ = 0 and Σ cᵢ (xᵢ, yᵢ) = 0, from the cofactors of [1; x; y]. Zero when the
// points are collinear (the dependency is then not one vector).
Eigen::Vector4d affine_dependency(const double (&x)[4], const double (&y)[4]) {
  auto minor = [&](int skip) {
    int c[3], n = 0;
    for (int i = 0; i < 4; ++i)
      if (i != skip) c[n++] = i;
    return (x[c[1]] - x[c[0]]) * (y[c[2]] - y[c[0]]) - (x[c[2]] - x[c[0]]) * (y[c[1]] - y[c[0]]);
  };
  Eigen::Vector4d c(minor(0), -minor(1), minor(2), -minor(3));
  const double length = c.norm();
  double size = 0.0;
  for (int i = 0; i < 4; ++i) size = std::max(size, std::abs(x[i] - x[0]) + std::abs(y[i] - y[0]));
  // Each minor is twice a triangle's area: collinear points leave only rounding.
  if (!(length > 1e-9 * size * size)) return Eigen::Vector4d::Zero();
  return c / length;
}

// Whether the rigid targets r of a manifold's points can all be met at once: for four points,
// only when r has no component along K's null vector c (c·w = c·r whatever the impulses, as
// cᵀK = 0). Up to rounding: a face resting flat has gaps of ±1e-16 m at its corners.
bool consistent(const double* c, const double* r, int count) {
  if (count < 4) return true;
  double along = 0.0, size = 0.0;
  for (int i = 0; i < 4; ++i) along += c[i] * r[i], size = std::max(size, std::abs(r[i]));
  return std::abs(along) <= 1e-9 * size + velocity_rounding;
}

// The matrix of a subset's free rows, K_F + Γ_F (rows and columns index[0..n)), the rest of
// it the identity: what solve_subset and solve_patterns factor.
template <class Matrix>
Eigen::Matrix4d free_rows_matrix(const Matrix& k, const int* index, int n, const double* gamma) {
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  for (int r = 0; r < n; ++r) {
    const int i = index[r];
    for (int c = 0; c < n; ++c) matrix(r, c) = k(i, index[c]);
    matrix(r, r) += gamma[i];
  }
  return matrix;
}

}  // namespace

// K = J W Jᵀ of the manifold's normal rows (coupling(), engine/constraint_row.hpp), then the
// rigid and soft block matrices of the header. Four points get their null vector c projected
// out; two or three points must give a well-conditioned K (else no block).
void ContactConstraints::prepare_block(std::size_t manifold, bool soft_too) {
  Manifold& m = manifolds_[manifold];
  m.block = false;
  m.block_state = prepared;
  const int count = static_cast<int>(m.count);
  // A lone point has no block, and its Block (1 kB) is never read: left untouched, a heap of
  // spheres keeps its blocks_ (13 MB at 4,096) out of the caches.
  if (count < 2) return;
  for (auto& kept : blocks_[manifold].subset) kept[0].key = kept[1].key = SubsetFactor::none;
  const SolverBody& a = found_with_[m.a];
  const SolverBody& b = found_with_[m.b];
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();  // unused rows and columns: decoupled
  double trace = 0.0;
  // From the prepared normal rows' W Jᵀ (coupling_weighted), each pair once (K is symmetric).
  // J_i W J_jᵀ of two normal rows: their linear parts are both the manifold's normal.
  const double linear = m.normal.dot(m.normal);
  for (int j = 0; j < count; ++j) {
    const NormalRow& row = normals_[m.first + j];
    for (int i = 0; i <= j; ++i) {
      const NormalRow& other = normals_[m.first + i];
      k(i, j) = k(j, i) = coupling_parts(linear, other.angular_a, other.angular_b, a.inverse_mass,
                                         row.weighted_a, b.inverse_mass, row.weighted_b);
    }
    trace += k(j, j);
  }
  if (!(trace > 0.0) || !std::isfinite(trace)) return;
  const double scale = trace / count;
  Eigen::Vector4d c = Eigen::Vector4d::Zero();
  if (count == 4) {
    Vec3 u, v;
    tangent_basis(m.normal, u, v);
    double x[4], y[4];
    for (int i = 0; i < 4; ++i) {
      x[i] = points_[m.first + i].r_b.dot(u);
      y[i] = points_[m.first + i].r_b.dot(v);
    }
    c = affine_dependency(x, y);
    if (c.isZero()) return;
  }
  Eigen::Matrix4d shifted = k + scale * c * c.transpose();
  bool invertible = false;
  Eigen::Matrix4d inverse;
  shifted.computeInverseWithCheck(inverse, invertible, 1e-12 * (scale * scale) * (scale * scale));
  if (!invertible || !inverse.allFinite()) return;
  Eigen::Matrix4d pseudo = inverse - c * c.transpose() / scale;
  for (int i = count; i < 4; ++i) pseudo(i, i) = 0.0, k(i, i) = 0.0;
  Block& block = blocks_[manifold];
  block.k = k;
  for (int i = count; i < 4; ++i) block.k(i, i) = 0.0;
  block.rigid_inverse = pseudo;
  block.null = c;
  // Soft: (K + γI)⁻¹ on the range of K (the component along c of a residual has no impulse
  // that could change it, and would be amplified by 1/γ).
  if (!soft_too) {  // after the positions moved: the push sweeps are done
    m.block = true;
    return;
  }
  m.compliance = scale * m.softness.compliance();
  if (m.compliance > 0.0) {
    Eigen::Matrix4d soft = k + m.compliance * Eigen::Matrix4d::Identity();
    for (int i = count; i < 4; ++i) soft(i, i) = 1.0;
    Eigen::Matrix4d soft_inverse = soft.inverse();
    if (count == 4) soft_inverse -= c * c.transpose() / m.compliance;
    for (int i = count; i < 4; ++i) soft_inverse(i, i) = 0.0;
    if (!soft_inverse.allFinite()) return;
    block.soft_inverse = soft_inverse;
  } else {
    block.soft_inverse = block.rigid_inverse;
  }
  m.block = true;
}

// λ' = P λ − A r on the manifold's points (see the header), r = J v + bias (the caller's
// `residual`, measured before the update), on the impulses `which` names. P is not stored:
// with c the null vector of K (zero for fewer than four points), K⁺K = I − c cᵀ, and for the
// soft block S = (K + γI)⁻¹ − c cᵀ/γ, S K = I − γ S − c cᵀ (as (K + γI)⁻¹K = I − γ(K + γI)⁻¹
// and K c = 0), so λ' = λ − c (c·λ) − A (r + γ λ), γ = 0 for the rigid block: one 4 x 4
// product instead of two. Nothing happens and false is returned when some λ' leaves [0, cap];
// the λ' found is left in `result` for solve_subset to start from.
bool ContactConstraints::solve_block(std::size_t manifold, const Mat4& inverse, double gamma,
                                     const double* residual, const double* cap, Impulse which,
                                     Vec4* result) {
  return with_impulse(which, [&](auto w) {
    return solve_block<decltype(w)::value>(manifold, inverse, gamma, residual, cap, result);
  });
}

template <ContactConstraints::Impulse which>
bool ContactConstraints::solve_block(std::size_t manifold, const Mat4& inverse, double gamma,
                                     const double* residual, const double* cap, Vec4* result) {
  Manifold& m = manifolds_[manifold];
  const int count = static_cast<int>(m.count);
  // Plain arrays, not packets: the impulses arrive one by one, and a packet load of values
  // just stored one by one waits for the stores.
  double old[max_manifold_points] = {0.0, 0.0, 0.0, 0.0}, r[max_manifold_points] = {0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < count; ++i) {
    old[i] = impulse_of<which>(m.first + i);
    r[i] = residual[i] + gamma * old[i];
  }
  const double* c = blocks_[manifold].null.data();
  const double* inv = inverse.data();  // column-major
  const double along = c[0] * old[0] + c[1] * old[1] + c[2] * old[2] + c[3] * old[3];
  double next[max_manifold_points];
  for (int i = 0; i < max_manifold_points; ++i)
    next[i] = old[i] - along * c[i] -
              (inv[i] * r[0] + inv[i + 4] * r[1] + inv[i + 8] * r[2] + inv[i + 12] * r[3]);
  if (result != nullptr) *result = Vec4(next[0], next[1], next[2], next[3]);
  for (int i = 0; i < count; ++i)
    if (!(next[i] >= 0.0) || (cap != nullptr && next[i] > cap[i])) return false;
  // Rigid rows of four points whose targets no motion of the face meets (c·r ≠ 0: a corner
  // with a gap may close it, the others may not approach): K⁺ then gives the least-squares
  // velocities, which sink two of the touching corners by |c·r|/2 each, and no impulse ≥ 0
  // reaches every target. The true solution leaves a corner free of load (solve_subset).
  if (gamma == 0.0 && !consistent(c, r, count)) return false;
  // The changes applied at once: the points share the normal (Δv = W Jᵀ Δλ of the block).
  SolverBody& a = solver_[m.a];
  SolverBody& b = solver_[m.b];
  double total = 0.0;
  Vec3 angular_a = Vec3::Zero(), angular_b = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const NormalRow& row = normals_[m.first + i];
    const double change = next[i] - old[i];
    total += change;
    angular_a += change * row.weighted_a;
    angular_b += change * row.weighted_b;
    impulse_of<which>(m.first + i) = next[i];
  }
  a.velocity -= (a.inverse_mass * total) * m.normal;
  a.angular_velocity -= angular_a;
  b.velocity += (b.inverse_mass * total) * m.normal;
  b.angular_velocity += angular_b;
  return true;
}

// The leading n x n system of a subset's matrix (the rest is the identity), made ready to
// solve: closed forms for n ≤ 2 (the matrix itself kept), the inverse of its size above; not
// `ok` when its determinant is not above `threshold` in size (Eigen's computeInverseWithCheck
// rule). No 4 x 4 inverse for the one or two points of a manifold left free. A subset's
// factor depends only on K, Γ and which rows are free, so solve_subset keeps the last one per
// manifold and softness (a pyramid's half-supported faces free the same rows sweep after
// sweep) and solves with it exactly as with a new one.
void ContactConstraints::SubsetFactor::make(const Eigen::Matrix4d& matrix, int size,
                                            double threshold) {
  n = size;
  ok = false;
  if (n == 1) {
    ok = std::abs(matrix(0, 0)) > threshold;
    data = matrix;
  } else if (n == 2) {
    const double det = matrix(0, 0) * matrix(1, 1) - matrix(0, 1) * matrix(1, 0);
    ok = std::abs(det) > threshold;
    data = matrix;
    data(3, 3) = det;
  } else if (n == 3) {
    // Zeroed: Eigen leaves the inverse unwritten when the check fails (GCC 12 warns of the
    // copy below), and the factor is then never used (ok is false).
    Eigen::Matrix3d inverse = Eigen::Matrix3d::Zero();
    matrix.topLeftCorner<3, 3>().computeInverseWithCheck(inverse, ok, threshold);
    data.topLeftCorner<3, 3>() = inverse;
  } else {
    Eigen::Matrix4d inverse = Eigen::Matrix4d::Zero();  // as above
    matrix.computeInverseWithCheck(inverse, ok, threshold);
    data = inverse;
  }
}

void ContactConstraints::SubsetFactor::solve(const Eigen::Vector4d& right,
                                             Eigen::Vector4d& solved) const {
  solved.setZero();
  if (n == 1) {
    solved[0] = right[0] / data(0, 0);
  } else if (n == 2) {
    const double det = data(3, 3);
    solved[0] = (data(1, 1) * right[0] - data(0, 1) * right[1]) / det;
    solved[1] = (data(0, 0) * right[1] - data(1, 0) * right[0]) / det;
  } else if (n == 3) {
    const Eigen::Matrix3d inverse = data.topLeftCorner<3, 3>();
    solved.head<3>() = inverse * right.head<3>();
  } else {
    const Eigen::Matrix4d inverse = data;
    solved = inverse * right;
  }
}

// The active normal rows of a manifold solved together (see the header), each λ' within
// [0, cap]: (K_s + Γ_s) λ'_s = K λ − r − K λ'_held over the rows not held at a bound, the
// rows' K entries from the block, Γ_ii = gamma[i], r = J v + bias. A row whose λ' leaves its
// bounds is held at the bound and the others solved again (an active-set method: symmetric
// loads stay symmetric where a Gauss-Seidel pass would load the first point solved more).
// `first`, when given, is a solution to start from (the prepared block's). False, with
// nothing applied, when the free rows' matrix is singular or the bounds are not settled in
// as many passes as rows.
bool ContactConstraints::solve_subset(std::size_t manifold, const bool* active,
                                      const double* residual, const double* gamma,
                                      const double* cap, Impulse which, const Vec4* first) {
  return with_impulse(which, [&](auto w) {
    return solve_subset<decltype(w)::value>(manifold, active, residual, gamma, cap, first);
  });
}

template <ContactConstraints::Impulse which>
bool ContactConstraints::solve_subset(std::size_t manifold, const bool* active,
                                      const double* residual_in, const double* gamma,
                                      const double* cap, const Vec4* first) {
  Manifold& m = manifolds_[manifold];
  SolverBody& a = solver_[m.a];
  SolverBody& b = solver_[m.b];
  const Mat4& k = blocks_[manifold].k;
  const int count = static_cast<int>(m.count);
  Vec4 old = Vec4::Zero(), residual = Vec4::Zero(), next = Vec4::Zero();
  bool held[max_manifold_points] = {false, false, false, false};
  for (int i = 0; i < count; ++i) {
    if (!active[i]) continue;
    old[i] = impulse_of<which>(m.first + i);
    residual[i] = residual_in[i];
  }
  auto upper = [&](int i) { return cap != nullptr ? cap[i] : unbounded; };
  int taking[max_manifold_points], taken = 0;  // the active rows, in order
  for (int i = 0; i < count; ++i)
    if (active[i]) taking[taken++] = i;
  for (int pass = 0; pass <= count; ++pass) {
    if (pass > 0 || first == nullptr) {
      int index[max_manifold_points], n = 0;
      double kept[max_manifold_points];  // λ of each active row, less λ' of a held one
      for (int t = 0; t < taken; ++t) {
        const int j = taking[t];
        kept[t] = held[j] ? old[j] - next[j] : old[j];
        if (!held[j]) index[n++] = j;
      }
      Eigen::Vector4d right = Eigen::Vector4d::Zero();
      std::uint16_t key = 0;
      for (int r = 0; r < n; ++r) {
        const int i = index[r];
        double sum = -residual[i];
        for (int t = 0; t < taken; ++t) sum += k(i, taking[t]) * kept[t];
        right[r] = sum;
        key |= static_cast<std::uint16_t>(1u << i);
      }
      for (int t = 0; t < taken; ++t) key |= static_cast<std::uint16_t>(1u << (4 + taking[t]));
      if (n > 0) {
        // Γ is the same for all the points of a manifold (0 or its compliance).
        // Two kept per softness: a subset settled in two passes frees two sets of rows.
        SubsetFactor* kept_factors = blocks_[manifold].subset[gamma[index[0]] != 0.0 ? 1 : 0];
        const bool second = kept_factors[1].key == key;
        SubsetFactor& factor = kept_factors[second ? 1 : 0];
        if (!second && factor.key != key) {
          std::swap(kept_factors[0], kept_factors[1]);  // the older one is replaced
          const Eigen::Matrix4d matrix = free_rows_matrix(k, index, n, gamma);
          factor.make(matrix, n, 1e-12 * matrix.diagonal().maxCoeff());
          factor.key = key;
        }
        if (!factor.ok) break;
        Eigen::Vector4d solved;
        factor.solve(right, solved);
        for (int r = 0; r < n; ++r) next[index[r]] = solved[r];
      }
    } else {
      next = *first;
    }
    bool settled = true;
    for (int i = 0; i < count; ++i) {
      if (!active[i] || held[i]) continue;
      if (!(next[i] >= 0.0)) next[i] = 0.0, held[i] = true, settled = false;
      else if (next[i] > upper(i)) next[i] = upper(i), held[i] = true, settled = false;
    }
    if (settled) break;
  }
  // The passes only ever hold rows, and a row held at zero may still approach, or a point of
  // four rigid rows left free may still sink (the least-squares answer): then every pattern.
  if (!complementary(k, taking, taken, old, next, residual, gamma, cap) &&
      !solve_patterns(k, taking, taken, old, residual, gamma, cap, next))
    return false;
  for (int i = 0; i < count; ++i) {
    if (!active[i]) continue;
    const std::uint32_t k = m.first + i;
    apply_normal(m.normal, k, a, b, next[i] - impulse_of<which>(k));
    impulse_of<which>(k) = next[i];
  }
  return true;
}

// Whether `next` solves the rows' complementarity problem (the header's block, with bounds):
// each λ'ᵢ within [0, capᵢ], and its row's w = r + K (λ' − λ) + Γ λ' (the velocity error the
// impulses leave) ≥ 0 where λ'ᵢ is below its cap (not approaching, or closing a gap faster
// than allowed), ≤ 0 where it is above zero (no pull, no push past the target). A soft row
// between its bounds is left out: its block answer keeps no component along K's null vector
// (prepare_block), so its w is not 0 there. Within rounding, relative to the velocities and
// impulses at hand.
bool ContactConstraints::complementary(const Mat4& k, const int* taking, int taken,
                                       const Vec4& old, const Vec4& next, const Vec4& residual,
                                       const double* gamma, const double* cap) {
  double w[max_manifold_points], size = 0.0, load = 0.0;
  for (int t = 0; t < taken; ++t) {
    const int i = taking[t];
    double change = gamma[i] * next[i];
    for (int s = 0; s < taken; ++s) change += k(i, taking[s]) * (next[taking[s]] - old[taking[s]]);
    w[t] = residual[i] + change;
    size = std::max({size, std::abs(residual[i]), std::abs(change)});
    load = std::max({load, std::abs(old[i]), std::abs(next[i])});
  }
  const double slack = 1e-9 * size + velocity_rounding, give = 1e-9 * load;
  for (int t = 0; t < taken; ++t) {
    const int i = taking[t];
    const double upper = cap != nullptr ? cap[i] : unbounded;
    if (!(next[i] >= -give) || next[i] > upper + give) return false;
    const bool lower_held = next[i] <= give, upper_held = next[i] >= upper - give;
    if (gamma[i] != 0.0 && !lower_held && !upper_held) continue;
    if (!upper_held && w[t] < -slack) return false;
    if (!lower_held && w[t] > slack) return false;
  }
  return true;
}

// Every pattern of rows free, held at zero and held at their caps, the most free first, until
// one is complementary (above): for up to four rows, 16 patterns (81 with caps), each a solve
// of the free rows (K_F + Γ_F) λ'_F = K_F λ − r_F − K_FH λ'_H. Only when the passes of
// solve_subset settled on a wrong set: K + Γ is positive semi-definite, so the rows are a
// convex quadratic program (minimise ½ λ'ᵀ(K + Γ)λ' + λ'ᵀ(r − K λ) over the box), whose
// solutions all share one w, and the first pattern that passes is one of them. False when
// none passes (singular free rows throughout).
bool ContactConstraints::solve_patterns(const Mat4& k, const int* taking, int taken,
                                        const Vec4& old, const Vec4& residual,
                                        const double* gamma, const double* cap, Vec4& next) {
  bool capped = false;
  for (int t = 0; t < taken; ++t) capped = capped || (cap != nullptr && cap[taking[t]] < unbounded);
  const int states = capped ? 3 : 2;  // free, at zero, at the cap
  int patterns = 1;
  for (int t = 0; t < taken; ++t) patterns *= states;
  for (int free_rows = taken; free_rows >= 0; --free_rows) {
    for (int code = 0; code < patterns; ++code) {
      int state[max_manifold_points], n = 0, index[max_manifold_points];
      bool possible = true;
      for (int t = 0, rest = code; t < taken; ++t, rest /= states) {
        state[t] = rest % states;
        if (state[t] == 0) index[n++] = taking[t];
        if (state[t] == 2 && !(cap[taking[t]] < unbounded)) possible = false;
      }
      if (n != free_rows || !possible) continue;
      Vec4 trial = Vec4::Zero();
      for (int t = 0; t < taken; ++t)
        if (state[t] == 2) trial[taking[t]] = cap[taking[t]];
      if (n > 0) {
        const Eigen::Matrix4d matrix = free_rows_matrix(k, index, n, gamma);
        const double diagonal = matrix.diagonal().head(n).maxCoeff();
        Eigen::Vector4d right = Eigen::Vector4d::Zero(), solved;
        for (int r = 0; r < n; ++r) {
          const int i = index[r];
          double sum = -residual[i];
          for (int t = 0; t < taken; ++t) {
            const int j = taking[t];
            sum += k(i, j) * (state[t] == 0 ? old[j] : old[j] - trial[j]);
          }
          right[r] = sum;
        }
        SubsetFactor factor;
        // |det| against the diagonal's size to the n-th power: four rigid corners of a face
        // (K singular) leave only rounding.
        factor.make(matrix, n, 1e-10 * std::pow(diagonal, n));
        if (!factor.ok) continue;
        factor.solve(right, solved);
        for (int r = 0; r < n; ++r) trial[index[r]] = solved[r];
      }
      if (!complementary(k, taking, taken, old, trial, residual, gamma, cap)) continue;
      for (int t = 0; t < taken; ++t) {
        const int i = taking[t];
        trial[i] = std::clamp(trial[i], 0.0, cap != nullptr ? cap[i] : unbounded);
      }
      next = trial;
      return true;
    }
  }
  return false;
}

template bool ContactConstraints::solve_block<ContactConstraints::Impulse::sweep>(
    std::size_t, const Mat4&, double, const double*, const double*, Vec4*);
template bool ContactConstraints::solve_block<ContactConstraints::Impulse::push>(
    std::size_t, const Mat4&, double, const double*, const double*, Vec4*);
template bool ContactConstraints::solve_subset<ContactConstraints::Impulse::sweep>(
    std::size_t, const bool*, const double*, const double*, const double*, const Vec4*);
template bool ContactConstraints::solve_subset<ContactConstraints::Impulse::push>(
    std::size_t, const bool*, const double*, const double*, const double*, const Vec4*);

}  // namespace rigidlab
