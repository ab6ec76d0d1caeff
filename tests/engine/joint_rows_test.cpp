// engine/joint.hpp's rows against document 000's table of kinematic pairs ("Kinematic pair"):
// for every joint type at a random pose, each free relative motion of the DOF table (a twist
// of body a relative to b) gives J v = 0 on every row (the joint does no work along it: the
// free motion is untouched), the constrained motions give the rows full rank (every other
// motion is resisted), and a common rigid motion of both bodies moves no row. Then through a
// world: random impulses, one step of sequential_impulses with many sweeps, and the solver's
// own measure of the rows' velocity error converges to 1e-9 while the constrained relative
// velocities of the DOF table vanish to O(h) (the rows aim at the end of the step: see
// engine/solver.cpp, "the curvature"); limits hold; a screw advances `pitch` per turn.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "engine/joint.hpp"
#include "engine/world.hpp"

namespace rigidlab {
namespace {

struct Twist {
  Vec3 v, w;  // velocity of a's COM, angular velocity
};

std::mt19937 rng(14);
double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
Vec3 random_vec(double scale = 1.0) { return scale * Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)); }
Quat random_quat() { return Quat(Eigen::AngleAxisd(uniform(0, 3), random_vec().normalized())); }

Body random_body() {
  const Vec3 d(uniform(1, 1.5), uniform(1, 1.5), uniform(1, 1.5));  // A + B >= C
  Body b = make_body(uniform(0.5, 3), d.asDiagonal());
  b.position = random_vec(2.0);
  b.orientation = random_quat();
  return b;
}

// A rotation of a about axis k through point p, and a translation along d.
Twist rotation_about(const Vec3& k, const Vec3& p, const Body& a) { return {k.cross(a.position - p), k}; }
Twist translation(const Vec3& d) { return {d, Vec3::Zero()}; }

// The DOF table: the free relative motions of a (b at rest) at the joint's present pose, and
// the constrained ones (the rest of the six), for the anchor p, unit axis u and p1, p2 across.
void motions(JointKind kind, const Body& a, const Vec3& p, const Vec3& u, const Vec3& end_b,
             double pitch, std::vector<Twist>& free, std::vector<Twist>& held) {
  const Vec3 p1 = u.unitOrthogonal(), p2 = u.cross(p1);
  const Vec3 e[3] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  free.clear(), held.clear();
  switch (kind) {
    case JointKind::ball:
      for (const Vec3& k : e) free.push_back(rotation_about(k, p, a)), held.push_back(translation(k));
      break;
    case JointKind::hinge:
      free = {rotation_about(u, p, a)};
      held = {translation(e[0]), translation(e[1]), translation(e[2]), rotation_about(p1, p, a),
              rotation_about(p2, p, a)};
      break;
    case JointKind::slider:
      free = {translation(u)};
      held = {translation(p1), translation(p2), rotation_about(e[0], p, a),
              rotation_about(e[1], p, a), rotation_about(e[2], p, a)};
      break;
    case JointKind::cylindrical:
      free = {rotation_about(u, p, a), translation(u)};
      held = {translation(p1), translation(p2), rotation_about(p1, p, a), rotation_about(p2, p, a)};
      break;
    case JointKind::planar:
      free = {translation(p1), translation(p2), rotation_about(u, p, a)};
      held = {translation(u), rotation_about(p1, p, a), rotation_about(p2, p, a)};
      break;
    case JointKind::screw: {
      Twist t = rotation_about(u, p, a);
      t.v += pitch / (2.0 * M_PI) * u;
      free = {t};
      held = {translation(p1), translation(p2), rotation_about(p1, p, a), rotation_about(p2, p, a),
              translation(u)};
      break;
    }
    case JointKind::fixed:
      for (const Vec3& k : e) held.push_back(translation(k)), held.push_back(rotation_about(k, p, a));
      break;
    case JointKind::distance: {  // p: a's end; end_b: b's end
      const Vec3 d = (p - end_b).normalized();
      const Vec3 q1 = d.unitOrthogonal(), q2 = d.cross(q1);
      for (const Vec3& k : e) free.push_back(rotation_about(k, p, a));
      free.push_back(translation(q1)), free.push_back(translation(q2));
      held = {translation(d)};
      break;
    }
  }
}

double row_rate(const JointRow& r, const Twist& ta, const Twist& tb) {
  return r.jacobian.linear.dot(tb.v - ta.v) + r.jacobian.angular_b.dot(tb.w) -
         r.jacobian.angular_a.dot(ta.w);
}

struct Made {
  std::unique_ptr<Joint> joint;
  Body a, b;
  JointDef def;
  // b's end of a distance joint (world)
  Vec3 end_b(bool to_world) const { return to_world ? def.b_point : to_world_point(b, def.b_point); }
  static Vec3 to_world_point(const Body& body, const Vec3& p) { return rigidlab::to_world(body, p); }
};

