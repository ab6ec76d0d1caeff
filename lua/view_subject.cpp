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

// What a view keeps of a world: World::save_state's state.
struct WorldTraits {
  using Object = World;
  using State = WorldState;
  static constexpr const char* changed = "the world's bodies changed";
  static World& object(lua_State* L) { return check_world(L, 1).world; }
  static void save(World& w, WorldState& to) { w.save_state(to); }
  static void restore(World& w, const WorldState& from) { w.restore_state(from); }
  static std::size_t bytes(const World& w, const WorldState& state) {
    return sizeof(WorldState) + w.bodies().size() * (sizeof(Body) + sizeof(BodyId)) +
           state.contacts.contacts.size() * sizeof(ContactInfo) +
           state.joint_impulses.size() * sizeof(double);
  }
  static std::size_t trail_count(const WorldState& state) { return state.bodies.size(); }
  static Vec3 trail_point(const WorldState& state, std::size_t i) {
    return state.bodies[i].position;
  }
  static present::Scene scene(World& w, const SceneRequest& request) {
    return scene_from_world(w, request);
  }
  static ViewTotals totals(World& w) {
    return {w.time(), w.energy(), w.angular_momentum().norm()};
  }
};

// Of an articulation: its state (Articulation::save_state) and, for the trails, each link's
// COM in it.
struct SavedArticulation {
  ArticulationState state;
  std::vector<Vec3> coms;
};
struct ArticulationTraits {
  using Object = Articulation;
  using State = SavedArticulation;
  static constexpr const char* changed = "links were added";
  static Articulation& object(lua_State* L) { return check_articulation(L, 1).art; }
  static void save(Articulation& a, SavedArticulation& to) {
    a.save_state(to.state);
    to.coms.resize(static_cast<std::size_t>(a.model().link_count()));
    for (std::size_t i = 0; i < to.coms.size(); ++i)
      to.coms[i] = a.link_com(static_cast<int>(i));
  }
  static void restore(Articulation& a, const SavedArticulation& from) {
    a.restore_state(from.state);
  }
  static std::size_t bytes(const Articulation&, const SavedArticulation& saved) {
    return sizeof(SavedArticulation) + saved.coms.size() * sizeof(Vec3) +
           static_cast<std::size_t>(saved.state.q.size() + saved.state.v.size() +
                                    saved.state.tau.size()) * sizeof(double);
  }
  static std::size_t trail_count(const SavedArticulation& saved) { return saved.coms.size(); }
  static Vec3 trail_point(const SavedArticulation& saved, std::size_t i) { return saved.coms[i]; }
  static present::Scene scene(Articulation& a, const SceneRequest& request) {
    return scene_from_articulation(a, request);
  }
  static ViewTotals totals(Articulation& a) {
    Vec3 linear, angular;
    a.momentum(linear, angular);
    return {a.time(), a.energy(), angular.norm()};
  }
};

// A ring of the object's recent states, preallocated within history_bytes (fewer slots
// under a memory limit, down to 2): ← restores the one before, → the one after, and past the
// newest the view steps the object and stepped() saves the new state. The trails are each
// body's or link's COM over the last trail_steps states up to the one shown.
template <class Traits>
class RewindSubject final : public ViewSubject {
  using Object = typename Traits::Object;
  using State = typename Traits::State;

 public:
  explicit RewindSubject(lua_State* L) {
    Object& object = Traits::object(L);
    State now;
    protect(L, [&] { Traits::save(object, now); });
    std::size_t capacity = std::clamp<std::size_t>(history_bytes / Traits::bytes(object, now), 2,
                                                   history_steps);
    while (history_ == nullptr) {
      try {
        history_ = std::make_unique<present::History<State>>(capacity, now);
      } catch (const std::bad_alloc&) {
        if (capacity <= 2) break;
        capacity /= 2;
      }
    }
    if (history_ == nullptr) memory_error(L);
    history_->record() = now;
  }

  void stepped(lua_State* L) override {
    Object& object = Traits::object(L);
    protect(L, [&] {
      State& saved = history_->record();
      Traits::save(object, saved);
      // A state that has grown (contacts made since) gets fewer slots: the ring stays within
      // history_bytes, give or take a third.
      const std::size_t fit =
          std::max<std::size_t>(2, history_bytes / Traits::bytes(object, saved));
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
    Object& object = Traits::object(L);
    return protect(L, [&] {
      if (!trails) return Traits::scene(object, overlays);
      SceneRequest with_trails = overlays;
      const std::size_t last = history_->position();
      const std::size_t first = last + 1 > trail_steps ? last + 1 - trail_steps : 0;
      const std::size_t count = Traits::trail_count(history_->at(last));
      bool same = true;  // the bodies or links of every state drawn are those of the last
      for (std::size_t k = first; k <= last; ++k)
        same = same && Traits::trail_count(history_->at(k)) == count;
      with_trails.trails.assign(same ? count : 0, {});
      for (std::size_t i = 0; i < with_trails.trails.size(); ++i) {
        with_trails.trails[i].reserve(last - first + 1);
        for (std::size_t k = first; k <= last; ++k)
          with_trails.trails[i].push_back(Traits::trail_point(history_->at(k), i));
      }
      return Traits::scene(object, with_trails);
    });
  }

  ViewTotals totals(lua_State* L) override {
    Object& object = Traits::object(L);
    return protect(L, [&] { return Traits::totals(object); });
  }

  std::string position() const override {
    if (history_->at_newest()) return {};
    char text[64];
    std::snprintf(text, sizeof text, "rewound %zu of %zu steps",
                  history_->size() - 1 - history_->position(), history_->size() - 1);
    return text;
  }

 private:
  // Puts the object in the history's current state. False, with `note`, when it has changed
  // since (a callback added or removed bodies, or added links): the history starts again.
  bool restore_current(lua_State* L, std::string& note) {
    Object& object = Traits::object(L);
    bool changed = false;
    protect(L, [&] {
      try {
        Traits::restore(object, history_->current());
      } catch (const std::invalid_argument&) {
        changed = true;
      }
    });
    if (!changed) return true;
    history_->clear();
    protect(L, [&] { Traits::save(object, history_->record()); });
    note = std::string(Traits::changed) + ": the history starts again here";
    return false;
  }

  std::unique_ptr<present::History<State>> history_;
};

}  // namespace

std::unique_ptr<ViewSubject> world_subject(lua_State* L) {
  return protect(L, [&] { return std::make_unique<RewindSubject<WorldTraits>>(L); });
}

std::unique_ptr<ViewSubject> articulation_subject(lua_State* L) {
  return protect(L, [&] { return std::make_unique<RewindSubject<ArticulationTraits>>(L); });
}

}  // namespace rigidlab::lua
