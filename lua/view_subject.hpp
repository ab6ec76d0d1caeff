// What a live view (lua/view.cpp) shows and steps: a world (w:view) or an articulation
// (art:view), at stack index 1 of the view's call. The view steps it through its Lua method
// `step` (force callbacks, controls, limits and Ctrl-C as in a script) and then tells the
// subject, which keeps the history the view steps back through and the trails.
#pragma once

#include <lua.hpp>

#include <memory>
#include <string>

#include "lua/render_scene.hpp"
#include "present/scene.hpp"

namespace rigidlab::lua {

struct ViewTotals {
  double time = 0, energy = 0, momentum = 0;  // s, J, ‖L‖ (kg m²/s about the origin)
};

class ViewSubject {
 public:
  virtual ~ViewSubject() = default;
  // After each step the view made: remembers the new state.
  virtual void stepped(lua_State* L) = 0;
  // Goes back to the state before the current one, exactly. False, with `note` saying why,
  // when it cannot.
  virtual bool back(lua_State* L, std::string& note) = 0;
  // After a rewind: goes forward to the next state of the history by restoring it (the same
  // states bit for bit, and nothing runs twice: force callbacks and controls are not called
  // again, and recorders attached to the object do not record the replayed steps a second
  // time). False at the newest state: the view then steps the object itself. `note` says
  // why when the history had to be dropped.
  virtual bool forward(lua_State*, std::string&) { return false; }
  // The scene with `overlays` and, when `trails`, each body's recent path.
  virtual present::Scene scene(lua_State* L, const SceneRequest& overlays, bool trails) = 0;
  virtual ViewTotals totals(lua_State* L) = 0;
  // Where the current state is in the history, for the status line ("" at the newest): the
  // same for the same state on the way back and forward again.
  virtual std::string position() const = 0;
};

// A ring of the world's (articulation's) recent states (World::save_state,
// Articulation::save_state), preallocated, at most history_bytes of them (fewer if the memory
// limit refuses them): from it the view steps back and forward and draws the trails. Raises
// Lua's memory error when not even a few states fit.
std::unique_ptr<ViewSubject> world_subject(lua_State* L);
std::unique_ptr<ViewSubject> articulation_subject(lua_State* L);

constexpr std::size_t history_bytes = std::size_t{32} << 20;
constexpr std::size_t history_steps = 600;  // 10 s of the default 1/60 s steps
constexpr std::size_t trail_steps = 300;

}  // namespace rigidlab::lua
