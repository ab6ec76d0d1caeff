// The recorder binding: w:record and art:record start one (it samples the state now and after
// every `every`-th completed step), and rec:series / rec:csv read what it holds. A world keeps
// its recorders while they record (for w:render's trails); a recorder outlives its world
// safely, holding the world's body store, whose world() is null once the world is gone. An
// articulation's recorder is stopped and detached when it is collected.
#include "lua/record.hpp"

#include <memory>
#include <string>

#include "lua/articulation.hpp"
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
constexpr int owner_slot = 1;  // the recorder's user value: its world or articulation

struct LuaRecorder {
  std::shared_ptr<Recording> recording;
  std::shared_ptr<WorldRecorder> world;       // a world's: its bodies' ids
  std::shared_ptr<BodyStore> store;           // of that world
  std::shared_ptr<ArticulationRecorder> art;  // an articulation's
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

// Pushes a new recorder userdata whose owner is the value at stack index 1; empty.
LuaRecorder& push_recorder(lua_State* L) {
  void* memory = lua_newuserdatauv(L, sizeof(Tagged<LuaRecorder>), 1);
  auto* box = static_cast<Tagged<LuaRecorder>*>(memory);
  box->tag = 0;
  new (&box->value) LuaRecorder();
  box->tag = recorder_tag;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &recorder_metatable_key);
  lua_setmetatable(L, -2);
  lua_pushvalue(L, 1);
  lua_setiuservalue(L, -2, owner_slot);
  return box->value;
}

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
  LuaRecorder& rec = push_recorder(L);
  rec.store = w.world.shared_store();
  rec.world = protect(L, [&] { return std::make_shared<WorldRecorder>(w.world, ids, every); });
  rec.recording = rec.world;
  push_recorders(L, 1);  // the world keeps its recorders while they record
  lua_pushvalue(L, -2);
  lua_rawseti(L, -2, static_cast<lua_Integer>(lua_rawlen(L, -2)) + 1);
  lua_pop(L, 1);
  protect(L, [&] { w.world.add_step_observer(rec.world); });
  return 1;
}

// art:record{every =}
int articulation_record(lua_State* L) {
  check_articulation(L, 1);
  check_no_extra_args(L, 2);
  long every = 1;
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_istable(L, 2)) type_error(L, 2, "table");
    static const char* const fields[] = {"every", nullptr};
    check_fields(L, 2, fields);
    if (lua_getfield(L, 2, "every") != LUA_TNIL)
      every = static_cast<long>(check_integer(L, lua_gettop(L), Where::field(2, "every"), 1,
                                              1'000'000'000));
    lua_pop(L, 1);
  }
  LuaArticulation& a = check_articulation_unlocked(L, 1, "start a recorder");
  LuaRecorder& rec = push_recorder(L);
  rec.art = protect(L, [&] { return std::make_shared<ArticulationRecorder>(a.art, every); });
  rec.recording = rec.art;
  protect(L, [&] { a.art.add_step_observer(rec.art); });
  return 1;
}

// ---- reading ---------------------------------------------------------------------------------

