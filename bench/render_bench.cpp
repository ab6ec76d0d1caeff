// Cost of one rendered frame (w:render: the scene built from the world, then drawn at 200 x 60
// cells in braille with colour) for 1,000 boxes, against one 60 Hz step of the same world, in
// the same run. bench/run prints both, their ratio and the frames per second it allows; the
// budget is 30 frames per second (33 ms a frame) on this machine.
//   build/bench/render_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <lua.hpp>

#include <memory>
#include <random>

#include "engine/world.hpp"
#include "lua/render_scene.hpp"
#include "lua/rigidlab.hpp"
#include "lua/view_subject.hpp"
#include "lua/world.hpp"
#include "present/wireframe.hpp"

namespace {

using namespace rigidlab;

// 1,000 boxes of random size and pose in a 30 m cube above a floor, spinning: spread out, so
// the step does the work of a scene that looks like this, not of a heap.
void fill(World& world, int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  world.add_plane(make_plane(Vec3::UnitY(), -16.0));
  for (int i = 0; i < n; ++i) {
    Body b = make_box_body(1.0, Vec3(0.6 + 0.3 * u(rng), 0.6 + 0.3 * u(rng), 0.6 + 0.3 * u(rng)));
    b.position = Vec3(15 * u(rng), 15 * u(rng), 15 * u(rng));
    b.orientation = quat_from_axis_angle(Vec3(u(rng), u(rng), 1.0), 3 * u(rng));
    b.angular_velocity = Vec3(3 * u(rng), 3 * u(rng), 3 * u(rng));
    world.add(b);
  }
}

void render_frame(benchmark::State& state) {
  World world;
  fill(world, static_cast<int>(state.range(0)));
  lua::SceneRequest request;
  request.omega = request.momentum = true;
  present::RenderOptions options;
  options.width = 200;
  options.height = 60;
  options.style = present::TextStyle{true, true};
  for (auto _ : state) {
    const present::Scene scene = lua::scene_from_world(world, request);
    options.camera = present::fit_camera(scene, 40, options.width, options.height);
    std::string frame = present::render_scene(scene, options);
    benchmark::DoNotOptimize(frame);
  }
}

void step_world(benchmark::State& state) {
  World world;
  fill(world, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    world.step(1.0 / 60);
    benchmark::ClobberMemory();
  }
}

// What the live view (w:view) does per frame for 100 bodies at 160 x 48 cells, through its
// own code (lua/view_subject: the ring of saved states, the trails taken from it): two 60 Hz
// steps, each saved into the ring (a frame at 30 fps), then the scene with ω, L and the last
// 300 states as trails, one render to count the legend's lines, one at full size. The ring is
// full and the trails at their longest from the start.
void view_frame(benchmark::State& state) {
  lua_State* L = luaL_newstate();
  lua::open_all(L);
  luaL_dostring(L, "return world{}");
  World& world = lua::check_world(L, 1).world;
  fill(world, static_cast<int>(state.range(0)));
  const std::unique_ptr<lua::ViewSubject> subject = lua::world_subject(L);
  for (std::size_t k = 0; k < lua::history_steps; ++k) {
    world.step(1.0 / 60);
    subject->stepped(L);
  }
  lua::SceneRequest request;
  request.omega = request.momentum = true;
  present::RenderOptions options;
  options.width = 160;
  options.style = present::TextStyle{true, true};
  options.camera = present::fit_camera(subject->scene(L, request, true), 40, 160, 45);
  for (auto _ : state) {
    for (int k = 0; k < 2; ++k) {
      world.step(1.0 / 60);
      subject->stepped(L);
    }
    const present::Scene scene = subject->scene(L, request, true);
    options.height = 1;
    std::string legend = present::render_scene(scene, options);
    options.height = 45;
    std::string frame = present::render_scene(scene, options);
    benchmark::DoNotOptimize(legend);
    benchmark::DoNotOptimize(frame);
  }
  lua_close(L);
}

}  // namespace

BENCHMARK(view_frame)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(step_world)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(render_frame)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(step_world)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
