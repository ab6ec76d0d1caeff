// Tests for engine/spatial, engine/articulation_model and the single-call algorithms of
// engine/articulation against independent references:
//   - spatial algebra: the power m·f is invariant under Plücker transforms; crf = −crmᵀ; the
//     spatial inertia times a velocity is the momentum of Newton and Euler (h = m v_com,
//     L_O = I_c ω + c × h);
//   - RBDL's published forward-dynamics cases (rbdl/rbdl tests/DynamicsTests.cc: single,
//     double, triple chain, 3-D chain and tree; gravity (0, −9.81, 0), each body m = 1 with its
//     COM 1 m out and I_c = E unless said) and their closed forms where short;
//   - the integrators on a prismatic joint under gravity: q = ½ g t² exactly for rk4, and the
//     Euler variants' known sums (003 "Explicit Euler");
//   - bad input refused with the rule stated, and a failed step changes nothing.
#include "engine/articulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "articulation_models.hpp"
#include "engine/aba.hpp"

namespace rigidlab {
namespace {

using Eigen::VectorXd;

// RBDL's DynamicsFixture: gravity (0, −9.81, 0), revolute joints.
LinkSpec rbdl_body(int parent, const Vec3& axis, const Vec3& origin, const Vec3& com,
                   const Mat3& inertia = Mat3::Identity()) {
  LinkSpec spec;
  spec.parent = parent;
  spec.axis = axis;
  spec.origin = origin;
  spec.mass = 1.0;
  spec.com = com;
  spec.inertia = inertia;
  return spec;
}

Articulation rbdl_chain(int n) {
  Articulation art;
  for (int k = 0; k < n; ++k)
    art.add_link(rbdl_body(k - 1, Vec3::UnitZ(), k == 0 ? Vec3::Zero() : Vec3(1, 0, 0),
                           Vec3(1, 0, 0)));
  return art;
}

std::string thrown_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

// ---- spatial algebra ------------------------------------------------------------------------

TEST(Spatial, PowerIsInvariantUnderPluckerTransforms) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const PluckerTransform X{
        quat_from_axis_angle(test::random_vec3(rng) + Vec3(0, 0, 1e-3), 2.0).toRotationMatrix(),
        test::random_vec3(rng, 2.0)};
    const Vec6 m = spatial(test::random_vec3(rng), test::random_vec3(rng));
    const Vec6 f = spatial(test::random_vec3(rng), test::random_vec3(rng));
    EXPECT_NEAR(X.apply_motion(m).dot(X.apply_force(f)), m.dot(f), 1e-13);
    EXPECT_LT((X.matrix() * m - X.apply_motion(m)).norm(), 1e-14);
    EXPECT_LT((X.matrix().transpose() * f - X.transpose_force(f)).norm(), 1e-14);
    EXPECT_LT((X.inverse_motion(X.apply_motion(m)) - m).norm(), 1e-14);
    EXPECT_LT((X.inverse().matrix() * X.matrix() - Mat6::Identity()).norm(), 1e-14);
    const PluckerTransform Y{X.E.transpose(), test::random_vec3(rng)};
    EXPECT_LT(((Y * X).matrix() - Y.matrix() * X.matrix()).norm(), 1e-14);
    const Mat6 I = rigid_body_inertia(1.5, test::random_vec3(rng), test::random_inertia(rng, 1.5));
    EXPECT_LT((inertia_to_parent(X, I) - X.matrix().transpose() * I * X.matrix()).norm(), 1e-13);
    EXPECT_LT((crm_matrix(m) * f - crm(m, f)).norm(), 1e-15);
    EXPECT_LT((-crm_matrix(m).transpose() * f - crf(m, f)).norm(), 1e-15);  // crf = −crmᵀ
  }
}

TEST(Spatial, InertiaTimesVelocityIsNewtonEulerMomentum) {
  const double m = 2.0;
  const Vec3 c(0.3, -0.2, 0.5), w(1.0, 2.0, -0.5), v_origin(0.4, 0.1, -0.3);
  const Mat3 Ic = Vec3(0.2, 0.3, 0.4).asDiagonal();
  const Vec6 h = rigid_body_inertia(m, c, Ic) * spatial(w, v_origin);
  const Vec3 linear = m * (v_origin + w.cross(c));  // m v_com
  EXPECT_LT((bottom(h) - linear).norm(), 1e-15);
  EXPECT_LT((top(h) - (Ic * w + c.cross(linear))).norm(), 1e-15);
}

TEST(Spatial, RotationCoordinatesMatchFeatherstonesRotz) {
  const double t = 0.7;
  Mat3 rotz;  // RBDA eq. 2.19
  rotz << std::cos(t), std::sin(t), 0, -std::sin(t), std::cos(t), 0, 0, 0, 1;
  EXPECT_LT((rotation_coordinates(Vec3::UnitZ(), t) - rotz).norm(), 1e-15);
}

