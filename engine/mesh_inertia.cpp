#include "engine/mesh_inertia.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "engine/format.hpp"
#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

// Ten significant digits: these messages list several values.
std::string number(double x, int digits = 10) { return format_number(x, digits); }

// A triangle whose doubled area is below this fraction of its longest edge squared is
// degenerate (collinear vertices); a volume below this fraction of the bounding box's
// largest side cubed is zero.
constexpr double degenerate_area_tolerance = 1e-12;
constexpr double zero_volume_tolerance = 1e-12;
// The second moments are sums of terms of order extent⁵ (a face normal, extent², times cubic
// polynomials of the coordinates), so a mesh spanning more than about 1e61 m overflows and one
// spanning less than about 1e-61 m underflows to nothing; these limits keep a margin.
constexpr double largest_extent = 1e60;
constexpr double smallest_extent = 1e-60;

const double pi = std::acos(-1.0);

// 1-based numbers for messages.
std::string nth(std::size_t index) { return std::to_string(index + 1); }

// The largest side of the bounding box of the vertices the triangles use (m); indices valid.
double extent_of(const std::vector<Vec3>& vertices, const std::vector<MeshTriangle>& triangles) {
  Vec3 low = vertices[triangles[0][0]], high = low;
  for (const MeshTriangle& tri : triangles)
    for (int index : tri) {
      low = low.cwiseMin(vertices[index]);
      high = high.cwiseMax(vertices[index]);
    }
  return (high - low).maxCoeff();
}

std::string extent_problem(double extent) {
  if (extent > largest_extent)
    return "the mesh is too large to integrate: it spans " + number(extent) +
           " m, and its second moments (of order span⁵) would overflow; express it in larger "
           "units (it must span at most " + number(largest_extent) + " m)";
  if (extent > 0.0 && extent < smallest_extent)
    return "the mesh is too small to integrate: it spans " + number(extent) +
           " m, and its second moments (of order span⁵) would underflow to zero; express it "
           "in smaller units (it must span at least " + number(smallest_extent) + " m)";
  return {};
}

// Collinear vertices: twice the area is below the tolerance times the longest edge squared.
// (Within the extents extent_problem admits, the squares neither overflow nor underflow.)
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !((b - a).cross(c - a).norm() > degenerate_area_tolerance * longest);
}

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
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      return "triangle " + nth(t) + " (" + nth(tri[0]) + ", " + nth(tri[1]) + ", " +
             nth(tri[2]) + ") is degenerate: it repeats a vertex";
  }
  const std::string problem = extent_problem(extent_of(vertices, triangles));
  if (!problem.empty()) return problem;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const MeshTriangle& tri = triangles[t];
    if (collinear(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]))
      return "triangle " + nth(t) + " (" + nth(tri[0]) + ", " + nth(tri[1]) + ", " +
             nth(tri[2]) + ") is degenerate: its vertices are collinear (zero area)";
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

