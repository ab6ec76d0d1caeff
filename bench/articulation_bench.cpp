// Forward dynamics of an n-link chain (n = 5 .. 200), two ways in the same run:
//   aba   the articulated-body algorithm (engine/aba): O(n), the three loops of document 000
//         "Featherstone's Algorithm";
//   crba  the composite-rigid-body mass matrix (engine/crba, O(n²) for a chain), the bias
//         forces by recursive Newton-Euler (engine/rnea, O(n)) and a dense Cholesky solve of
//         M q̈ = τ − C q̇ − g (O(n³)): what one writes without ABA.
// bench/run prints both curves, their ratio and ABA's time per link (flat when linear).
// And one step of a planar chain (hinges about z, 1 ms, semi_implicit) two ways:
//   articulation_step  reduced coordinates: one ABA per step, the joints exact by construction;
//   hinge_world_step   the same links as bodies of a world joined by hinge joints (maximal
//                      coordinates, the world's default solver: rows, iterations, relax).
//   build/bench/articulation_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <random>

#include "engine/aba.hpp"
#include "engine/articulation.hpp"
#include "engine/joint.hpp"
#include "engine/world.hpp"
#include "engine/crba.hpp"
#include "engine/rnea.hpp"

namespace {

using namespace rigidlab;

// A 3-D chain: revolute joints about alternating z and x axes, 0.3 m apart, each link a box
// of 1 kg; a random state so no term vanishes.
struct Chain {
  ArticulationModel model;
  ArticulationWorkspace ws;
  Eigen::VectorXd q, v, tau, qdd;

  explicit Chain(int n) {
    for (int k = 0; k < n; ++k) {
      LinkSpec spec;
      spec.parent = k - 1;
      spec.axis = k % 2 == 0 ? Vec3::UnitZ() : Vec3::UnitX();
      spec.origin = k == 0 ? Vec3::Zero() : Vec3(0, -0.3, 0);
      spec.mass = 1.0;
      spec.com = Vec3(0, -0.15, 0);
      spec.inertia = Vec3(0.008, 0.002, 0.008).asDiagonal();
      model.add_link(spec);
    }
    ws.resize(model);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    q = v = tau = qdd = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < n; ++k) {
      q[k] = u(rng);
      v[k] = u(rng);
      tau[k] = u(rng);
    }
  }
};

void aba(benchmark::State& state) {
  Chain chain(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    articulated_body_algorithm(chain.model, chain.q, chain.v, chain.tau, chain.ws, chain.qdd);
    benchmark::DoNotOptimize(chain.qdd.data());
    benchmark::ClobberMemory();
  }
}

void crba(benchmark::State& state) {
  Chain chain(static_cast<int>(state.range(0)));
  Eigen::MatrixXd M;
  Eigen::VectorXd bias;
  Eigen::LLT<Eigen::MatrixXd> cholesky(chain.model.nv());
  for (auto _ : state) {
    composite_rigid_body(chain.model, chain.q, chain.ws, M);
    bias_forces(chain.model, chain.q, chain.v, chain.ws, bias);
    cholesky.compute(M);
    chain.qdd = cholesky.solve(chain.tau - bias);
    benchmark::DoNotOptimize(chain.qdd.data());
    benchmark::ClobberMemory();
  }
}

// The planar chain of both step benchmarks: link k's joint at (0, -0.3 k, 0), its COM 0.15 m
// below it, 1 kg, the same inertia; released 0.3 rad from hanging.
LinkSpec planar_link(int k) {
  LinkSpec spec;
  spec.parent = k - 1;
  spec.axis = Vec3::UnitZ();
  spec.origin = k == 0 ? Vec3::Zero() : Vec3(0, -0.3, 0);
  spec.mass = 1.0;
  spec.com = Vec3(0, -0.15, 0);
  spec.inertia = Vec3(0.008, 0.002, 0.008).asDiagonal();
  return spec;
}

void articulation_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Articulation art;
  for (int k = 0; k < n; ++k) art.add_link(planar_link(k));
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  q[0] = 0.3;
  art.set_state(q, Eigen::VectorXd::Zero(n));
  for (auto _ : state) art.step(0.001);
  benchmark::DoNotOptimize(art.q().data());
}

void hinge_world_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  World w;
  const Quat turn(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));  // the whole chain turned 0.3 rad
  std::vector<BodyId> ids;
  for (int k = 0; k < n; ++k) {
    const LinkSpec spec = planar_link(k);
    Body b = make_body(spec.mass, spec.inertia);
    b.position = turn * Vec3(0, -0.3 * k - 0.15, 0);
    b.orientation = turn;
    ids.push_back(w.add(b));
  }
  for (int k = 0; k < n; ++k) {
    JointDef def;
    def.type = JointKind::hinge;
    def.a = ids[static_cast<std::size_t>(k)];
    if (k > 0) def.b = ids[static_cast<std::size_t>(k - 1)];
    def.anchor = turn * Vec3(0, -0.3 * k, 0);
    def.axis = Vec3::UnitZ();
    const Body* b = k > 0 ? &w.store().get(def.b) : nullptr;
    w.add_constraint(std::make_unique<Joint>(def, w.store().get(def.a), b));
  }
  for (auto _ : state) w.step(0.001);
  benchmark::DoNotOptimize(w.bodies().data());
}

void step_lengths(benchmark::internal::Benchmark* b) {
  for (int n : {5, 10, 20, 50, 100}) b->Arg(n);
}

void chain_lengths(benchmark::internal::Benchmark* b) {
  for (int n : {5, 10, 20, 50, 100, 200}) b->Arg(n);
}

BENCHMARK(aba)->Apply(chain_lengths);
BENCHMARK(crba)->Apply(chain_lengths);
BENCHMARK(articulation_step)->Apply(step_lengths);
BENCHMARK(hinge_world_step)->Apply(step_lengths);

}  // namespace

BENCHMARK_MAIN();
