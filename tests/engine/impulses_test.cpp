// engine/impulses.hpp against the documents' numbers and against physics that does not use
// the code under test: conservation of linear and angular momentum, the kinetic energy lost
// ½(1 − e²) m_eff v_n², Newton's restitution law, rolling without slipping (v = 5/7 v₀ for a
// solid sphere), the Coulomb limit, the 12x12 J W Jᵀ of 001_* Appendix D, and the velocity
// change an impulse causes through Body's own apply_impulse.
#include "engine/impulses.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

// ---- one dimension (001_* "System Of Particles") -------------------------------------------

TEST(Impulse1D, DocumentNumbersEqualMasses) {
  const Impulse1D r = impulse_1d(1.0, 2.0, 1.0, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(r.impulse, 2.0);
  EXPECT_DOUBLE_EQ(r.velocity_a, 0.0);
  EXPECT_DOUBLE_EQ(r.velocity_b, 2.0);
}

TEST(Impulse1D, DocumentNumbersOneAgainstFour) {
  const Impulse1D r = impulse_1d(1.0, 2.0, 1.0 / 4.0, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(r.impulse, 3.2);
  EXPECT_DOUBLE_EQ(r.velocity_a, -1.2);
  EXPECT_DOUBLE_EQ(r.velocity_b, 0.8);
}

TEST(Impulse1D, ImmovableWall) {
  // 003_* "Collision Response": against an immovable body p = −(ε + 1) m₁ v₁·n, so v₁' = −ε v₁.
  const Impulse1D r = impulse_1d(1.0 / 3.0, 4.0, 0.0, 0.0, 0.5);
  EXPECT_DOUBLE_EQ(r.impulse, 1.5 * 3.0 * 4.0);
  EXPECT_DOUBLE_EQ(r.velocity_a, -2.0);
  EXPECT_DOUBLE_EQ(r.velocity_b, 0.0);
}

TEST(Impulse1D, MomentumAndRestitutionLaw) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mass(0.1, 10.0), speed(-5.0, 5.0), unit(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double ma = mass(rng), mb = mass(rng), va = speed(rng), vb = speed(rng), e = unit(rng);
    const Impulse1D r = impulse_1d(1 / ma, va, 1 / mb, vb, e);
    EXPECT_NEAR(ma * r.velocity_a + mb * r.velocity_b, ma * va + mb * vb, 1e-12);
    EXPECT_NEAR(r.velocity_b - r.velocity_a, -e * (vb - va), 1e-12);
  }
}

TEST(Impulse1D, RefusesBadInput) {
  EXPECT_THROW(impulse_1d(0.0, 1.0, 0.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(impulse_1d(1.0, 1.0, -1.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(impulse_1d(1.0, 1.0, 1.0, 0.0, 1.5), std::invalid_argument);
  EXPECT_THROW(impulse_1d(1.0, 1.0, 1.0, 0.0, -0.1), std::invalid_argument);
}

// ---- rigid bodies ----------------------------------------------------------------------------

struct Random {
  std::mt19937 rng{2024};
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  Vec3 vec(double scale) { return Vec3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)); }
  Quat rotation() { return Quat(Eigen::AngleAxisd(uniform(0, 3), vec(1).normalized())); }
  // A box of random size with its body axes turned (a full, non-diagonal body-frame tensor),
  // at a random pose with random velocities.
  Body body() {
    const double mass = uniform(0.5, 5.0);
    const Mat3 box = inertia_solid_box(mass, Vec3(uniform(0.2, 2), uniform(0.2, 2), uniform(0.2, 2)));
    Body b = make_body(mass, rotate_inertia(box, rotation()));
    b.position = vec(3);
    b.orientation = rotation();
    b.velocity = vec(4);
    b.angular_velocity = vec(3);
    return b;
  }
};

// Angular momentum about point q: Σ (x − q) × m v + I_world ω (002_* "Rigid Body Dynamics").
Vec3 angular_momentum_about(const Body& b, const Vec3& q) {
  return (b.position - q).cross(linear_momentum(b)) + angular_momentum(b);
}

TEST(InverseMassMatrix, GivesTheVelocityChangeAnImpulseCauses) {
  // 002_* "Inverse Mass Matrix": an impulse j at offset r1 changes the velocity of the point at
  // offset r2 by M⁻¹ j. Measured with Body's apply_impulse and point_velocity.
  Random random;
  for (int i = 0; i < 100; ++i) {
    Body b = random.body();
    const Vec3 r1 = random.vec(1), r2 = random.vec(1), j = random.vec(2);
    const Vec3 before = point_velocity(b, b.position + r2);
    const Mat3 m_inv = inverse_mass_matrix(b, r1, r2);
    apply_impulse(b, j, b.position + r1);
    EXPECT_LT((point_velocity(b, b.position + r2) - before - m_inv * j).norm(), 1e-12);
  }
  EXPECT_EQ(inverse_mass_matrix(make_static_body(), Vec3(1, 2, 3), Vec3(0, 1, 0)), Mat3::Zero());
  // r1 = r2 = 0: a push at the COM, (1/m) E.
  Body b = random.body();
  EXPECT_LT((inverse_mass_matrix(b, Vec3::Zero(), Vec3::Zero()) - Mat3::Identity() / b.mass)
                .norm(), 1e-15);
}

TEST(EffectiveMass, MatchesJWJtBuiltAsTwelveByTwelve) {
  // 001_* Appendix D: J = [−n, −(r_a × n), n, r_b × n], W = diag(m_a⁻¹E, I_a⁻¹, m_b⁻¹E, I_b⁻¹).
  Random random;
  for (int i = 0; i < 100; ++i) {
    const Body a = random.body(), b = random.body();
    const Vec3 p = random.vec(2), n = random.vec(1).normalized();
    Eigen::Matrix<double, 1, 12> jacobian;
    jacobian << -n.transpose(), -(p - a.position).cross(n).transpose(), n.transpose(),
        (p - b.position).cross(n).transpose();
    Eigen::Matrix<double, 12, 12> w = Eigen::Matrix<double, 12, 12>::Zero();
    w.block<3, 3>(0, 0) = Mat3::Identity() / a.mass;
    w.block<3, 3>(3, 3) = world_inertia(a).inverse();
    w.block<3, 3>(6, 6) = Mat3::Identity() / b.mass;
    w.block<3, 3>(9, 9) = world_inertia(b).inverse();
    const double direct = 1.0 / (jacobian * w * jacobian.transpose())(0, 0);
    EXPECT_NEAR(effective_mass(a, b, p, 3.0 * n), direct, 1e-12 * direct);
  }
}

TEST(EffectiveMass, ImmovablePartnerAndPureTranslation) {
  // Against a floor, through the COM: the body's own mass (no lever arm).
  Body sphere = make_sphere_body(2.0, 0.5);
  sphere.position = Vec3(0, 0.5, 0);
  const Body floor = make_static_body();
  EXPECT_NEAR(effective_mass(floor, sphere, Vec3::Zero(), Vec3::UnitY()), 2.0, 1e-15);
  // Two free particles through their centres: the reduced mass m_a m_b/(m_a + m_b).
  Body other = make_sphere_body(6.0, 0.5);
  other.position = Vec3(0, 1.5, 0);
  EXPECT_NEAR(effective_mass(sphere, other, Vec3(0, 1, 0), Vec3::UnitY()), 12.0 / 8.0, 1e-15);
  EXPECT_THROW(effective_mass(floor, make_static_body(), Vec3::Zero(), Vec3::UnitY()),
               std::invalid_argument);
  EXPECT_THROW(effective_mass(sphere, sphere, Vec3::Zero(), Vec3::UnitY()), std::invalid_argument);
  EXPECT_THROW(effective_mass(floor, sphere, Vec3::Zero(), Vec3::Zero()), std::invalid_argument);
}

// A random approaching contact between two random bodies.
struct Collision {
  Body a, b;
  Contact contact;
};
Collision random_collision(Random& random, double restitution, double friction) {
  Collision c{random.body(), random.body(), {}};
  c.contact.point = 0.5 * (c.a.position + c.b.position) + random.vec(0.5);
  Vec3 n = random.vec(1).normalized();
  const Vec3 v_rel = point_velocity(c.b, c.contact.point) - point_velocity(c.a, c.contact.point);
  if (n.dot(v_rel) > 0) n = -n;  // make them approach
  c.contact.normal = n;
  c.contact.restitution = restitution;
  c.contact.friction = friction;
  return c;
}

TEST(ResolveContact, ConservesLinearAndAngularMomentumAboutAnyPoint) {
  Random random;
  for (int i = 0; i < 200; ++i) {
    Collision c = random_collision(random, random.uniform(0, 1), random.uniform(0, 2));
    const Vec3 q = random.vec(5);
    const Vec3 p0 = linear_momentum(c.a) + linear_momentum(c.b);
    const Vec3 l0 = angular_momentum_about(c.a, q) + angular_momentum_about(c.b, q);
    const ContactImpulse r = resolve_contact(c.a, c.b, c.contact);
    EXPECT_GT(r.normal_impulse, 0.0);
    EXPECT_LT((linear_momentum(c.a) + linear_momentum(c.b) - p0).norm(), 1e-12 * (1 + p0.norm()));
    const Vec3 l1 = angular_momentum_about(c.a, q) + angular_momentum_about(c.b, q);
    EXPECT_LT((l1 - l0).norm(), 1e-11 * (1 + l0.norm()));
  }
}

TEST(ResolveContact, RestitutionLawAndEnergyLossWithoutFriction) {
  // Newton's law (003_* "Collision Response"): v_n' = −e v_n. Energy lost by an impulse along n
  // with effective mass m_eff: ½ (1 − e²) m_eff v_n² (zero for e = 1).
  Random random;
  for (int i = 0; i < 200; ++i) {
    const double e = i % 4 == 0 ? 1.0 : random.uniform(0, 1);
    Collision c = random_collision(random, e, 0.0);
    const Vec3 p = c.contact.point, n = c.contact.normal;
    const double vn = n.dot(point_velocity(c.b, p) - point_velocity(c.a, p));
    const double m_eff = effective_mass(c.a, c.b, p, n);
    const double t0 = kinetic_energy(c.a) + kinetic_energy(c.b);
    resolve_contact(c.a, c.b, c.contact);
    const double vn_after = n.dot(point_velocity(c.b, p) - point_velocity(c.a, p));
    EXPECT_NEAR(vn_after, -e * vn, 1e-12 * (1 + std::abs(vn)));
    const double t1 = kinetic_energy(c.a) + kinetic_energy(c.b);
    EXPECT_NEAR(t0 - t1, 0.5 * (1 - e * e) * m_eff * vn * vn, 1e-11 * t0);
  }
}

TEST(ResolveContact, FrictionNeverAddsEnergy) {
  Random random;
  for (int i = 0; i < 200; ++i) {
    Collision c = random_collision(random, 1.0, random.uniform(0.01, 3));
    const double t0 = kinetic_energy(c.a) + kinetic_energy(c.b);
    const ContactImpulse r = resolve_contact(c.a, c.b, c.contact);
    EXPECT_LE(kinetic_energy(c.a) + kinetic_energy(c.b), t0 * (1 + 1e-13));
    EXPECT_LE(r.friction_impulse.norm(), c.contact.friction * r.normal_impulse * (1 + 1e-14));
    EXPECT_NEAR(r.friction_impulse.dot(c.contact.normal), 0.0, 1e-12);
  }
}

// The contact's inverse mass matrix measured, not computed by the code under test: column k is
// the change of v_b(p) − v_a(p) when b gets the unit impulse e_k at p and a gets −e_k
// (Body's own apply_impulse and point_velocity, 002_* "Inverse Mass Matrix").
Mat3 measured_inverse_mass(const Body& a, const Body& b, const Vec3& p) {
  Mat3 k;
  const Vec3 v0 = point_velocity(b, p) - point_velocity(a, p);
  for (int i = 0; i < 3; ++i) {
    Body a1 = a, b1 = b;
    apply_impulse(a1, -Vec3::Unit(i), p);
    apply_impulse(b1, Vec3::Unit(i), p);
    k.col(i) = point_velocity(b1, p) - point_velocity(a1, p) - v0;
  }
  return k;
}

TEST(ResolveContact, WithFrictionNewtonsLawCoulombsConeAndNoEnergyGain) {
  // With friction the normal condition must still hold (v_n' = −e v_n, 003_* "Collision
  // Response"), the friction impulse must stay in Coulomb's cone, and no energy may appear,
  // for bodies whose normal and tangential motions are coupled (boxes turned at random).
  Random random;
  for (int i = 0; i < 400; ++i) {
    const double e = i % 5 == 0 ? 1.0 : i % 5 == 1 ? 0.0 : random.uniform(0, 1);
    const double mu = i % 3 == 0 ? 100.0 : random.uniform(0, 2);
    Collision c = random_collision(random, e, mu);
    const Vec3 p = c.contact.point, n = c.contact.normal;
    const double vn = n.dot(point_velocity(c.b, p) - point_velocity(c.a, p));
    const double t0 = kinetic_energy(c.a) + kinetic_energy(c.b);
    const ContactImpulse r = resolve_contact(c.a, c.b, c.contact);
    const double vn_after = n.dot(point_velocity(c.b, p) - point_velocity(c.a, p));
    EXPECT_NEAR(vn_after, -e * vn, 1e-12 * (1 + std::abs(vn))) << i;
    EXPECT_GT(r.normal_impulse, 0.0);
    EXPECT_LE(r.friction_impulse.norm(), mu * r.normal_impulse * (1 + 1e-12)) << i;
    EXPECT_NEAR(r.friction_impulse.dot(n), 0.0, 1e-12 * r.normal_impulse);
    EXPECT_LE(kinetic_energy(c.a) + kinetic_energy(c.b), t0 * (1 + 1e-13)) << i;
  }
}

TEST(ResolveContact, EndsStickingWhenTheConeHoldsTheStoppingImpulse) {
  // The impulse that leaves the contact point with v' = −e v_n n (no slip) is P = K⁻¹(v' − v),
  // K measured above. When P lies in the cone (P_n > 0, |P_t| ≤ μ P_n) and costs no energy
  // (P·v + ½ P·K P ≤ 0), the contact must end sticking; with e = 0 it never costs energy.
  Random random;
  int sticking = 0;
  for (int i = 0; i < 400; ++i) {
    const double e = i % 2 == 0 ? 0.0 : random.uniform(0, 1);
    Collision c = random_collision(random, e, 100.0);
    const Vec3 p = c.contact.point, n = c.contact.normal;
    const Vec3 v = point_velocity(c.b, p) - point_velocity(c.a, p);
    const Mat3 k = measured_inverse_mass(c.a, c.b, p);
    const Vec3 stop = k.inverse() * (-e * n.dot(v) * n - v);
    const double stop_n = stop.dot(n);
    const bool in_cone = stop_n > 0 && (stop - stop_n * n).norm() <= 100.0 * stop_n;
    const bool free_of_charge = stop.dot(v) + 0.5 * stop.dot(k * stop) <= -1e-9;
    if (!in_cone || !free_of_charge) continue;
    ++sticking;
    resolve_contact(c.a, c.b, c.contact);
    const Vec3 after = point_velocity(c.b, p) - point_velocity(c.a, p);
    EXPECT_LT((after - after.dot(n) * n).norm(), 1e-10 * (1 + v.norm())) << i;
  }
  EXPECT_GT(sticking, 150);  // the case is common, not vacuous
}

// A solid sphere (m = 2 kg, R = 0.5 m) hits an immovable floor at y = 0 with velocity
// (3, −4, 0) m/s, no spin; the contact is its lowest point.
struct SphereOnFloor {
  Body floor = make_static_body();
  Body sphere = make_sphere_body(2.0, 0.5);
  Contact contact;
  explicit SphereOnFloor(double friction) {
    sphere.position = Vec3(0, 0.5, 0);
    sphere.velocity = Vec3(3, -4, 0);
    contact.point = Vec3::Zero();
    contact.normal = Vec3::UnitY();  // from the floor (a) to the sphere (b)
    contact.restitution = 0.0;
    contact.friction = friction;
  }
};

TEST(ResolveContact, SphereWithHighFrictionLeavesRolling) {
  // Friction impulse s opposite to the slip: v = v₀ − s/m, ω_z = −R s/I. The contact point
  // stops when v₀ = s (1/m + R²/I) with I = (2/5) m R², so s = (2/7) m v₀ and v = (5/7) v₀.
  SphereOnFloor s(10.0);
  const ContactImpulse r = resolve_contact(s.floor, s.sphere, s.contact);
  EXPECT_NEAR(r.normal_impulse, 2.0 * 4.0, 1e-14);  // e = 0: stops the normal motion, m v_n
  EXPECT_NEAR(s.sphere.velocity.x(), 5.0 / 7.0 * 3.0, 1e-14);
  EXPECT_NEAR(s.sphere.velocity.y(), 0.0, 1e-14);
  EXPECT_NEAR(s.sphere.angular_velocity.z(), -(5.0 / 7.0 * 3.0) / 0.5, 1e-14);  // v = −ω_z R
  EXPECT_LT(point_velocity(s.sphere, Vec3::Zero()).norm(), 1e-14);  // contact point at rest
  EXPECT_NEAR(r.friction_impulse.x(), -2.0 / 7.0 * 2.0 * 3.0, 1e-14);
  EXPECT_EQ(s.floor.velocity, Vec3::Zero());
}

TEST(ResolveContact, SphereWithLowFrictionSlidesAtTheCoulombLimit) {
  SphereOnFloor s(0.1);
  const ContactImpulse r = resolve_contact(s.floor, s.sphere, s.contact);
  const double j = 2.0 * 4.0;
  EXPECT_NEAR(r.normal_impulse, j, 1e-14);
  EXPECT_NEAR(r.friction_impulse.x(), -0.1 * j, 1e-14);  // exactly μ J, opposite the slip
  EXPECT_NEAR(s.sphere.velocity.x(), 3.0 - 0.1 * j / 2.0, 1e-14);
  EXPECT_NEAR(s.sphere.angular_velocity.z(), -0.5 * 0.1 * j / (0.4 * 2.0 * 0.25), 1e-13);
  EXPECT_GT(point_velocity(s.sphere, Vec3::Zero()).x(), 0.0);  // still sliding forward
}

TEST(ResolveContact, SeparatingOrRestingBodiesAreLeftAlone) {
  SphereOnFloor s(1.0);
  s.sphere.velocity = Vec3(3, 1, 0);
  const Body before = s.sphere;
  const ContactImpulse r = resolve_contact(s.floor, s.sphere, s.contact);
  EXPECT_EQ(r.normal_impulse, 0.0);
  EXPECT_EQ(r.friction_impulse, Vec3::Zero());
  EXPECT_EQ(s.sphere.velocity, before.velocity);
  s.sphere.velocity = Vec3(3, 0, 0);  // sliding along the floor, not approaching
  EXPECT_EQ(resolve_contact(s.floor, s.sphere, s.contact).normal_impulse, 0.0);
  EXPECT_EQ(s.sphere.velocity, Vec3(3, 0, 0));
}

TEST(ResolveContact, NormalLengthDoesNotMatter) {
  SphereOnFloor unit(0.3), longer(0.3);
  longer.contact.normal = Vec3(0, 7, 0);
  const double j1 = resolve_contact(unit.floor, unit.sphere, unit.contact).normal_impulse;
  const double j2 = resolve_contact(longer.floor, longer.sphere, longer.contact).normal_impulse;
  EXPECT_EQ(j1, j2);
  EXPECT_EQ(unit.sphere.velocity, longer.sphere.velocity);
}

TEST(ResolveContact, ProblemsAreNamed) {
  SphereOnFloor s(0.5);
  Contact c = s.contact;
  EXPECT_EQ(contact_problem(s.floor, s.sphere, c), "");
  c.normal = Vec3::Zero();
  EXPECT_EQ(contact_problem(s.floor, s.sphere, c), "normal must not be zero");
  c = s.contact;
  c.restitution = 1.5;
  EXPECT_EQ(contact_problem(s.floor, s.sphere, c), "restitution must be in [0, 1], got 1.5");
  c = s.contact;
  c.friction = -1;
  EXPECT_EQ(contact_problem(s.floor, s.sphere, c), "friction must be >= 0, got -1");
  EXPECT_EQ(contact_problem(s.sphere, s.sphere, s.contact), "a and b are the same body");
  Body other_floor = make_static_body();
  EXPECT_EQ(contact_problem(s.floor, other_floor, s.contact), "both bodies are immovable");
  const Body before = s.sphere;
  c = s.contact;
  c.restitution = -0.5;
  EXPECT_THROW(resolve_contact(s.floor, s.sphere, c), std::invalid_argument);
  EXPECT_EQ(s.sphere.velocity, before.velocity);  // unchanged after a refused call
}

TEST(ResolveContact, HugeNormalsAndFarPointsAreHandledOrRefused) {
  // A long normal is a direction like any other: (1e300, 1e300, 0) acts as (1, 1, 0).
  SphereOnFloor unit(0.3), huge(0.3);
  unit.contact.normal = Vec3(0, 1, 0);
  huge.contact.normal = Vec3(0, 1e300, 0);
  const double j1 = resolve_contact(unit.floor, unit.sphere, unit.contact).normal_impulse;
  const double j2 = resolve_contact(huge.floor, huge.sphere, huge.contact).normal_impulse;
  EXPECT_GT(j1, 0.0);
  EXPECT_EQ(j1, j2);
  EXPECT_NEAR(effective_mass(unit.floor, unit.sphere, Vec3::Zero(), Vec3(1e300, 1e300, 0)),
              effective_mass(unit.floor, unit.sphere, Vec3::Zero(), Vec3(1, 1, 0)), 1e-15);
  // A point 1e160 m away overflows K: refused, and the bodies keep their velocities.
  SphereOnFloor far(0.3);
  far.contact.point = Vec3(1, 1e160, 0);
  const Body before = far.sphere;
  EXPECT_THROW(resolve_contact(far.floor, far.sphere, far.contact), std::invalid_argument);
  EXPECT_EQ(far.sphere.velocity, before.velocity);
  EXPECT_EQ(far.sphere.angular_velocity, before.angular_velocity);
  EXPECT_THROW(effective_mass(far.floor, far.sphere, Vec3(1e300, 0, 0), Vec3::UnitY()),
               std::invalid_argument);
  EXPECT_THROW(impulse_1d(1.0, 1e308, 1.0, -1e308, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace rigidlab
