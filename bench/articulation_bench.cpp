// Forward dynamics of an n-link chain (n = 5 .. 200), two ways in the same run:
//   aba   the articulated-body algorithm (engine/aba): O(n), the three loops of document 000
//         "Featherstone's Algorithm";
//   crba  the composite-rigid-body mass matrix (engine/crba, O(n²) for a chain), the bias
//         forces by recursive Newton-Euler (engine/rnea, O(n)) and a dense Cholesky solve of
//         M q̈ = τ − C q̇ − g (O(n³)): what one writes without ABA.
// bench/run prints both curves, their ratio and ABA's time per link (flat when linear).
//   build/bench/articulation_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <random>

#include "engine/aba.hpp"
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

void chain_lengths(benchmark::internal::Benchmark* b) {
  for (int n : {5, 10, 20, 50, 100, 200}) b->Arg(n);
}

BENCHMARK(aba)->Apply(chain_lengths);
BENCHMARK(crba)->Apply(chain_lengths);

}  // namespace

BENCHMARK_MAIN();