// ---- RBDL's published cases -----------------------------------------------------------------

TEST(RbdlCases, SingleChainAtRest) {
  Articulation art = rbdl_chain(1);
  art.set_gravity(Vec3(0, -9.81, 0));
  const double qdd = art.forward_dynamics(VectorXd::Zero(1))[0];
  EXPECT_NEAR(qdd, -4.905, 1e-14);
  // Closed form: −m g L / (I_zz + m L²) = −9.81 / 2.
  EXPECT_NEAR(qdd, -9.81 / 2.0, 1e-14);
}

TEST(RbdlCases, SingleChainWithSpatialInertia) {
  Articulation art;
  art.add_link(rbdl_body(-1, Vec3::UnitZ(), Vec3::Zero(), Vec3(1.5, 1, 1),
                         Vec3(1, 2, 3).asDiagonal()));
  // RBDL: −2.3544; closed form: −m g c_x / (I_zz + m (c_x² + c_y²)) = −14.715 / 6.25.
  const double qdd = art.forward_dynamics(VectorXd::Zero(1))[0];
  EXPECT_NEAR(qdd, -2.3544, 1e-13);
  EXPECT_NEAR(qdd, -1.5 * 9.81 / 6.25, 1e-14);
}

TEST(RbdlCases, DoubleAndTripleChain) {
  Articulation two = rbdl_chain(2);
  const VectorXd qdd2 = two.forward_dynamics(VectorXd::Zero(2));
  EXPECT_NEAR(qdd2[0], -5.886, 1e-13);
  EXPECT_NEAR(qdd2[1], 3.924, 1e-13);
  Articulation three = rbdl_chain(3);
  const VectorXd qdd3 = three.forward_dynamics(VectorXd::Zero(3));
  EXPECT_NEAR(qdd3[0], -6.03692307692308, 1e-13);
  EXPECT_NEAR(qdd3[1], 3.77307692307692, 1e-13);
  EXPECT_NEAR(qdd3[2], 1.50923076923077, 1e-13);
}

TEST(RbdlCases, DoubleChain3D) {
  Articulation art;
  art.add_link(rbdl_body(-1, Vec3::UnitZ(), Vec3::Zero(), Vec3(1, 0, 0)));
  art.add_link(rbdl_body(0, Vec3::UnitY(), Vec3(1, 0, 0), Vec3(0, 1, 0)));
  const VectorXd qdd = art.forward_dynamics(VectorXd::Zero(2));
  EXPECT_NEAR(qdd[0], -3.924, 1e-13);
  EXPECT_NEAR(qdd[1], 0.0, 1e-13);
}

TEST(RbdlCases, SimpleTree3D) {
  Articulation art;
  art.add_link(rbdl_body(-1, Vec3::UnitZ(), Vec3::Zero(), Vec3(1, 0, 0)));         // a
  art.add_link(rbdl_body(0, Vec3::UnitY(), Vec3(1, 0, 0), Vec3(0, 1, 0)));         // b1
  art.add_link(rbdl_body(1, Vec3::UnitX(), Vec3(0, 1, 0), Vec3(0, 0, 1)));         // c1
  art.add_link(rbdl_body(0, Vec3::UnitY(), Vec3(-0.5, 0, 0), Vec3(0, 1, 0)));      // b2
  art.add_link(rbdl_body(3, Vec3::UnitX(), Vec3(0, -0.5, 0), Vec3(0, 0, 1)));      // c2
  const VectorXd qdd = art.forward_dynamics(VectorXd::Zero(5));
  const double want[5] = {-1.60319066147860E+00, -5.34396887159533E-01, 4.10340466926070E+00,
                          2.67198443579767E-01, 5.30579766536965E+00};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(qdd[k], want[k], 1e-13) << "joint " << k + 1;
}

// A free base carrying one rigid body falls with g and does not turn; a free body with spin
// about a principal axis keeps it.
TEST(FreeBase, SingleBodyFallsWithGravity) {
  Articulation art(BaseType::free, Vec3(1, 2, 3));
  LinkSpec spec;
  spec.joint = JointType::fixed;
  spec.mass = 2.0;
  spec.com = Vec3(0.3, 0.1, -0.2);
  spec.inertia = Vec3(0.1, 0.2, 0.25).asDiagonal();
  art.add_link(spec);
  const VectorXd qdd = art.forward_dynamics(VectorXd::Zero(6));
  EXPECT_LT((qdd.head<3>() - Vec3(0, -9.81, 0)).norm(), 1e-14);
  EXPECT_LT(qdd.segment<3>(3).norm(), 1e-14);
}

