#include "cli/options.hpp"

#include <cstring>

namespace rigidlab::cli {
namespace {

// -e and -l take the rest of their argument ("-eCODE") or the next one, which may not be an
// option (as in lua.c, so that `-e -i` is an error rather than code).
bool take_value(int argc, char** argv, int& i, std::string& value) {
  if (argv[i][2] != '\0') {
    value = argv[i] + 2;
    return true;
  }
  if (i + 1 >= argc || argv[i + 1][0] == '-') return false;
  value = argv[++i];
  return true;
}

// Handles the long option at argv[i]; false if it is unknown.
bool parse_long_option(const char* option, Options& options) {
  if (std::strcmp(option, "--help") == 0) options.help = true;
  else if (std::strcmp(option, "--version") == 0) options.version = true;
  else return false;
  return true;
}

}  // namespace

std::string parse_options(int argc, char** argv, Options& options) {
  const auto unrecognized = [&](int i) { return "unrecognized option '" + std::string(argv[i]) + "'"; };
  for (int i = 1; i < argc; ++i) {
    const char* arg = argv[i];
    if (arg[0] != '-' || arg[1] == '\0') {  // the script, or "-" for stdin
      options.script = i;
      return "";
    }
    if (arg[1] == '-') {
      if (arg[2] == '\0') {  // "--": the next argument is the script, whatever it looks like
        options.script = i + 1 < argc ? i + 1 : 0;
        return "";
      }
      if (!parse_long_option(arg, options)) return unrecognized(i);
      continue;
    }
    const char letter = arg[1];
    if (letter == 'e' || letter == 'l') {
      Options::Action action{letter, ""};
      if (!take_value(argc, argv, i, action.value))
        return std::string("'-") + letter + "' needs an argument";
      options.actions.push_back(action);
      continue;
    }
    if (arg[2] != '\0') return unrecognized(i);
    switch (letter) {
      case 'i': options.interactive = true; break;
      case 'v': options.version = true; break;
      case 'h': options.help = true; break;
      case 'W': options.warnings = true; break;
      case 'E': options.ignore_environment = true; break;
      default: return unrecognized(i);
    }
  }
  return "";
}

bool script_is_stdin(char** argv, const Options& options) {
  return options.script > 0 && std::strcmp(argv[options.script], "-") == 0 &&
         std::strcmp(argv[options.script - 1], "--") != 0;
}

}  // namespace rigidlab::cli
