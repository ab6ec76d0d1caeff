#include "lua/output_file.hpp"

#include "lua/binding.hpp"
#include "lua/sandbox.hpp"

namespace rigidlab::lua {

std::string check_output_path(lua_State* L, int arg, int index, const char* field) {
  index = lua_absindex(L, index);
  const Where where = field ? Where::field(arg, field) : Where::argument(arg, "path");
  if (field == nullptr && lua_type(L, index) != LUA_TSTRING) type_error(L, arg, "string (a file path)");
  std::size_t size = 0;
  const char* path = check_name(L, index, where, &size);  // a string without NUL bytes
  if (size == 0) where.error(L, "must not be empty");
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
