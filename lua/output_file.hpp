// The files scripts ask rigidlab to write (plot.lines' svg, csv.write, rec:csv,
// w:export_html): one check of the path and one bridge from present::FileError to a Lua error
// naming the function and argument, so every writer refuses and reports alike.
#pragma once

#include <lua.hpp>

#include <string>

namespace rigidlab::lua {

// The string at stack index `index` as a file path to write, for argument `arg` (`field` names
// the option field holding it, or nullptr): a string, not empty, without a NUL byte (the C
// library would write to the path cut at the NUL: check_name), and not in the sandbox. Raises
// "bad argument #1 to 'plot.lines' (field 'svg' must not contain a NUL byte ...)" otherwise.
std::string check_output_path(lua_State* L, int arg, int index, const char* field);

// Calls write(), which may throw present::FileError or std::invalid_argument, and raises its
// message as an error on argument `arg` ("cannot write '/dev/full': No space left on
// device"), outside the catch.
template <class Write>
void write_or_raise(lua_State* L, int arg, const char* field, Write&& write);

// The non-template part: raises the message as write_or_raise does.
[[noreturn]] void raise_write_error(lua_State* L, int arg, const char* field,
                                    const std::string& message);

template <class Write>
void write_or_raise(lua_State* L, int arg, const char* field, Write&& write) {
  std::string message;
  try {
    write();
    return;
  } catch (const std::exception& e) {
    message = e.what();
  }
  raise_write_error(L, arg, field, message);
}

}  // namespace rigidlab::lua