// Which body, link or coordinate the value at `arg` names for an indexed series: a body of the
// recording (a world's), a link object, number or name (an articulation's links), or a number
// from 1 (a coordinate, or the position in rec.bodies).
std::size_t check_index(lua_State* L, const LuaRecorder& rec, const SeriesInfo& series, int arg) {
  const std::size_t count = rec.recording->index_count(series);
  const bool link = rec.art != nullptr && std::string(series.name) != "q" &&
                    std::string(series.name) != "qd";
  if (link) {
    lua_getiuservalue(L, 1, owner_slot);
    const int art = lua_gettop(L);
    if (test_articulation(L, art) == nullptr) arg_error(L, arg, "the articulation was finalised");
    const int k = check_link_of(L, art, arg, Where::argument(arg, "link"));
    lua_pop(L, 1);
    return static_cast<std::size_t>(k);
  }
  lua_Integer k = 0;
  if (to_integer(L, arg, k) || rec.world == nullptr) {
    if (!to_integer(L, arg, k)) type_error(L, arg, "number");
    if (k < 1 || static_cast<std::size_t>(k) > count)
      arg_error(L, arg, "%s must be from 1 to %d, got %d", rec.world ? "body number" : "the index",
                static_cast<int>(count), static_cast<int>(k));
    return static_cast<std::size_t>(k - 1);
  }
  const BodyHandle& handle = check_body_handle(L, arg, Where::argument(arg));
  const auto& ids = rec.world->ids();
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
  const Recording& r = *rec.recording;
  std::size_t length = 0;
  const std::string name = check_name(L, 2, Where::argument(2, "name"), &length);
  check_no_extra_args(L, 3);
  const bool indexed = !lua_isnoneornil(L, 3) || (r.find(name, false) == nullptr &&
                                                  r.find(name, true) != nullptr);
  const SeriesInfo* series = r.find(name, indexed);
  const char* what = rec.art ? (indexed ? "indexed articulation" : "articulation")
                             : (indexed ? "body" : "world");
  if (series == nullptr) {
    std::string names;
    for (const SeriesInfo& s : r.series())
      if (s.indexed == indexed || std::string(s.name) == "t")
        names += std::string(names.empty() ? "" : ", ") + "'" + s.name + "'";
    arg_error(L, 2, "no %s series '%s'; the %s series are %s", what, name.c_str(), what,
              names.c_str());
  }
  std::size_t index = 0;
  if (series->indexed) {
    if (!lua_isnoneornil(L, 3)) {
      index = check_index(L, rec, *series, 3);
    } else if (r.index_count(*series) != 1) {
      const bool coordinate = rec.art != nullptr && std::string(series->name)[0] == 'q';
      const char* one = rec.world ? "body" : coordinate ? "coordinate" : "link";
      const char* many = rec.world ? "bodies" : coordinate ? "coordinates" : "links";
      arg_error(L, 3, "a %s is needed for '%s' (%d %s are recorded)", one, name.c_str(),
                static_cast<int>(r.index_count(*series)), many);
    }
  }
  if (series->kind == SeriesKind::number) {
    push_numbers(L, r.numbers(*series, index));
  } else if (series->kind == SeriesKind::vector) {
    const std::vector<Vec3> values = r.vectors(*series, index);
    lua_createtable(L, static_cast<int>(values.size()), 0);
    for (std::size_t i = 0; i < values.size(); ++i) {
      push_vec3(L, values[i]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
    }
  } else {
    const std::vector<Quat> values = r.rotations(*series, index);
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
  const std::vector<present::Column> columns = protect(L, [&] { return rec.recording->columns(); });
  write_or_raise(L, 2, nullptr, [&] { present::write_csv(path, columns); });
  return 0;
}

// Detaches an articulation's recorder (when the articulation is still there and not stepping).
void detach_from_articulation(lua_State* L, LuaRecorder& rec) {
  lua_getiuservalue(L, 1, owner_slot);
  LuaArticulation* a = test_articulation(L, -1);
  if (a != nullptr && !a->art.stepping()) a->art.remove_step_observer(rec.art.get());
  lua_pop(L, 1);
}

int recorder_stop(lua_State* L) {
  LuaRecorder& rec = check_recorder(L, 1);
  check_no_extra_args(L, 1);
  if (rec.art != nullptr) {
    lua_getiuservalue(L, 1, owner_slot);
    const LuaArticulation* a = test_articulation(L, -1);
    if (a != nullptr && a->art.stepping())
      arg_error(L, 1, "the articulation is stepping: cannot stop a recorder until it returns");
    lua_pop(L, 1);
    rec.recording->stop("stopped by rec:stop()");
    detach_from_articulation(L, rec);
    return 0;
  }
  World* world = rec.store->world();
  if (world != nullptr && world->stepping())
    arg_error(L, 1, "the world is stepping: cannot stop a recorder until world:step returns");
  rec.recording->stop("stopped by rec:stop()");
  if (world != nullptr) world->remove_step_observer(rec.world.get());
  if (lua_getiuservalue(L, 1, owner_slot) == LUA_TUSERDATA && test_world(L, -1) != nullptr) {
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
  push_numbers(L, check_recorder(L, object).recording->times());
}
void get_count(lua_State* L, int object, const Property&) {
  lua_pushinteger(L, static_cast<lua_Integer>(check_recorder(L, object).recording->samples()));
}
void get_every(lua_State* L, int object, const Property&) {
  lua_pushinteger(L, check_recorder(L, object).recording->every());
}
void get_recording(lua_State* L, int object, const Property&) {
  const LuaRecorder& rec = check_recorder(L, object);  // and its world still there
  bool owner = true;
  if (rec.world != nullptr) {
    owner = rec.store->world() != nullptr;
  } else {
    lua_getiuservalue(L, object, owner_slot);
    owner = test_articulation(L, -1) != nullptr;
    lua_pop(L, 1);
  }
  lua_pushboolean(L, rec.recording->recording() && owner);
}
void get_stop_reason(lua_State* L, int object, const Property&) {
  const Recording& r = *check_recorder(L, object).recording;
  if (r.recording()) lua_pushnil(L);
  else lua_pushstring(L, r.stop_reason().c_str());
}
void get_bodies(lua_State* L, int object, const Property&) {
  const LuaRecorder& rec = check_recorder(L, object);
  object = lua_absindex(L, object);
  lua_getiuservalue(L, object, owner_slot);
  const int owner = lua_gettop(L);
  if (rec.art != nullptr) {  // the links, all of them
    const std::size_t links = rec.art->links();
    lua_createtable(L, static_cast<int>(links), 0);
    if (test_articulation(L, owner) != nullptr)
      for (std::size_t k = 0; k < links; ++k) {
        push_link(L, owner, static_cast<int>(k));
        lua_rawseti(L, -2, static_cast<lua_Integer>(k) + 1);
      }
    lua_remove(L, owner);
    return;
  }
  const std::vector<BodyStore::Id> ids = rec.world->ids();
  lua_createtable(L, static_cast<int>(ids.size()), 0);
  if (test_world(L, owner) != nullptr) {
    const BodyStore& store = *rec.store;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (!store.contains(ids[i])) continue;  // left the world: recording stopped then
      push_world_body(L, owner, store.index_of(ids[i]));
      lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
    }
  }
  lua_remove(L, owner);
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
    {"bodies", get_bodies, nullptr,
     "the bodies recorded (an articulation's: its links), in the order of rec:csv's columns",
     "set by w:record{bodies =}", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}};

int recorder_len(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(check_recorder(L, 1).recording->samples()));
  return 1;
}

int recorder_tostring(lua_State* L) {
  const LuaRecorder& rec = check_recorder(L, 1);
  const Recording& r = *rec.recording;
  const std::size_t n = rec.art ? rec.art->links() : rec.world->ids().size();
  const char* what = rec.art ? (n == 1 ? "link" : "links") : (n == 1 ? "body" : "bodies");
  lua_pushfstring(L, "recorder(%d %s, %d samples, every %d step%s, %s)", static_cast<int>(n), what,
                  static_cast<int>(r.samples()), static_cast<int>(r.every()),
                  r.every() == 1 ? "" : "s", r.recording() ? "recording" : "stopped");
  return 1;
}

int recorder_gc(lua_State* L) {
  LuaRecorder* r = test_tagged<LuaRecorder>(L, 1, recorder_tag);
  if (r == nullptr) return 0;
  if (r->art != nullptr) {  // nobody can read it any more: stop it, and detach it if possible
    r->recording->stop("collected");
    detach_from_articulation(L, *r);
  }
  r->~LuaRecorder();  // a world keeps its share of a recorder still observing it
  static_cast<Tagged<LuaRecorder>*>(lua_touserdata(L, 1))->tag = 0;
  return 0;
}

const Entry world_methods[] = {
    {"record", world_record, "world:record", "w:record{every =, bodies =} -> recorder",
     "Records the world from now on: a sample now and after every `every`-th step (default\n"
     "1) of the time, the energies, the momenta, and of each body in `bodies` (default all)\n"
     "its position, orientation, velocity and angular velocity (world and body frame), kinetic\n"
     "energy and angular momentum about its COM. rec.t, rec:series(name [, body]),\n"
     "rec:csv(path), rec:stop(); w:render{show = 'trail'} draws the newest recorder's paths.\n"
     "If the world steps on from an earlier time (a view quit after a rewind), the samples\n"
     "from then on are replaced by the new motion."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry articulation_methods[] = {
    {"record", articulation_record, "articulation:record", "art:record{every =} -> recorder",
     "Records the articulation from now on: a sample now and after every `every`-th step\n"
     "(default 1) of the time, the energies, q and qd, and each link's pose, COM and angular\n"
     "velocity. rec:series(name [, index]), rec:csv(path), rec:stop() as for a world."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const Entry methods[] = {
    {"series", recorder_series, "recorder:series", "rec:series(name [, body]) -> list",
     "The samples of one quantity, ready for plot.lines: world series 't', 'kinetic_energy',\n"
     "'potential_energy', 'energy' (numbers, J), 'linear_momentum', 'angular_momentum' (vec3,\n"
     "about the origin); with a body (a body, or its number in rec.bodies; may be left out\n"
     "when one body is recorded): 'position', 'velocity', 'angular_velocity' (world),\n"
     "'velocity_body', 'angular_velocity_body' (body frame), 'orientation' (quat),\n"
     "'kinetic_energy', 'angular_momentum' (about the COM, world), 'angular_momentum_body'.\n"
     "An articulation's: 't', 'kinetic_energy', 'potential_energy', 'energy'; 'q' and 'qd'\n"
     "with a coordinate number; with a link (object, number or name): 'position' (its joint),\n"
     "'orientation', 'com', 'angular_velocity' (world)."},
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
  const SeriesInfo* position = rec.world->find("position", true);
  for (std::size_t b = 0; b < rec.world->ids().size(); ++b) {
    std::vector<Vec3> points = rec.world->vectors(*position, b);
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
  add_methods(L, articulation_type, articulation_methods);
}

}  // namespace rigidlab::lua