// ---- integrators: a prismatic joint along gravity, q̈ = g exactly ---------------------------

double slide_after(Integrator integrator, double dt, int steps) {
  Articulation art;
  LinkSpec spec;
  spec.joint = JointType::prismatic;
  spec.axis = Vec3(0, -1, 0);
  spec.inertia = Mat3::Identity();
  art.add_link(spec);
  art.set_integrator(integrator);
  art.step(dt, steps);
  EXPECT_NEAR(art.time(), dt * steps, 1e-12);
  return art.q()[0];
}

TEST(Integrators, ConstantAccelerationClosedForms) {
  const double g = 9.81, dt = 0.1;
  const int n = 10;
  // Explicit Euler: q_n = g dt² n(n−1)/2; semi-implicit: g dt² n(n+1)/2; RK4: ½ g t².
  EXPECT_NEAR(slide_after(Integrator::euler, dt, n), g * dt * dt * n * (n - 1) / 2, 1e-12);
  EXPECT_NEAR(slide_after(Integrator::semi_implicit, dt, n), g * dt * dt * n * (n + 1) / 2,
              1e-12);
  EXPECT_NEAR(slide_after(Integrator::rk4, dt, n), 0.5 * g * 1.0, 1e-12);
}

// θ(1 s) of a rod pendulum released from 1 rad; orders measured against RK4 at 0.1 ms (whose
// own error, ~1e-16, is far below the others'): ≈ 1, 1, 4.
double pendulum_angle(Integrator integrator, double dt) {
  Articulation art = test::rod_chain(1);
  art.set_integrator(integrator);
  art.set_state(VectorXd::Constant(1, 1.0), VectorXd::Zero(1));
  art.step(dt, static_cast<int>(std::lround(1.0 / dt)));
  return art.q()[0];
}

TEST(Integrators, MeasuredOrders) {
  const double reference = pendulum_angle(Integrator::rk4, 1e-4);
  auto order = [reference](Integrator method, double dt) {
    return std::log2(std::abs(pendulum_angle(method, dt) - reference) /
                     std::abs(pendulum_angle(method, dt / 2) - reference));
  };
  EXPECT_NEAR(order(Integrator::euler, 1e-4), 1.0, 0.05);
  EXPECT_NEAR(order(Integrator::semi_implicit, 1e-4), 1.0, 0.05);
  EXPECT_NEAR(order(Integrator::rk4, 0.02), 4.0, 0.15);
}

// ---- growing a model that is moving ---------------------------------------------------------

TEST(AddLink, AppendsZeroCoordinatesAndKeepsTheState) {
  Articulation art(BaseType::free);
  LinkSpec body;
  body.joint = JointType::fixed;
  body.inertia = Mat3::Identity();
  art.add_link(body);
  VectorXd q(7), v(6);
  q << 1, 2, 3, 0, 1, 0, 0;
  v << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
  art.set_state(q, v);
  art.set_torques((VectorXd(6) << 1, 0, 0, 0, 0, 0).finished());
  LinkSpec arm;
  arm.parent = 0;
  arm.com = Vec3(0.5, 0, 0);
  art.add_link(arm);
  EXPECT_EQ(art.q().head(7), q);
  EXPECT_EQ(art.q()[7], 0.0);
  EXPECT_EQ(art.v().head(6), v);
  EXPECT_EQ(art.v()[6], 0.0);
  EXPECT_EQ(art.torques()[0], 1.0);
  EXPECT_EQ(art.torques()[6], 0.0);
  EXPECT_EQ(art.model().links()[1].q_index, 7);
  EXPECT_EQ(art.model().links()[1].v_index, 6);
  art.step(0.01);  // the grown workspace and scratch vectors are used
  EXPECT_TRUE(art.q().allFinite());
}

// ---- bad input --------------------------------------------------------------------------------

TEST(BadInput, LinksRefusedWithTheRule) {
  Articulation art;
  LinkSpec spec;
  spec.parent = 0;
  EXPECT_EQ(thrown_message([&] { art.add_link(spec); }),
            "parent must be the base (nil): the articulation has no links yet");
  spec.parent = -1;
  art.add_link(spec);
  spec.parent = 3;
  EXPECT_EQ(thrown_message([&] { art.add_link(spec); }),
            "parent must be the base (nil) or one of the links 1 to 1 of this articulation, "
            "got link 4");
  spec.parent = 0;
  spec.axis = Vec3::Zero();
  EXPECT_EQ(thrown_message([&] { art.add_link(spec); }),
            "axis must be non-zero for a revolute joint, got (0, 0, 0)");
  spec.axis = Vec3::UnitX();
  spec.mass = -1;
  EXPECT_EQ(thrown_message([&] { art.add_link(spec); }), "mass must be finite and >= 0, got -1");
  spec.mass = 1;
  spec.inertia = Vec3(1, 1, 3).asDiagonal();
  EXPECT_NE(thrown_message([&] { art.add_link(spec); }).find("inertia is not a valid tensor"),
            std::string::npos);
  spec.inertia.setZero();
  spec.name = "arm";
  art.add_link(spec);
  EXPECT_EQ(thrown_message([&] { art.add_link(spec); }),
            "name must be unique: link 2 is already called 'arm'");
  EXPECT_EQ(art.model().link_count(), 2);  // the refused links changed nothing
  EXPECT_EQ(art.model().nv(), 2);
  EXPECT_FALSE(parse_joint_type("hinge").has_value());
  EXPECT_EQ(parse_joint_type("prismatic"), JointType::prismatic);
}

