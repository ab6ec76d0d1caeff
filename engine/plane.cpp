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
  // Divided by its largest component first, so that neither a tiny (1e-300) nor a huge
  // (1e300) normal underflows or overflows in the norm.
  const double largest = normal.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) throw std::invalid_argument("normal must be a non-zero vector");
  if (!std::isfinite(offset))
    throw std::invalid_argument("offset must be finite, got " + format_number(offset));
  const std::string problem = material_problem(restitution, friction);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const Vec3 scaled = normal / largest;
  const double length = scaled.norm();
  Plane plane;
  plane.normal = scaled / length;
  plane.offset = offset / largest / length;
  if (!std::isfinite(plane.offset))
    throw std::invalid_argument("offset / |normal| must be finite, got " +
                                format_number(plane.offset) + " (the normal is too short)");
  plane.restitution = restitution;
  plane.friction = friction;
  return plane;
}

}  // namespace rigidlab
