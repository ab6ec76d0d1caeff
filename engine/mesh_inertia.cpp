#include "engine/mesh_inertia.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "engine/format.hpp"

namespace rigidlab {
namespace {

// Ten significant digits: these messages list several values.
std::string number(double x, int digits = 10) { return format_number(x, digits); }

// A triangle whose doubled area is below this fraction of its longest edge squared is
// degenerate (collinear vertices); a volume below this fraction of the bounding box's
// largest side cubed is zero.
constexpr double degenerate_area_tolerance = 1e-12;
constexpr double zero_volume_tolerance = 1e-12;


// 1-based numbers for messages.
std::string nth(std::size_t index) { return std::to_string(index + 1); }

std::string element_problem(const std::vector<Vec3>& vertices,
                            const std::vector<MeshTriangle>& triangles) {
  if (vertices.size() < 4)
    return "a closed mesh needs at least 4 vertices, got " + std::to_string(vertices.size());
  if (triangles.size() < 4)
    return "a closed mesh needs at least 4 triangles, got " + std::to_string(triangles.size());
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (!is_finite(vertices[v])) return "vertex " + nth(v) + " is not finite";
  const long long count = static_cast<long long>(vertices.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const MeshTriangle& tri = triangles[t];
    for (int index : tri)
      if (index < 0 || index >= count)
        return "triangle " + nth(t) + " refers to vertex " + std::to_string(index + 1LL) +
               ", but the vertices are numbered 1 to " + std::to_string(count);
    const std::string listed =
        "(" + nth(tri[0]) + ", " + nth(tri[1]) + ", " + nth(tri[2]) + ")";
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      return "triangle " + nth(t) + " " + listed + " is degenerate: it repeats a vertex";
    const Vec3 &a = vertices[tri[0]], &b = vertices[tri[1]], &c = vertices[tri[2]];
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (!((b - a).cross(c - a).norm() > degenerate_area_tolerance * longest))
      return "triangle " + nth(t) + " " + listed +
             " is degenerate: its vertices are collinear (zero area)";
  }
  return {};
}

// One use of an edge by a triangle: `key` identifies the undirected edge, `from`/`to` give the
// direction in which the triangle's boundary (counter-clockwise) runs along it.
struct EdgeUse {
  std::uint64_t key;
  int from, to;
  std::size_t triangle;
};

std::vector<EdgeUse> edge_uses(const std::vector<MeshTriangle>& triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int from = triangles[t][k], to = triangles[t][(k + 1) % 3];
      const auto low = static_cast<std::uint64_t>(std::min(from, to));
      const auto high = static_cast<std::uint64_t>(std::max(from, to));
      uses.push_back({low << 32 | high, from, to, t});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key != y.key ? x.key < y.key : x.triangle < y.triangle;
  });
  return uses;
}

// What is wrong with the edge used by uses[first, last), or "".
std::string edge_group_problem(const std::vector<EdgeUse>& uses, std::size_t first,
                               std::size_t last) {
  const EdgeUse& e = uses[first];
  const std::string edge = nth(std::min(e.from, e.to)) + "-" + nth(std::max(e.from, e.to));
  if (last - first == 1)
    return "the mesh is not closed: edge " + edge + " belongs only to triangle " +
           nth(e.triangle) + " (each edge of a closed surface is shared by exactly two triangles)";
  if (last - first > 2) {
    std::string list;
    for (std::size_t i = first; i < last; ++i)
      list += (i > first ? ", " : "") + nth(uses[i].triangle);
    return "the mesh is not a simple closed surface: edge " + edge + " is shared by " +
           std::to_string(last - first) + " triangles (" + list + "), not exactly two";
  }
  const EdgeUse& f = uses[first + 1];
  if (e.from == f.from)
    return "triangles " + nth(e.triangle) + " and " + nth(f.triangle) + " both run along edge " +
           nth(e.from) + "->" + nth(e.to) +
           " in the same direction, so their windings disagree: reverse the vertex order of "
           "one of them (every triangle must be counter-clockwise seen from outside)";
  return {};
}

