#include "engine/ode.hpp"

namespace rigidlab::ode {

std::optional<FirstOrderMethod> parse_first_order_method(std::string_view name) {
  return parse_name<FirstOrderMethod>(first_order_method_names, name);
}

}  // namespace rigidlab::ode
