// Articulations shared by the articulation tests and the benchmark: random trees with random
// joints and inertias, chains of pendulum links, the point-mass double pendulum.
#pragma once

#include <cmath>
#include <random>

#include "engine/articulation.hpp"

namespace rigidlab::test {

inline Vec3 random_vec3(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

// A random physical inertia tensor: principal moments built from positive second moments
// (∫x², ∫y², ∫z² > 0, so A + B >= C always holds), turned by a random rotation.
inline Mat3 random_inertia(std::mt19937& rng, double mass) {
  std::uniform_real_distribution<double> u(0.01, 0.3);
  const double x2 = mass * u(rng), y2 = mass * u(rng), z2 = mass * u(rng);
  const Mat3 principal = Vec3(y2 + z2, x2 + z2, x2 + y2).asDiagonal();
  const Mat3 R = quat_from_axis_angle(random_vec3(rng) + Vec3(0, 0, 1e-3), 3.0 *
                                      std::uniform_real_distribution<double>(-1, 1)(rng))
                     .toRotationMatrix();
  return R * principal * R.transpose();
}

// `links` links, each hung from a random earlier link or the base, with revolute and
// prismatic joints about random axes (every fifth link fixed to its parent), random origins,
// masses in [0.5, 2] kg, COMs and inertias.
inline Articulation random_tree(int links, BaseType base, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Articulation art(base, random_vec3(rng),
                   quat_from_axis_angle(random_vec3(rng) + Vec3(1e-3, 0, 0), 2.0));
  for (int k = 0; k < links; ++k) {
    LinkSpec spec;
    spec.parent = k == 0 ? -1 : static_cast<int>(u(rng) * (k + 1)) - 1;
    spec.joint = k % 5 == 4 ? JointType::fixed
                            : (u(rng) < 0.6 ? JointType::revolute : JointType::prismatic);
    spec.axis = random_vec3(rng) + Vec3(0, 0, 1e-3);
    spec.origin = random_vec3(rng, 0.8);
    spec.mass = 0.5 + 1.5 * u(rng);
    spec.com = random_vec3(rng, 0.4);
    spec.inertia = random_inertia(rng, spec.mass);
    art.add_link(spec);
  }
  return art;
}

// A random state for `art`: q and q̇ entries in [−1, 1] (a free base's orientation a random
// unit quaternion).
inline void randomize_state(Articulation& art, unsigned seed, double speed = 1.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(art.model().nq()), v(art.model().nv());
  for (int k = 0; k < q.size(); ++k) q[k] = u(rng);
  for (int k = 0; k < v.size(); ++k) v[k] = speed * u(rng);
  if (art.model().free_base()) q.segment<4>(3).normalize();
  art.set_state(q, v);
}

// A chain of `n` uniform rods of mass m and length L hanging along −y from revolute joints
// about z (a planar n-link pendulum), the first at the base origin.
inline Articulation rod_chain(int n, double mass = 1.0, double length = 0.5,
                              Vec3 axis = Vec3::UnitZ()) {
  Articulation art;
  for (int k = 0; k < n; ++k) {
    LinkSpec spec;
    spec.parent = k - 1;
    spec.axis = axis;
    spec.origin = k == 0 ? Vec3::Zero() : Vec3(0, -length, 0);
    spec.mass = mass;
    spec.com = Vec3(0, -0.5 * length, 0);
    const double across = mass * length * length / 12.0;  // thin rod about its centre
    spec.inertia = Vec3(across, 1e-4 * across, across).asDiagonal();
    art.add_link(spec);
  }
  return art;
}

// The double pendulum of point masses m = 1 kg on massless rods L = 1 m, hinges about z at the
// base origin and at the first mass; angles from the downward vertical, counter-clockwise.
inline Articulation point_double_pendulum(double g = 9.80665) {
  Articulation art;
  art.set_gravity(Vec3(0, -g, 0));
  for (int k = 0; k < 2; ++k) {
    LinkSpec spec;
    spec.parent = k - 1;
    spec.origin = k == 0 ? Vec3::Zero() : Vec3(0, -1, 0);
    spec.mass = 1.0;
    spec.com = Vec3(0, -1, 0);
    art.add_link(spec);
  }
  return art;
}

}  // namespace rigidlab::test