// The first bad edge in the order of the triangles that use it.
std::string edge_problem(const std::vector<MeshTriangle>& triangles) {
  const std::vector<EdgeUse> uses = edge_uses(triangles);
  std::string problem;
  std::size_t problem_triangle = triangles.size();
  for (std::size_t first = 0; first < uses.size();) {
    std::size_t last = first + 1;
    while (last < uses.size() && uses[last].key == uses[first].key) ++last;
    if (uses[first].triangle < problem_triangle) {
      std::string p = edge_group_problem(uses, first, last);
      if (!p.empty()) {
        problem = std::move(p);
        problem_triangle = uses[first].triangle;
      }
    }
    first = last;
  }
  return problem;
}

// Eberly (2002), "Subexpressions": the polynomials in one coordinate (w0, w1, w2 at the three
// vertices) whose products with the face normal give the face's surface integrals.
struct Subexpressions {
  double f1, f2, f3, g0, g1, g2;
};

Subexpressions subexpressions(double w0, double w1, double w2) {
  Subexpressions s;
  const double temp0 = w0 + w1;
  const double temp1 = w0 * w0;
  const double temp2 = temp1 + w1 * temp0;
  s.f1 = temp0 + w2;
  s.f2 = temp2 + w2 * s.f1;
  s.f3 = w0 * temp1 + w1 * temp2 + w2 * s.f2;
  s.g0 = s.f2 + w0 * (s.f1 + w0);
  s.g1 = s.f2 + w1 * (s.f1 + w1);
  s.g2 = s.f2 + w2 * (s.f1 + w2);
  return s;
}

// Volume integrals of 1, r and r rᵀ over the solid, with r measured from `reference`.
struct VolumeIntegrals {
  Vec3 reference = Vec3::Zero();
  double volume = 0.0;
  Vec3 first = Vec3::Zero();          // ∫ r dV
  Mat3 second = Mat3::Zero();         // ∫ r rᵀ dV
};