Made make(JointKind kind, bool to_world) {
  Made m;
  m.a = random_body();
  m.b = random_body();
  JointDef def;
  def.type = kind;
  def.a = BodyId{0, 0};
  def.b = to_world ? no_body_id : BodyId{1, 0};
  def.anchor = random_vec(2.0);
  def.axis = random_vec();
  def.pitch = kind == JointKind::screw ? 0.3 : 0.0;
  def.a_point = random_vec(0.5);
  def.b_point = random_vec(0.5);
  m.joint = std::make_unique<Joint>(def, m.a, to_world ? nullptr : &m.b);
  m.def = def;
  return m;
}

// Moves a by the finite screw motion of twist t scaled by s (rotation about the twist's axis
// and travel along it).
void move_along(Body& a, const Twist& t, double s) {
  const double w = t.w.norm();
  if (w == 0.0) {
    a.position += s * t.v;
    return;
  }
  const Vec3 k = t.w / w;
  const Vec3 c = a.position + t.w.cross(t.v) / (w * w);  // a point on the axis
  const Quat r(Eigen::AngleAxisd(s * w, k));
  a.position = c + r * (a.position - c) + s * k.dot(t.v) * k;
  a.orientation = r * a.orientation;
}

TEST(JointRows, FreeMotionsMoveNoRowAndHeldOnesAreAllResisted) {
  for (int k = 0; k < joint_kind_count; ++k)
    for (bool to_world : {true, false})
      for (int trial = 0; trial < 5; ++trial) {
        const JointKind kind = static_cast<JointKind>(k);
        Made m = make(kind, to_world);
        const Body* b = to_world ? nullptr : &m.b;
        const int n = m.joint->row_count();
        std::vector<JointRow> rows(static_cast<std::size_t>(n));
        std::vector<Twist> free, held;
        const std::string what = std::string(joint_kind_names[k]) + (to_world ? " to the world" : "");
        // A finite move along each free motion (a distance joint's ends only turn: a finite
        // sideways step would change its length), then the table at the new pose.
        double turned = 0.0, travelled = 0.0;
        const std::size_t moves = kind == JointKind::distance ? 3 : 6;
        for (std::size_t i = 0; i < moves; ++i) {
          motions(kind, m.a, m.joint->world_anchor(m.a), m.joint->world_axis(b), m.end_b(to_world),
                  m.def.pitch, free, held);
          if (i >= free.size()) break;
          const double amount = uniform(-2.5, 2.5);
          move_along(m.a, free[i], amount);
          m.joint->track(m.a, b);
          if (free[i].w.isZero()) travelled += amount;
          else turned += amount;
        }
        m.joint->build_rows(m.a, b, rows.data());
        for (const JointRow& r : rows) EXPECT_NEAR(r.error, 0.0, 1e-12) << what << ": still holds";
        if (kind == JointKind::hinge || kind == JointKind::screw)
          EXPECT_NEAR(m.joint->angle(m.a, b), turned, 1e-12) << what << ": the angle turned";
        if (kind == JointKind::slider)
          EXPECT_NEAR(m.joint->offset(m.a, b), travelled, 1e-12) << what << ": the offset";
        if (kind == JointKind::screw)
          EXPECT_NEAR(m.joint->offset(m.a, b), 0.3 * turned / (2 * M_PI), 1e-12) << what;
        if (kind == JointKind::cylindrical) {
          EXPECT_NEAR(m.joint->angle(m.a, b), turned, 1e-12) << what;
          EXPECT_NEAR(m.joint->offset(m.a, b), travelled, 1e-12) << what;
        }
        motions(kind, m.a, m.joint->world_anchor(m.a), m.joint->world_axis(b), m.end_b(to_world),
                m.def.pitch, free, held);
        const Twist rest{Vec3::Zero(), Vec3::Zero()};
        for (const Twist& t : free)
          for (const JointRow& r : rows) EXPECT_NEAR(row_rate(r, t, rest), 0.0, 1e-12) << what;
        Eigen::MatrixXd resisted(n, static_cast<int>(held.size()));
        for (int i = 0; i < n; ++i)
          for (std::size_t j = 0; j < held.size(); ++j)
            resisted(i, static_cast<int>(j)) = row_rate(rows[static_cast<std::size_t>(i)], held[j], rest);
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(resisted);
        svd.setThreshold(1e-9);
        EXPECT_EQ(svd.rank(), static_cast<long>(held.size())) << what;
        EXPECT_EQ(n, static_cast<int>(held.size())) << what << ": one row per held motion";
        if (!to_world) {  // both bodies in one rigid motion: no row moves
          const Vec3 w = random_vec(), v = random_vec();
          const Twist ta{v + w.cross(m.a.position), w}, tb{v + w.cross(m.b.position), w};
          for (const JointRow& r : rows) EXPECT_NEAR(row_rate(r, ta, tb), 0.0, 1e-12) << what;
        }
      }
}