TEST(BadInput, StatesAndTorquesOfWrongLength) {
  Articulation art = test::rod_chain(2);
  EXPECT_EQ(thrown_message([&] { art.set_state(VectorXd::Zero(3), VectorXd::Zero(2)); }),
            "q must have 2 entries (one per moving joint), got 3");
  EXPECT_EQ(thrown_message([&] { art.set_torques(VectorXd::Zero(1)); }),
            "tau must have 2 entries (one per velocity coordinate), got 1");
  VectorXd q = VectorXd::Zero(2);
  q[1] = NAN;
  EXPECT_EQ(thrown_message([&] { art.set_state(q, VectorXd::Zero(2)); }),
            "q[2] must be finite, got nan");
  Articulation floating(BaseType::free);
  VectorXd q7 = VectorXd::Zero(7);
  q7[3] = 2.0;
  EXPECT_EQ(thrown_message([&] { floating.set_state(q7, VectorXd::Zero(6)); }),
            "q[4..7] (the base orientation w, x, y, z) must be a unit quaternion, got length 2");
  EXPECT_EQ(thrown_message([&] { art.step(0.0); }), "dt must be finite and > 0, got 0");
  EXPECT_EQ(thrown_message([&] { art.jacobian(2, Vec3::Zero()); }),
            "link must be one of the links 1 to 2, got 3");
  EXPECT_THROW(Articulation(BaseType::fixed, Vec3::Zero(), Quat(2, 0, 0, 0)),
               std::invalid_argument);
}

TEST(BadInput, MasslessLastLinkIsSingular) {
  Articulation art = test::rod_chain(1);
  LinkSpec massless;
  massless.parent = 0;
  massless.mass = 0.0;
  art.add_link(massless);
  EXPECT_NE(thrown_message([&] { art.forward_dynamics(VectorXd::Zero(2)); })
                .find("link 2 has no inertia about its revolute joint"),
            std::string::npos);
  const VectorXd q = art.q();
  EXPECT_THROW(art.step(0.01), ArticulationStepError);
  EXPECT_EQ(art.q(), q);
  EXPECT_EQ(art.time(), 0.0);
}

TEST(BadInput, MasslessFreeBaseIsSingular) {
  Articulation art(BaseType::free);
  LinkSpec spec;
  spec.mass = 1.0;
  spec.com = Vec3(1, 0, 0);
  art.add_link(spec);  // one revolute link: nothing resists the base turning about the axis
  EXPECT_NE(thrown_message([&] { art.forward_dynamics(VectorXd::Zero(7)); })
                .find("the free base has no inertia in some direction"),
            std::string::npos);
}

TEST(BadInput, AFailingControlLeavesTheStateAsItWas) {
  Articulation art = test::rod_chain(2);
  art.set_integrator(Integrator::rk4);
  art.set_state(VectorXd::Constant(2, 0.5), VectorXd::Constant(2, 0.1));
  int calls = 0;
  art.add_control([&](double, VectorXd&) {
    if (++calls == 3) throw std::runtime_error("control failed");
  });
  const VectorXd q = art.q(), v = art.v();
  EXPECT_EQ(thrown_message([&] { art.step(0.01); }), "control failed");
  EXPECT_EQ(art.q(), q);
  EXPECT_EQ(art.v(), v);
  EXPECT_EQ(art.time(), 0.0);
  EXPECT_FALSE(art.stepping());
}

TEST(BadInput, ControlsCannotReenter) {
  Articulation art = test::rod_chain(1);
  std::string inner;
  art.add_control([&](double, VectorXd&) {
    inner = thrown_message([&] { art.forward_dynamics(); });
    inner += " | " + thrown_message([&] { art.step(0.1); });
  });
  art.step(0.01);
  EXPECT_NE(inner.find("a control cannot ask for the controls' torques"), std::string::npos);
  EXPECT_NE(inner.find("the articulation is stepping: cannot step"), std::string::npos);
}

}  // namespace
}  // namespace rigidlab
