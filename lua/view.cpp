// w:view{...}: the live view in the terminal. Runs the world in real time (times `speed`),
// drawing frames with w:render's pieces at the terminal's size, read again every frame (so it
// follows resizes); keys pause, step forward, change the speed, orbit the camera, cycle the
// overlays, quit. The frame rate is held by drawing fewer frames, never by slowing simulated
// time; only when the steps alone take longer than real time does the status say so.
// ← steps back through a ring of the world's saved states (World::save_state, restored
// exactly), → and space go forward through it again by restoring the next saved state (the
// same states bit for bit, so the same frames, and no callback or recorder runs twice); past
// its newest state they step the world (lua/view_subject.hpp keeps the ring and the trails).
// present/terminal restores the terminal however the view ends: q, Ctrl-C (an error raised
// at the next stop check), an error in a force callback, a limit, os.exit.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "lua/modules.hpp"
#include "lua/articulation.hpp"
#include "lua/render.hpp"
#include "lua/view_subject.hpp"
#include "lua/world.hpp"
#include "present/terminal.hpp"
#include "present/text.hpp"
#include "present/wireframe.hpp"

namespace rigidlab::lua {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double frame_period = 1.0 / 30;  // s of wall time between frames

struct ViewRequest {
  RenderRequest render;
  double dt = 1.0 / 60, speed = 1.0;
  bool paused = false;
};

ViewRequest check_view_request(lua_State* L) {
  ViewRequest r;
  r.render.style = present::terminal_style(STDOUT_FILENO);
  if (lua_isnoneornil(L, 2)) return r;
  if (!lua_istable(L, 2)) type_error(L, 2, "table");
  static const char* const fields[] = {"show", "camera", "dt", "speed", "paused", "ascii",
                                       "color", nullptr};
  check_fields(L, 2, fields);
  if (lua_getfield(L, 2, "show") != LUA_TNIL)
    read_show(L, lua_gettop(L), Where::field(2, "show"), r.render);
  if (lua_getfield(L, 2, "camera") != LUA_TNIL) read_camera(L, 2, lua_gettop(L), r.render);
  if (lua_getfield(L, 2, "dt") != LUA_TNIL)
    r.dt = check_number(L, lua_gettop(L), Where::field(2, "dt"), 1e-6, 1, "from 1e-6 to 1 (s)");
  if (lua_getfield(L, 2, "speed") != LUA_TNIL)
    r.speed = check_number(L, lua_gettop(L), Where::field(2, "speed"), 1.0 / 64, 64,
                           "from 1/64 to 64");
  if (lua_getfield(L, 2, "paused") != LUA_TNIL)
    r.paused = check_boolean(L, lua_gettop(L), Where::field(2, "paused"));
  if (lua_getfield(L, 2, "ascii") != LUA_TNIL)
    r.render.style.unicode = !check_boolean(L, lua_gettop(L), Where::field(2, "ascii"));
  if (lua_getfield(L, 2, "color") != LUA_TNIL)
    r.render.style.color = check_boolean(L, lua_gettop(L), Where::field(2, "color"));
  lua_pop(L, 7);
  return r;
}

// The overlay sets 'o' cycles through: those asked for, all, none.
SceneRequest overlay_mode(const SceneRequest& asked, int mode) {
  SceneRequest r;
  if (mode == 0) return asked;
  if (mode == 1) r.frames = r.omega = r.momentum = r.contacts = r.ellipsoid = true;
  return r;
}

class View {
 public:
  View(lua_State* L, const ViewRequest& request, std::unique_ptr<ViewSubject> subject)
      : L_(L), request_(request), subject_(std::move(subject)), paused_(request.paused),
        speed_(request.speed) {}

  void run(present::TerminalSession& terminal) {
    const StopPoller stop(L_);
    Clock::time_point last = Clock::now(), next_frame = last;
    bool dirty = true;
    std::string input;
    for (;;) {
      stop.poll();  // Ctrl-C and the time limit, as in w:step
      const double wait = paused_ ? 0.1 : seconds(next_frame - Clock::now());
      terminal.read(input, static_cast<int>(std::max(0.0, wait) * 1000));
      for (const present::Key key : present::decode_keys(input)) {
        if (key == present::Key::quit) return;
        dirty |= handle(key);
      }
      int columns = 0, rows = 0;  // a resize (SIGWINCH also cuts the wait short) redraws
      if (terminal.size(columns, rows) && (columns != columns_ || rows != rows_)) {
        columns_ = columns;
        rows_ = rows;
        dirty = true;
      }
      const Clock::time_point now = Clock::now();
      if (!paused_) dirty |= advance(seconds(now - last) * speed_, now);
      last = now;
      if (dirty && now >= next_frame) {
        draw(terminal);
        dirty = false;
        next_frame = now + std::chrono::microseconds(static_cast<long>(frame_period * 1e6));
      }
    }
  }

