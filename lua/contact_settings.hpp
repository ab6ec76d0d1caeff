// The contact solver's settings (engine/contact_solver.hpp ContactSettings) as fields of a
// world: world{iterations = 20}, w.slop, w.baumgarte = 0.1. One table of the fields, their
// ranges and units serves the constructor, the reads, the writes and the help text.
#pragma once

#include <lua.hpp>

#include "engine/contact_solver.hpp"

namespace rigidlab::lua {

// The names, in the order help lists them; nullptr-terminated.
extern const char* const contact_setting_names[];

bool is_contact_setting(const char* name);

// Checks the value on top of the stack and stores it as setting `name`. A bad value raises,
// in the constructor (`in_table`), "bad argument #arg to 'world' (field 'slop' must be a
// finite number >= 0 (m), got -1)", and for an assignment "bad field 'slop' of world (must
// be a finite number >= 0 (m), got -1)".
void read_contact_setting(lua_State* L, int arg, const char* name, bool in_table,
                          ContactSettings& settings);

// Pushes the value of setting `name`.
void push_contact_setting(lua_State* L, const char* name, const ContactSettings& settings);

// One line per setting for help("world"): name, default, unit and meaning.
extern const char* const contact_settings_doc;

}  // namespace rigidlab::lua
