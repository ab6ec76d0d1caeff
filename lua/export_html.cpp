// w:export_html(path, {seconds =, fps =, dt =, show =, camera =, title =}): runs the world on
// for `seconds` (as w:step would, so force callbacks, limits and Ctrl-C behave as there) and
// writes a self-contained HTML page that plays those seconds with a time slider
// (present/html), with the overlays of w:render.
#include <cmath>
#include <string>
#include <vector>

#include "lua/modules.hpp"
#include "lua/output_file.hpp"
#include "lua/render.hpp"
#include "lua/world.hpp"
#include "present/file.hpp"
#include "present/html.hpp"

namespace rigidlab::lua {
namespace {

struct ExportRequest {
  double seconds = 5.0, fps = 30.0, dt = 0.0;  // dt 0: the largest of 1/60 s that divides a frame
  RenderRequest render;
  std::string title = "rigidlab";
};

ExportRequest check_export_request(lua_State* L) {
  ExportRequest r;
  if (lua_isnoneornil(L, 3)) return r;
  if (!lua_istable(L, 3)) type_error(L, 3, "table");
  static const char* const fields[] = {"seconds", "fps", "dt", "show", "camera", "title", nullptr};
  check_fields(L, 3, fields);
  if (lua_getfield(L, 3, "seconds") != LUA_TNIL)
    r.seconds = check_number(L, lua_gettop(L), Where::field(3, "seconds"), 0, 3600,
                             "in [0, 3600] (s)");
  if (lua_getfield(L, 3, "fps") != LUA_TNIL)
    r.fps = check_number(L, lua_gettop(L), Where::field(3, "fps"), 1, 240, "from 1 to 240");
  if (lua_getfield(L, 3, "dt") != LUA_TNIL) {
    r.dt = check_number(L, lua_gettop(L), Where::field(3, "dt"), 0, 1, "in (0, 1] (s)");
    if (!(r.dt > 0)) Where::field(3, "dt").error(L, "must be > 0, got 0");
  }
  if (lua_getfield(L, 3, "show") != LUA_TNIL)
    read_show(L, lua_gettop(L), Where::field(3, "show"), r.render);
  if (lua_getfield(L, 3, "camera") != LUA_TNIL) read_camera(L, 3, lua_gettop(L), r.render);
  if (lua_getfield(L, 3, "title") != LUA_TNIL) {
    std::size_t length = 0;
    const char* title = check_name(L, lua_gettop(L), Where::field(3, "title"), &length);
    r.title.assign(title, length);
  }
  lua_pop(L, 6);
  if (r.seconds * r.fps > 20000)
    arg_error(L, 3, "seconds x fps must be at most 20000 frames, got %s",
              format_number(r.seconds * r.fps).c_str());
  return r;
}

// Calls w:step(dt, n) on the world at stack index 1 through Lua, so it behaves as a script's.
void step(lua_State* L, double dt, long n) {
  lua_getfield(L, 1, "step");
  lua_pushvalue(L, 1);
  lua_pushnumber(L, dt);
  lua_pushinteger(L, n);
  lua_call(L, 3, 0);
}

present::HtmlFrame frame_of(const World& world, const SceneRequest& request) {
  present::HtmlFrame f;
  f.time = world.time();
  f.scene = scene_from_world(world, request);
  char status[160];
  std::snprintf(status, sizeof status, "t = %.3f s   E = %.6g J   |L| = %.6g kg m²/s", world.time(),
                world.energy(), world.angular_momentum().norm());
  f.status = status;
  return f;
}

int world_export_html(lua_State* L) {
  check_world(L, 1);
  const std::string path = check_output_path(L, 2, 2, nullptr);
  check_no_extra_args(L, 3);
  const ExportRequest r = check_export_request(L);
  // Steps of at most 1/60 s, a whole number of them per frame.
  const double frame_time = 1.0 / r.fps;
  const long per_frame = r.dt > 0 ? std::max(1L, std::lround(frame_time / r.dt))
                                  : static_cast<long>(std::ceil(frame_time * 60 - 1e-9));
  const double dt = frame_time / static_cast<double>(per_frame);
  const long count = static_cast<long>(std::floor(r.seconds * r.fps + 1e-9));
  SceneRequest request = r.render.scene;
  std::vector<present::HtmlFrame> frames;
  for (long k = 0;; ++k) {
    const World& world = check_world(L, 1).world;
    if (r.render.trail) {  // the path so far, from the frames before
      request.trails.resize(world.bodies().size());
      for (std::size_t i = 0; i < world.bodies().size(); ++i)
        request.trails[i].push_back(world.bodies()[i].position);
    }
    protect(L, [&] { frames.push_back(frame_of(world, request)); });
    if (k == count) break;
    step(L, dt, per_frame);
  }
  present::Camera camera = present::fit_camera_to_frames(frames, r.render.camera.fov, 800.0 / 500);
  std::string problem;
  if (!apply_camera(r.render.camera, camera, problem))
    arg_error(L, 3, "field 'camera': %s", problem.c_str());
  const std::string page = protect(L, [&] { return present::html_player(frames, camera, r.title); });
  write_or_raise(L, 2, nullptr, [&] { present::write_file(path, page); });
  lua_pushinteger(L, static_cast<lua_Integer>(frames.size()));
  return 1;
}

const Entry methods[] = {
    {"export_html", world_export_html, "world:export_html",
     "w:export_html(path, {seconds =, fps =, dt =, show =, camera =, title =}) -> frames",
     "Runs the world on for `seconds` (default 5; it is then that much later, as after\n"
     "w:step) and writes a single HTML page that plays them in a browser: a time slider,\n"
     "play/pause, the camera turned by dragging, and the overlays of w:render (show =\n"
     "{'omega', 'L', 'frames', 'contacts', 'ellipsoid', 'trail'}) with their legend. fps\n"
     "(default 30) frames per second, steps of dt (default: 1/60 s or less, a whole number\n"
     "per frame). The page references nothing outside itself. Returns the number of frames."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_export_html(lua_State* L, int) { add_methods(L, world_type, methods); }

}  // namespace rigidlab::lua
