#include "cli/completion.hpp"

#include <editline/readline.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cli/lua_names.hpp"

namespace rigidlab::cli {
namespace {

lua_State* completion_state = nullptr;
std::vector<std::string> candidates;  // of the completion in progress

// Everything below reads tables raw (lua_rawget, lua_next, lua_getmetatable): Tab runs none of
// the user's code, so a metamethod that loops or fails cannot hang or break the line editor.

// Pushes field `name` of the table at `index`, read raw (nil if it is not a table).
void push_raw_field(lua_State* L, int index, const char* name) {
  if (lua_type(L, index) != LUA_TTABLE) {
    lua_pushnil(L);
    return;
  }
  index = lua_absindex(L, index);
  lua_pushstring(L, name);
  lua_rawget(L, index);
}

// Adds to `out` the identifier keys of the table at `index` that start with `partial`, then
// those of its metatable's __index table (objects with methods in a class table).
void add_keys(lua_State* L, int index, const std::string& partial, std::vector<std::string>& out,
              int depth = 0) {
  index = lua_absindex(L, index);
  if (lua_type(L, index) != LUA_TTABLE || depth > 4) return;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) continue;
    const char* key = lua_tostring(L, -1);
    const bool hidden = std::strncmp(key, "__", 2) == 0 && partial.compare(0, 2, "__") != 0;
    if (!hidden && is_name(key, std::strlen(key)) && std::strncmp(key, partial.c_str(), partial.size()) == 0)
      out.emplace_back(key);
  }
  if (lua_getmetatable(L, index)) {
    push_raw_field(L, -1, "__index");
    add_keys(L, -1, partial, out, depth + 1);
    lua_pop(L, 2);
  }
}

// Adds the keys of the global table named by the __name of the value's metatable: the
// methods of a vec3 are the functions of the global `vec3`.
void add_type_methods(lua_State* L, int index, const std::string& partial,
                      std::vector<std::string>& out) {
  if (!lua_getmetatable(L, index)) return;
  push_raw_field(L, -1, "__name");
  if (lua_type(L, -1) == LUA_TSTRING) {
    lua_pushglobaltable(L);
    push_raw_field(L, -1, lua_tostring(L, -2));
    add_keys(L, -1, partial, out);
    lua_pop(L, 2);
  }
  lua_pop(L, 2);
}

// Pushes the value named by the dotted `path` ("inertia", "a.b"), read raw from the globals.
void push_path(lua_State* L, const std::string& path) {
  lua_pushglobaltable(L);
  size_t start = 0;
  while (start <= path.size()) {
    const size_t dot = std::min(path.find('.', start), path.size());
    const std::string name = path.substr(start, dot - start);
    if (lua_type(L, -1) == LUA_TTABLE) {
      lua_pushlstring(L, name.data(), name.size());
      lua_rawget(L, -2);
    } else {
      lua_pushnil(L);
    }
    lua_remove(L, -2);
    start = dot + 1;
  }
}

// lua_CFunction, run protected: fills `candidates` for the word at argument 1.
int collect_candidates(lua_State* L) {
  const std::string word = lua_tostring(L, 1);
  const size_t separator = word.find_last_of(".:");
  std::vector<std::string> found;
  if (separator == std::string::npos) {
    lua_pushglobaltable(L);
    add_keys(L, -1, word, found);
    for (const char* keyword : lua_keywords)
      if (std::strncmp(keyword, word.c_str(), word.size()) == 0) found.emplace_back(keyword);
  } else {
    const std::string head = word.substr(0, separator + 1), partial = word.substr(separator + 1);
    push_path(L, word.substr(0, separator));
    add_keys(L, -1, partial, found);
    add_type_methods(L, -1, partial, found);
    for (std::string& name : found) name = head + name;
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  candidates.swap(found);
  return 0;
}

char* next_candidate(const char*, int state) {
  static size_t next = 0;
  if (state == 0) next = 0;
  return next < candidates.size() ? strdup(candidates[next++].c_str()) : nullptr;
}

// Where the string literal around the cursor starts (after its quote), or -1 outside one.
int string_start(const char* line, int cursor) {
  char quote = 0;
  int start = -1;
  for (int i = 0; i < cursor; ++i) {
    if (quote != 0 && line[i] == '\\') ++i;
    else if (quote != 0 && line[i] == quote) quote = 0;
    else if (quote == 0 && (line[i] == '"' || line[i] == '\'')) {
      quote = line[i];
      start = i + 1;
    }
  }
  return quote != 0 ? start : -1;
}

// File names completing the string typed from `begin` to `end` (directories with a final
// '/'); each candidate is cut to the part from `word` on, the word libedit replaces.
void collect_file_names(const char* line, int begin, int word, int end) {
  const std::string typed(line + begin, line + end);
  const size_t cut = static_cast<size_t>(word - begin);
  for (int state = 0;; ++state) {
    char* match = rl_filename_completion_function(typed.c_str(), state);
    if (match == nullptr) break;
    struct stat info {};
    const bool directory = stat(match, &info) == 0 && S_ISDIR(info.st_mode);
    if (std::strncmp(match, typed.c_str(), cut) == 0)
      candidates.push_back(std::string(match + cut) + (directory ? "/" : ""));
    std::free(match);
  }
}

char** complete(const char* text, int start, int end) {
  rl_attempted_completion_over = 1;
  candidates.clear();
  const int string = string_start(rl_line_buffer, end);
  if (string >= 0) {
    collect_file_names(rl_line_buffer, string, start, end);
  } else {
    lua_State* L = completion_state;
    lua_pushcfunction(L, collect_candidates);
    lua_pushstring(L, text);
    if (lua_pcall(L, 1, 0, 0) != LUA_OK) lua_pop(L, 1);  // no completion rather than an error
  }
  return rl_completion_matches(text, next_candidate);
}

}  // namespace

void install_completion(lua_State* L) {
  completion_state = L;
  static char word_breaks[] = " \t\n\"'`@$><=;|&{}()[]+-*/%^#~,";
  rl_basic_word_break_characters = word_breaks;
  rl_completer_word_break_characters = word_breaks;
  rl_completion_append_character = '\0';
  rl_attempted_completion_function = complete;
}

}  // namespace rigidlab::cli
