#include "engine/inertia.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/format.hpp"

namespace rigidlab {
namespace {

// Ten significant digits: these messages list several values.
std::string number(double x, int digits = 10) { return format_number(x, digits); }

// Relative tolerances of inertia_tensor_problem and rotation_problem (see inertia.hpp).
constexpr double asymmetry_tolerance = 1e-9;
constexpr double triangle_tolerance = 1e-9;
constexpr double zero_moment_tolerance = 1e-12;
constexpr double rotation_tolerance = 1e-9;

// Throws "<what> must be finite, got nan" or "<what> must be > 0, got -1" (">= 0" when zero
// is allowed).
void require(double x, const char* what, bool zero_allowed) {
  const char* rule = nullptr;
  if (!std::isfinite(x))
    rule = " must be finite, got ";
  else if (zero_allowed ? !(x >= 0.0) : !(x > 0.0))
    rule = zero_allowed ? " must be >= 0, got " : " must be > 0, got ";
  if (rule != nullptr) throw std::invalid_argument(std::string(what) + rule + number(x));
}
void require_positive(double x, const char* what) { require(x, what, false); }
void require_nonnegative(double x, const char* what) { require(x, what, true); }

Mat3 diagonal(double xx, double yy, double zz) { return Vec3(xx, yy, zz).asDiagonal(); }

}  // namespace

// Seed 000_*, "Inertia of primitive shapes": derived there by summing thin discs along z.
Mat3 inertia_solid_sphere(double mass, double radius) {
  require_positive(mass, "mass");
  require_positive(radius, "radius");
  const double moment = 0.4 * mass * radius * radius;
  return diagonal(moment, moment, moment);
}

// Seed 000_*, "Inertia of primitive shapes" (hollow sphere: a thin shell).
Mat3 inertia_hollow_sphere(double mass, double radius) {
  require_positive(mass, "mass");
  require_positive(radius, "radius");
  const double moment = 2.0 / 3.0 * mass * radius * radius;
  return diagonal(moment, moment, moment);
}

// Seed 000_*, "Inertia of primitive shapes" (solid box w, h, d); seed 001_* Appendix B.
Mat3 inertia_solid_box(double mass, const Vec3& size) {
  require_positive(mass, "mass");
  require_positive(size.x(), "width");
  require_positive(size.y(), "height");
  require_positive(size.z(), "depth");
  const Vec3 s2 = size.cwiseProduct(size);
  const double k = mass / 12.0;
  return diagonal(k * (s2.y() + s2.z()), k * (s2.x() + s2.z()), k * (s2.x() + s2.y()));
}

// Seed 000_*, "Inertia of primitive shapes" (solid cylinder); seed 001_* Appendix B.
Mat3 inertia_solid_cylinder(double mass, double radius, double height) {
  require_positive(mass, "mass");
  require_positive(radius, "radius");
  require_positive(height, "height");
  const double transverse = mass * (3.0 * radius * radius + height * height) / 12.0;
  return diagonal(transverse, transverse, 0.5 * mass * radius * radius);
}

// Seed 000_*, "Inertia of primitive shapes" (hollow cylinder): the lateral surface of radius r.
// Each ring at height z contributes (r²/2 + z²) dm about x, hence m(r²/2 + h²/12).
Mat3 inertia_hollow_cylinder(double mass, double radius, double height) {
  require_positive(mass, "mass");
  require_positive(radius, "radius");
  require_positive(height, "height");
  const double transverse = mass * (6.0 * radius * radius + height * height) / 12.0;
  return diagonal(transverse, transverse, mass * radius * radius);
}

// Seed 000_* and 003_* ("List of 3D inertia tensors"): solid ellipsoid with semi-axes a, b, c.
Mat3 inertia_solid_ellipsoid(double mass, double a, double b, double c) {
  require_positive(mass, "mass");
  require_positive(a, "a");
  require_positive(b, "b");
  require_positive(c, "c");
  const double k = mass / 5.0;
  return diagonal(k * (b * b + c * c), k * (a * a + c * c), k * (a * a + b * b));
}

// Capsule = cylinder (radius r, length h) + two hemispheres, built from the cylinder and sphere
// formulas of seed 000_* and its "Parallel axis theorem". A solid hemisphere of mass m_h has
// its COM 3r/8 from its flat face (a standard centroid, e.g. Wikipedia "List of centroids");
// about the sphere centre its transverse moment is (2/5) m_h r², so about its own COM
// (2/5 − 9/64) m_h r², and about the capsule centre, a distance h/2 + 3r/8 away,
// m_h (2r²/5 + h²/4 + 3hr/8). The two caps together have the mass m_s of a whole sphere.
Mat3 inertia_capsule(double mass, double radius, double height) {
  require_positive(mass, "mass");
  require_positive(radius, "radius");
  require_nonnegative(height, "height");
  const double r = radius, h = height;
  // Volumes π r² h and (4/3) π r³: the cylinder's share of the mass is h / (h + 4r/3).
  const double cylinder_mass = mass * h / (h + 4.0 / 3.0 * r);
  const double caps_mass = mass - cylinder_mass;
  const double transverse = cylinder_mass * (3.0 * r * r + h * h) / 12.0 +
                            caps_mass * (0.4 * r * r + 0.25 * h * h + 0.375 * h * r);
  const double axial = 0.5 * cylinder_mass * r * r + 0.4 * caps_mass * r * r;
  return diagonal(transverse, transverse, axial);
}

// Solid cone (Wikipedia "List of moments of inertia", solid cone): about the apex, transverse
// (3/5) m (r²/4 + h²); the COM is 3h/4 from the apex, so by the parallel axis theorem (seed
// 000_*) the transverse moment about the COM is (3/5) m (r²/4 + h²) − m (3h/4)² =
// (3/80) m (4r² + h²). Axial: (3/10) m r².
Mat3 inertia_solid_cone(double mass, double radius, double height) {
  require_positive(mass, "mass");
  require_positive(radius, "radius");
  require_positive(height, "height");
  const double transverse = 3.0 / 80.0 * mass * (4.0 * radius * radius + height * height);
  return diagonal(transverse, transverse, 0.3 * mass * radius * radius);
}

// Seed 000_*, "Inertia": I = ∫((r·r)E − r⊗r) dm for a single mass element.
Mat3 inertia_point(double mass, const Vec3& offset) {
  require_nonnegative(mass, "mass");
  return mass * (offset.squaredNorm() * Mat3::Identity() - offset * offset.transpose());
}

// Seed 000_*, "Center of mass": COM = Σ mᵢ pᵢ / Σ mᵢ; tensors of particles add.
MassProperties inertia_points(const std::vector<PointMass>& points) {
  if (points.empty()) throw std::invalid_argument("at least one point mass is required");
  MassProperties result;
  Vec3 moment = Vec3::Zero();
  for (const PointMass& p : points) {
    require_positive(p.mass, "mass");
    if (!is_finite(p.position)) throw std::invalid_argument("position must be finite");
    result.mass += p.mass;
    moment += p.mass * p.position;
  }
  result.com = moment / result.mass;
  for (const PointMass& p : points)
    result.inertia += inertia_point(p.mass, p.position - result.com);
  return result;
}

Mat3 parallel_axis(const Mat3& inertia_com, double mass, const Vec3& d) {
  return inertia_com + inertia_point(mass, d);
}

Mat3 rotate_inertia(const Mat3& inertia, const Mat3& rotation) {
  return rotation * inertia * rotation.transpose();
}

Mat3 rotate_inertia(const Mat3& inertia, const Quat& rotation) {
  if (!is_finite(rotation) || is_zero(rotation))
    throw std::invalid_argument("rotation quaternion must be finite and non-zero");
  return rotate_inertia(inertia, Mat3(unit(rotation).toRotationMatrix()));
}

double about_axis(const Mat3& inertia, const Vec3& axis) {
  if (!is_finite(axis) || is_zero(axis))
    throw std::invalid_argument("axis must be a finite non-zero vector");
  const Vec3 n = unit(axis);
  return n.dot(inertia * n);
}

SymmetricEigen principal_inertia(const Mat3& inertia) {
  return symmetric_eigen(0.5 * (inertia + inertia.transpose()));
}

MassProperties composite_inertia(const std::vector<MassProperties>& parts) {
  if (parts.empty()) throw std::invalid_argument("at least one part is required");
  MassProperties result;
  Vec3 moment = Vec3::Zero();
  for (const MassProperties& part : parts) {
    require_positive(part.mass, "mass");
    result.mass += part.mass;
    moment += part.mass * part.com;
  }
  result.com = moment / result.mass;
  for (const MassProperties& part : parts)
    result.inertia += parallel_axis(part.inertia, part.mass, part.com - result.com);
  return result;
}

std::string inertia_tensor_problem(const Mat3& inertia, InertiaRules rules) {
  if (!is_finite(inertia)) return "the tensor has entries that are not finite";
  const double largest_entry = inertia.cwiseAbs().maxCoeff();
  const double asym = asymmetry(inertia);
  if (asym > asymmetry_tolerance * largest_entry)
    return "the tensor is not symmetric (entries (i, j) and (j, i) differ by up to " +
           number(asym, 3) + ")";
  const Vec3 moments = principal_inertia(inertia).values;  // ascending
  if (!is_finite(moments))
    return "the tensor is too large: its principal moments overflow (largest entry " +
           number(largest_entry) + ")";
  const double a = moments.x(), b = moments.y(), c = moments.z();
  const std::string listed = number(a) + ", " + number(b) + ", " + number(c);
  const double zero_level = zero_moment_tolerance * std::max(c, 0.0);
  if (rules == InertiaRules::body && !(a > 0.0))
    return "principal moments " + listed + " are not all > 0 (the smallest is " + number(a) +
           "): a body needs three positive principal moments";
  if (rules == InertiaRules::body && !(a > zero_level))
    return "principal moments " + listed + ": the smallest is zero to rounding, less than " +
           number(zero_moment_tolerance, 3) + " of the largest (a particle or an infinitely "
           "thin rod); a body needs three positive principal moments";
  if (rules == InertiaRules::body && !std::isfinite(1.0 / a))
    return "principal moments " + listed + " are too small for a body: the inverse tensor "
           "overflows (1/" + number(a) + " = " + number(1.0 / a) + ")";
  if (a < -zero_level)
    return "principal moments " + listed + " are not all >= 0 (the smallest is " + number(a) +
           ")";
  const double shortfall = c - (a + b);
  if (shortfall > triangle_tolerance * c)
    return "principal moments " + listed + " violate A + B >= C (" + number(a) + " + " +
           number(b) + " < " + number(c) + " by " + number(shortfall, 3) + ")";
  return {};
}

std::string rotation_problem(const Mat3& rotation) {
  if (!is_finite(rotation)) return "the matrix has entries that are not finite";
  const double departure =
      (rotation.transpose() * rotation - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (departure > rotation_tolerance)
    return "the matrix is not orthonormal (RᵀR differs from the identity by up to " +
           number(departure, 3) + ")";
  const double det = rotation.determinant();
  if (std::abs(det - 1.0) > rotation_tolerance)
    return "the matrix is a reflection, not a rotation (det = " + number(det, 6) + ", want +1)";
  return {};
}

}  // namespace rigidlab
