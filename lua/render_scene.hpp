// The 3-D scene of a world, for w:render, the viewer and the HTML export: bodies with their
// shapes and poses, planes, and the overlays asked for, scaled to lengths in the world that
// sit well beside the bodies. No Lua here: the engine's state in, present::Scene out.
#pragma once

#include <vector>

#include "engine/articulation.hpp"
#include "engine/world.hpp"
#include "present/scene.hpp"

namespace rigidlab::lua {

struct SceneRequest {
  bool frames = false;     // body axes
  bool omega = false;      // angular velocity at the COM
  bool momentum = false;   // angular momentum about the COM
  bool contacts = false;   // contact points and the impulses of the last step
  bool ellipsoid = false;  // the inertia ellipsoid
  bool joints = false;     // joint markers (none yet: the engine has no joints)
  // Trails: past COM positions per body (by engine index), oldest first; empty when none.
  std::vector<std::vector<Vec3>> trails;
};

// Scales: every ω arrow uses one scale, chosen so the longest is 1.5 times the reach (half
// diagonal or radius) of a typical body; L likewise, and contact impulses at the reach. The
// ellipsoid is the Poinsot ellipsoid ωᵀ I ω = 2T at ω's scale (so ω's tip lies on it, 000
// "Torque-free motion"; Goldstein, "Classical Mechanics", section 5.6), or, for a body at
// rest, the inertia ellipsoid xᵀ I x = const with its longest semi-axis at the reach. The
// legend notes give the magnitudes, in ASCII.
present::Scene scene_from_world(const World& world, const SceneRequest& request);

// The scene of an articulation: each link as segments from its joint to its COM and to its
// children's joints, a cross at the COM; `joints` marks the joints (and a fixed base), `frames`
// the link axes at each joint, `omega` each link's angular velocity at its COM (one scale).
// `momentum`, `contacts` and `ellipsoid` have nothing to show for an articulation yet.
present::Scene scene_from_articulation(Articulation& art, const SceneRequest& request);

}  // namespace rigidlab::lua