// Random impulses on both bodies, one step: the solver's sweeps converge (its own measure,
// |J v + target| of every row, below 1e-9 at the last sweep), and the rows rebuilt at the end
// of the step see relative velocities of O(h) only.
TEST(JointRows, RandomImpulsesAreSolvedInEveryType) {
  for (SolverKind solver : {SolverKind::sequential_impulses, SolverKind::soft_step})
    for (int k = 0; k < joint_kind_count; ++k)
      for (bool to_world : {true, false}) {
        const JointKind kind = static_cast<JointKind>(k);
        World w;
        w.set_solver(solver);
        w.set_gravity(Vec3::Zero());
        ContactSettings settings = w.contact_settings();
        settings.iterations = 200;
        w.set_contact_settings(settings);
        Made m = make(kind, to_world);
        m.def.a = w.add(m.a);
        m.def.b = to_world ? no_body_id : w.add(m.b);
        w.add_constraint(std::make_unique<Joint>(m.def, w.store().get(m.def.a),
                                                 to_world ? nullptr : &w.store().get(m.def.b)));
        for (Body& body : w.bodies()) {
          apply_impulse(body, random_vec(), body.position + random_vec(0.5));
          apply_angular_impulse(body, random_vec());
        }
        const double h = 1e-3;
        w.step(h);
        const std::string what = std::string(solver_names[static_cast<int>(solver)]) + " " +
                                 joint_kind_names[k] + (to_world ? " to the world" : "");
        EXPECT_LT(w.solver_report().back(), 1e-9) << what;
        const Joint& j = static_cast<const Joint&>(w.constraint(0));
        const Body& a = w.bodies()[0];
        const Body* b = to_world ? nullptr : &w.bodies()[1];
        std::vector<JointRow> rows(static_cast<std::size_t>(j.row_count()));
        j.build_rows(a, b, rows.data());
        const Twist ta{a.velocity, a.angular_velocity};
        const Twist tb = b != nullptr ? Twist{b->velocity, b->angular_velocity}
                                      : Twist{Vec3::Zero(), Vec3::Zero()};
        for (const JointRow& r : rows) EXPECT_LT(std::abs(row_rate(r, ta, tb)), 20 * h) << what;
      }
}

TEST(JointLimits, LimitsHoldAgainstAPush) {
  for (SolverKind solver : {SolverKind::soft_step, SolverKind::sequential_impulses}) {
    World w;
    w.set_solver(solver);
    w.set_gravity(Vec3::Zero());
    Body slider = make_body(1.0, 0.01 * Mat3::Identity());  // no shapes: no contacts
    slider.velocity = Vec3(2, 0, 0);
    JointDef def;
    def.type = JointKind::slider;
    def.a = w.add(slider);
    def.axis = Vec3::UnitX();
    def.lower = -0.1, def.upper = 0.25;
    Joint& s = static_cast<Joint&>(w.add_constraint(std::make_unique<Joint>(def, w.bodies()[0], nullptr)));
    Body wheel = make_body(1.0, Vec3(0.01, 0.08, 0.08).asDiagonal());
    wheel.angular_velocity = Vec3(0, 0, -4);
    def.type = JointKind::hinge;
    def.a = w.add(wheel);
    def.axis = Vec3::UnitZ();
    def.anchor = w.bodies()[1].position;
    def.lower = -1.0, def.upper = 0.5;
    Joint& hinge = static_cast<Joint&>(w.add_constraint(std::make_unique<Joint>(def, w.bodies()[1], nullptr)));
    double highest = 0.0, lowest = 0.0;
    for (int step = 0; step < 120; ++step) {
      if (step == 60) {  // push the other way
        w.bodies()[0].velocity = Vec3(-2, 0, 0);
        w.bodies()[1].angular_velocity = Vec3(0, 0, 4);
      }
      w.step(1.0 / 60.0);
      const double x = s.offset(w.bodies()[0], nullptr), angle = hinge.angle(w.bodies()[1], nullptr);
      highest = std::max(highest, x);
      lowest = std::min(lowest, angle);
      EXPECT_LE(x, 0.25 + 0.005) << solver_names[static_cast<int>(solver)];
      EXPECT_GE(x, -0.1 - 0.005);
      EXPECT_LE(angle, 0.5 + 0.005);
      EXPECT_GE(angle, -1.0 - 0.005);
    }
    EXPECT_GT(highest, 0.24);   // it did reach the stop
    EXPECT_LT(lowest, -0.99);
  }
}

TEST(JointScrew, AdvancesPitchPerTurn) {
  World w;
  w.set_gravity(Vec3::Zero());
  Body nut = make_body(1.0, Mat3::Identity());
  nut.angular_velocity = Vec3(0, 3, 0);
  JointDef def;
  def.type = JointKind::screw;
  def.a = w.add(nut);
  def.axis = Vec3::UnitY();
  def.pitch = 0.05;
  Joint& screw = static_cast<Joint&>(w.add_constraint(std::make_unique<Joint>(def, w.bodies()[0], nullptr)));
  w.step(1.0 / 60.0, 300);
  const double angle = screw.angle(w.bodies()[0], nullptr);
  EXPECT_GT(angle, 4 * M_PI);  // two turns and more
  EXPECT_NEAR(screw.offset(w.bodies()[0], nullptr), 0.05 * angle / (2 * M_PI), 1e-6);
  EXPECT_NEAR(w.bodies()[0].position.y(), 0.05 * angle / (2 * M_PI), 1e-6);
}

}  // namespace
}  // namespace rigidlab
