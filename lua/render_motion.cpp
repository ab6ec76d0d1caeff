// ctx:motion(object, {...}): a lesson shows a motion as a film strip of a few frames, drawn
// by w:render's pieces, fitted to the lesson's width, one camera for every frame (framing the
// whole motion) so that what moves is seen to move. In check mode (nothing is written) it
// only steps, so `rigidlab check` stays fast and the state after it is the same either way.
// When it draws, it also leaves the live view of the same motion (from the strip's first
// state) for the lesson runner, which offers it on the key v in a terminal.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "lua/articulation.hpp"
#include "lua/lesson.hpp"
#include "lua/render.hpp"
#include "lua/world.hpp"
#include "present/filmstrip.hpp"
#include "present/text.hpp"
#include "present/wireframe.hpp"

namespace rigidlab::lua {
namespace {

struct MotionRequest {
  RenderRequest render;
  double seconds = 2.0, dt = 1.0 / 60;
  int frames = 4;
  int height = 0;  // 0: from the frames' width
};

MotionRequest check_motion_request(lua_State* L, int arg) {
  MotionRequest r;
  r.render.style = present::terminal_style(STDOUT_FILENO);
  r.render.style.color = false;  // a lesson's page (and its transcript) has no colour
  if (lua_isnoneornil(L, arg)) return r;
  if (!lua_istable(L, arg)) type_error(L, arg, "table");
  static const char* const fields[] = {"seconds", "frames", "dt", "show", "camera", "height",
                                       "ascii", nullptr};
  check_fields(L, arg, fields);
  const int top = lua_gettop(L);
  if (lua_getfield(L, arg, "seconds") != LUA_TNIL)
    r.seconds = check_number(L, -1, Where::field(arg, "seconds"), 1e-3, 600, "from 0.001 to 600 (s)");
  if (lua_getfield(L, arg, "frames") != LUA_TNIL)
    r.frames = static_cast<int>(check_integer(L, -1, Where::field(arg, "frames"), 1, 12));
  if (lua_getfield(L, arg, "dt") != LUA_TNIL)
    r.dt = check_number(L, -1, Where::field(arg, "dt"), 1e-6, 1, "from 1e-6 to 1 (s)");
  if (lua_getfield(L, arg, "show") != LUA_TNIL)
    read_show(L, lua_gettop(L), Where::field(arg, "show"), r.render);
  if (lua_getfield(L, arg, "camera") != LUA_TNIL) read_camera(L, arg, lua_gettop(L), r.render);
  if (lua_getfield(L, arg, "height") != LUA_TNIL)
    r.height = static_cast<int>(check_integer(L, -1, Where::field(arg, "height"), 3, 60));
  if (lua_getfield(L, arg, "ascii") != LUA_TNIL)
    r.render.style.unicode = !check_boolean(L, -1, Where::field(arg, "ascii"));
  lua_settop(L, top);
  if (r.frames > 1 && r.seconds / (r.frames - 1) / r.dt > 1e6)
    arg_error(L, arg, "seconds / dt must be at most 1e6 steps between frames");
  return r;
}

// Calls object:step(dt, n) through Lua, as a script would (force callbacks, controls, limits).
void step(lua_State* L, int object, double dt, lua_Integer n) {
  lua_getfield(L, object, "step");
  lua_pushvalue(L, object);
  lua_pushnumber(L, dt);
  lua_pushinteger(L, n);
  lua_call(L, 3, 0);
}

// The object's scene now (trails: the COM paths so far), and its time.
present::Scene scene_of(lua_State* L, int object, const SceneRequest& request, double& time) {
  if (LuaWorld* w = test_world(L, object)) {
    time = w->world.time();
    return protect(L, [&] { return scene_from_world(w->world, request); });
  }
  LuaArticulation& a = check_articulation(L, object);
  time = a.art.time();
  return protect(L, [&] { return scene_from_articulation(a.art, request); });
}

// Appends each body's COM (each link's for an articulation) to its trail.
void extend_trails(lua_State* L, int object, std::vector<std::vector<Vec3>>& trails) {
  std::vector<Vec3> points;
  if (LuaWorld* w = test_world(L, object)) {
    for (const Body& b : w->world.bodies()) points.push_back(b.position);
  } else {
    Articulation& a = check_articulation(L, object).art;
    for (int i = 0; i < a.model().link_count(); ++i)
      points.push_back(a.link_com(i));
  }
  trails.resize(std::max(trails.size(), points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) trails[i].push_back(points[i]);
}

// Every frame's bodies and overlays in one scene, for one camera that frames them all.
present::Scene union_of(const std::vector<present::Scene>& scenes) {
  present::Scene all = scenes.front();
  for (std::size_t k = 1; k < scenes.size(); ++k) {
    const present::Scene& s = scenes[k];
    all.bodies.insert(all.bodies.end(), s.bodies.begin(), s.bodies.end());
    all.arrows.insert(all.arrows.end(), s.arrows.begin(), s.arrows.end());
    all.ellipsoids.insert(all.ellipsoids.end(), s.ellipsoids.begin(), s.ellipsoids.end());
    all.markers.insert(all.markers.end(), s.markers.begin(), s.markers.end());
    all.curves.insert(all.curves.end(), s.curves.begin(), s.curves.end());
  }
  return all;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    lines.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  return lines;
}

// The frames as a film strip `columns` wide (4 of indent), and the legend below it.
std::string strip_text(lua_State* L, const std::vector<present::Scene>& scenes,
                       const std::vector<double>& times, const MotionRequest& r, int columns) {
  const std::string indent = "    ";
  const int available = std::max(columns - static_cast<int>(indent.size()), 20);
  const int count = static_cast<int>(scenes.size());
  const int per_row = present::frames_per_row(available, count, 26, present::filmstrip_gap);
  const int width = (available - present::filmstrip_gap * (per_row - 1)) / per_row - 2;
  const int height = r.height > 0 ? r.height : std::clamp(static_cast<int>(width * 0.3), 5, 10);
  present::RenderOptions options;
  options.style = r.render.style;
  options.width = width;
  options.height = height;
  options.legend = false;
  std::string problem;
  options.camera = present::fit_camera(union_of(scenes), r.render.camera.fov, width, height);
  if (!apply_camera(r.render.camera, options.camera, problem))
    arg_error(L, 3, "field 'camera': %s", problem.c_str());
  std::vector<present::FilmFrame> frames;
  for (int k = 0; k < count; ++k) {
    char caption[48];
    std::snprintf(caption, sizeof caption, "t = %.2f s", times[k]);
    std::vector<std::string> lines = split_lines(present::render_scene(scenes[k], options));
    lines.resize(static_cast<std::size_t>(height));
    for (std::string& line : lines) {
      const std::size_t shown = present::display_width(line);
      if (shown < static_cast<std::size_t>(width)) line.append(width - shown, ' ');
    }
    frames.push_back({caption, std::move(lines)});
  }
  std::string text = "\n" + present::filmstrip(frames, width, per_row, indent, options.style.unicode);
  options.width = available;  // the legend of the last frame, under the whole strip
  options.height = 1;
  options.legend = true;
  const std::vector<std::string> legend = split_lines(present::render_scene(scenes.back(), options));
  for (std::size_t k = 1; k < legend.size(); ++k) text += indent + legend[k] + "\n";
  return text + "\n";
}

// The live view of the last strip, for the lesson runner's key v: a function (the object,
// the world's state when the strip began, w:view's options as upvalues) in the registry.
const char motion_view_key = 0;
const char saved_state_key = 0;

struct SavedState {
  WorldState state;
};

int saved_state_gc(lua_State* L) {
  static_cast<SavedState*>(lua_touserdata(L, 1))->~SavedState();
  return 0;
}

// Pushes a userdata holding `world`'s state now (freed by __gc).
void push_saved_state(lua_State* L, const World& world) {
  void* memory = lua_newuserdatauv(L, sizeof(SavedState), 0);
  SavedState* saved = new (memory) SavedState{};
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &saved_state_key) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_createtable(L, 0, 1);
    lua_pushcfunction(L, saved_state_gc);
    lua_setfield(L, -2, "__gc");
    lua_pushvalue(L, -1);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &saved_state_key);
  }
  lua_setmetatable(L, -2);  // from here on __gc destroys it, whatever happens next
  protect(L, [&] { world.save_state(saved->state); });
}

