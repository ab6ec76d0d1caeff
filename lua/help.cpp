// help(): the documentation of any rigidlab function, type or module, given the value itself
// (help(inertia.solid_box), help(vec3(1, 2, 3))) or its dotted name (help("world"),
// help("vec3:cross")); help() lists the topics. The texts are the `signature` and `doc` of
// each binding's Entry table, so the help shown is the help written beside the code.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "lua/binding.hpp"
#include "lua/modules.hpp"

namespace rigidlab::lua {
namespace {

void print_text(lua_State* L, const std::string& text) {
  lua_getglobal(L, "print");
  lua_pushlstring(L, text.data(), text.size());
  lua_call(L, 1, 0);
}

std::string describe(const Entry& e) {
  std::string text = e.signature;
  if (e.doc != nullptr && *e.doc != '\0') {
    std::string doc = e.doc;
    std::string indented = "  ";
    for (char c : doc) {
      indented += c;
      if (c == '\n') indented += "  ";
    }
    text += "\n" + indented;
  }
  return text;
}

// One line per documented function in the table at `index`, sorted by name.
std::string list_functions(lua_State* L, int index) {
  index = lua_absindex(L, index);
  std::vector<std::string> lines;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING) {
      if (const Entry* e = find_entry(L, -1)) {
        if (e->function != nullptr) lines.push_back(std::string("  ") + e->signature);
      }
    }
    lua_pop(L, 1);
  }
  std::sort(lines.begin(), lines.end());
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Pushes the value a dotted name ("inertia.solid_box", "vec3:cross") refers to, or nil.
// Method names resolve through the type's table: vec3.cross is vec3:cross.
void resolve_name(lua_State* L, const std::string& name) {
  lua_pushglobaltable(L);
  size_t start = 0;
  while (start <= name.size()) {
    const size_t end = name.find_first_of(".:", start);
    const std::string part = name.substr(start, end == std::string::npos ? end : end - start);
    if (lua_type(L, -1) != LUA_TTABLE) {
      lua_pop(L, 1);
      lua_pushnil(L);
      return;
    }
    lua_pushlstring(L, part.data(), part.size());
    lua_rawget(L, -2);  // raw: a table's __index cannot raise an error of its own here
    lua_remove(L, -2);
    if (end == std::string::npos) return;
    start = end + 1;
  }
}

// `text` broken at spaces into lines of at most 92 columns (counting UTF-8 characters, so
// "Δt" is two bytes but one column), the first starting with `first`, the others with `next`.
std::string wrap(const std::string& text, const char* first, const char* next) {
  constexpr std::size_t width = 92;
  std::string result = first;
  std::size_t columns = result.size(), start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    std::size_t word_columns = 0;
    for (std::size_t i = start; i < end; ++i)
      word_columns += (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80;
    if (columns + 1 + word_columns > width && columns > std::strlen(next)) {
      result += std::string("\n") + next;
      columns = std::strlen(next);
    } else if (start > 0) {
      result += ' ';
      ++columns;
    }
    result.append(text, start, end - start);
    columns += word_columns;
    start = end + 1;
  }
  return result;
}

// The fields of a type (its properties, lua/binding.hpp section 5), in the order they were
// added: "  name (read-only): doc".
std::string list_properties(lua_State* L, int index) {
  std::string text;
  for (const Property* p : topic_properties(L, index)) {
    const std::string line =
        std::string(p->name) + (p->set == nullptr ? " (read-only): " : ": ") + p->doc;
    text += wrap(line, "  ", "    ") + "\n";
  }
  return text.empty() ? text : "Fields (read/write unless marked):\n" + text + "Methods:\n";
}

// "world.gravity": the help of a property, pushed as a string, or false when `name` is no
// type's property.
bool push_property_help(lua_State* L, const std::string& name) {
  const std::size_t dot = name.rfind('.');
  if (dot == std::string::npos) return false;
  resolve_name(L, name.substr(0, dot));
  const std::vector<const Property*> properties = topic_properties(L, -1);
  lua_pop(L, 1);
  for (const Property* p : properties) {
    if (name.compare(dot + 1, std::string::npos, p->name) != 0) continue;
    std::string text = name + (p->set == nullptr ? " (read-only)" : "") + "\n  " + p->doc;
    if (p->fixed != nullptr) text += std::string("\n  Read-only: ") + p->fixed + ".";
    lua_pushlstring(L, text.data(), text.size());
    return true;
  }
  return false;
}

// For a name that is no topic ("hinge", "gravity"): the dotted names of the topics' members
// and fields with that name ("joint.hinge", "world.gravity"), sorted, for the error message.
std::string suggestions(lua_State* L, const std::string& name) {
  if (name.find_first_of(".:") != std::string::npos) return "";
  std::vector<std::string> found;
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_getfield(L, -1, "rigidlab");
  if (lua_type(L, -1) == LUA_TTABLE) {
    lua_pushnil(L);
    while (lua_next(L, -2) != 0) {
      if (lua_type(L, -2) == LUA_TSTRING && lua_type(L, -1) == LUA_TTABLE) {
        const std::string topic = lua_tostring(L, -2);
        lua_pushlstring(L, name.data(), name.size());
        const bool member = lua_rawget(L, -2) != LUA_TNIL;
        lua_pop(L, 1);
        bool field = false;
        for (const Property* p : topic_properties(L, -1)) field = field || name == p->name;
        if (member || field) found.push_back(topic + "." + name);
      }
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 2);
  std::sort(found.begin(), found.end());
  constexpr std::size_t shown = 4;
  std::string text;
  for (std::size_t i = 0; i < found.size() && i < shown; ++i)
    text += (i == 0 ? "" : ", ") + ("'" + found[i] + "'");
  if (found.size() > shown) text += ", ...";
  return text.empty() ? text : "did you mean " + text + "? ";
}

const char* const overview =
    "rigidlab: rigid-body dynamics in Lua. help(x) documents a function, type or module,\n"
    "given the value or its name: help(vec3), help(\"inertia.solid_box\"), help(vec3.cross).\n"
    "Topics:";

int help(lua_State* L) {
  check_no_extra_args(L, 1);
  if (lua_isnoneornil(L, 1)) {
    std::string text = overview;
    luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);  // works without `require`
    lua_getfield(L, -1, "rigidlab");
    std::vector<std::string> topics;
    lua_pushnil(L);
    while (lua_next(L, -2) != 0) {
      if (lua_type(L, -2) == LUA_TSTRING && find_entry(L, -1) != nullptr)
        topics.push_back(lua_tostring(L, -2));
      lua_pop(L, 1);
    }
    std::sort(topics.begin(), topics.end());
    for (const std::string& t : topics) text += " " + t;
    print_text(L, text);
    return 0;
  }
  if (lua_type(L, 1) == LUA_TSTRING) {
    std::size_t length = 0;
    const char* chars = check_name(L, 1, Where::argument(1, "the topic name"), &length);
    const std::string name(chars, length);
    resolve_name(L, name);
    if (lua_isnil(L, -1) && push_property_help(L, name)) {
      print_text(L, lua_tostring(L, -1));
      return 0;
    }
    if (lua_isnil(L, -1))
      arg_error(L, 1, "no topic '%s' (%shelp() lists the topics)", name.c_str(),
                suggestions(L, name).c_str());
    lua_replace(L, 1);
  }
  if (lua_type(L, 1) == LUA_TUSERDATA) {
    const std::string type = value_type_name(L, 1);  // a value: the help of its type
    resolve_name(L, type);
    if (find_entry(L, -1) == nullptr)
      arg_error(L, 1, "no help for a %s value (help() lists the topics)", type.c_str());
    lua_replace(L, 1);
  }
  const Entry* entry = find_entry(L, 1);
  std::string text;
  if (entry != nullptr) text = describe(*entry);
  if (lua_type(L, 1) == LUA_TTABLE) {
    const std::string fields = list_properties(L, 1);
    if (!fields.empty()) text += (text.empty() ? "" : "\n") + fields;
    const std::string functions = list_functions(L, 1);
    if (!functions.empty())
      text += (text.empty() || text.back() == '\n' ? "" : "\n") + functions;
    if (!text.empty() && text.back() == '\n') text.pop_back();
  }
  if (text.empty())
    arg_error(L, 1, "no help for a %s value (help() lists the topics)", value_type_name(L, 1));
  print_text(L, text);
  return 0;
}

const Entry functions[] = {
    {"help", help, "help", "help([x])",
     "Prints the documentation of x: a function, type or module, or its name as a string.\n"
     "help() lists the topics."},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

}  // namespace

void open_help(lua_State* L, int lib) { register_entries(L, lib, functions); }

}  // namespace rigidlab::lua
