#include "engine/ode.hpp"

#include <cstddef>

namespace rigidlab::ode {
namespace {
// The index of `name` in `names`, or -1.
template <std::size_t N>
int find_name(const char* const (&names)[N], std::string_view name) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<int>(i);
  return -1;
}
}  // namespace

std::optional<SecondOrderMethod> parse_second_order_method(std::string_view name) {
  const int i = find_name(second_order_method_names, name);
  if (i < 0) return std::nullopt;
  return static_cast<SecondOrderMethod>(i);
}

std::optional<FirstOrderMethod> parse_first_order_method(std::string_view name) {
  const int i = find_name(first_order_method_names, name);
  if (i < 0) return std::nullopt;
  return static_cast<FirstOrderMethod>(i);
}

}  // namespace rigidlab::ode
