// Tests for engine/body.cpp against hand-computed values and defining identities: the rotated
// tensor of a box turned 90° (its moments swap), r × f for torques, Δω = I⁻¹(r × j) for a
// sphere, ½ m v² + ½ I ω², and the immovability of static bodies.
#include "engine/body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

constexpr double pi = 3.14159265358979323846;

std::string error_of(double mass, const Mat3& inertia) {
  try {
    make_body(mass, inertia);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(MakeBody, RefusesBadMassAndInertia) {
  EXPECT_EQ(error_of(-1, Mat3::Identity()), "mass must be > 0, got -1");
  EXPECT_EQ(error_of(0, Mat3::Identity()), "mass must be > 0, got 0");
  EXPECT_EQ(error_of(std::nan(""), Mat3::Identity()), "mass must be finite, got nan");
  EXPECT_EQ(error_of(1, Mat3::Identity() * std::numeric_limits<double>::infinity()),
            "inertia must be finite");
  const std::string triangle = error_of(1, Vec3(1, 1, 3).asDiagonal());
  EXPECT_NE(triangle.find("A + B >= C"), std::string::npos) << triangle;
  Mat3 asymmetric = Mat3::Identity();
  asymmetric(0, 1) = 0.5;
  EXPECT_NE(error_of(1, asymmetric).find("symmetric"), std::string::npos) << error_of(1, asymmetric);
  EXPECT_NE(error_of(1, -Mat3::Identity()), "");
}

// A subnormal mass or tensor has an inverse that overflows (1/1e-320 = inf); entries near
// DBL_MAX have principal moments that overflow. Both are refused, saying so.
TEST(MakeBody, RefusesMassesAndTensorsWhoseInverseOrMomentsOverflow) {
  EXPECT_EQ(error_of(1e-320, Mat3::Identity()),
            "mass is too small: 1/mass overflows, got 9.9998886718268e-321");
  EXPECT_EQ(mass_problem(1e-320), "is too small: 1/mass overflows, got 9.9998886718268e-321");
  EXPECT_EQ(mass_problem(1e-300), "");
  const std::string tiny = error_of(1, 1e-320 * Mat3::Identity());
  EXPECT_NE(tiny.find("are too small for a body: the inverse tensor overflows (1/"),
            std::string::npos) << tiny;
  EXPECT_EQ(error_of(1, 1e308 * Mat3::Identity()),
            "inertia is not a valid tensor: the tensor is too large: its principal moments "
            "overflow (largest entry 1e+308)");
}

// The inverse of diag(a, b, c) is diag(1/a, 1/b, 1/c) also where the determinant abc would
// underflow (1e-360) or overflow (1e360); and I I⁻¹ = E for a turned tensor at those scales.
TEST(MakeBody, InverseInertiaAtTinyAndHugeScales) {
  for (double s : {1e-120, 1e120}) {
    const Body b = make_body(1.0, s * Vec3(2, 3, 4).asDiagonal());
    const Mat3 want = (Vec3(1.0 / 2, 1.0 / 3, 1.0 / 4) / s).asDiagonal();
    EXPECT_LT(((b.inverse_inertia - want) * s).norm(), 1e-15) << s;
    const Mat3 turned = rotate_inertia(Mat3(s * Vec3(2, 3, 4).asDiagonal()),
                                       quat_from_axis_angle(Vec3(1, 2, 3), 0.7));
    const Body c = make_body(1.0, turned);
    EXPECT_LT((c.inertia * c.inverse_inertia - Mat3::Identity()).norm(), 1e-14) << s;
  }
}

TEST(MakeBody, StoresInverses) {
  const Body b = make_body(4.0, Vec3(1, 2, 3).asDiagonal());
  EXPECT_EQ(b.inverse_mass, 0.25);
  EXPECT_LT((b.inverse_inertia - Vec3(1, 0.5, 1.0 / 3).asDiagonal().toDenseMatrix()).norm(), 1e-15);
  EXPECT_FALSE(is_static(b));
}

TEST(ShapedBodies, SphereAndBoxCarryShapeAndTensor) {
  const Body s = make_sphere_body(2.0, 0.5);
  EXPECT_EQ(s.shape.kind, ShapeKind::sphere);
  EXPECT_EQ(s.shape.radius, 0.5);
  EXPECT_NEAR(s.inertia(0, 0), 0.4 * 2.0 * 0.25, 1e-15);  // (2/5) m r²
  const Body b = make_box_body(12.0, Vec3(1, 2, 3));
  EXPECT_EQ(b.shape.kind, ShapeKind::box);
  EXPECT_EQ(b.shape.half_extents, Vec3(0.5, 1, 1.5));
  EXPECT_NEAR(b.inertia(0, 0), 4.0 + 9.0, 1e-14);  // m (h² + d²)/12
  EXPECT_NEAR(b.inertia(2, 2), 1.0 + 4.0, 1e-14);
  EXPECT_THROW(make_sphere_body(1.0, -1.0), std::invalid_argument);
}

TEST(WorldInertia, BoxTurnedAboutZSwapsItsXAndYMoments) {
  Body b = make_body(1.0, Vec3(1, 2, 3).asDiagonal());
  b.orientation = quat_from_axis_angle(Vec3::UnitZ(), pi / 2);
  const Mat3 expected = Vec3(2, 1, 3).asDiagonal();
  EXPECT_LT((world_inertia(b) - expected).norm(), 1e-14);
  EXPECT_LT((inverse_world_inertia(b) * world_inertia(b) - Mat3::Identity()).norm(), 1e-14);
}

TEST(Frames, ToWorldAndToLocalAreInverseRigidMotions) {
  Body b = make_body(1.0, Mat3::Identity());
  b.position = Vec3(1, 2, 3);
  b.orientation = quat_from_axis_angle(Vec3::UnitZ(), pi / 2);
  EXPECT_LT((to_world(b, Vec3(1, 0, 0)) - Vec3(1, 3, 3)).norm(), 1e-15);
  const Vec3 p(0.3, -2, 5);
  EXPECT_LT((to_local(b, to_world(b, p)) - p).norm(), 1e-14);
}

TEST(PointVelocity, IsVPlusOmegaCrossR) {
  Body b = make_body(1.0, Mat3::Identity());
  b.position = Vec3(5, 0, 0);
  b.velocity = Vec3(1, 0, 0);
  b.angular_velocity = Vec3(0, 0, 2);
  // r = (1, 0, 0): ω × r = (0, 2, 0).
  EXPECT_EQ(point_velocity(b, Vec3(6, 0, 0)), Vec3(1, 2, 0));
}

TEST(ApplyForce, AddsForceAndMomentAboutTheCom) {
  Body b = make_body(1.0, Mat3::Identity());
  b.position = Vec3(1, 1, 0);
  apply_force(b, Vec3(0, 3, 0), Vec3(3, 1, 0));  // r = (2, 0, 0): τ = r × f = (0, 0, 6)
  apply_force(b, Vec3(1, 0, 0));
  apply_torque(b, Vec3(0, 0, -1));
  EXPECT_EQ(b.force, Vec3(1, 3, 0));
  EXPECT_EQ(b.torque, Vec3(0, 0, 5));
}

TEST(ApplyImpulse, ChangesVelocitiesByInverseMassAndInverseInertia) {
  Body b = make_sphere_body(2.0, 1.0);  // I = 0.8 E
  apply_impulse(b, Vec3(0, 4, 0), Vec3(1, 0, 0));  // r × j = (0, 0, 4)
  EXPECT_LT((b.velocity - Vec3(0, 2, 0)).norm(), 1e-15);
  EXPECT_LT((b.angular_velocity - Vec3(0, 0, 5)).norm(), 1e-14);
  apply_angular_impulse(b, Vec3(0.8, 0, 0));
  EXPECT_LT((b.angular_velocity - Vec3(1, 0, 5)).norm(), 1e-14);
  apply_impulse(b, Vec3(2, 0, 0));
  EXPECT_LT((b.velocity - Vec3(1, 2, 0)).norm(), 1e-15);
}

TEST(Momenta, MatchHandComputedValues) {
  Body b = make_sphere_body(2.0, 1.0);  // I = 0.8
  b.velocity = Vec3(3, 0, 0);
  b.angular_velocity = Vec3(0, 0, 1);
  EXPECT_EQ(linear_momentum(b), Vec3(6, 0, 0));
  EXPECT_LT((angular_momentum(b) - Vec3(0, 0, 0.8)).norm(), 1e-15);
  EXPECT_NEAR(kinetic_energy(b), 0.5 * 2 * 9 + 0.5 * 0.8, 1e-14);
}

TEST(Momenta, RotatedBodyUsesTheWorldTensor) {
  Body b = make_body(1.0, Vec3(1, 2, 3).asDiagonal());
  b.orientation = quat_from_axis_angle(Vec3::UnitZ(), pi / 2);  // world moments (2, 1, 3)
  b.angular_velocity = Vec3(1, 1, 1);
  EXPECT_LT((angular_momentum(b) - Vec3(2, 1, 3)).norm(), 1e-14);
  EXPECT_NEAR(kinetic_energy(b), 0.5 * (2 + 1 + 3), 1e-14);
}

TEST(StaticBody, IsImmovableAndReportsInfiniteMass) {
  Body b = make_static_body();
  EXPECT_TRUE(is_static(b));
  EXPECT_TRUE(std::isinf(b.mass));
  EXPECT_EQ(b.inverse_inertia, Mat3::Zero());
  apply_impulse(b, Vec3(1, 2, 3), Vec3(1, 0, 0));
  apply_angular_impulse(b, Vec3(1, 0, 0));
  apply_force(b, Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_EQ(b.velocity, Vec3::Zero());
  EXPECT_EQ(b.angular_velocity, Vec3::Zero());
  EXPECT_EQ(b.force, Vec3::Zero());
  EXPECT_EQ(b.torque, Vec3::Zero());
  EXPECT_EQ(kinetic_energy(b), 0.0);
  EXPECT_EQ(linear_momentum(b), Vec3::Zero());
  b.orientation = quat_from_axis_angle(Vec3(1, 1, 0), 0.3);
  const Mat3 w = world_inertia(b);  // infinite on the diagonal, no NaN from ∞ − ∞
  EXPECT_TRUE(std::isinf(w(0, 0)));
  EXPECT_EQ(w(0, 1), 0.0);
  EXPECT_EQ(inverse_world_inertia(b), Mat3::Zero());
}

TEST(StaticBody, MakeStaticKeepsPlaceAndShape) {
  Body b = make_box_body(1.0, Vec3(2, 2, 2));
  b.position = Vec3(0, -1, 0);
  b.velocity = Vec3(1, 0, 0);
  make_static(b);
  EXPECT_EQ(b.position, Vec3(0, -1, 0));
  EXPECT_EQ(b.velocity, Vec3::Zero());
  EXPECT_EQ(b.shape.kind, ShapeKind::box);
}

}  // namespace
}  // namespace rigidlab
