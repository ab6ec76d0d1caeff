#include "cli/pretty_print.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "cli/limits.hpp"
#include "cli/lua_names.hpp"
#include "lua/binding.hpp"
#include "lua/text_layout.hpp"

namespace rigidlab::cli {
namespace {

constexpr int max_depth = 4;               // tables nested deeper show as {…}
constexpr int max_entries = 50;            // shown per table, the rest counted
constexpr std::size_t max_string = 200;    // bytes of a string or tostring inside a table
constexpr std::size_t max_total = 20000;   // bytes of one value's leaves; then "…"
constexpr int poll_interval = 1024;        // keys between two polls of Ctrl-C and the clock

// A string as a Lua literal, cut after max_string bytes.
std::string quoted(const char* text, std::size_t length) {
  return lua::quoted(text, length, max_string);
}

// The terminal's width, or COLUMNS, or 80.
int output_width() {
  winsize size{};
  if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0)
    return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) {
    const int value = std::atoi(columns);
    if (value > 0) return value;
  }
  return 80;
}

// The sort order of the keys that are not in the array part: numbers, strings, then others
// by type; each group in its natural order (others by address, as tostring shows them).
struct Key {
  int group;  // 0 number, 1 string, 2 boolean, 3 other
  double number = 0.0;
  std::string text;
  const void* pointer = nullptr;
  int slot;  // index of the key in the keys table
  bool operator<(const Key& other) const {
    if (group != other.group) return group < other.group;
    if (group == 0) return number < other.number;
    if (group == 1 || group == 2) return text < other.text;
    return pointer < other.pointer;
  }
};

class Formatter {
 public:
  explicit Formatter(lua_State* L) : L_(L), width_(output_width()), stop_(L) {}
  std::string top(int index);

 private:
  std::string value(int index, int depth, int indent);
  std::string table(int index, int depth, int indent);
  std::string key_text(int index);
  std::string tostring(int index);
  std::string leaf(std::string text);
  std::string layout(const std::vector<std::string>& entries, std::size_t packable,
                     int indent) const;
  void poll(int& count) const {
    if (++count % poll_interval == 0) stop_.poll();
  }

  lua_State* L_;
  int width_;
  std::size_t produced_ = 0;
  std::vector<const void*> path_;  // the tables being shown, outermost first
  lua::StopPoller stop_;
};

// Counts the leaf against the limit on the whole: past it, leaves become "…".
std::string Formatter::leaf(std::string text) {
  if (produced_ > max_total) return "…";
  produced_ += text.size();
  return text;
}

// luaL_tolstring (__tostring, __name) run protected: an error in a __tostring is shown, not
// raised, unless it is a limit, Ctrl-C or the memory error, which stop the printing too.
std::string Formatter::tostring(int index) {
  index = lua_absindex(L_, index);
  lua_pushcfunction(L_, [](lua_State* L) {
    luaL_tolstring(L, 1, nullptr);
    return 1;
  });
  lua_pushvalue(L_, index);
  const int status = lua_pcall(L_, 1, 1, 0);
  const char* text = lua_tostring(L_, -1);
  std::string result = text != nullptr ? text : "(error object is not a string)";
  if (status != LUA_OK) {
    const LimitedState* limits = LimitedState::of(L_);
    if (status == LUA_ERRMEM || (limits != nullptr && limits->stopped_by(result.c_str())))
      lua_error(L_);
    result = "<error in __tostring: " + result.substr(0, result.find('\n')) + ">";
  }
  lua_pop(L_, 1);
  return result;
}

std::string Formatter::key_text(int index) {
  switch (lua_type(L_, index)) {
    case LUA_TSTRING: {
      std::size_t length = 0;
      const char* text = lua_tolstring(L_, index, &length);
      return is_name(text, length) && !is_keyword(text, length) ? std::string(text, length) + " = "
                                         : "[" + quoted(text, length) + "] = ";
    }
    case LUA_TNUMBER: {
      lua_pushvalue(L_, index);  // lua_tolstring converts in place: a copy
      std::string text = "[" + std::string(lua_tostring(L_, -1)) + "] = ";
      lua_pop(L_, 1);
      return text;
    }
    case LUA_TBOOLEAN:
      return lua_toboolean(L_, index) ? "[true] = " : "[false] = ";
    default: {  // no metamethod runs for a key
      char text[64];
      std::snprintf(text, sizeof text, "[%s: %p] = ", luaL_typename(L_, index),
                    lua_topointer(L_, index));
      return text;
    }
  }
}

// One line when every entry is on one line and it fits the width. Else the first `packable`
// entries (values of the array part, on one line each) are packed into lines as wide as the
// terminal (a column of numbers would run off the screen), and the others (with keys, or
// over lines) come one a line.
std::string Formatter::layout(const std::vector<std::string>& entries, std::size_t packable,
                              int indent) const {
  std::size_t length = static_cast<std::size_t>(indent) + 2;
  bool one_line = true;
  for (const std::string& entry : entries) {
    length += entry.size() + 2;
    one_line = one_line && entry.find('\n') == std::string::npos;
  }
  if (one_line && length <= static_cast<std::size_t>(width_)) {
    std::string result = "{";
    for (std::size_t i = 0; i < entries.size(); ++i) result += (i > 0 ? ", " : "") + entries[i];
    return result + "}";
  }
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  std::string result = "{\n" + pad;
  std::size_t column = pad.size();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const bool last = i + 1 == entries.size();
    const std::size_t room = entries[i].size() + (last ? 0 : 1);
    const bool pack = i < packable && entries[i].find('\n') == std::string::npos &&
                      entries[i - (i > 0 ? 1 : 0)].find('\n') == std::string::npos;
    if (i > 0 && (!pack || column + 1 + room > static_cast<std::size_t>(width_))) {
      result += "\n" + pad;
      column = pad.size();
    } else if (i > 0) {
      result += ' ';
      ++column;
    }
    result += entries[i] + (last ? "" : ",");
    column += room;
  }
  return result + "\n" + std::string(static_cast<std::size_t>(indent), ' ') + "}";
}

