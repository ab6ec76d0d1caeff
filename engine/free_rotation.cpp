#include "engine/free_rotation.hpp"

#include <cmath>

#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

// free_rotation_step runs once per body and step: everything it calls is inlined into it
// (as in the integrators' body loops; bench/world_bench).
#if defined(__GNUC__)
#define RIGIDLAB_FLATTEN __attribute__((flatten))
#else
#define RIGIDLAB_FLATTEN
#endif

bool is_diagonal(const Mat3& m) {
  return m(0, 1) == 0.0 && m(1, 0) == 0.0 && m(0, 2) == 0.0 && m(2, 0) == 0.0 &&
         m(1, 2) == 0.0 && m(2, 1) == 0.0;
}

// The flow of the part c Πi²/2 for a time h, in coordinates where i is axis I (0 or 1) of a
// right-handed frame: Πi stays, θ = h c Πi; the orientation turns by θ about axis I (a
// body-fixed rotation: turn ← turn ⊗ (cos θ/2, sin θ/2 e_I)) and Π by −θ about the same
// axis. One sin/cos pair of θ/2 gives both (cos θ = c² − s², sin θ = 2sc). The axes are fixed
// at compile time, so Π and turn stay in registers.
template <int I>
inline void axis_flow(double c, double h, Vec3& pi, Quat& turn) {
  constexpr int J = (I + 1) % 3, K = (I + 2) % 3;  // e_I × e_J = e_K
  const double half_angle = 0.5 * h * c * pi[I];
  const double s = std::sin(half_angle), co = std::cos(half_angle);  // one sincos call
  const double cos_angle = co * co - s * s, sin_angle = 2.0 * s * co;
  const double pj = pi[J], pk = pi[K];
  pi[J] = cos_angle * pj + sin_angle * pk;
  pi[K] = -sin_angle * pj + cos_angle * pk;
  // turn ⊗ (co, s e_I), written out: the axis quaternion has one non-zero vector component.
  const double w = turn.w(), vi = turn.vec()[I], vj = turn.vec()[J], vk = turn.vec()[K];
  turn.w() = co * w - s * vi;
  turn.vec()[I] = co * vi + s * w;
  turn.vec()[J] = co * vj + s * vk;
  turn.vec()[K] = co * vk - s * vj;
}

// The end of one step for the principal frame's orientation qp (principal -> world, unit):
// kick, drift A(dt/2) B(dt) A(dt/2) S(dt), kick. Returns the end orientation of the principal
// frame (unit) and writes the end ω (world). The drift runs in the frame (e_a, e_b, σ e_k),
// σ = ±1 making it right-handed, so that A and B turn about its fixed axes x and y.
Quat advance(const RotationSplitting& p, const Quat& qp, const Vec3& omega, const Vec3& torque,
             double dt, Vec3& omega_end) {
  const double half = 0.5 * dt;
  const bool torqued = !is_zero(torque);
  // Kick: Π = Rᵀ (L + dt/2 τ) with L = R diag(I) Rᵀ ω.
  const Quat to_principal = qp.conjugate();
  Vec3 pi = p.moments.cwiseProduct(to_principal * omega);
  if (torqued) pi += half * (to_principal * torque);
  // Drift; the spherical part commutes with the two axis parts (|Π|² is a Casimir).
  const int a = p.outer, b = p.inner, k = p.spherical;
  const double sigma = b == (a + 1) % 3 ? 1.0 : -1.0;
  const double k_inverse = p.inverse_moments[k];
  Vec3 u(pi[a], pi[b], sigma * pi[k]);
  Quat turn = Quat::Identity();  // body-fixed increment R' = R turn, in the frame of u
  axis_flow<0>(p.inverse_moments[a] - k_inverse, half, u, turn);
  axis_flow<1>(p.inverse_moments[b] - k_inverse, dt, u, turn);
  axis_flow<0>(p.inverse_moments[a] - k_inverse, half, u, turn);
  turn = turn * rotation_quat(dt * k_inverse * u);
  pi[a] = u.x();
  pi[b] = u.y();
  pi[k] = sigma * u.z();
  Quat turn_principal(turn.w(), 0.0, 0.0, 0.0);
  turn_principal.vec()[a] = turn.x();
  turn_principal.vec()[b] = turn.y();
  turn_principal.vec()[k] = sigma * turn.z();
  const Quat qp_end = unit(Quat(qp * turn_principal));
  // Kick: the second half of the torque impulse, at the new orientation.
  if (torqued) pi += half * (qp_end.conjugate() * torque);
  omega_end = qp_end * p.inverse_moments.cwiseProduct(pi);
  return qp_end;
}