// The first bad edge in the order of the triangles that use it (`uses` from edge_uses).
std::string edge_problem(const std::vector<EdgeUse>& uses, std::size_t triangle_count) {
  std::string problem;
  std::size_t problem_triangle = triangle_count;
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

// ---- pieces: the closed surfaces a mesh is made of -------------------------------------------

// Triangles that share an edge belong to the same piece, so on a mesh whose edges passed
// edge_problem each piece is a closed surface of its own. The piece of every triangle,
// numbered from 0 in the order of the pieces' first triangles (union-find over the edges).
std::vector<std::size_t> piece_of_triangles(const std::vector<EdgeUse>& uses,
                                            std::size_t triangle_count) {
  std::vector<std::size_t> parent(triangle_count);
  for (std::size_t t = 0; t < triangle_count; ++t) parent[t] = t;
  const auto root = [&parent](std::size_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  for (std::size_t i = 0; i + 1 < uses.size(); ++i)
    if (uses[i].key == uses[i + 1].key)
      parent[root(uses[i + 1].triangle)] = root(uses[i].triangle);
  const std::size_t none = triangle_count;
  std::vector<std::size_t> piece(triangle_count), number_of_root(triangle_count, none);
  std::size_t count = 0;
  for (std::size_t t = 0; t < triangle_count; ++t) {
    std::size_t& number = number_of_root[root(t)];
    if (number == none) number = count++;
    piece[t] = number;
  }
  return piece;
}

struct Piece {
  double volume = 0.0;            // signed, m³: negative when wound inside-out
  std::size_t first_triangle = 0;
  std::size_t triangle_count = 0;
};

// The signed volume of each piece: Σ p0·(p1 × p2)/6 over its triangles, the signed volumes of
// the tetrahedra they span with `reference` (divergence theorem; Mirtich 1996, section 2).
std::vector<Piece> pieces_of(const std::vector<Vec3>& vertices,
                             const std::vector<MeshTriangle>& triangles,
                             const std::vector<std::size_t>& piece_of, const Vec3& reference) {
  std::vector<Piece> pieces;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (piece_of[t] == pieces.size()) pieces.push_back({0.0, t, 0});
    Piece& piece = pieces[piece_of[t]];
    const Vec3 p0 = vertices[triangles[t][0]] - reference;
    const Vec3 p1 = vertices[triangles[t][1]] - reference;
    const Vec3 p2 = vertices[triangles[t][2]] - reference;
    piece.volume += p0.dot(p1.cross(p2)) / 6.0;
    ++piece.triangle_count;
  }
  return pieces;
}

// The winding number at p of the triangles outside piece `skip`: the sum of their signed solid
// angles over 4π, each by Van Oosterom & Strackee, "The Solid Angle of a Plane Triangle"
// (IEEE Trans. Biomed. Eng. 30(2), 1983): tan(Ω/2) = a·(b × c) / (|a||b||c| + (a·b)|c| +
// (a·c)|b| + (b·c)|a|), a, b, c the vertices relative to p. It is 1 inside a closed surface
// wound counter-clockwise seen from outside, 0 outside it, −1 inside an inside-out one.
double winding_number(const std::vector<Vec3>& vertices,
                      const std::vector<MeshTriangle>& triangles,
                      const std::vector<std::size_t>& piece_of, std::size_t skip, const Vec3& p) {
  double solid_angle = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (piece_of[t] == skip) continue;
    const Vec3 a = vertices[triangles[t][0]] - p;
    const Vec3 b = vertices[triangles[t][1]] - p;
    const Vec3 c = vertices[triangles[t][2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    solid_angle += 2.0 * std::atan2(a.dot(b.cross(c)), denominator);
  }
  return solid_angle / (4.0 * pi);
}

// An inside-out piece (negative signed volume) of a mesh with several pieces is a cavity when
// the other pieces wind once around it: then the solid is hollow there. Anywhere else it would
// be a solid of negative mass. The exact integrals weight every point by its winding number,
// so where solid pieces overlap their densities add up; that is allowed (inertia.mesh's
// documentation says so) and not checked. A mesh of one piece is left to volume_problem.
std::string piece_problem(const std::vector<Vec3>& vertices,
                          const std::vector<MeshTriangle>& triangles,
                          const std::vector<std::size_t>& piece_of,
                          const std::vector<Piece>& pieces) {
  if (pieces.size() < 2) return {};
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& piece = pieces[k];
    if (!(piece.volume < 0.0)) continue;
    const Vec3& p = vertices[triangles[piece.first_triangle][0]];
    if (std::lround(winding_number(vertices, triangles, piece_of, k, p)) >= 1) continue;
    return "piece " + nth(k) + " of the mesh's " + std::to_string(pieces.size()) +
           " separate closed surfaces (" + std::to_string(piece.triangle_count) +
           " triangles, the first is triangle " + nth(piece.first_triangle) +
           ") is inside-out: its signed volume " + number(piece.volume) +
           " m³ is negative, and it does not lie inside another piece as a cavity would; "
           "reverse the vertex order of its triangles";
  }
  return {};
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

// The total signed volume (finite) against the mesh's extent.
std::string volume_problem(double volume, double extent) {
  if (!(std::abs(volume) > zero_volume_tolerance * extent * extent * extent))
    return "the mesh encloses no volume (signed volume " + number(volume) +
           " m³, zero compared with its extent " + number(extent) + " m)";
  if (volume < 0.0)
    return "the mesh is inside-out (signed volume " + number(volume) +
           " m³ is negative): its triangles are clockwise seen from outside; reverse the "
           "vertex order of every triangle";
  return {};
}

// Eberly (2002), "Computing the Integrals", final step: the COM is ∫r/V; the tensor about the
// COM follows from the central second moments S = ∫ r rᵀ dV − V c cᵀ as ρ (tr(S) E − S)
// (seed 000_*, "Inertia": Ixx = ∫(y² + z²) dm, Ixy = −∫xy dm).
MeshMassProperties mass_properties(const VolumeIntegrals& integrals, double density) {
  const Vec3 offset = integrals.first / integrals.volume;  // COM relative to the reference
  const Mat3 central = integrals.second - integrals.volume * offset * offset.transpose();
  MeshMassProperties result;
  result.volume = integrals.volume;
  result.mass = density * integrals.volume;
  result.com = integrals.reference + offset;
  result.inertia = density * (central.trace() * Mat3::Identity() - central);
  return result;
}

// Elements, topology, then the pieces' and the total volume from the integrals, and last the
// tensor (of density 1), which must be one a solid can have (engine/inertia.hpp's validator):
// this catches what the piece test cannot see, such as a cavity that pokes out of its solid.
std::string full_problem(const std::vector<Vec3>& vertices,
                         const std::vector<MeshTriangle>& triangles, VolumeIntegrals& integrals) {
  std::string problem = element_problem(vertices, triangles);
  if (!problem.empty()) return problem;
  const std::vector<EdgeUse> uses = edge_uses(triangles);
  problem = edge_problem(uses, triangles.size());
  if (!problem.empty()) return problem;
  const Vec3 reference = reference_point(vertices, triangles);
  integrals = integrate(vertices, triangles, reference);
  const double extent = extent_of(vertices, triangles);
  if (!std::isfinite(integrals.volume))
    return "the volume integrals overflow (coordinates too large: " + number(extent) + " m)";
  const std::vector<std::size_t> piece_of = piece_of_triangles(uses, triangles.size());
  problem = piece_problem(vertices, triangles, piece_of,
                          pieces_of(vertices, triangles, piece_of, reference));
  if (problem.empty()) problem = volume_problem(integrals.volume, extent);
  if (!problem.empty()) return problem;
  const std::string tensor =
      inertia_tensor_problem(mass_properties(integrals, 1.0).inertia, InertiaRules::idealized);
  if (!tensor.empty())
    return "the mesh's pieces give an inertia tensor no solid has (" + tensor +
           "): an inside-out piece (a cavity) must lie wholly inside a solid piece";
  return {};
}

}  // namespace

std::string mesh_problem(const std::vector<Vec3>& vertices,
                         const std::vector<MeshTriangle>& triangles) {
  VolumeIntegrals integrals;
  return full_problem(vertices, triangles, integrals);
}

MeshMassProperties inertia_mesh(const std::vector<Vec3>& vertices,
                                const std::vector<MeshTriangle>& triangles, double density) {
  if (!std::isfinite(density) || !(density > 0.0))
    throw std::invalid_argument("density must be finite and > 0, got " + number(density));
  VolumeIntegrals integrals;
  const std::string problem = full_problem(vertices, triangles, integrals);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const MeshMassProperties result = mass_properties(integrals, density);
  if (!std::isfinite(result.mass) || !is_finite(result.com) || !is_finite(result.inertia))
    throw std::invalid_argument("the mass properties overflow (coordinates or density too large)");
  return result;
}

}  // namespace rigidlab