// Mirtich (1996) turns each volume integral into surface integrals by the divergence theorem;
// Eberly (2002), "Computing the Integrals", evaluates them per triangle from the vertex
// coordinates and the (unnormalised) normal d = (p1 − p0) × (p2 − p0). Coordinates are taken
// relative to a point inside the mesh's extent to keep the cubic terms from cancelling.
VolumeIntegrals integrate(const std::vector<Vec3>& vertices,
                          const std::vector<MeshTriangle>& triangles, const Vec3& reference) {
  double sum[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (const MeshTriangle& tri : triangles) {
    const Vec3 p0 = vertices[tri[0]] - reference;
    const Vec3 p1 = vertices[tri[1]] - reference;
    const Vec3 p2 = vertices[tri[2]] - reference;
    const Vec3 d = (p1 - p0).cross(p2 - p0);
    const Subexpressions x = subexpressions(p0.x(), p1.x(), p2.x());
    const Subexpressions y = subexpressions(p0.y(), p1.y(), p2.y());
    const Subexpressions z = subexpressions(p0.z(), p1.z(), p2.z());
    sum[0] += d.x() * x.f1;
    sum[1] += d.x() * x.f2;
    sum[2] += d.y() * y.f2;
    sum[3] += d.z() * z.f2;
    sum[4] += d.x() * x.f3;
    sum[5] += d.y() * y.f3;
    sum[6] += d.z() * z.f3;
    sum[7] += d.x() * (p0.y() * x.g0 + p1.y() * x.g1 + p2.y() * x.g2);  // ∫ xy
    sum[8] += d.y() * (p0.z() * y.g0 + p1.z() * y.g1 + p2.z() * y.g2);  // ∫ yz
    sum[9] += d.z() * (p0.x() * z.g0 + p1.x() * z.g1 + p2.x() * z.g2);  // ∫ zx
  }
  VolumeIntegrals result;
  result.reference = reference;
  result.volume = sum[0] / 6.0;
  result.first = Vec3(sum[1], sum[2], sum[3]) / 24.0;
  const double xy = sum[7] / 120.0, yz = sum[8] / 120.0, zx = sum[9] / 120.0;
  result.second << sum[4] / 60.0, xy, zx,
                   xy, sum[5] / 60.0, yz,
                   zx, yz, sum[6] / 60.0;
  return result;
}

// The mean of the triangles' vertices: inside the mesh's extent, so a good origin.
Vec3 reference_point(const std::vector<Vec3>& vertices,
                     const std::vector<MeshTriangle>& triangles) {
  Vec3 sum = Vec3::Zero();
  for (const MeshTriangle& tri : triangles)
    sum += vertices[tri[0]] + vertices[tri[1]] + vertices[tri[2]];
  return sum / (3.0 * static_cast<double>(triangles.size()));
}

std::string volume_problem(const std::vector<Vec3>& vertices,
                           const std::vector<MeshTriangle>& triangles, double volume) {
  Vec3 low = vertices[triangles[0][0]], high = low;
  for (const MeshTriangle& tri : triangles)
    for (int index : tri) {
      low = low.cwiseMin(vertices[index]);
      high = high.cwiseMax(vertices[index]);
    }
  const double extent = (high - low).maxCoeff();
  if (!std::isfinite(volume))
    return "the volume integrals overflow (coordinates too large: " + number(extent) + " m)";
  if (!(std::abs(volume) > zero_volume_tolerance * extent * extent * extent))
    return "the mesh encloses no volume (signed volume " + number(volume) +
           " m³, zero compared with its extent " + number(extent) + " m)";
  if (volume < 0.0)
    return "the mesh is inside-out (signed volume " + number(volume) +
           " m³ is negative): its triangles are clockwise seen from outside; reverse the "
           "vertex order of every triangle";
  return {};
}

// Topology and elements, then the volume from the integrals.
std::string full_problem(const std::vector<Vec3>& vertices,
                         const std::vector<MeshTriangle>& triangles, VolumeIntegrals& integrals) {
  std::string problem = element_problem(vertices, triangles);
  if (problem.empty()) problem = edge_problem(triangles);
  if (!problem.empty()) return problem;
  integrals = integrate(vertices, triangles, reference_point(vertices, triangles));
  return volume_problem(vertices, triangles, integrals.volume);
}

}  // namespace

std::string mesh_problem(const std::vector<Vec3>& vertices,
                         const std::vector<MeshTriangle>& triangles) {
  VolumeIntegrals integrals;
  return full_problem(vertices, triangles, integrals);
}

// Eberly (2002), "Computing the Integrals", final step: the COM is ∫r/V; the tensor about the
// COM follows from the central second moments S = ∫ r rᵀ dV − V c cᵀ as ρ (tr(S) E − S)
// (seed 000_*, "Inertia": Ixx = ∫(y² + z²) dm, Ixy = −∫xy dm).
MeshMassProperties inertia_mesh(const std::vector<Vec3>& vertices,
                                const std::vector<MeshTriangle>& triangles, double density) {
  if (!std::isfinite(density) || !(density > 0.0))
    throw std::invalid_argument("density must be finite and > 0, got " + number(density));
  VolumeIntegrals integrals;
  const std::string problem = full_problem(vertices, triangles, integrals);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const Vec3 offset = integrals.first / integrals.volume;  // COM relative to the reference
  const Mat3 central = integrals.second - integrals.volume * offset * offset.transpose();
  MeshMassProperties result;
  result.volume = integrals.volume;
  result.mass = density * integrals.volume;
  result.com = integrals.reference + offset;
  result.inertia = density * (central.trace() * Mat3::Identity() - central);
  if (!std::isfinite(result.mass) || !is_finite(result.com) || !is_finite(result.inertia))
    throw std::invalid_argument("the mass properties overflow (coordinates or density too large)");
  return result;
}

}  // namespace rigidlab