// One step from q (body -> world); returns the end orientation (unit) and writes the end ω.
Quat step_orientation(const RotationSplitting& p, const Quat& q, const Vec3& omega,
                      const Vec3& torque, double dt, Vec3& omega_end) {
  if (p.aligned) return advance(p, q, omega, torque, dt, omega_end);
  const Quat qp_end = advance(p, unit(Quat(q * p.axes)), omega, torque, dt, omega_end);
  return unit(Quat(qp_end * p.axes.conjugate()));
}

}  // namespace

RotationSplitting rotation_splitting(const Mat3& inertia) {
  RotationSplitting p;
  if (is_diagonal(inertia)) {
    p.moments = inertia.diagonal();
    p.axes = Quat::Identity();
    p.aligned = true;
  } else {
    const SymmetricEigen eigen = principal_inertia(inertia);  // right-handed axes
    p.moments = eigen.values;
    p.axes = unit(Quat(eigen.axes));
    p.aligned = false;
  }
  p.inverse_moments = p.moments.cwiseInverse();
  // k is the index of neither the smallest moment (the lowest index among equals) nor the
  // largest (the highest index among equals): the intermediate moment, one of an equal pair.
  // Written as selects rather than a sort: bodies come in any order and branches mispredict.
  const Vec3& m = p.moments;
  int smallest = m[1] < m[0] ? 1 : 0;
  smallest = m[2] < m[smallest] ? 2 : smallest;
  int largest = m[1] >= m[0] ? 1 : 0;
  largest = m[2] >= m[largest] ? 2 : largest;
  p.spherical = 3 - smallest - largest;
  const double k_inverse = p.inverse_moments[p.spherical];
  const bool smallest_outside = std::abs(p.inverse_moments[smallest] - k_inverse) >=
                                std::abs(p.inverse_moments[largest] - k_inverse);
  p.outer = smallest_outside ? smallest : largest;
  p.inner = smallest_outside ? largest : smallest;
  return p;
}

FreeRotation free_rotation(const RotationSplitting& p, const Quat& q, const Vec3& omega,
                           const Vec3& torque, double dt) {
  FreeRotation result;
  const Quat end = step_orientation(p, q, omega, torque, dt, result.angular_velocity);
  result.rotation = end * q.conjugate();  // world frame: end = rotation q
  return result;
}

FreeRotation free_rotation(const Body& b, double dt) {
  return free_rotation(rotation_splitting(b.inertia), b.orientation, b.angular_velocity, b.torque,
                       dt);
}

RIGIDLAB_FLATTEN void free_rotation_step(Body& b, double dt) {
  Vec3 omega_end;
  b.orientation = step_orientation(rotation_splitting(b.inertia), b.orientation,
                                   b.angular_velocity, b.torque, dt, omega_end);
  b.angular_velocity = omega_end;
}

Quat finish_rotation(const Quat& q, const FreeRotation& turn, const Vec3& omega, double dt) {
  const Vec3 change = omega - turn.angular_velocity;
  const Quat rotation =
      is_zero(change) ? turn.rotation : Quat(rotation_quat(dt * change) * turn.rotation);
  return unit(Quat(rotation * q));
}

}  // namespace rigidlab
