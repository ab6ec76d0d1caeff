#include "lua/view_subject.hpp"

#include <algorithm>
#include <cstdio>
#include <new>
#include <stdexcept>
#include <utility>
#include <vector>

#include "lua/articulation.hpp"
#include "lua/world.hpp"
#include "present/history.hpp"

namespace rigidlab::lua {
namespace {

// The bytes one saved state of `world` holds (its vectors' contents and the struct).
std::size_t state_bytes(const World& world, const WorldState& state) {
  return sizeof(WorldState) + world.bodies().size() * (sizeof(Body) + sizeof(BodyId)) +
         state.contacts.contacts.size() * sizeof(ContactInfo) +
         state.joint_impulses.size() * sizeof(double);
}

// Each body's COM over the states `first`..`last` of `history` (indices among those held).
template <class PositionOf>
std::vector<std::vector<Vec3>> paths(std::size_t first, std::size_t last, std::size_t bodies,
                                     PositionOf position_of) {
  std::vector<std::vector<Vec3>> out(bodies);
  for (std::vector<Vec3>& path : out) path.reserve(last - first + 1);
  for (std::size_t k = first; k <= last; ++k)
    for (std::size_t i = 0; i < bodies; ++i) out[i].push_back(position_of(k, i));
  return out;
}

class WorldSubject final : public ViewSubject {
 public:
  explicit WorldSubject(lua_State* L) {
    World& w = world(L);
    WorldState now;
    protect(L, [&] { w.save_state(now); });
    std::size_t capacity = std::clamp<std::size_t>(history_bytes / state_bytes(w, now), 2,
                                                   history_steps);
    // Under a memory limit the ring takes what the limit allows, down to 2 states.
    while (history_ == nullptr) {
      try {
        history_ = std::make_unique<present::History<WorldState>>(capacity, now);
      } catch (const std::bad_alloc&) {
        if (capacity <= 2) break;
        capacity /= 2;
      }
    }
    if (history_ == nullptr) memory_error(L);
    history_->record() = now;
  }

  void stepped(lua_State* L) override {
    World& w = world(L);
    protect(L, [&] {
      WorldState& saved = history_->record();
      w.save_state(saved);
      // A state that has grown (contacts made since) gets fewer slots: the ring stays within
      // history_bytes, give or take a third.
      const std::size_t fit = std::max<std::size_t>(2, history_bytes / state_bytes(w, saved));
      if (4 * fit < 3 * history_->capacity()) history_->shrink(fit);
    });
  }

  bool back(lua_State* L, std::string& note) override {
    if (!history_->back()) {
      char text[96];
      std::snprintf(text, sizeof text, "the oldest state kept (%zu steps back)",
                    history_->size() - 1);
      note = text;
      return false;
    }
    return restore_current(L, note);
  }

  bool forward(lua_State* L, std::string& note) override {
    return history_->forward() && restore_current(L, note);
  }

  present::Scene scene(lua_State* L, const SceneRequest& overlays, bool trails) override {
    const World& w = world(L);
    return protect(L, [&] {
      if (!trails) return scene_from_world(w, overlays);
      SceneRequest with_trails = overlays;
      const std::size_t last = history_->position();
      const std::size_t first = last + 1 > trail_steps ? last + 1 - trail_steps : 0;
      with_trails.trails = paths(first, last, w.bodies().size(), [&](std::size_t k, std::size_t i) {
        return history_->at(k).bodies[i].position;
      });
      return scene_from_world(w, with_trails);
    });
  }

  ViewTotals totals(lua_State* L) override {
    const World& w = world(L);
    return {w.time(), w.energy(), w.angular_momentum().norm()};
  }

  std::string position() const override {
    if (history_->at_newest()) return {};
    char text[64];
    std::snprintf(text, sizeof text, "rewound %zu of %zu steps",
                  history_->size() - 1 - history_->position(), history_->size() - 1);
    return text;
  }

 private:
  static World& world(lua_State* L) { return check_world(L, 1).world; }

  // Puts the world in the history's current state. False, with `note`, when its bodies have
  // changed since (a callback added or removed some): the history starts again from now.
  bool restore_current(lua_State* L, std::string& note) {
    World& w = world(L);
    bool changed = false;
    protect(L, [&] {
      try {
        w.restore_state(history_->current());
      } catch (const std::invalid_argument&) {
        changed = true;
      }
    });
    if (!changed) return true;
    history_->clear();
    protect(L, [&] { w.save_state(history_->record()); });
    note = "the world's bodies changed: the history starts again here";
    return false;
  }

  std::unique_ptr<present::History<WorldState>> history_;
};

class ArticulationSubject final : public ViewSubject {
 public:
  explicit ArticulationSubject(lua_State* L) {
    Articulation& a = check_articulation(L, 1).art;
    const std::size_t links = static_cast<std::size_t>(a.model().link_count());
    history_ = std::make_unique<present::History<std::vector<Vec3>>>(
        trail_steps, std::vector<Vec3>(links, Vec3::Zero()));
    stepped(L);
  }

  void stepped(lua_State* L) override {
    Articulation& a = check_articulation(L, 1).art;
    protect(L, [&] {
      std::vector<Vec3>& coms = history_->record();
      coms.resize(static_cast<std::size_t>(a.model().link_count()));
      for (std::size_t i = 0; i < coms.size(); ++i)
        coms[i] = a.point_position(static_cast<int>(i), a.model().links()[i].spec.com);
    });
  }

  bool back(lua_State*, std::string& note) override {
    note = "cannot step back: no saved articulation states in the engine yet";
    return false;
  }

  present::Scene scene(lua_State* L, const SceneRequest& overlays, bool trails) override {
    Articulation& a = check_articulation(L, 1).art;
    return protect(L, [&] {
      SceneRequest with_trails = overlays;
      const std::size_t links = static_cast<std::size_t>(a.model().link_count());
      if (trails && history_->at(0).size() == links)
        with_trails.trails = paths(0, history_->size() - 1, links,
                                   [&](std::size_t k, std::size_t i) { return history_->at(k)[i]; });
      return scene_from_articulation(a, with_trails);
    });
  }

  ViewTotals totals(lua_State* L) override {
    Articulation& a = check_articulation(L, 1).art;
    return protect(L, [&] {
      Vec3 linear, angular;
      a.momentum(linear, angular);
      return ViewTotals{a.time(), a.energy(), angular.norm()};
    });
  }

  std::string position() const override { return {}; }

 private:
  std::unique_ptr<present::History<std::vector<Vec3>>> history_;
};

}  // namespace

std::unique_ptr<ViewSubject> world_subject(lua_State* L) {
  return protect(L, [&] { return std::make_unique<WorldSubject>(L); });
}

std::unique_ptr<ViewSubject> articulation_subject(lua_State* L) {
  return protect(L, [&] { return std::make_unique<ArticulationSubject>(L); });
}

}  // namespace rigidlab::lua