// The registered view: restores the state the strip began with (when the world still has the
// same bodies) and calls object:view(options).
int view_motion(lua_State* L) {
  if (LuaWorld* w = test_world(L, lua_upvalueindex(1))) {
    if (auto* saved = static_cast<SavedState*>(lua_touserdata(L, lua_upvalueindex(2)))) {
      if (!w->world.stepping())
        try_call([&] { w->world.restore_state(saved->state); });  // else: from where it is
    }
  }
  lua_getfield(L, lua_upvalueindex(1), "view");
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushvalue(L, lua_upvalueindex(3));
  lua_call(L, 2, 0);
  return 0;
}

// Registers the view of the object at `object` (options: the table at `options` or none),
// the saved state (or nil) at the top of the stack, which it pops.
void remember_motion(lua_State* L, int object, int options) {
  lua_pushvalue(L, object);
  lua_insert(L, -2);
  lua_createtable(L, 0, 3);  // w:view's options: those ctx:motion shares with it
  if (lua_istable(L, options))
    for (const char* field : {"show", "camera", "dt"}) {
      lua_getfield(L, options, field);
      lua_setfield(L, -2, field);
    }
  lua_pushcclosure(L, view_motion, 3);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &motion_view_key);
}

}  // namespace

void push_motion_view(lua_State* L) { lua_rawgetp(L, LUA_REGISTRYINDEX, &motion_view_key); }

