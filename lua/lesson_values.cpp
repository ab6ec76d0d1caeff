// ctx:expect's comparison and the lesson's way of writing values. See lua/lesson_values.hpp.
// Tables are read raw (lua_next, lua_rawget): comparing or showing a value runs none of its
// metamethods, so a check cannot be talked into passing by an __index or __eq.
#include "lua/lesson_values.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <utility>
#include <vector>

#include "lua/binding.hpp"
#include "lua/text_layout.hpp"

namespace rigidlab::lua {
namespace {

constexpr int max_depth = 64;          // of a comparison
constexpr int max_shown_depth = 3;     // of a table as written
constexpr int max_shown_entries = 16;  // per table as written

// ---- keys in a fixed order -------------------------------------------------------------------

// A key of a table, for sorting: numbers by value, then booleans, then strings by their bytes,
// then anything else by its type name (and address: no better order exists for a function).
struct SortKey {
  int category;  // 0 number, 1 boolean, 2 string, 3 other
  double number = 0.0;
  std::string text;
  const void* address = nullptr;
  int slot;  // where the key is kept: keys[slot] of the key table
};

bool operator<(const SortKey& a, const SortKey& b) {
  if (a.category != b.category) return a.category < b.category;
  if (a.number != b.number) return a.number < b.number;
  if (a.text != b.text) return a.text < b.text;
  return std::less<const void*>()(a.address, b.address);
}

SortKey sort_key(lua_State* L, int index, int slot) {
  SortKey key{3, 0.0, "", nullptr, slot};
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      key.category = 0;
      key.number = lua_tonumber(L, index);
      break;
    case LUA_TBOOLEAN:
      key.category = 1;
      key.number = lua_toboolean(L, index);
      break;
    case LUA_TSTRING: {
      size_t length = 0;
      const char* text = lua_tolstring(L, index, &length);
      key.category = 2;
      key.text.assign(text, length);
      break;
    }
    default:
      key.text = lua_typename(L, lua_type(L, index));
      key.address = lua_topointer(L, index);
  }
  return key;
}

// Pushes a list of the keys of the tables at `first` and (if not 0) `second`, each once,
// sorted; returns how many.
int push_sorted_keys(lua_State* L, int first, int second) {
  luaL_checkstack(L, 4, "table nested too deeply");
  lua_newtable(L);
  const int keys = lua_gettop(L);
  std::vector<SortKey> order;
  for (int table : {first, second}) {
    if (table == 0) continue;
    lua_pushnil(L);
    while (lua_next(L, table) != 0) {
      lua_pop(L, 1);
      if (table == second && first != 0) {  // already listed when the first has it too
        lua_pushvalue(L, -1);
        const bool listed = lua_rawget(L, first) != LUA_TNIL;
        lua_pop(L, 1);
        if (listed) continue;
      }
      const int slot = static_cast<int>(order.size()) + 1;
      order.push_back(sort_key(L, -1, slot));
      lua_pushvalue(L, -1);
      lua_rawseti(L, keys, slot);
    }
  }
  std::sort(order.begin(), order.end());
  lua_createtable(L, static_cast<int>(order.size()), 0);
  for (size_t i = 0; i < order.size(); ++i) {
    lua_rawgeti(L, keys, order[i].slot);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i) + 1);
  }
  lua_remove(L, keys);
  return static_cast<int>(order.size());
}

