// The contact solver's settings (engine/solver_settings.hpp ContactSettings) as properties of
// the world: world{iterations = 20}, w.slop, w.baumgarte = 0.1. One table of the settings,
// their ranges, units and help serves the constructor, the reads, the writes and help().
#pragma once

#include <lua.hpp>

namespace rigidlab::lua {

// Adds the settings to the world type (lua/world.hpp), after its own properties.
void add_contact_setting_properties(lua_State* L);

// What help("world") says after the fields: the solver and its limits.
extern const char* const contact_settings_doc;

}  // namespace rigidlab::lua
