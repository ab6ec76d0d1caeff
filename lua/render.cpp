// w:render{width =, height =, camera =, show =, ascii =, color =, legend =}: one frame of the
// world as text, drawn by present/wireframe from the scene lua/render_scene builds. Pure: it
// returns the text and writes nothing, so tests can compare frames.
#include "lua/render.hpp"

#include <unistd.h>

#include "lua/articulation.hpp"
#include "lua/modules.hpp"
#include "lua/record.hpp"
#include "lua/world.hpp"
#include "present/wireframe.hpp"

namespace rigidlab::lua {

namespace {
const char* const overlay_names[] = {"frames", "omega", "L", "contacts", "ellipsoid", "joints",
                                     "trail"};

}  // namespace

void read_show(lua_State* L, int value, const Where& where, RenderRequest& request) {
  auto one = [&](int index) {
    switch (check_option(L, index, where, overlay_names)) {
      case 0: request.scene.frames = true; break;
      case 1: request.scene.omega = true; break;
      case 2: request.scene.momentum = true; break;
      case 3: request.scene.contacts = true; break;
      case 4: request.scene.ellipsoid = true; break;
      case 5: request.scene.joints = true; break;
      default: request.trail = true; break;
    }
  };
  if (lua_type(L, value) == LUA_TSTRING) return one(value);
  if (lua_type(L, value) != LUA_TTABLE)
    where.type_error(L, value, "string or list of strings");
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, value));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, value, i);
    one(lua_gettop(L));
    lua_pop(L, 1);
  }
}

void read_camera(lua_State* L, int arg, int value, RenderRequest& request) {
  if (lua_type(L, value) != LUA_TTABLE) Where::field(arg, "camera").type_error(L, value, "table");
  static const char* const fields[] = {"eye", "target", "up", "fov", nullptr};
  check_fields(L, value, fields, Where::argument(arg, "field 'camera':"));
  CameraRequest& c = request.camera;
  const struct {
    const char* name;
    const char* shown;
    bool* given;
    Vec3* into;
  } vectors[] = {{"eye", "camera.eye", &c.has_eye, &c.eye},
                 {"target", "camera.target", &c.has_target, &c.target},
                 {"up", "camera.up", &c.has_up, &c.up}};
  for (const auto& v : vectors) {
    if (lua_getfield(L, value, v.name) != LUA_TNIL) {
      *v.into = check_vec3(L, lua_gettop(L), Where::field(arg, v.shown));
      *v.given = true;
    }
    lua_pop(L, 1);
  }
  if (lua_getfield(L, value, "fov") != LUA_TNIL)
    c.fov = check_number(L, lua_gettop(L), Where::field(arg, "camera.fov"), 1, 170,
                         "from 1 to 170 (degrees)");
  lua_pop(L, 1);
}

RenderRequest check_render_request(lua_State* L, int arg) {
  RenderRequest request;
  const present::TextStyle terminal = present::terminal_style(STDOUT_FILENO);
  request.style = terminal;
  if (lua_isnoneornil(L, arg)) return request;
  if (!lua_istable(L, arg)) type_error(L, arg, "table");
  static const char* const fields[] = {"width", "height", "camera", "show", "ascii", "color",
                                       "legend", nullptr};
  check_fields(L, arg, fields);
  if (lua_getfield(L, arg, "width") != LUA_TNIL)
    request.width = static_cast<int>(check_integer(L, -1, Where::field(arg, "width"), 10, 1000));
  if (lua_getfield(L, arg, "height") != LUA_TNIL)
    request.height = static_cast<int>(check_integer(L, -1, Where::field(arg, "height"), 4, 500));
  if (lua_getfield(L, arg, "show") != LUA_TNIL)
    read_show(L, lua_gettop(L), Where::field(arg, "show"), request);
  if (lua_getfield(L, arg, "camera") != LUA_TNIL) read_camera(L, arg, lua_gettop(L), request);
  if (lua_getfield(L, arg, "ascii") != LUA_TNIL)
    request.style.unicode = !check_boolean(L, -1, Where::field(arg, "ascii"));
  if (lua_getfield(L, arg, "color") != LUA_TNIL)
    request.style.color = check_boolean(L, -1, Where::field(arg, "color"));
  if (lua_getfield(L, arg, "legend") != LUA_TNIL)
    request.legend = check_boolean(L, -1, Where::field(arg, "legend"));
  lua_pop(L, 7);
  return request;
}

