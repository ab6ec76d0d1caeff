#include "lua/output_file.hpp"

#include <cstring>

#include "lua/binding.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::lua {

std::string check_output_path(lua_State* L, int arg, int index, const char* field) {
  index = lua_absindex(L, index);
  const std::string what = field ? std::string("field '") + field + "'" : std::string("path");
  if (lua_type(L, index) != LUA_TSTRING) {
    if (field == nullptr) type_error(L, arg, "string (a file path)");
    arg_error(L, arg, "%s must be a string, got %s", what.c_str(),
              value_type_name(L, index));
  }
  std::size_t size = 0;
  const char* path = lua_tolstring(L, index, &size);
  if (size == 0) arg_error(L, arg, "%s must not be empty", what.c_str());
  if (std::strlen(path) != size)
    arg_error(L, arg, "%s may not contain a NUL byte ('\\0' at byte %d of %d)", what.c_str(),
              static_cast<int>(std::strlen(path) + 1), static_cast<int>(size));
  if (is_sandboxed(L))
    arg_error(L, arg, "%s%sfiles cannot be written in the sandbox", field ? field : "",
              field ? " " : "");
  return std::string(path, size);
}

void raise_write_error(lua_State* L, int arg, const char* field, const std::string& message) {
  if (field != nullptr) arg_error(L, arg, "field '%s': %s", field, message.c_str());
  arg_error(L, arg, "%s", message.c_str());
}

}  // namespace rigidlab::lua
