// How text output may look where it is shown: Unicode (braille, box drawing) in a UTF-8 locale,
// else plain ASCII; ANSI colours only in a terminal and when NO_COLOR is unset (no-color.org).
// Renderers take a TextStyle and stay pure; only terminal_style() looks at the environment.
#pragma once

namespace rigidlab::present {

struct TextStyle {
  bool unicode = true;  // braille dots and box drawing; false: bytes 0x20 to 0x7E only
  bool color = false;   // ANSI SGR colours
};

// True when the locale the environment selects for characters (LC_ALL, else LC_CTYPE, else
// LANG: the first one set and not empty, as POSIX orders them) names UTF-8.
bool utf8_locale();

// The style for output to file descriptor `fd`: Unicode in a UTF-8 locale; colour when `fd`
// is a terminal, NO_COLOR is unset or empty, and TERM is not "dumb".
TextStyle terminal_style(int fd);

}  // namespace rigidlab::present