bool apply_camera(const CameraRequest& c, present::Camera& camera, std::string& problem) {
  if (c.has_up) camera.up = c.up;
  if (c.has_target && !c.has_eye) {  // keep the default direction and distance
    camera.eye += c.target - camera.target;
    camera.target = c.target;
  } else {
    if (c.has_target) camera.target = c.target;
    if (c.has_eye) camera.eye = c.eye;
  }
  problem = present::camera_problem(camera);
  return problem.empty();
}

namespace {

// Draws `scene` as the request asks, the camera framing the scene where the request leaves
// it free.
std::string draw(lua_State* L, const present::Scene& scene, const RenderRequest& request) {
  present::RenderOptions options;
  options.width = request.width;
  options.height = request.height;
  options.style = request.style;
  options.legend = request.legend;
  std::string problem;
  options.camera = present::fit_camera(scene, request.camera.fov, request.width, request.height);
  if (!apply_camera(request.camera, options.camera, problem))
    arg_error(L, 2, "field 'camera': %s", problem.c_str());
  return present::render_scene(scene, options);
}

}  // namespace

const char* missing_articulation_overlay(const RenderRequest& request, bool trail_ok) {
  const SceneRequest& s = request.scene;
  return s.momentum ? "L" : s.contacts ? "contacts" : s.ellipsoid ? "ellipsoid"
         : request.trail && !trail_ok ? "trail" : nullptr;
}

std::string render_world(lua_State* L, int world, const RenderRequest& request) {
  SceneRequest scene_request = request.scene;
  if (request.trail) scene_request.trails = recorded_trails(L, world, 2);
  const LuaWorld& w = check_world(L, world);  // after every option was read
  return draw(L, scene_from_world(w.world, scene_request), request);
}

namespace {

int world_render(lua_State* L) {
  check_world(L, 1);
  check_no_extra_args(L, 2);
  const RenderRequest request = check_render_request(L, 2);
  const std::string frame = render_world(L, 1, request);
  lua_pushlstring(L, frame.data(), frame.size());
  return 1;
}

// art:render{...}: the same options; the overlays an articulation has are frames, omega and
// joints, and asking for another is an error rather than a picture without it.
int articulation_render(lua_State* L) {
  check_articulation(L, 1);
  check_no_extra_args(L, 2);
  const RenderRequest request = check_render_request(L, 2);
  const SceneRequest& s = request.scene;
  if (const char* missing = missing_articulation_overlay(request, false))
    arg_error(L, 2, "field 'show': '%s' is not drawn for articulations (they show 'frames', "
              "'omega' and 'joints')", missing);
  LuaArticulation& a = check_articulation(L, 1);  // after every option was read
  const present::Scene scene = protect(L, [&] { return scene_from_articulation(a.art, s); });
  const std::string frame = draw(L, scene, request);
  lua_pushlstring(L, frame.data(), frame.size());
  return 1;
}

const Entry articulation_methods[] = {
    {"render", articulation_render, "articulation:render",
     "art:render{width =, height =, camera =, show =, ascii =, color =, legend =}",
     "One frame of the articulation as text, as w:render draws a world: each link as lines\n"
     "from its joint to its COM (a cross) and to its children's joints. show: 'frames' (link\n"
     "axes at the joints), 'omega' (each link's angular velocity at its COM), 'joints'\n"
     "(markers at the joints and the fixed base)."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry methods[] = {
    {"render", world_render, "world:render",
     "w:render{width =, height =, camera =, show =, ascii =, color =, legend =}",
     "One frame of the world as text (braille in a UTF-8 locale, ASCII otherwise): bodies as\n"
     "wireframes (boxes by their edges, spheres by outline and three great circles, point\n"
     "masses as crosses), planes as grids, in perspective. width x height cells (default 80\n"
     "x 24; the legend adds lines below). camera = {eye =, target =, up =, fov =} (degrees,\n"
     "default 40); left out, the camera frames the whole scene. show lists overlays: 'frames'\n"
     "(body axes x y z), 'omega' and 'L' (at the COM, one scale each, the largest given in the\n"
     "legend), 'contacts' (points and impulses of the last step), 'ellipsoid' (the Poinsot\n"
     "ellipsoid w.I.w = 2T: the tip of omega stays on it), 'trail' (past positions from\n"
     "w:record), 'joints'. Colour per body in a terminal without NO_COLOR (color = true or\n"
     "false to choose), else a dash pattern per body; ascii = true forces ASCII. Pure: returns\n"
     "the text, prints nothing."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_render(lua_State* L, int) {
  add_methods(L, world_type, methods);
  add_methods(L, articulation_type, articulation_methods);
}

}  // namespace rigidlab::lua
