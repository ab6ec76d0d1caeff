// engine/joint_tree.hpp, the exact solve of joint trees (Baraff 1996), against references
// independent of it: a dense solve of the same system (K + Γ) Δλ = −(J v + b + Γ λ) assembled
// entry by entry from the rows' Jacobians on random trees of random bodies; the rows' velocity
// after one sweep in a world; issue 14's chain (joint position error and energy); and a closed
// ring, whose loop-closing joint stays with Gauss-Seidel.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "engine/joint.hpp"
#include "engine/joint_tree.hpp"
#include "engine/world.hpp"

namespace rigidlab {
namespace {

Joint& add_joint(World& w, const JointDef& def) {
  const Body& a = w.store().get(def.a);
  const Body* b = def.b.valid() ? &w.store().get(def.b) : nullptr;
  return static_cast<Joint&>(w.add_constraint(std::make_unique<Joint>(def, a, b)));
}

// ---- the tree solve against a dense solve ------------------------------------------------------

struct RandomJoint {
  std::uint32_t a, b;
  std::vector<Jacobian> rows;
};

Vec3 random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

SolverBody random_body(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.2, 5.0);
  SolverBody b;
  b.inverse_mass = u(rng);
  const Mat3 r = Quat(Eigen::AngleAxisd(u(rng), random_vector(rng, 1.0).normalized())).toRotationMatrix();
  b.inverse_inertia = r * Vec3(u(rng), u(rng), u(rng)).asDiagonal() * r.transpose();
  b.velocity = random_vector(rng, 3.0);
  b.angular_velocity = random_vector(rng, 3.0);
  return b;
}

// A joint's equality rows as the joints build them: a rod (1 row along a direction), a ball
// (3 point rows), a hinge (3 point rows and 2 angular rows), a fixed joint (3 + 3).
std::vector<Jacobian> random_rows(std::mt19937& rng, int kind) {
  const Vec3 ra = random_vector(rng, 0.6), rb = random_vector(rng, 0.6);
  const Mat3 frame =
      Quat(Eigen::AngleAxisd(1.0 + kind, random_vector(rng, 1.0).normalized())).toRotationMatrix();
  std::vector<Jacobian> rows;
  if (kind == 0) return {point_jacobian(frame.col(0), ra, rb)};
  for (int i = 0; i < 3; ++i) rows.push_back(point_jacobian(frame.col(i), ra, rb));
  const int angular = kind == 2 ? 2 : kind == 3 ? 3 : 0;
  for (int i = 0; i < angular; ++i) rows.push_back(angular_jacobian(frame.col(i)));
  return rows;
}

TEST(JointTree, MatchesADenseSolveOnRandomTrees) {
  std::mt19937 rng(14);
  double worst_impulse = 0.0, worst_residual = 0.0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 12;
    // slots 0..n−1 dynamic, n a static body, n+1 the ground
    std::vector<SolverBody> bodies;
    for (int i = 0; i < n; ++i) bodies.push_back(random_body(rng));
    bodies.push_back(SolverBody{});
    bodies.push_back(SolverBody{});
    std::vector<RandomJoint> joints;
    for (int i = 0; i < n; ++i) {
      // each body to an earlier one or to the world / the static body (a leaf joint)
      std::uniform_int_distribution<int> pick(i == 0 ? -2 : -1, i - 1);
      const int p = pick(rng);
      const std::uint32_t other = p >= 0 ? static_cast<std::uint32_t>(p) : static_cast<std::uint32_t>(n + 2 + p);
      std::uniform_int_distribution<int> kind(0, 3);
      const int k = kind(rng);
      joints.push_back({static_cast<std::uint32_t>(i), other, random_rows(rng, k)});
      if (i % 4 == 0) std::swap(joints.back().a, joints.back().b);  // either side may be the world
    }
    const double compliance = trial % 2 == 0 ? 0.0 : 0.01 * (1 + trial % 7);

    JointTree tree;
    tree.clear(bodies.size());
    // Joints that would close a loop through the world (a second world joint in a tree) are
    // refused: the reference is the system of the joints taken.
    std::vector<RandomJoint> taken;
    for (const RandomJoint& j : joints)
      if (tree.offer(j.a, j.b, j.rows.data(), static_cast<int>(j.rows.size()), bodies.data()))
        taken.push_back(j);
    joints = taken;
    tree.order();
    JointTree::Factor f;
    tree.factor(bodies.data(), compliance, f);
    ASSERT_TRUE(f.valid) << "trial " << trial << " n " << n << " joints " << joints.size();

    // The dense system: J (rows x 6n), W, K = J W Jᵀ, Γ = c blockdiag(K_jj).
    const int m = static_cast<int>(tree.row_count());
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, 6 * n), W = Eigen::MatrixXd::Zero(6 * n, 6 * n);
    Eigen::VectorXd v(6 * n);
    for (int i = 0; i < n; ++i) {
      W.block<3, 3>(6 * i, 6 * i) = bodies[i].inverse_mass * Mat3::Identity();
      W.block<3, 3>(6 * i + 3, 6 * i + 3) = bodies[i].inverse_inertia;
      v.segment<3>(6 * i) = bodies[i].velocity;
      v.segment<3>(6 * i + 3) = bodies[i].angular_velocity;
    }
    std::vector<int> first;
    int row = 0;
    for (const RandomJoint& j : joints) {
      first.push_back(row);
      for (const Jacobian& jac : j.rows) {
        if (j.a < static_cast<std::uint32_t>(n)) {
          J.block<1, 3>(row, 6 * j.a) = -jac.linear.transpose();
          J.block<1, 3>(row, 6 * j.a + 3) = -jac.angular_a.transpose();
        }
        if (j.b < static_cast<std::uint32_t>(n)) {
          J.block<1, 3>(row, 6 * j.b) = jac.linear.transpose();
          J.block<1, 3>(row, 6 * j.b + 3) = jac.angular_b.transpose();
        }
        ++row;
      }
    }
    const Eigen::MatrixXd K = J * W * J.transpose();
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(m, m);
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const int s = static_cast<int>(joints[k].rows.size());
      G.block(first[k], first[k], s, s) = compliance * K.block(first[k], first[k], s, s);
    }
    Eigen::VectorXd bias = Eigen::VectorXd::Random(m), impulse = Eigen::VectorXd::Random(m);
    const Eigen::VectorXd change = (K + G).ldlt().solve(-(J * v + bias + G * impulse));
    const Eigen::VectorXd v_after = v + W * J.transpose() * change;

    Eigen::VectorXd tree_impulse = impulse;
    tree.solve(f, bodies.data(), bias.data(), tree_impulse.data());
    const double scale = 1.0 + change.cwiseAbs().maxCoeff();
    worst_impulse = std::max(worst_impulse, (tree_impulse - impulse - change).cwiseAbs().maxCoeff() / scale);
    Eigen::VectorXd v_tree(6 * n);
    for (int i = 0; i < n; ++i) {
      v_tree.segment<3>(6 * i) = bodies[i].velocity;
      v_tree.segment<3>(6 * i + 3) = bodies[i].angular_velocity;
    }
    EXPECT_LT((v_tree - v_after).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + v_after.cwiseAbs().maxCoeff()))
        << "trial " << trial;
    // The rows reach their targets: J v' + b + Γ λ' = 0.
    worst_residual =
        std::max(worst_residual, (J * v_tree + bias + G * tree_impulse).cwiseAbs().maxCoeff());
  }
  std::printf("tree vs dense: impulses agree to %.2g (relative), J v' + b + Γλ' = %.2g\n",
              worst_impulse, worst_residual);
  EXPECT_LT(worst_impulse, 1e-10);
  EXPECT_LT(worst_residual, 1e-12);
}

