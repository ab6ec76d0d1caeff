// csv.write(path, columns, order): a header line and one row per index, numbers written with
// 17 significant digits so they read back exactly. Every number must be finite (like
// plot.lines): a NaN in a data file is a diverged simulation nobody noticed. Tables are read
// raw, so their metamethods cannot raise errors of their own from inside csv.write.
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "lua/binding.hpp"
#include "lua/modules.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::lua {
namespace {

int csv_write(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) type_error(L, 1, "string (a file path)");
  const char* path = lua_tostring(L, 1);
  if (is_sandboxed(L)) arg_error(L, 1, "files cannot be written in the sandbox");
  if (lua_type(L, 2) != LUA_TTABLE) type_error(L, 2, "table");
  if (lua_type(L, 3) != LUA_TTABLE) type_error(L, 3, "table");
  check_no_extra_args(L, 3);
  const int count = static_cast<int>(std::min<size_t>(lua_rawlen(L, 3), INT_MAX));
  if (count == 0) arg_error(L, 3, "order must list at least one column name");
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  for (int c = 1; c <= count; ++c) {
    if (lua_rawgeti(L, 3, c) != LUA_TSTRING)
      arg_error(L, 3, "order[%d] must be a column name (string), got %s", c, value_type_name(L, -1));
    names.push_back(lua_tostring(L, -1));
    if (names.back().find_first_of(",\"\n") != std::string::npos)
      arg_error(L, 3, "column name '%s' may not contain a comma, quote or newline",
                names.back().c_str());
    lua_pushvalue(L, -1);
    if (lua_rawget(L, 2) != LUA_TTABLE)
      arg_error(L, 2, "column '%s' must be a list of numbers, got %s", names.back().c_str(),
                value_type_name(L, -1));
    std::vector<double> values;
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      if (lua_rawgeti(L, -1, i) != LUA_TNUMBER)
        arg_error(L, 2, "column '%s' entry %d must be a number, got %s", names.back().c_str(),
                  (int)i, value_type_name(L, -1));
      const double x = lua_tonumber(L, -1);
      if (!std::isfinite(x))
        arg_error(L, 2, "column '%s' entry %d must be finite, got %s", names.back().c_str(),
                  (int)i, format_number(x).c_str());
      values.push_back(x);
      lua_pop(L, 1);
    }
    if (!columns.empty() && values.size() != columns[0].size())
      arg_error(L, 2, "column '%s' has %d entries but column '%s' has %d", names.back().c_str(),
                (int)values.size(), names[0].c_str(), (int)columns[0].size());
    columns.push_back(std::move(values));
    lua_pop(L, 2);
  }
  std::FILE* file = std::fopen(path, "w");
  if (file == nullptr) arg_error(L, 1, "cannot open '%s' for writing: %s", path, std::strerror(errno));
  for (size_t c = 0; c < names.size(); ++c) std::fprintf(file, c ? ",%s" : "%s", names[c].c_str());
  std::fputc('\n', file);
  for (size_t row = 0; row < columns[0].size(); ++row) {
    for (size_t c = 0; c < columns.size(); ++c)
      std::fprintf(file, c ? ",%.17g" : "%.17g", columns[c][row]);
    std::fputc('\n', file);
  }
  const bool ok = std::fclose(file) == 0;
  if (!ok) function_error(L, "could not finish writing '%s'", path);
  return 0;
}

const Entry functions[] = {
    {"write", csv_write, "csv.write", "csv.write(path, columns, order)",
     "Writes a CSV file: columns maps a name to a list of numbers (all the same length), order\n"
     "lists the names in column order. A header line, then one row per index; numbers with 17\n"
     "significant digits, so they read back exactly."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_csv(lua_State* L, int lib) {
  lua_newtable(L);
  register_entries(L, -1, functions);
  register_topic(L, -1, "csv", "CSV files: csv.write(path, columns, order).");
  lua_setfield(L, lib, "csv");
}

}  // namespace rigidlab::lua
