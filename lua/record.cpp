// The recorder binding: w:record starts one (it samples the state now and after every
// `every`-th completed step), the world keeps it while it records, and rec:series / rec:csv
// read what it holds. A recorder outlives its world safely: it holds the world's body store,
// whose world() is null once the world is gone.
#include "lua/record.hpp"

#include <memory>
#include <string>

#include "lua/body.hpp"
#include "lua/modules.hpp"
#include "lua/output_file.hpp"
#include "lua/recorder.hpp"
#include "lua/world.hpp"

namespace rigidlab::lua {
namespace {

const char recorder_metatable_key = 0;
const char recorders_key = 0;  // the world's list of its recording recorders
constexpr std::uint64_t recorder_tag = 0x7265'636f'7264'6572ULL;
constexpr int world_slot = 1;  // the recorder's user value: its world

struct LuaRecorder {
  std::shared_ptr<Recorder> recorder;
  std::shared_ptr<BodyStore> store;  // of its world
};

LuaRecorder& check_recorder(lua_State* L, int arg) {
  LuaRecorder* r = test_tagged<LuaRecorder>(L, arg, recorder_tag);
  if (r != nullptr) return *r;
  // A recorder whose __gc has run (by hand, through debug) keeps its size and metatable.
  if (lua_rawlen(L, arg) == sizeof(Tagged<LuaRecorder>) && has_metatable(L, arg, &recorder_metatable_key))
    arg_error(L, arg, "the recorder was finalised (its __gc has run)");
  type_error(L, arg, "recorder");
}

const TypeSpec recorder_type = {"recorder", &recorder_metatable_key, nullptr};

// Pushes the world's list of recorders (recording ones, oldest first).
void push_recorders(lua_State* L, int world) { push_world_table(L, world, &recorders_key); }

// ---- w:record ------------------------------------------------------------------------------

int world_record(lua_State* L) {
  check_world(L, 1);
  check_no_extra_args(L, 2);
  if (!lua_isnoneornil(L, 2) && !lua_istable(L, 2)) type_error(L, 2, "table");
  if (lua_isnone(L, 2)) lua_pushnil(L);
  long every = 1;
  std::vector<BodyStore::Id> ids;
  bool all_bodies = true;
  if (lua_istable(L, 2)) {
    static const char* const fields[] = {"every", "bodies", nullptr};
    check_fields(L, 2, fields);
    if (lua_getfield(L, 2, "every") != LUA_TNIL)
      every = static_cast<long>(check_integer(L, lua_gettop(L), Where::field(2, "every"), 1,
                                              1'000'000'000));
    if (lua_getfield(L, 2, "bodies") != LUA_TNIL) {
      const int list = lua_gettop(L);
      if (!lua_istable(L, list)) Where::field(2, "bodies").type_error(L, list, "list of bodies");
      all_bodies = false;
      const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, list));
      // Read into a plain list of Lua values first: check_member runs no Lua code, but a
      // list's entries are read raw, so nothing in between can change the world.
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, list, i);
        const std::string what = "bodies[" + std::to_string(i) + "]";
        const std::size_t index =
            check_member(L, check_world(L, 1), lua_gettop(L), Where::field(2, what.c_str()));
        ids.push_back(check_world(L, 1).world.shared_store()->id_at(index));
        lua_pop(L, 1);
      }
    }
    lua_pop(L, 2);
  }
  LuaWorld& w = check_world_unlocked(L, 1, "start a recorder");
  if (all_bodies) {
    const BodyStore& store = *w.world.shared_store();
    protect(L, [&] {
      for (std::size_t i = 0; i < store.size(); ++i) ids.push_back(store.id_at(i));
    });
  }
  void* memory = lua_newuserdatauv(L, sizeof(Tagged<LuaRecorder>), 1);
  auto* box = static_cast<Tagged<LuaRecorder>*>(memory);
  box->tag = 0;
  new (&box->value) LuaRecorder();
  box->tag = recorder_tag;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &recorder_metatable_key);
  lua_setmetatable(L, -2);
  lua_pushvalue(L, 1);
  lua_setiuservalue(L, -2, world_slot);
  LuaRecorder& rec = box->value;
  rec.store = w.world.shared_store();
  rec.recorder = protect(L, [&] { return std::make_shared<Recorder>(w.world, ids, every); });
  push_recorders(L, 1);  // the world keeps its recorders while they record
  lua_pushvalue(L, -2);
  lua_rawseti(L, -2, static_cast<lua_Integer>(lua_rawlen(L, -2)) + 1);
  lua_pop(L, 1);
  protect(L, [&] { w.world.add_step_observer(rec.recorder); });
  return 1;
}

