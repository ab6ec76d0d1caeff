// w:render's options and the frame they ask for, shared with the live view (w:view), which
// reads the same options and draws frame after frame.
#pragma once

#include <lua.hpp>

#include <string>

#include "lua/binding.hpp"
#include "lua/render_scene.hpp"
#include "present/camera.hpp"
#include "present/style.hpp"

namespace rigidlab::lua {

// camera = {eye =, target =, up =, fov =}, each part optional.
struct CameraRequest {
  bool has_eye = false, has_target = false, has_up = false;
  Vec3 eye = Vec3::Zero(), target = Vec3::Zero(), up = Vec3::UnitY();
  double fov = 40.0;
};

struct RenderRequest {
  int width = 80, height = 24;
  CameraRequest camera;
  SceneRequest scene;     // the overlays
  bool trail = false;     // trails from the world's recorder
  present::TextStyle style;
  bool legend = true;
};

// Option fields shared with w:view and w:export_html. show = "omega" or {"omega", "L", ...} at
// stack index `value`; camera = {eye =, target =, up =, fov =} (each optional) at `value`,
// a field of the option table at `arg`.
void read_show(lua_State* L, int value, const Where& where, RenderRequest& request);
void read_camera(lua_State* L, int arg, int value, RenderRequest& request);

// Reads the option table at `arg` (absent: the defaults); errors name its fields. The style
// defaults to the terminal's (stdout): Unicode in a UTF-8 locale, colour in a terminal
// without NO_COLOR.
RenderRequest check_render_request(lua_State* L, int arg);

// The camera the request asks for: `camera` holds the default framing (its fov is the
// request's) and gets the parts the request gives; false (and `problem`) when they cannot
// make a camera.
bool apply_camera(const CameraRequest& request, present::Camera& camera, std::string& problem);

// The first overlay asked for that an articulation does not draw ('L', 'contacts',
// 'ellipsoid'; `trail` too unless `trail_ok`), or nullptr: art:render and art:view refuse it.
const char* missing_articulation_overlay(const RenderRequest& request, bool trail_ok);

// The frame of the world at stack index `world` (options read already from the table at stack
// index 2, which errors blame): the scene with the
// overlays asked for, drawn through the camera asked for.
std::string render_world(lua_State* L, int world, const RenderRequest& request);

// ctx:motion(object [, {seconds =, frames =, dt =, show =, camera =, height =, ascii =}]):
// steps the world or articulation and shows a film strip of its frames in the lesson
// (lua/render_motion.cpp); a method of the lesson's ctx (lua/lesson.cpp registers it).
int context_motion(lua_State* L);
// The live view of the last strip ctx:motion drew: pushes a function that shows it (w:view
// from the state the strip began with), or nil; forget_motion drops it (a new step).
void push_motion_view(lua_State* L);
void forget_motion(lua_State* L);

}  // namespace rigidlab::lua