 private:
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  // After a rewind, the next state of the history; past its end, a step through the object's
  // own step method (force callbacks, controls, limits and Ctrl-C as in a script), and the
  // subject remembers the state.
  void step() {
    if (subject_->forward(L_, note_)) return;
    lua_getfield(L_, 1, "step");
    lua_pushvalue(L_, 1);
    lua_pushnumber(L_, request_.dt);
    lua_call(L_, 2, 0);
    subject_->stepped(L_);
  }

  // Runs `simulated` more seconds of the world, but steps for at most half a frame of wall
  // time: what it cannot do then is dropped, and the status says the view runs slow.
  bool advance(double simulated, Clock::time_point start) {
    owed_ += simulated;
    const long steps = static_cast<long>(std::floor(owed_ / request_.dt));
    if (steps <= 0) return false;
    owed_ -= static_cast<double>(steps) * request_.dt;
    slow_ = false;
    for (long k = 0; k < steps; ++k) {
      step();
      if (seconds(Clock::now() - start) > frame_period / 2 && k + 1 < steps) {
        slow_ = true;
        owed_ = 0;
        break;
      }
    }
    return true;
  }

  bool handle(present::Key key) {
    note_.clear();
    switch (key) {
      case present::Key::pause: paused_ = !paused_; owed_ = 0; return true;
      case present::Key::step_forward: paused_ = true; step(); return true;
      case present::Key::step_back: paused_ = true; subject_->back(L_, note_); return true;
      case present::Key::faster: speed_ = std::min(64.0, speed_ * 2); return true;
      case present::Key::slower: speed_ = std::max(1.0 / 64, speed_ / 2); return true;
      case present::Key::orbit_left: return orbit(-0.15, 0);
      case present::Key::orbit_right: return orbit(0.15, 0);
      case present::Key::orbit_up: return orbit(0, 0.1);
      case present::Key::orbit_down: return orbit(0, -0.1);
      case present::Key::overlays: overlays_ = (overlays_ + 1) % 3; return true;
      case present::Key::quit: return false;
    }
    return false;
  }

  bool orbit(double azimuth, double elevation) {
    if (!has_camera_) return false;
    camera_ = present::orbit(camera_, azimuth, elevation);
    return true;
  }

  static std::size_t lines(const std::string& text) {
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  }

  void draw(present::TerminalSession& terminal) {
    int columns = 80, rows = 24;
    terminal.size(columns, rows);
    columns = std::max(columns, 20);
    rows = std::max(rows, 6);
    SceneRequest overlays = overlay_mode(request_.render.scene, overlays_);
    const bool trails = (request_.render.trail && overlays_ == 0) || overlays_ == 1;
    const present::Scene scene = subject_->scene(L_, overlays, trails);
    present::RenderOptions options;
    options.style = request_.render.style;
    options.width = columns;
    options.height = 1;  // first only to count the legend's lines
    const std::size_t legend = lines(present::render_scene(scene, options)) - 1;
    options.height = std::max(3, rows - 1 - static_cast<int>(legend));
    if (!has_camera_) {  // framed once, then kept: frames of the same state are the same
      camera_ = present::fit_camera(scene, request_.render.camera.fov, columns, options.height);
      std::string problem;
      if (!apply_camera(request_.render.camera, camera_, problem))
        arg_error(L_, 2, "field 'camera': %s", problem.c_str());
      has_camera_ = true;
    }
    options.camera = camera_;
    std::string frame = "\x1b[H";
    const std::string picture = present::render_scene(scene, options);
    for (std::size_t at = 0; at <= picture.size();) {
      const std::size_t end = std::min(picture.find('\n', at), picture.size());
      frame.append(picture, at, end - at);
      frame += "\x1b[K\r\n";
      at = end + 1;
    }
    frame += status(columns) + "\x1b[K\x1b[J";
    terminal.write(frame);
  }