// ---- reading ---------------------------------------------------------------------------------

// The position of `body` (a body, or an index from 1) among the recorder's bodies.
std::size_t check_recorded_body(lua_State* L, const LuaRecorder& rec, int arg) {
  const std::size_t count = rec.recorder->body_count();
  lua_Integer k = 0;
  if (to_integer(L, arg, k)) {
    if (k < 1 || static_cast<std::size_t>(k) > count)
      arg_error(L, arg, "body number must be from 1 to %d (the bodies recorded), got %d",
                static_cast<int>(count), static_cast<int>(k));
    return static_cast<std::size_t>(k - 1);
  }
  const BodyHandle& handle = check_body_handle(L, arg, Where::argument(arg));
  const auto& ids = rec.recorder->ids();
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (handle.store == rec.store && ids[i] == handle.id) return i;
  arg_error(L, arg, "the body is not one this recorder records (see rec.bodies)");
}

void push_numbers(lua_State* L, const std::vector<double>& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
  }
}

int recorder_series(lua_State* L) {
  const LuaRecorder& rec = check_recorder(L, 1);
  std::size_t length = 0;
  const std::string name = check_name(L, 2, Where::argument(2, "name"), &length);
  check_no_extra_args(L, 3);
  const bool per_body = !lua_isnoneornil(L, 3) ||
                        (find_series(name, false) == nullptr && find_series(name, true) != nullptr);
  const SeriesInfo* series = find_series(name, per_body);
  if (series == nullptr) {
    std::string names;
    for (const SeriesInfo& s : series_list())
      if (s.per_body == per_body || std::string(s.name) == "t")
        names += std::string(names.empty() ? "" : ", ") + "'" + s.name + "'";
    arg_error(L, 2, "no %s series '%s'; %s series are %s", per_body ? "body" : "world",
              name.c_str(), per_body ? "body" : "world", names.c_str());
  }
  std::size_t body = 0;
  if (series->per_body) {
    if (!lua_isnoneornil(L, 3)) {
      body = check_recorded_body(L, rec, 3);
    } else if (rec.recorder->body_count() != 1) {
      arg_error(L, 3, "a body is needed for '%s' (%d bodies are recorded)", name.c_str(),
                static_cast<int>(rec.recorder->body_count()));
    }
  }
  if (series->kind == SeriesKind::number) {
    push_numbers(L, rec.recorder->numbers(*series, body));
  } else if (series->kind == SeriesKind::vector) {
    const std::vector<Vec3> values = rec.recorder->vectors(*series, body);
    lua_createtable(L, static_cast<int>(values.size()), 0);
    for (std::size_t i = 0; i < values.size(); ++i) {
      push_vec3(L, values[i]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
    }
  } else {
    const std::vector<Quat> values = rec.recorder->rotations(*series, body);
    lua_createtable(L, static_cast<int>(values.size()), 0);
    for (std::size_t i = 0; i < values.size(); ++i) {
      push_quat(L, values[i]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
    }
  }
  return 1;
}

int recorder_csv(lua_State* L) {
  const std::string path = check_output_path(L, 2, 2, nullptr);
  check_no_extra_args(L, 2);
  const LuaRecorder& rec = check_recorder(L, 1);
  const std::vector<present::Column> columns = protect(L, [&] { return rec.recorder->columns(); });
  write_or_raise(L, 2, nullptr, [&] { present::write_csv(path, columns); });
  return 0;
}

int recorder_stop(lua_State* L) {
  LuaRecorder& rec = check_recorder(L, 1);
  check_no_extra_args(L, 1);
  World* world = rec.store->world();
  if (world != nullptr && world->stepping())
    arg_error(L, 1, "the world is stepping: cannot stop a recorder until world:step returns");
  rec.recorder->stop("stopped by rec:stop()");
  if (world != nullptr) world->remove_step_observer(rec.recorder.get());
  if (lua_getiuservalue(L, 1, world_slot) == LUA_TUSERDATA && test_world(L, -1) != nullptr) {
    push_recorders(L, -1);  // remove it from the world's list
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1, j = 1; i <= n; ++i) {
      lua_rawgeti(L, -1, i);
      const bool self = lua_rawequal(L, -1, 1);
      if (!self) lua_rawseti(L, -2, j++);
      else lua_pop(L, 1);
      if (i == n && j <= n) {
        lua_pushnil(L);
        lua_rawseti(L, -2, n);
      }
    }
  }
  return 0;
}

// ---- properties --------------------------------------------------------------------------

void get_t(lua_State* L, int object, const Property&) {
  push_numbers(L, check_recorder(L, object).recorder->times());
}
void get_count(lua_State* L, int object, const Property&) {
  lua_pushinteger(L, static_cast<lua_Integer>(check_recorder(L, object).recorder->samples()));
}
void get_every(lua_State* L, int object, const Property&) {
  lua_pushinteger(L, check_recorder(L, object).recorder->every());
}
void get_recording(lua_State* L, int object, const Property&) {
  const LuaRecorder& rec = check_recorder(L, object);  // and its world still there
  lua_pushboolean(L, rec.recorder->recording() && rec.store->world() != nullptr);
}
void get_stop_reason(lua_State* L, int object, const Property&) {
  const Recorder& r = *check_recorder(L, object).recorder;
  if (r.recording()) lua_pushnil(L);
  else lua_pushstring(L, r.stop_reason().c_str());
}
void get_bodies(lua_State* L, int object, const Property&) {
  const LuaRecorder& rec = check_recorder(L, object);
  const std::vector<BodyStore::Id> ids = rec.recorder->ids();
  lua_createtable(L, static_cast<int>(ids.size()), 0);
  const int list = lua_gettop(L);
  if (lua_getiuservalue(L, object, world_slot) != LUA_TUSERDATA || test_world(L, -1) == nullptr) {
    lua_pop(L, 1);
    return;
  }
  const int world = lua_gettop(L);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const BodyStore& store = *rec.store;
    if (!store.contains(ids[i])) continue;  // left the world: recording stopped then
    push_world_body(L, world, store.index_of(ids[i]));
    lua_rawseti(L, list, static_cast<lua_Integer>(i) + 1);
  }
  lua_pop(L, 1);
}

