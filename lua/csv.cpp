// csv.write(path, columns [, order]): argument parsing; present/csv writes the file (a header
// line and one row per index, numbers in the shortest form that reads back exactly). A column
// is a list of numbers or of vec3 (written as name.x, name.y, name.z). Every number must be
// finite (like plot.lines): a NaN in a data file is a diverged simulation nobody noticed.
// Tables are read raw, so their metamethods cannot raise errors of their own from inside.
#include <algorithm>
#include <climits>
#include <cmath>
#include <string>
#include <vector>

#include "lua/binding.hpp"
#include "lua/modules.hpp"
#include "lua/output_file.hpp"
#include "present/csv.hpp"

namespace rigidlab::lua {
namespace {

// The column names: `order` (argument 3) when given, else every key of `columns`, sorted.
std::vector<std::string> column_names(lua_State* L) {
  std::vector<std::string> names;
  if (lua_isnoneornil(L, 3)) {
    for (lua_pushnil(L); lua_next(L, 2) != 0; lua_pop(L, 1)) {
      if (lua_type(L, -2) != LUA_TSTRING)
        arg_error(L, 2, "column names must be strings, got the %s key '%s'",
                  value_type_name(L, -2), push_key_name(L, -2));
      std::size_t size = 0;
      const char* name = lua_tolstring(L, -2, &size);
      names.emplace_back(name, size);
    }
    if (names.empty()) arg_error(L, 2, "at least one column expected");
    std::sort(names.begin(), names.end());
    return names;
  }
  const int count = static_cast<int>(std::min<size_t>(lua_rawlen(L, 3), INT_MAX));
  if (count == 0) arg_error(L, 3, "order must list at least one column name");
  for (int c = 1; c <= count; ++c) {
    if (lua_rawgeti(L, 3, c) != LUA_TSTRING)
      arg_error(L, 3, "order[%d] must be a column name (string), got %s", c, value_type_name(L, -1));
    std::size_t size = 0;
    const char* name = lua_tolstring(L, -1, &size);
    names.emplace_back(name, size);
    lua_pop(L, 1);
    if (std::find(names.begin(), names.end() - 1, names.back()) != names.end() - 1)
      arg_error(L, 3, "order lists '%s' twice", names.back().c_str());
  }
  return names;
}

// With `order`: every column must be in it (a column left out would be dropped silently).
void check_all_listed(lua_State* L, const std::vector<std::string>& names) {
  for (lua_pushnil(L); lua_next(L, 2) != 0; lua_pop(L, 1)) {
    std::size_t size = 0;
    const char* key = lua_type(L, -2) == LUA_TSTRING ? lua_tolstring(L, -2, &size) : nullptr;
    const bool listed =
        key && std::find(names.begin(), names.end(), std::string(key, size)) != names.end();
    if (!listed)
      arg_error(L, 3, "column '%s' is not in order (list every column, or leave order out)",
                push_key_name(L, -2));
  }
}

// Appends column `name` of `columns` (a list of numbers, or of vec3: three columns).
void read_column(lua_State* L, const std::string& name, std::vector<present::Column>& out) {
  const int arg = lua_isnoneornil(L, 3) ? 2 : 3;
  if (const std::string problem = present::column_name_problem(name); !problem.empty())
    arg_error(L, arg, "column name '%s' %s", name.c_str(), problem.c_str());
  lua_pushlstring(L, name.data(), name.size());
  if (lua_rawget(L, 2) != LUA_TTABLE)
    arg_error(L, 2, "column '%s' must be a list of numbers or vec3, got %s", name.c_str(),
              value_type_name(L, -1));
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
  const bool vectors = n > 0 && lua_rawgeti(L, -1, 1) != LUA_TNUMBER && test_vec3(L, -1);
  if (n > 0) lua_pop(L, 1);
  const std::size_t first = out.size();
  for (const char* part : vectors ? std::vector<const char*>{".x", ".y", ".z"}
                                  : std::vector<const char*>{""})
    out.push_back(present::Column{name + part, {}});
  for (lua_Integer i = 1; i <= n; ++i) {
    const int type = lua_rawgeti(L, -1, i);
    const Vec3* v = vectors ? test_vec3(L, -1) : nullptr;
    if (vectors ? v == nullptr : type != LUA_TNUMBER)
      arg_error(L, 2, "column '%s' entry %d must be a %s, got %s", name.c_str(), (int)i,
                vectors ? "vec3 like entry 1" : "number", value_type_name(L, -1));
    for (int k = 0; k < (vectors ? 3 : 1); ++k) {
      const double x = vectors ? (*v)[k] : lua_tonumber(L, -1);
      if (!std::isfinite(x))
        arg_error(L, 2, "column '%s' entry %d must be finite, got %s", name.c_str(), (int)i,
                  format_number(x).c_str());
      out[first + k].values.push_back(x);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (first > 0 && out[first].values.size() != out[0].values.size())
    arg_error(L, 2, "column '%s' has %d entries but column '%s' has %d", name.c_str(),
              (int)out[first].values.size(), out[0].name.c_str(), (int)out[0].values.size());
}

int csv_write(lua_State* L) {
  const std::string path = check_output_path(L, 1, 1, nullptr);
  if (lua_type(L, 2) != LUA_TTABLE) type_error(L, 2, "table");
  if (!lua_isnoneornil(L, 3) && lua_type(L, 3) != LUA_TTABLE) type_error(L, 3, "table");
  check_no_extra_args(L, 3);
  std::vector<present::Column> columns;
  const std::vector<std::string> names = column_names(L);
  for (const std::string& name : names) read_column(L, name, columns);
  if (!lua_isnoneornil(L, 3)) check_all_listed(L, names);
  write_or_raise(L, 1, nullptr, [&] { present::write_csv(path, columns); });
  return 0;
}

const Entry functions[] = {
    {"write", csv_write, "csv.write", "csv.write(path, columns [, order])",
     "Writes a CSV file: columns maps a name to a list of numbers or of vec3 (all the same\n"
     "length; a vec3 column becomes three, name.x, name.y, name.z); order lists the names in\n"
     "column order (default: sorted) and must list them all. A header line, then one row per\n"
     "index; numbers in the shortest form that reads back exactly."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_csv(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "csv", "CSV files: csv.write(path, columns [, order]).");
  lua_setfield(L, lib, "csv");
}

}  // namespace rigidlab::lua
