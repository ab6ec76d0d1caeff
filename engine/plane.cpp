#include "engine/plane.hpp"

#include <stdexcept>

#include "engine/format.hpp"

namespace rigidlab {

std::string material_problem(double restitution, double friction) {
  if (!(restitution >= 0.0 && restitution <= 1.0))
    return "restitution must be in [0, 1], got " + format_number(restitution);
  if (!(friction >= 0.0) || !std::isfinite(friction))
    return "friction must be finite and >= 0, got " + format_number(friction);
  return "";
}

Plane make_plane(const Vec3& normal, double offset, double restitution, double friction) {
  if (!is_finite(normal)) throw std::invalid_argument("normal must be finite");
  const double length = normal.norm();
  // The norm of a finite vector can overflow (components near 1e308): refuse it as well.
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("normal must be a non-zero vector");
  if (!std::isfinite(offset))
    throw std::invalid_argument("offset must be finite, got " + format_number(offset));
  const std::string problem = material_problem(restitution, friction);
  if (!problem.empty()) throw std::invalid_argument(problem);
  Plane plane;
  plane.normal = normal / length;
  plane.offset = offset / length;
  plane.restitution = restitution;
  plane.friction = friction;
  return plane;
}

}  // namespace rigidlab