TEST(JointTree, RefusesLoopsAndDropsTheTreesTheyWouldClose) {
  std::mt19937 rng(1996);
  std::vector<SolverBody> bodies;
  for (int i = 0; i < 6; ++i) bodies.push_back(random_body(rng));
  bodies.push_back(SolverBody{});  // slot 6: the world
  const std::vector<Jacobian> ball = random_rows(rng, 1);
  JointTree tree;
  tree.clear(bodies.size());
  EXPECT_TRUE(tree.offer(0, 6, ball.data(), 3, bodies.data()));   // #0 held by the world
  EXPECT_TRUE(tree.offer(1, 0, ball.data(), 3, bodies.data()));   // #1
  EXPECT_TRUE(tree.offer(2, 1, ball.data(), 3, bodies.data()));   // #2
  EXPECT_FALSE(tree.offer(0, 2, ball.data(), 3, bodies.data()));  // #3 closes the ring 0-1-2
  EXPECT_FALSE(tree.offer(2, 6, ball.data(), 3, bodies.data()));  // #4 a second hold on the world
  EXPECT_TRUE(tree.offer(3, 6, ball.data(), 3, bodies.data()));   // #5 another tree
  EXPECT_TRUE(tree.offer(4, 3, ball.data(), 3, bodies.data()));   // #6
  EXPECT_TRUE(tree.offer(5, 4, ball.data(), 3, bodies.data()));   // #7
  EXPECT_FALSE(tree.offer(6, 6, ball.data(), 3, bodies.data()));  // #8 no dynamic body
  EXPECT_EQ(tree.joint_count(), 6u);
  tree.drop_looped();  // the tree of 0, 1, 2 had loops
  for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(tree.taken(k), k >= 5 && k <= 7) << k;
  EXPECT_EQ(tree.joint_count(), 3u);
  EXPECT_EQ(tree.row_count(), 9u);
  EXPECT_EQ(tree.body_count(), 3u);
  // What is left is solved exactly: J v' = 0 on the kept joints' rows.
  tree.order();
  JointTree::Factor f;
  tree.factor(bodies.data(), 0.0, f);
  ASSERT_TRUE(f.valid);
  std::vector<double> bias(9, 0.0), impulse(9, 0.0);
  tree.solve(f, bodies.data(), bias.data(), impulse.data());
  const std::uint32_t kept[3][2] = {{3, 6}, {4, 3}, {5, 4}};
  for (const auto& k : kept)
    for (const Jacobian& jac : ball) {
      ConstraintRow row;
      row.jacobian = jac;
      EXPECT_LT(std::abs(row_velocity(row, bodies[k[0]], bodies[k[1]])), 1e-12);
    }
}