void forget_motion(lua_State* L) {
  lua_pushnil(L);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &motion_view_key);
}

int context_motion(lua_State* L) {
  if (test_lesson_context(L, 1) == nullptr) type_error(L, 1, "live lesson context");
  if (test_world(L, 2) == nullptr && test_articulation(L, 2) == nullptr)
    type_error(L, 2, "world or articulation");
  check_no_extra_args(L, 3);
  const MotionRequest r = check_motion_request(L, 3);
  if (test_articulation(L, 2) != nullptr) {
    if (const char* missing = missing_articulation_overlay(r.render, true))
      arg_error(L, 3, "field 'show': '%s' is not drawn for articulations", missing);
  }
  lua_settop(L, 3);
  LessonContext* context = test_lesson_context(L, 1);
  if (context->ended) arg_error(L, 1, "the lesson has ended: its ctx can no longer show anything");
  const bool drawing = context->output != nullptr;
  if (drawing) {  // the start, for the runner's live view (key v)
    if (LuaWorld* w = test_world(L, 2))
      push_saved_state(L, w->world);
    else
      lua_pushnil(L);
  }
  const lua_Integer per_frame =
      r.frames > 1 ? std::max<lua_Integer>(1, std::llround(r.seconds / (r.frames - 1) / r.dt)) : 0;
  SceneRequest request = r.render.scene;
  std::vector<present::Scene> scenes;
  std::vector<double> times;
  for (int k = 0; k < r.frames; ++k) {
    if (k > 0) {
      const lua_Integer chunk = drawing && r.render.trail ? 1 : per_frame;
      for (lua_Integer done = 0; done < per_frame; done += chunk) {
        step(L, 2, r.dt, chunk);
        if (drawing && r.render.trail) protect(L, [&] { extend_trails(L, 2, request.trails); });
      }
    } else if (drawing && r.render.trail) {
      protect(L, [&] { extend_trails(L, 2, request.trails); });
    }
    if (!drawing) continue;
    double time = 0;
    scenes.push_back(scene_of(L, 2, request, time));
    times.push_back(time);
  }
  context = test_lesson_context(L, 1);  // the steps ran Lua code: look again
  if (!drawing || context == nullptr || context->ended || context->output == nullptr) return 0;
  remember_motion(L, 2, 3);
  const std::string text = strip_text(L, scenes, times, r, context->width);
  context->output->write(text);
  return 0;
}

}  // namespace rigidlab::lua