  std::string status(int columns) {
    const ViewTotals totals = subject_->totals(L_);
    const bool unicode = request_.render.style.unicode;
    char text[256];
    std::snprintf(text, sizeof text, "t %.3f s  E %.6g J  |L| %.6g  x%g  %s", totals.time,
                  totals.energy, totals.momentum, speed_,
                  paused_ ? "paused" : slow_ ? "running (slower than real time)" : "running");
    std::string line = text;
    const std::string position = subject_->position();
    if (!position.empty()) line += "  " + position;
    if (!note_.empty()) line += "  (" + note_ + ")";
    static const char* const modes[] = {"", "  overlays: all", "  overlays: none"};
    line += modes[overlays_];
    line += unicode ? "   space pause  ←→ step  +− speed  ⇧←→↑↓ orbit  o overlays  q quit"
                    : "   space pause  <- -> step  +- speed  shift+arrows orbit  o overlays  q quit";
    return present::fit_width(line, static_cast<std::size_t>(columns) - 1, unicode);
  }

  lua_State* L_;
  ViewRequest request_;
  std::unique_ptr<ViewSubject> subject_;
  bool paused_, slow_ = false, has_camera_ = false;
  double speed_, owed_ = 0;
  int overlays_ = 0, columns_ = 0, rows_ = 0;
  present::Camera camera_;
  std::string note_;
};

// Runs the view of the object at stack index 1 (options read, at index 2) until q.
void run_view(lua_State* L, const ViewRequest& request, std::unique_ptr<ViewSubject> subject) {
  std::string problem;
  std::unique_ptr<present::TerminalSession> terminal;
  try {
    terminal = std::make_unique<present::TerminalSession>(STDIN_FILENO, STDOUT_FILENO);
  } catch (const std::runtime_error& e) {
    problem = e.what();
  }
  if (!problem.empty()) function_error(L, "%s", problem.c_str());
  View view(L, request, std::move(subject));
  view.run(*terminal);  // a Lua error unwinds through here: ~TerminalSession restores
}

int world_view(lua_State* L) {
  check_world(L, 1);
  check_no_extra_args(L, 2);
  const ViewRequest request = check_view_request(L);
  lua_settop(L, 2);
  check_world(L, 1);  // after every option was read
  run_view(L, request, world_subject(L));
  return 0;
}

// art:view{...}: as w:view; the overlays an articulation has are frames, omega, joints and
// trail (as art:render, asking for another is an error).
int articulation_view(lua_State* L) {
  check_articulation(L, 1);
  check_no_extra_args(L, 2);
  const ViewRequest request = check_view_request(L);
  if (const char* missing = missing_articulation_overlay(request.render, true))
    arg_error(L, 2, "field 'show': '%s' is not drawn for articulations (they show 'frames', "
              "'omega', 'joints' and 'trail')", missing);
  lua_settop(L, 2);
  check_articulation_unlocked(L, 1, "view");
  run_view(L, request, articulation_subject(L));
  return 0;
}

const Entry methods[] = {
    {"view", world_view, "world:view",
     "w:view{show =, camera =, dt =, speed =, paused =, ascii =, color =}",
     "The world live in the terminal, at the terminal's size: it runs in real time (times\n"
     "speed, default 1) in steps of dt (default 1/60 s) until you press q. Keys: space pause,\n"
     "-> one step (and pause), <- one step back (the last 600 steps, fewer for a large world,\n"
     "are kept and restored exactly: stepping forward again restores the same states, without\n"
     "calling force callbacks or recorders twice), + and -\n"
     "speed, shift+arrows (or a d w s, up and down) orbit the camera, o cycles the overlays\n"
     "(those in show, all, none). A status line shows t, the energy and |L|. The world stays\n"
     "where the view leaves it (after a rewind: at the state shown). Frames as w:render draws\n"
     "them; the terminal is restored however the view ends (q, Ctrl-C, an error)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry articulation_methods[] = {
    {"view", articulation_view, "articulation:view",
     "art:view{show =, camera =, dt =, speed =, paused =, ascii =, color =}",
     "The articulation live in the terminal, as w:view shows a world (frames as art:render\n"
     "draws them; show: 'frames', 'omega', 'joints', 'trail'). Same keys: <- steps back\n"
     "through the last 600 states (q, qd, the held torques and the time, restored exactly)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_view(lua_State* L, int) {
  add_methods(L, world_type, methods);
  add_methods(L, articulation_type, articulation_methods);
}

}  // namespace rigidlab::lua