// ---- issue 14's chain in a world ----------------------------------------------------------------

struct ChainRun {
  double worst = 0.0;  // the largest joint position error over the run (m)
  double rise = 0.0;   // the highest energy above the start, as a fraction of |E0|
  std::vector<double> first_report;  // w:solver_report() after the first step
};

// 10 links 0.1 × 0.5 × 0.1 m of 1 kg (a box's inertia), joined end to end by ball joints and
// hung from the world, released at 45°; 10 s at 60 Hz. `ring` joins the last link back to the
// first one's top with a ball joint too (a loop: that joint stays with Gauss-Seidel).
// `shapes`: the links are boxes that collide; otherwise inertia only.
ChainRun run_chain(SolverKind solver, bool shapes, int iterations = 10, bool garland = false) {
  World w;
  w.set_solver(solver);
  ContactSettings settings = w.contact_settings();
  settings.iterations = iterations;
  w.set_contact_settings(settings);
  const Vec3 down = Vec3(std::sin(M_PI / 4), -std::cos(M_PI / 4), 0.0);
  const Quat tilt(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()));
  std::vector<Joint*> joints;
  std::vector<BodyId> ids;
  const Vec3 up = Vec3(std::sin(M_PI / 4), std::cos(M_PI / 4), 0.0);
  const Quat back(Eigen::AngleAxisd(-M_PI / 4, Vec3::UnitZ()));
  Vec3 top = Vec3::Zero();  // the upper end of the next link
  for (int i = 0; i < 10; ++i) {
    const bool rising = garland && i >= 5;
    Body link = make_box_body(1.0, Vec3(0.1, 0.5, 0.1));
    if (!shapes) link = make_body(1.0, link.inertia);
    const Vec3 along = rising ? Vec3(-up) : down;  // from the joint above to the link's far end
    const Vec3 joint_point = rising ? Vec3(top + 0.5 * up) : top;
    link.position = (rising ? top : joint_point) + 0.25 * (rising ? up : down);
    link.orientation = rising ? back : tilt;
    JointDef def;
    def.type = JointKind::ball;
    def.a = w.add(link);
    def.b = ids.empty() ? no_body_id : ids.back();
    def.anchor = rising ? top : joint_point;
    joints.push_back(&add_joint(w, def));
    ids.push_back(def.a);
    top = rising ? Vec3(top + 0.5 * up) : Vec3(top + 0.5 * down);
    (void)along;
  }
  if (garland) {  // the last link's upper end held by the world
    JointDef def;
    def.type = JointKind::ball;
    def.a = ids.back();
    def.anchor = top;
    joints.push_back(&add_joint(w, def));
  }
  const double e0 = w.energy();
  ChainRun run;
  double highest = e0;
  for (int step = 0; step < 600; ++step) {
    w.step(1.0 / 60.0);
    if (step == 0) run.first_report = w.solver_report();
    for (const Joint* j : joints) {
      const Body& a = w.store().get(j->body_a());
      const Body* b = j->body_b().valid() ? &w.store().get(j->body_b()) : nullptr;
      double position = 0.0, angle = 0.0;
      j->error(a, b, position, angle);
      run.worst = std::max(run.worst, position);
    }
    highest = std::max(highest, w.energy());
  }
  run.rise = (highest - e0) / std::abs(e0);
  return run;
}