bool is_identifier(const char* text, size_t length) {
  if (length == 0 || std::isdigit(static_cast<unsigned char>(text[0]))) return false;
  for (size_t i = 0; i < length; ++i)
    if (!(std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) return false;
  static const char* const reserved[] = {"and",   "break", "do",       "else", "elseif", "end",
                                         "false", "for",   "function", "goto", "if",     "in",
                                         "local", "nil",   "not",      "or",   "repeat", "return",
                                         "then",  "true",  "until",    "while"};
  for (const char* word : reserved)
    if (std::strlen(word) == length && std::memcmp(word, text, length) == 0) return false;
  return true;
}

// A key as a path step: ".name" (just "name" first), "[2]", "[\"a b\"]", "[true]".
std::string path_step(lua_State* L, int key, bool first) {
  size_t length = 0;
  if (lua_type(L, key) == LUA_TSTRING) {
    const char* text = lua_tolstring(L, key, &length);
    if (is_identifier(text, length)) return (first ? "" : ".") + std::string(text, length);
    return "[" + quoted(text, length) + "]";
  }
  if (lua_type(L, key) == LUA_TNUMBER)
    return "[" +
           (lua_isinteger(L, key) ? std::to_string(lua_tointeger(L, key))
                                  : lesson_number(lua_tonumber(L, key))) +
           "]";
  if (lua_type(L, key) == LUA_TBOOLEAN) return lua_toboolean(L, key) ? "[true]" : "[false]";
  return std::string("[") + value_type_name(L, key) + "]";
}

// ---- writing values --------------------------------------------------------------------------

std::string number_list(const double* x, int n) {
  std::string text;
  for (int i = 0; i < n; ++i) text += (i ? ", " : "") + lesson_number(x[i]);
  return text;
}

std::string format_at_depth(lua_State* L, int index, const std::string& indent, bool quote,
                            int depth);

// {1, 2, x = 5}: the entries 1, 2, ... while they follow on, then `key = value`.
std::string format_table(lua_State* L, int index, int depth) {
  if (depth >= max_shown_depth) return "{…}";
  const int count = push_sorted_keys(L, index, 0);
  const int keys = lua_gettop(L);
  std::string text = "{";
  lua_Integer next_position = 1;
  for (int i = 1; i <= count; ++i) {
    if (i > max_shown_entries) {
      text += ", … (" + std::to_string(count) + " entries)";
      break;
    }
    lua_rawgeti(L, keys, i);
    const int key = lua_gettop(L);
    if (i > 1) text += ", ";
    if (lua_isinteger(L, key) && lua_tointeger(L, key) == next_position) {
      ++next_position;
    } else {
      next_position = 0;  // the list has ended
      std::string step = path_step(L, key, true);
      text += step + " = ";
    }
    lua_pushvalue(L, key);
    lua_rawget(L, index);
    text += format_at_depth(L, -1, "", true, depth + 1);
    lua_pop(L, 2);
  }
  lua_pop(L, 1);
  return text + "}";
}

std::string format_at_depth(lua_State* L, int index, const std::string& indent, bool quote,
                            int depth) {
  index = lua_absindex(L, index);
  luaL_checkstack(L, 6, "table nested too deeply");
  if (lua_type(L, index) == LUA_TNUMBER) {
    if (lua_isinteger(L, index)) return std::to_string(lua_tointeger(L, index));
    return lesson_number(lua_tonumber(L, index));
  }
  if (lua_type(L, index) == LUA_TSTRING) {
    size_t length = 0;
    const char* text = lua_tolstring(L, index, &length);
    return quote ? quoted(text, length) : std::string(text, length);
  }
  if (const Vec3* v = test_vec3(L, index)) return "(" + number_list(v->data(), 3) + ")";
  if (const Quat* q = test_quat(L, index)) {
    const double wxyz[] = {q->w(), q->x(), q->y(), q->z()};
    return "quat(" + number_list(wxyz, 4) + ")";
  }
  if (const Mat3* m = test_mat3(L, index)) {
    std::string text = indent.empty() ? "(" : "";
    for (int i = 0; i < 3; ++i) {
      const double row[] = {(*m)(i, 0), (*m)(i, 1), (*m)(i, 2)};
      const std::string opening = indent.empty() ? (i ? ", (" : "(") : "\n" + indent + "(";
      text += opening + number_list(row, 3) + ")";
    }
    return indent.empty() ? text + ")" : text;
  }
  if (lua_type(L, index) == LUA_TTABLE) return format_table(L, index, depth);
  std::string text = luaL_tolstring(L, index, nullptr);
  lua_pop(L, 1);
  return text;
}

// ---- comparing -------------------------------------------------------------------------------

// Component names for the reason: x, y, z of a vec3; w, x, y, z of a quat.
const char* const vec3_names[] = {"x", "y", "z"};
const char* const quat_names[] = {"w", "x", "y", "z"};

class Comparison {
 public:
  Comparison(lua_State* L, const Tolerance& tolerance) : L_(L), tolerance_(tolerance), poller_(L) {}

  // The reason got and want differ ("" when they agree); `path` names where they are.
  std::string compare(int got, int want, const std::string& path, int depth) {
    return difference(got, want, path, depth);
  }

 private:
  std::string at(const std::string& path, const std::string& reason) const {
    if (reason.empty() || path.empty()) return reason;
    return "key " + path + ": " + reason;
  }

  // Within tolerance, or equal (±inf); NaN never is.
  bool close(double got, double want) const {
    if (got == want) return true;
    if (!std::isfinite(got) || !std::isfinite(want)) return false;  // inf: no bound holds it
    const double bound =
        std::max(tolerance_.absolute, tolerance_.relative * std::max(1.0, std::fabs(want)));
    return std::fabs(got - want) <= bound;
  }

  std::string off_by(double got, double want) const {
    if (std::isnan(got)) return "got nan: nan equals nothing";
    if (std::isnan(want)) return "want nan: nan equals nothing";
    return "off by " + format_number(std::fabs(got - want), 4);  // 4 digits tell how far
  }

  std::string components(const double* got, const double* want, int n, const char* const* names,
                         int columns) const {
    for (int i = 0; i < n; ++i) {
      if (close(got[i], want[i])) continue;
      std::string which = names != nullptr ? std::string("component ") + names[i]
                                           : "entry (" + std::to_string(i / columns + 1) + ", " +
                                                 std::to_string(i % columns + 1) + ")";
      return which + " " + off_by(got[i], want[i]);
    }
    return "";
  }

  std::string strings(int got, int want) const {
    size_t got_length = 0, want_length = 0;
    const char* a = lua_tolstring(L_, got, &got_length);
    const char* b = lua_tolstring(L_, want, &want_length);
    if (got_length == want_length && std::memcmp(a, b, got_length) == 0) return "";
    size_t same = 0;  // bytes in common, then back to the start of a code point
    while (same < got_length && same < want_length && a[same] == b[same]) ++same;
    while (same > 0 && same < got_length && (static_cast<unsigned char>(a[same]) & 0xC0) == 0x80)
      --same;
    const std::string character = std::to_string(display_width(std::string(a, same)) + 1);
    if (same == got_length) return "got ends at character " + character + ", want goes on";
    if (same == want_length) return "want ends at character " + character + ", got goes on";
    return "strings differ at character " + character;
  }

  std::string difference(int got, int want, const std::string& path, int depth) {
    const int type = lua_type(L_, want);
    if (type == LUA_TNUMBER && lua_type(L_, got) == LUA_TNUMBER) {
      if (lua_isinteger(L_, got) && lua_isinteger(L_, want) &&
          lua_tointeger(L_, got) == lua_tointeger(L_, want))
        return "";
      const double a = lua_tonumber(L_, got), b = lua_tonumber(L_, want);
      return close(a, b) ? "" : at(path, off_by(a, b));
    }
    if (type == LUA_TSTRING && lua_type(L_, got) == LUA_TSTRING) {
      const std::string reason = strings(got, want);
      return reason.empty() ? "" : at(path, reason);
    }
    if (const Vec3* b = test_vec3(L_, want)) {
      if (const Vec3* a = test_vec3(L_, got))
        return at(path, components(a->data(), b->data(), 3, vec3_names, 0));
    } else if (const Quat* b = test_quat(L_, want)) {
      if (const Quat* a = test_quat(L_, got)) {
        const double x[] = {a->w(), a->x(), a->y(), a->z()};
        const double y[] = {b->w(), b->x(), b->y(), b->z()};
        return at(path, components(x, y, 4, quat_names, 0));
      }
    } else if (const Mat3* b = test_mat3(L_, want)) {
      if (const Mat3* a = test_mat3(L_, got)) {
        double x[9], y[9];
        for (int k = 0; k < 9; ++k) x[k] = (*a)(k / 3, k % 3), y[k] = (*b)(k / 3, k % 3);
        return at(path, components(x, y, 9, nullptr, 3));
      }
    } else if (type == LUA_TTABLE && lua_type(L_, got) == LUA_TTABLE) {
      return tables(got, want, path, depth);
    } else if (lua_type(L_, got) == type && type != LUA_TUSERDATA) {
      if (lua_rawequal(L_, got, want)) return "";
      if (type == LUA_TBOOLEAN)
        return at(path, std::string("got ") + (lua_toboolean(L_, got) ? "true" : "false") +
                            ", want " + (lua_toboolean(L_, want) ? "true" : "false"));
      return at(path, "got another " + std::string(value_type_name(L_, got)));
    }
    if (lua_rawequal(L_, got, want)) return "";  // the same userdata (a body, a world)
    if (std::strcmp(value_type_name(L_, got), value_type_name(L_, want)) == 0)
      return at(path, "got another " + std::string(value_type_name(L_, got)));
    return at(path, "got " + a_type_name(L_, got) + ", want " + a_type_name(L_, want));
  }

  std::string tables(int got, int want, const std::string& path, int depth) {
    if (depth >= max_depth)
      return at(path, "tables nested deeper than " + std::to_string(max_depth) + " levels");
    // A pair already being compared (a cycle) agrees so far: the comparison of the pair
    // that is open decides.
    const auto pair = std::make_pair(lua_topointer(L_, got), lua_topointer(L_, want));
    if (agreed_.count(pair) != 0 || !open_.insert(pair).second) return "";
    poller_.poll();  // a huge table takes a while: Ctrl-C and the time limit stop it here
    const int count = push_sorted_keys(L_, want, got);
    const int keys = lua_gettop(L_);
    std::string reason;
    for (int i = 1; i <= count && reason.empty(); ++i) {
      lua_rawgeti(L_, keys, i);
      const int key = lua_gettop(L_);
      lua_pushvalue(L_, key);
      const bool in_got = lua_rawget(L_, got) != LUA_TNIL;
      lua_pushvalue(L_, key);
      const bool in_want = lua_rawget(L_, want) != LUA_TNIL;
      const std::string where = path + path_step(L_, key, path.empty());
      if (!in_got)
        reason = "key " + where + ": missing (want " + short_value(-1) + ")";
      else if (!in_want)
        reason = "key " + where + ": not expected (got " + short_value(-2) + ")";
      else
        reason = compare(key + 1, key + 2, where, depth + 1);
      lua_settop(L_, key - 1);
    }
    lua_pop(L_, 1);
    open_.erase(pair);
    if (reason.empty()) agreed_.insert(pair);  // a table shared twice is compared once
    return reason;
  }

  std::string short_value(int index) {
    std::string text = format_at_depth(L_, index, "", true, max_shown_depth - 1);
    return text.size() > 40 ? text.substr(0, 37) + "..." : text;
  }

  lua_State* L_;
  const Tolerance& tolerance_;
  StopPoller poller_;
  std::set<std::pair<const void*, const void*>> open_;    // being compared (cycles)
  std::set<std::pair<const void*, const void*>> agreed_;  // compared and equal
};

}  // namespace

std::string describe_tolerance(const Tolerance& tolerance) {
  std::string text;
  if (tolerance.relative > 0.0) text += "rel " + format_number(tolerance.relative);
  if (tolerance.absolute > 0.0)
    text += (text.empty() ? "abs " : ", abs ") + format_number(tolerance.absolute);
  return text.empty() ? "exact" : text;
}

std::string compare_values(lua_State* L, int got, int want, const Tolerance& tolerance) {
  got = lua_absindex(L, got);
  want = lua_absindex(L, want);
  Comparison comparison(L, tolerance);
  return comparison.compare(got, want, "", 0);
}

std::string format_value(lua_State* L, int index, const std::string& indent, bool quote) {
  return format_at_depth(L, index, indent, quote, 0);
}

std::string a_type_name(lua_State* L, int index) {
  if (lua_isnil(L, index)) return "nil";
  const std::string name = value_type_name(L, index);
  const bool vowel = std::strchr("aeiou", name[0]) != nullptr;
  return (vowel ? "an " : "a ") + name;
}

std::string lesson_number(double x) { return format_number(x == 0.0 ? 0.0 : x, 10); }

}  // namespace rigidlab::lua
