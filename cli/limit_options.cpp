#include "cli/limit_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace rigidlab::cli {
namespace {

// The largest values: beyond them a limit means nothing (about 30 years of instructions or of
// seconds, 1 PB of memory), and the conversions below stay exact.
constexpr double max_instructions = 1e18;
constexpr double max_megabytes = 1e9;
constexpr double max_seconds = 1e9;

// A number >= 0 and <= `largest` written in full ("1e9" and "0.5" are fine; "", "x", "1s",
// "-1", "nan" and "inf" are not).
bool parse_amount(const std::string& text, double largest, double& value) {
  if (text.empty() || text[0] == '-' || text[0] == '+' || std::isspace(static_cast<unsigned char>(text[0])))
    return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return errno == 0 && *end == '\0' && std::isfinite(value) && value >= 0.0 && value <= largest;
}

}  // namespace

bool take_limit_option(const std::vector<std::string>& arguments, std::size_t& i, Limits& limits,
                       std::string& error) {
  const std::string& argument = arguments[i];
  const std::size_t equals = argument.find('=');
  const std::string name = argument.substr(0, equals);
  const char* wanted;
  double largest;
  if (name == "--max-instructions") {
    wanted = "a whole number of instructions >= 0";
    largest = max_instructions;
  } else if (name == "--max-memory") {
    wanted = "a number of megabytes >= 0";
    largest = max_megabytes;
  } else if (name == "--timeout") {
    wanted = "a number of seconds >= 0";
    largest = max_seconds;
  } else {
    return false;
  }
  error.clear();
  std::string text;
  if (equals != std::string::npos) {
    text = argument.substr(equals + 1);
  } else if (i + 1 < arguments.size()) {
    text = arguments[++i];
  } else {
    error = "'" + name + "' needs an argument (" + wanted + ")";
    return true;
  }
  double value = 0.0;
  if (!parse_amount(text, largest, value) ||
      (name == "--max-instructions" && value != std::floor(value))) {
    error = "'" + name + "' needs " + wanted + ", got '" + text + "'";
    return true;
  }
  if (name == "--max-instructions")
    limits.max_instructions = static_cast<long long>(value);
  else if (name == "--max-memory")
    limits.max_memory_megabytes = value;
  else
    limits.timeout_seconds = value;
  return true;
}

}  // namespace rigidlab::cli
