#include "cli/options.hpp"

#include <cstring>

#include "cli/limit_options.hpp"

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

// Handles the long option at argv[i] (and its value: i moves past it); false if it is unknown,
// with `error` set when its value is wrong.
bool parse_long_option(int argc, char** argv, int& i, Options& options, std::string& error) {
  const char* option = argv[i];
  if (std::strcmp(option, "--help") == 0) options.help = true;
  else if (std::strcmp(option, "--version") == 0) options.version = true;
  else if (std::strcmp(option, "--sandbox") == 0) options.sandbox = true;
  else {
    const std::vector<std::string> arguments(argv + i, argv + argc);
    std::size_t k = 0;
    if (!take_limit_option(arguments, k, options.limits, error)) return false;
    i += static_cast<int>(k);
    return error.empty();
  }
  return true;
}

// Everything but the checks across options.
std::string parse_arguments(int argc, char** argv, Options& options) {
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
      std::string error;
      if (!parse_long_option(argc, argv, i, options, error))
        return error.empty() ? unrecognized(i) : error;
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

}  // namespace

std::string parse_options(int argc, char** argv, Options& options) {
  const std::string error = parse_arguments(argc, argv, options);
  if (!error.empty()) return error;
  for (const Options::Action& action : options.actions)
    if (action.option == 'l' && options.sandbox)
      return "'-l' cannot be used with '--sandbox' (the sandbox has no require)";
  return "";
}

bool script_is_stdin(char** argv, const Options& options) {
  return options.script > 0 && std::strcmp(argv[options.script], "-") == 0 &&
         std::strcmp(argv[options.script - 1], "--") != 0;
}

}  // namespace rigidlab::cli