// The target, for the joint solve itself: the links' inertia without their shapes (the
// boxes touch end to end at every joint, and the contacts between joined links are another
// matter: tests/engine/joint_test.cpp "Chain"). Gauss-Seidel passing the load one joint per
// sweep left 2.7 mm; the exact tree solve with its curvature refresh (engine/solver.cpp)
// leaves 0.06 mm. sequential_impulses is document 000's Gauss-Seidel (no tree): 3.1 mm.
// Energy is measured from its size (the potential energy is negative below the pivot):
// "rising by 1 %" is 1 % of |E0|.
TEST(JointChain, TenLinkBallChainHoldsToAMillimetreAndKeepsItsEnergy) {
  for (SolverKind solver : {SolverKind::soft_step, SolverKind::sequential_impulses}) {
    const ChainRun run = run_chain(solver, false);
    std::printf("chain %s: worst joint error %.3g m, energy rise %.3g %%\n",
                solver_names[static_cast<int>(solver)], run.worst, 100.0 * run.rise);
    EXPECT_LT(run.worst, solver == SolverKind::soft_step ? 1e-3 : 3.5e-3)
        << solver_names[static_cast<int>(solver)];
    EXPECT_LE(run.rise, 0.01) << solver_names[static_cast<int>(solver)];
  }
}

// One sweep solves every row of a joint tree: with three sweeps (the first, then the curvature
// refresh retargets the rows, then the second), the rows' velocity error the third sweep finds
// before it updates anything is round-off (w:solver_report()). Gauss-Seidel
// (sequential_impulses) is still far from it.
TEST(JointChain, ASweepLeavesTheTreeRowsAtTheirTargets) {
  const ChainRun run = run_chain(SolverKind::soft_step, false, 3);
  ASSERT_EQ(run.first_report.size(), 3u);
  EXPECT_GT(run.first_report[0], 0.1);  // g h on the released links
  EXPECT_LT(run.first_report[2], 1e-12);
  const ChainRun gauss_seidel = run_chain(SolverKind::sequential_impulses, false, 3);
  EXPECT_GT(gauss_seidel.first_report[2], 1e-3);
}

// A loop: a garland of ten links held by the world at both ends. Its second hold on the world
// closes a loop, so the whole garland is swept by Gauss-Seidel (engine/solver.cpp
// build_tree), as before the tree solve: 3.7 mm with both solvers.
TEST(JointChain, AGarlandsLoopIsSweptByGaussSeidelAndHolds) {
  for (SolverKind solver : {SolverKind::soft_step, SolverKind::sequential_impulses}) {
    const ChainRun run = run_chain(solver, false, 10, true);
    std::printf("garland %s: worst joint error %.3g m, energy rise %.3g %%\n",
                solver_names[static_cast<int>(solver)], run.worst, 100.0 * run.rise);
    EXPECT_LT(run.worst, 4.0e-3) << solver_names[static_cast<int>(solver)];
    EXPECT_LE(run.rise, 0.01) << solver_names[static_cast<int>(solver)];
  }
}

}  // namespace
}  // namespace rigidlab