std::string Formatter::table(int index, int depth, int indent) {
  index = lua_absindex(L_, index);
  luaL_checkstack(L_, 8, "a table nested too deep to print");
  std::vector<std::string> entries;
  int polls = 0;
  lua_Integer array = 0;  // the array part: 1..array are non-nil
  while (lua_rawgeti(L_, index, array + 1) != LUA_TNIL) {
    ++array;
    if (array <= max_entries) entries.push_back(value(-1, depth + 1, indent + 2));
    lua_pop(L_, 1);
    poll(polls);
  }
  lua_pop(L_, 1);
  std::vector<Key> keys;
  lua_newtable(L_);  // the other keys, to sort them
  const int stash = lua_gettop(L_);
  for (lua_pushnil(L_); lua_next(L_, index) != 0;) {
    lua_pop(L_, 1);
    poll(polls);
    lua_Integer n = 0;
    if (lua_isinteger(L_, -1) && (n = lua_tointeger(L_, -1)) >= 1 && n <= array) continue;
    Key key{3, 0.0, "", lua_topointer(L_, -1), static_cast<int>(keys.size()) + 1};
    if (lua_type(L_, -1) == LUA_TNUMBER) key = Key{0, lua_tonumber(L_, -1), "", nullptr, key.slot};
    if (lua_type(L_, -1) == LUA_TSTRING) key = Key{1, 0.0, lua_tostring(L_, -1), nullptr, key.slot};
    if (lua_type(L_, -1) == LUA_TBOOLEAN)
      key = Key{2, 0.0, lua_toboolean(L_, -1) ? "true" : "false", nullptr, key.slot};
    keys.push_back(key);
    lua_pushvalue(L_, -1);
    lua_rawseti(L_, stash, key.slot);
  }
  std::sort(keys.begin(), keys.end());
  const std::size_t room = static_cast<std::size_t>(std::max<lua_Integer>(0, max_entries - array));
  for (std::size_t i = 0; i < keys.size() && i < room; ++i) {
    lua_rawgeti(L_, stash, keys[i].slot);
    std::string key = key_text(-1);
    lua_rawget(L_, index);
    entries.push_back(key + value(-1, depth + 1, indent + 2));
    lua_pop(L_, 1);
  }
  lua_pop(L_, 1);
  const std::size_t total = static_cast<std::size_t>(array) + keys.size();
  if (total > entries.size())
    entries.push_back("… (" + std::to_string(total - entries.size()) + " more)");
  const std::size_t values = static_cast<std::size_t>(std::min<lua_Integer>(array, max_entries));
  return layout(entries, keys.empty() ? entries.size() : values, indent);
}

std::string Formatter::value(int index, int depth, int indent) {
  index = lua_absindex(L_, index);
  switch (lua_type(L_, index)) {
    case LUA_TNIL:
      return leaf("nil");
    case LUA_TBOOLEAN:
      return leaf(lua_toboolean(L_, index) ? "true" : "false");
    case LUA_TNUMBER: {
      lua_pushvalue(L_, index);  // no metamethod: numbers as tostring writes them
      std::string text = lua_tostring(L_, -1);
      lua_pop(L_, 1);
      return leaf(text);
    }
    case LUA_TSTRING: {
      std::size_t length = 0;
      const char* text = lua_tolstring(L_, index, &length);
      return leaf(depth == 0 ? std::string(text, length) : quoted(text, length));
    }
    case LUA_TTABLE:
      break;
    default: {
      std::string text = tostring(index);
      if (depth > 0 && text.size() > max_string) text = text.substr(0, max_string) + "…";
      return leaf(text);
    }
  }
  std::string title;
  if (lua_getmetatable(L_, index)) {
    lua_pushliteral(L_, "__tostring");  // read raw, as Lua reads metamethods
    const int tostring_type = lua_rawget(L_, -2);
    lua_pop(L_, 1);
    lua_pushliteral(L_, "__name");
    if (lua_rawget(L_, -2) == LUA_TSTRING) title = std::string(lua_tostring(L_, -1)) + " ";
    lua_pop(L_, 2);
    if (tostring_type != LUA_TNIL) return leaf(tostring(index));
  }
  const void* self = lua_topointer(L_, index);
  if (std::find(path_.begin(), path_.end(), self) != path_.end()) return leaf("<cycle>");
  if (depth >= max_depth || produced_ > max_total) return leaf(title + "{…}");
  path_.push_back(self);
  std::string text = title + table(index, depth, indent + static_cast<int>(title.size()));
  path_.pop_back();
  return text;
}

std::string Formatter::top(int index) { return value(index, 0, 0); }

}  // namespace

int pretty_print(lua_State* L) {
  const int count = lua_gettop(L);
  std::string line;
  bool out_of_memory = false;
  try {
    Formatter formatter(L);
    for (int i = 1; i <= count; ++i) line += (i > 1 ? "\t" : "") + formatter.top(i);
    line += '\n';
  } catch (const std::bad_alloc&) {  // the text passed the memory limit
    out_of_memory = true;
  }
  if (out_of_memory) lua::memory_error(L);
  std::fwrite(line.data(), 1, line.size(), stdout);
  return 0;
}

}  // namespace rigidlab::cli
