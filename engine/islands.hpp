// Sleeping islands (opt-in: World::set_sleeping), in the manner of Box2D v3 (island.c: islands
// of bodies linked by contacts and joints; solver_set.c: b2TrySleepIsland moves a whole island
// out of the awake set, b2WakeSolverSet brings it back), written for this world's pipeline.
//
// The rule. After each step, a dynamic body whose speed is below `linear` (m/s) and whose
// angular speed is below `angular` (rad/s) adds the step's dt to its sleep timer; any faster
// body resets it to zero (Box2D v2.4: b2_linearSleepTolerance 0.05 m/s,
// b2_angularSleepTolerance 2°/s, b2_timeToSleep 0.5 s). A body with a shape also counts as at
// rest when no point of it moves faster than `linear` (|v| + R|ω|, R its bounding radius:
// Box2D v3's rule), so a ball spinning slowly about its contact normal can sleep
// (islands.cpp, at_rest). An island is a connected component of the dynamic bodies through
// contacts, joints and springs between two bodies; static bodies and planes link nothing (a
// floor does not make one island of everything on it). Contacts link whether they touch or
// are speculative (a gap the step could close), as in Box2D v3 (a contact with manifold
// points links): the same contacts wake a sleeping island, and linking only the touching ones
// lets a body resting a hair away from an island fall asleep alone, be woken by its awake
// neighbour, and the two keep each other awake by turns (measured: a settled heap of 1,024
// balls never slept so; it sleeps after 6 s with speculative links). When every body of an
// island has been at rest for `time` seconds the island falls asleep: its velocities are set
// to zero (they are below the tolerances, so the jump is at most `linear` m/s and `angular`
// rad/s — the price of sleeping, and why it is off by default in a teaching lab) and its
// bodies carry a label naming the island.
//
// How the step skips sleeping bodies. At the start of each step `freeze` gives every sleeping
// body zero inverse mass and inverse inertia for the duration of the step (kept here and
// given back by `thaw`), so every stage treats it as immovable: the integrator passes skip it,
// the broad phase files it among the fixed proxies (no pair of two fixed proxies is looked
// at, so the pairs between sleeping bodies, and between a sleeping body and static geometry,
// cost nothing and are not solved), the planes skip it, joints wholly inside sleeping islands
// are left out of the solve. Their contact impulses are not remembered while asleep: a woken
// island starts its contacts without a warm start (its joints keep theirs).
//
// Waking. Within a step, when the contacts found for a substep include a pair of an awake
// dynamic body and a sleeping one (a point touching, or one the step could close: the contact
// finder's speculative contacts), the sleeping body's island is woken and the substep is
// prepared again, so the impact is solved against the island's real masses in that same step
// (Box2D wakes islands when a contact begins touching, before its solve). Between steps the
// world wakes an island when its bodies are disturbed (a velocity, force or torque not zero
// at the start of a step; the world's setters: joints, springs, drags added or removed, a
// body removed, planes added, gravity changed; World::wake). Everything runs in the order of
// the bodies' indices and links, never of addresses: the same script gives the same states.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/body.hpp"
#include "engine/body_store.hpp"

namespace rigidlab {

struct SleepSettings {
  double linear = 0.05;                          // m/s (Box2D b2_linearSleepTolerance)
  double angular = 2.0 * 3.14159265358979323846 / 180.0;  // rad/s, 2°/s (Box2D)
  double time = 0.5;                             // s (Box2D b2_timeToSleep)
};

// Why the settings cannot be used ("" when they can): each must be finite and > 0.
std::string sleep_settings_problem(const SleepSettings& s);

class Islands {
 public:
  // ---- during a step (World::step) ----
  // Freezes the sleeping bodies (zero inverse mass and inertia) unless their island was
  // disturbed since it fell asleep (a velocity, force or torque not zero): that island wakes.
  void freeze(std::vector<Body>& bodies);
  bool any_frozen() const { return frozen_count_ > 0; }
  bool frozen(std::size_t i) const { return i < state_.size() && state_[i] == State::frozen; }
  // Wakes the island of frozen body i for the rest of the step: its bodies get their mass
  // properties back. The flags change in finish(), so a step that fails changes nothing.
  void wake_in_step(std::vector<Body>& bodies, std::size_t i);
  // Gives the bodies still frozen their mass properties back (end of a step, or its failure).
  void thaw(std::vector<Body>& bodies);

  // ---- after a committed step: the islands ----
  void begin_links(std::size_t body_count);
  // Links bodies a and b (indices; no_body for the world or a plane). A link between an awake
  // body and a sleeping one wakes the sleeping island.
  void link(std::vector<Body>& bodies, std::size_t a, std::size_t b);
  // The woken islands' flags cleared, the timers advanced by dt, the islands whose bodies
  // all have been slow for settings.time put to sleep (with may_sleep; else every timer 0).
  void finish(std::vector<Body>& bodies, const std::vector<BodyId>& ids, double dt,
              const SleepSettings& settings, bool may_sleep);

  // ---- outside a step ----
  // Wakes every body of the sleeping island `label` (Body::island); returns how many woke.
  static std::size_t wake_island(std::vector<Body>& bodies, std::uint32_t label);
  static void wake_all(std::vector<Body>& bodies);

 private:
  enum class State : std::uint8_t { awake, frozen, woken };
  struct Frozen {
    std::size_t index;
    double inverse_mass;
    Mat3 inverse_inertia;
  };
  std::size_t find(std::size_t i);
  void restore(std::vector<Body>& bodies, const Frozen& f);

  std::vector<State> state_;          // by body index, for the step under way
  std::vector<Frozen> frozen_;        // the sleeping bodies' mass properties, by index
  std::size_t frozen_count_ = 0;      // of them still frozen
  std::vector<std::uint32_t> disturbed_;  // labels of islands woken by freeze
  std::vector<std::size_t> parent_;   // union-find over body indices (finish)
  std::vector<double> island_time_;   // the least sleep timer of each root's island
};

}  // namespace rigidlab
