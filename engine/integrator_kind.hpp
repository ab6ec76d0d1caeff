// The names of the engine's methods, shared by every part that offers a choice of them: the
// world's and an articulation's integrator and the particle integrators of engine/ode.hpp
// (document 003's explicit Euler, its semi-implicit variant, and RK4), and the one lookup
// from a user-facing name to its enum value.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace rigidlab {

// Of a second-order system (bodies, links, particles): explicit Euler (positions from the old
// velocities), semi-implicit Euler (velocities first), classical RK4.
enum class Integrator { euler, semi_implicit, rk4 };
inline constexpr const char* integrator_names[] = {"euler", "semi_implicit", "rk4"};

// The value of Enum whose user-facing name (`names`, in enum order) is `name`, or nothing.
template <class Enum, std::size_t N>
std::optional<Enum> parse_name(const char* const (&names)[N], std::string_view name) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<Enum>(i);
  return std::nullopt;
}

inline std::optional<Integrator> parse_integrator(std::string_view name) {
  return parse_name<Integrator>(integrator_names, name);
}

}  // namespace rigidlab