const Property properties[] = {
    {"t", get_t, nullptr, "the times of the samples (s), a new list", "it grows as the world steps",
     nullptr},
    {"count", get_count, nullptr, "the number of samples", "it grows as the world steps", nullptr},
    {"every", get_every, nullptr, "a sample every this many steps", "set by w:record{every =}",
     nullptr},
    {"recording", get_recording, nullptr, "true until rec:stop() (or a recorded body leaves)",
     "rec:stop() ends it", nullptr},
    {"stop_reason", get_stop_reason, nullptr, "why recording stopped, or nil",
     "the recorder sets it", nullptr},
    {"bodies", get_bodies, nullptr, "the bodies recorded, in the order of rec:csv's columns",
     "set by w:record{bodies =}", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

int recorder_len(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(check_recorder(L, 1).recorder->samples()));
  return 1;
}

int recorder_tostring(lua_State* L) {
  const Recorder& r = *check_recorder(L, 1).recorder;
  lua_pushfstring(L, "recorder(%d bod%s, %d samples, every %d step%s, %s)",
                  static_cast<int>(r.body_count()), r.body_count() == 1 ? "y" : "ies",
                  static_cast<int>(r.samples()), static_cast<int>(r.every()),
                  r.every() == 1 ? "" : "s", r.recording() ? "recording" : "stopped");
  return 1;
}

int recorder_gc(lua_State* L) {
  LuaRecorder* r = test_tagged<LuaRecorder>(L, 1, recorder_tag);
  if (r == nullptr) return 0;
  r->~LuaRecorder();  // the world keeps its share of a recorder still observing it
  static_cast<Tagged<LuaRecorder>*>(lua_touserdata(L, 1))->tag = 0;
  return 0;
}

const Entry world_methods[] = {
    {"record", world_record, "world:record", "w:record{every =, bodies =} -> recorder",
     "Records the world from now on: a sample now and after every `every`-th step (default\n"
     "1) of the time, the energies, the momenta, and of each body in `bodies` (default all)\n"
     "its position, orientation, velocity and angular velocity (world and body frame), kinetic\n"
     "energy and angular momentum about its COM. rec.t, rec:series(name [, body]),\n"
     "rec:csv(path), rec:stop(); w:render{show = 'trail'} draws the newest recorder's paths."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry methods[] = {
    {"series", recorder_series, "recorder:series", "rec:series(name [, body]) -> list",
     "The samples of one quantity, ready for plot.lines: world series 't', 'kinetic_energy',\n"
     "'potential_energy', 'energy' (numbers, J), 'linear_momentum', 'angular_momentum' (vec3,\n"
     "about the origin); with a body (a body, or its number in rec.bodies; may be left out\n"
     "when one body is recorded): 'position', 'velocity', 'angular_velocity' (world),\n"
     "'velocity_body', 'angular_velocity_body' (body frame), 'orientation' (quat),\n"
     "'kinetic_energy', 'angular_momentum' (about the COM, world), 'angular_momentum_body'."},
    {"csv", recorder_csv, "recorder:csv", "rec:csv(path)",
     "Writes every series as CSV: t, the world's, then body1.position.x and so on (vec3 as\n"
     ".x .y .z, quat as .w .x .y .z), one row per sample."},
    {"stop", recorder_stop, "recorder:stop", "rec:stop()",
     "Stops recording; the samples stay. The world no longer keeps the recorder."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry metamethods[] = {
    {"__len", recorder_len, "recorder.__len", "#rec", "The number of samples."},
    {"__tostring", recorder_tostring, "recorder.__tostring", "tostring(rec)",
     "Short form: recorder(1 body, 61 samples, every 1 step, recording)."},
    {"__gc", recorder_gc, "recorder.__gc", "", "Releases the recorder's samples."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

std::vector<std::vector<Vec3>> recorded_trails(lua_State* L, int world, int arg) {
  push_recorders(L, world);
  const LuaRecorder* newest = nullptr;  // the newest one not finalised by hand
  for (lua_Integer i = static_cast<lua_Integer>(lua_rawlen(L, -1)); i >= 1 && !newest; --i) {
    lua_rawgeti(L, -1, i);
    newest = test_tagged<LuaRecorder>(L, -1, recorder_tag);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (newest == nullptr)
    arg_error(L, arg, "field 'show': 'trail' needs a recorder: rec = w:record{} first");
  const LuaRecorder& rec = *newest;
  std::vector<std::vector<Vec3>> trails;
  const SeriesInfo* position = find_series("position", true);
  for (std::size_t b = 0; b < rec.recorder->body_count(); ++b) {
    std::vector<Vec3> points = rec.recorder->vectors(*position, b);
    if (points.size() > 2000) points.erase(points.begin(), points.end() - 2000);
    trails.push_back(std::move(points));
  }
  return trails;
}

void open_record(lua_State* L, int lib) {
  lua_newtable(L);  // the type's table, for help("recorder") and help(rec)
  new_type(L, recorder_type, lua_gettop(L), metamethods);
  add_properties(L, recorder_type, properties);
  add_methods(L, recorder_type, methods);
  register_topic(L, -1, "recorder",
                 "A recording of a world's motion, made by w:record{every =, bodies =}; #rec is\n"
                 "the number of samples.");
  lua_setfield(L, lib, "recorder");
  add_methods(L, world_type, world_methods);
}

}  // namespace rigidlab::lua
