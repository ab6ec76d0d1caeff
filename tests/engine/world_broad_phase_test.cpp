// The world's bodies in the broad phase (engine/contact_pairs.hpp), judged against the
// brute-force answer: every pair of bodies the narrow phase finds a contact for within the
// step's margin (all n² pairs tested by engine/narrow_phase.hpp) must be a candidate pair, while
// bodies move, spin, are removed and added (their slots reused under new generations), and
// change between static and moving; the pairs come sorted by the bodies' ids and name the
// bodies by their present indices.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "engine/body_store.hpp"
#include "engine/contact_pairs.hpp"
#include "engine/narrow_phase.hpp"

namespace rigidlab {
namespace {

constexpr double speculative = 0.02, h = 1.0 / 60.0;

struct Scene {
  std::mt19937 rng{7};
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  BodyStore store;
  std::vector<SolverBody> solver;

  Body random_body() {
    Body b = (rng() % 2 == 0) ? make_sphere_body(1.0, 0.2 + 0.3 * (u(rng) + 1))
                              : make_box_body(1.0, Vec3(0.3 + 0.5 * (u(rng) + 1),
                                                        0.2 + 0.4 * (u(rng) + 1), 0.6));
    b.position = 6.0 * Vec3(u(rng), u(rng), u(rng));
    b.orientation = Quat(Eigen::AngleAxisd(3.0 * u(rng), Vec3(u(rng), 1, u(rng)).normalized()));
    b.velocity = 8.0 * Vec3(u(rng), u(rng), u(rng));
    b.angular_velocity = 3.0 * Vec3(u(rng), u(rng), u(rng));
    if (rng() % 8 == 0) b.inverse_mass = 0.0;  // static
    return b;
  }
  void fill_solver() {
    solver.resize(store.size() + 1);
    for (std::size_t i = 0; i < store.size(); ++i) {
      solver[i].velocity = store.bodies()[i].velocity;
      solver[i].angular_velocity = store.bodies()[i].angular_velocity;
    }
  }
  void move() {
    for (Body& b : store.bodies()) {
      b.position += h * b.velocity;
      if (b.position.norm() > 8.0) b.velocity = -b.velocity;  // stay in the cloud
      b.orientation = Quat(Eigen::AngleAxisd(h * b.angular_velocity.norm(),
                                             b.angular_velocity.normalized()) * b.orientation);
    }
  }
};

// The pairs (by id) whose shapes come within the margin the contact finder gives them.
std::set<std::pair<BodyId, BodyId>> brute_force(const Scene& s, const ContactPairs& pairs) {
  std::set<std::pair<BodyId, BodyId>> touching;
  const std::vector<Body>& bodies = s.store.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      if (is_static(bodies[i]) && is_static(bodies[j])) continue;
      const double margin = speculative + pairs.sweep(i) + pairs.sweep(j);
      const Manifold m = collide_shapes(bodies[i].shape, pose_of(bodies[i]), bodies[j].shape,
                                        pose_of(bodies[j]), margin);
      if (m.count == 0) continue;
      BodyId a = s.store.id_at(i), b = s.store.id_at(j);
      if (b < a) std::swap(a, b);
      touching.insert({a, b});
    }
  return touching;
}

TEST(ContactPairs, EveryPairTheNarrowPhaseFindsIsACandidateWhileBodiesComeAndGo) {
  Scene s;
  for (int k = 0; k < 150; ++k) s.store.insert(s.random_body());
  ContactPairs pairs;
  std::size_t most_touching = 0;
  for (int step = 0; step < 120; ++step) {
    if (step % 3 == 1) {  // one leaves, one comes (often into the slot just freed)
      s.store.erase(s.store.id_at(s.rng() % s.store.size()));
      s.store.insert(s.random_body());
    }
    if (step % 10 == 5) {  // one turns static or moving
      Body& b = s.store.bodies()[s.rng() % s.store.size()];
      b.inverse_mass = b.inverse_mass == 0.0 ? 1.0 : 0.0;
    }
    s.fill_solver();
    pairs.update(s.store.bodies(), s.store.ids(), s.solver.data(), h, speculative);
    ASSERT_EQ(pairs.broad_phase().check(), "");
    std::set<std::pair<BodyId, BodyId>> candidates;
    std::pair<BodyId, BodyId> last{BodyId{0, 0}, BodyId{0, 0}};
    for (const BodyPair& p : pairs.pairs()) {
      const BodyId a = s.store.id_at(p.a), b = s.store.id_at(p.b);
      ASSERT_TRUE(a < b);
      ASSERT_FALSE(is_static(s.store.bodies()[p.a]) && is_static(s.store.bodies()[p.b]));
      if (!candidates.empty()) ASSERT_TRUE(last < std::make_pair(a, b)) << "sorted, each once";
      last = {a, b};
      candidates.insert(last);
    }
    const auto touching = brute_force(s, pairs);
    most_touching = std::max(most_touching, touching.size());
    for (const auto& t : touching)
      ASSERT_TRUE(candidates.count(t)) << "step " << step << ": bodies in slots " << t.first.slot
                                       << " and " << t.second.slot << " missed";
    s.move();
  }
  EXPECT_GT(most_touching, 20u);  // the scene is dense enough to test something
}

TEST(ContactPairs, BodiesWithoutShapesAndPairsOfStaticBodiesAreNeverCandidates) {
  BodyStore store;
  Body ground = make_box_body(1.0, Vec3(10, 2, 10));
  ground.inverse_mass = 0.0;
  Body wall = ground;
  store.insert(ground);
  store.insert(wall);  // overlaps the ground: both static
  Body ghost = make_sphere_body(1.0, 0.5);
  ghost.shape.kind = ShapeKind::none;
  store.insert(ghost);
  Body ball = make_sphere_body(1.0, 0.5);
  ball.position = Vec3(0, 1.4, 0);
  const BodyId ball_id = store.insert(ball);
  std::vector<SolverBody> solver(store.size() + 1);
  ContactPairs pairs;
  pairs.update(store.bodies(), store.ids(), solver.data(), h, speculative);
  ASSERT_EQ(pairs.pairs().size(), 2u);  // the ball with the ground and with the wall
  for (const BodyPair& p : pairs.pairs()) EXPECT_EQ(p.b, store.index_of(ball_id));
}

TEST(ContactPairs, BoxesAreBoundedByTheirRotatedExtents) {
  // A 2 x 0.2 x 0.2 box turned 90° about z reaches 1 m up: a ball 0.95 m above its centre
  // (radius 0.1) is a candidate; 1.5 m up (beyond the margins) it is not, but beside the box at
  // 0.95 m (where the unturned box would reach) it is not either.
  auto candidates = [](const Vec3& ball_at) {
    BodyStore store;
    Body box = make_box_body(1.0, Vec3(2, 0.2, 0.2));
    box.orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
    store.insert(box);
    Body ball = make_sphere_body(1.0, 0.1);
    ball.position = ball_at;
    store.insert(ball);
    std::vector<SolverBody> solver(store.size() + 1);
    ContactPairs pairs;
    pairs.update(store.bodies(), store.ids(), solver.data(), h, speculative);
    return pairs.pairs().size();
  };
  EXPECT_EQ(candidates(Vec3(0, 1.05, 0)), 1u);
  EXPECT_EQ(candidates(Vec3(0, 1.5, 0)), 0u);
  EXPECT_EQ(candidates(Vec3(0.95, 0, 0)), 0u);
}

// Document: a 1.5 x 0.5 x 0.5 box turning at 5 rad/s changes its rotated box by up to
// |ω| R h = 0.069 m a step (R = |half extents| = 0.829 m), so with the 0.1 m margin it would
// leave its fat box every few steps and be re-inserted into the tree; bounded by its sphere,
// centre ± (R + sweep + speculative/2), its box stays the same while it only turns, and its fat
// box is never renewed. A box turning slowly (0.2 rad/s) keeps its tighter rotated box.
TEST(ContactPairs, AFastTurningBoxKeepsItsFatBoxWhileItOnlyTurns) {
  auto run = [](double spin, int* renewals) {
    BodyStore store;
    Body box = make_box_body(1.0, Vec3(1.5, 0.5, 0.5));
    box.position = Vec3(1, 2, 3);
    box.angular_velocity = spin * Vec3(1, 2, 3).normalized();
    store.insert(box);
    std::vector<SolverBody> solver(2);
    solver[0].angular_velocity = box.angular_velocity;
    ContactPairs pairs;
    const double radius = Vec3(0.75, 0.25, 0.25).norm();
    const double sweep = spin * radius * h;
    *renewals = 0;
    Aabb fat;
    for (int step = 0; step < 120; ++step) {
      Body& b = store.bodies()[0];
      pairs.update(store.bodies(), store.ids(), solver.data(), h, speculative);
      EXPECT_NEAR(pairs.sweep(0), sweep, 1e-15);
      const Aabb& tight = pairs.broad_phase().box(0);
      const Vec3 extent = b.orientation.toRotationMatrix().cwiseAbs() * Vec3(0.75, 0.25, 0.25);
      // The turning box's half width on every axis, or the rotated box's, both grown alike.
      const Vec3 half = spin > 1.0 ? Vec3::Constant(radius) : extent;
      EXPECT_TRUE(tight.lower.isApprox(b.position - half - Vec3::Constant(sweep + speculative / 2),
                                       1e-12));
      EXPECT_TRUE(tight.upper.isApprox(b.position + half + Vec3::Constant(sweep + speculative / 2),
                                       1e-12));
      const Aabb& now = pairs.broad_phase().fat_box(0);
      if (step > 0 && (now.lower != fat.lower || now.upper != fat.upper)) ++*renewals;
      fat = now;
      b.orientation = Quat(Eigen::AngleAxisd(h * spin, b.angular_velocity.normalized()) *
                           b.orientation).normalized();
    }
  };
  int renewals = 0;
  run(5.0, &renewals);
  EXPECT_EQ(renewals, 0);
  run(0.2, &renewals);  // the rotated box, checked step by step above
}

}  // namespace
}  // namespace rigidlab
