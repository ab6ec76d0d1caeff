// Tests for engine/mesh_inertia.cpp against independent values: the closed forms of a box and
// of an L-shaped prism made of two boxes (exact, since the mesh is the solid), a published
// tetrahedron (Tonon 2005) and the unit tetrahedron's textbook moments, the convergence of
// tessellated spheres, cylinders and capsules to their closed forms at the rate of the
// tessellation's geometric error, and the exact transformation rules under rigid motions.
#include "engine/mesh_inertia.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

const double pi = std::acos(-1.0);

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<MeshTriangle> triangles;
};

// A prism over a counter-clockwise polygon in the xy plane, z from 0 to depth; the caps are
// `cap` triangles (counter-clockwise, indices into the polygon).
Mesh prism(const std::vector<Eigen::Vector2d>& polygon, const std::vector<MeshTriangle>& cap,
           double depth) {
  Mesh mesh;
  const int n = static_cast<int>(polygon.size());
  for (double z : {0.0, depth})
    for (const auto& p : polygon) mesh.vertices.emplace_back(p.x(), p.y(), z);
  for (const MeshTriangle& t : cap) {
    mesh.triangles.push_back({t[0], t[2], t[1]});             // bottom, seen from −z
    mesh.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});  // top
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    mesh.triangles.push_back({i, j, j + n});
    mesh.triangles.push_back({i, j + n, i + n});
  }
  return mesh;
}

Mesh box_mesh(const Vec3& size) {
  Mesh mesh = prism({{0, 0}, {size.x(), 0}, {size.x(), size.y()}, {0, size.y()}},
                    {{0, 1, 2}, {0, 2, 3}}, size.z());
  for (Vec3& v : mesh.vertices) v -= size / 2;  // centred on the origin
  return mesh;
}

// The surface of revolution about z of a profile (ρ, z) running from the bottom of the axis
// (ρ = 0) to its top (ρ = 0), with `segments` vertices per ring: the polyhedron inscribed in
// the smooth surface, its faces counter-clockwise seen from outside.
Mesh revolve(const std::vector<Eigen::Vector2d>& profile, int segments) {
  Mesh mesh;
  std::vector<int> ring_start;
  for (const auto& p : profile) {
    ring_start.push_back(static_cast<int>(mesh.vertices.size()));
    const int count = p.x() == 0.0 ? 1 : segments;
    for (int j = 0; j < count; ++j) {
      const double phi = 2 * pi * j / segments;
      mesh.vertices.emplace_back(p.x() * std::cos(phi), p.x() * std::sin(phi), p.y());
    }
  }
  for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
    const bool bottom_pole = profile[k].x() == 0.0, top_pole = profile[k + 1].x() == 0.0;
    for (int j = 0; j < segments; ++j) {
      const int jn = (j + 1) % segments;
      // a, b on ring k; c, d above them on ring k + 1 (a pole is one vertex for all j).
      const int a = ring_start[k] + (bottom_pole ? 0 : j);
      const int b = ring_start[k] + (bottom_pole ? 0 : jn);
      const int c = ring_start[k + 1] + (top_pole ? 0 : jn);
      const int d = ring_start[k + 1] + (top_pole ? 0 : j);
      if (!bottom_pole) mesh.triangles.push_back({a, b, c});
      if (!top_pole) mesh.triangles.push_back({a, c, d});
    }
  }
  return mesh;
}

// Half-circle arcs of radius r centred at height z, from angle `from` to `to` (radians from
// the −z axis), `steps` pieces, the first point included only when `with_first`.
void add_arc(std::vector<Eigen::Vector2d>& profile, double r, double z, double from, double to,
             int steps, bool with_first) {
  for (int k = with_first ? 0 : 1; k <= steps; ++k) {
    const double t = from + (to - from) * k / steps;
    profile.emplace_back(k == 0 && from == 0.0 ? 0.0 : r * std::sin(t), z - r * std::cos(t));
  }
  if (to == pi) profile.back().x() = 0.0;  // exactly on the axis
}

Mesh sphere_mesh(double r, int segments) {
  std::vector<Eigen::Vector2d> profile;
  add_arc(profile, r, 0.0, 0.0, pi, segments / 2, true);
  return revolve(profile, segments);
}

Mesh cylinder_mesh(double r, double h, int segments) {
  return revolve({{0, -h / 2}, {r, -h / 2}, {r, h / 2}, {0, h / 2}}, segments);
}

Mesh capsule_mesh(double r, double h, int segments) {
  std::vector<Eigen::Vector2d> profile;
  add_arc(profile, r, -h / 2, 0.0, pi / 2, segments / 4, true);
  add_arc(profile, r, h / 2, pi / 2, pi, segments / 4, true);
  return revolve(profile, segments);
}

double relative_error(const Mat3& got, const Mat3& want) {
  return (got - want).norm() / want.norm();
}

// ---- exact cases ---------------------------------------------------------------------------

TEST(MeshInertia, BoxMeshEqualsSolidBox) {
  const Vec3 size(0.4, 1.0, 2.2);
  const double density = 7.5;
  const Mesh mesh = box_mesh(size);
  const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles, density);
  const double volume = size.prod();
  EXPECT_NEAR(p.volume, volume, 1e-14);
  EXPECT_NEAR(p.mass, density * volume, 1e-13);
  EXPECT_LT(p.com.norm(), 1e-15);
  EXPECT_LT((p.inertia - inertia_solid_box(density * volume, size)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(MeshInertia, NonConvexLPrismEqualsTwoBoxes) {
  // The L of cells [0,2]×[0,1] and [0,1]×[1,2], depth 0.5, fanned from its reflex vertex.
  const Mesh mesh = prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
                          {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}}, 0.5);
  const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles, 2.0);
  const double cell_mass = 2.0 * 1 * 1 * 0.5;  // density · volume of a 1 × 1 × 0.5 cell
  const MassProperties want = composite_inertia(
      {{2 * cell_mass, Vec3(1.0, 0.5, 0.25), inertia_solid_box(2 * cell_mass, Vec3(2, 1, 0.5))},
       {cell_mass, Vec3(0.5, 1.5, 0.25), inertia_solid_box(cell_mass, Vec3(1, 1, 0.5))}});
  EXPECT_NEAR(p.mass, want.mass, 1e-14);
  EXPECT_LT((p.com - want.com).norm(), 1e-14);
  EXPECT_LT((p.inertia - want.inertia).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_GT(std::abs(p.inertia(0, 1)), 0.1) << "the L has a real product of inertia";
}

// The tetrahedron with faces counter-clockwise from outside, whatever the vertex order.
Mesh tetrahedron(Vec3 a, Vec3 b, const Vec3& c, const Vec3& d) {
  if ((b - a).cross(c - a).dot(d - a) < 0) std::swap(a, b);
  return {{a, b, c, d}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
}

TEST(MeshInertia, UnitTetrahedronHasTheTextbookMoments) {
  // Vertices 0, x, y, z: volume 1/6, centroid (1/4, 1/4, 1/4), and about the origin
  // ∫x² dV = 1/60, ∫xy dV = 1/120 (integrate x² over 0 ≤ x, y, z, x + y + z ≤ 1).
  const Mesh mesh = tetrahedron(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
  const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles);
  EXPECT_NEAR(p.volume, 1.0 / 6, 1e-16);
  EXPECT_LT((p.com - Vec3(0.25, 0.25, 0.25)).norm(), 1e-16);
  Mat3 origin;  // (tr S) E − S with S_ii = 1/60, S_ij = 1/120
  origin << 2.0 / 60, -1.0 / 120, -1.0 / 120,
            -1.0 / 120, 2.0 / 60, -1.0 / 120,
            -1.0 / 120, -1.0 / 120, 2.0 / 60;
  const Mat3 about_origin = parallel_axis(p.inertia, p.mass, p.com);
  EXPECT_LT((about_origin - origin).cwiseAbs().maxCoeff(), 1e-16);
}

TEST(MeshInertia, TononTetrahedronMatchesThePublishedValues) {
  // F. Tonon, "Explicit Exact Formulas for the 3-D Tetrahedron Inertia Tensor in Terms of its
  // Vertex Coordinates", J. Math. Stat. 1(1):8-11, 2005, numerical example, density 1.
  // The paper defines a = ∫(y² + z²), b = ∫(x² + z²), c = ∫(x² + y²) and the products
  // a' = ∫yz, b' = ∫xz, c' = ∫xy (its Eqs. 9d-f) about the centroid, so the tensor is
  // [[a, −c', −b'], [−c', b, −a'], [−b', −a', c]]. (The matrix printed as its Eq. 2 swaps b'
  // and c'; the published numbers follow Eqs. 9.) The coordinates are printed to 5 decimals
  // and the results differ from the exact values for those coordinates in the 8th digit.
  const Mesh mesh = tetrahedron(Vec3(8.33220, -11.86875, 0.93355), Vec3(0.75523, 5.00000, 16.37072),
                                Vec3(52.61236, 5.00000, -5.38580), Vec3(2.00000, 5.00000, 3.00000));
  const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles, 1.0);
  const double a = 43520.33257, b = 194711.28938, c = 191168.76173;
  const double a1 = 4417.66150, b1 = -46343.16662, c1 = 11996.20119;
  Mat3 published;
  published << a, -c1, -b1,
               -c1, b, -a1,
               -b1, -a1, c;
  EXPECT_NEAR(p.volume, 1873.233236, 1e-6 * 1873.233236);
  EXPECT_LT((p.com - Vec3(15.92492, 0.78281, 3.72962)).norm(), 1e-4);  // 5 printed decimals
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(p.inertia(i, j), published(i, j), 1e-6 * c) << "entry " << i << ", " << j;
}

// ---- rigid motions -------------------------------------------------------------------------

// A lopsided non-convex solid: a vase of revolution, squashed and sheared so that no axis is
// principal and the COM is off the origin.
Mesh irregular_mesh() {
  Mesh mesh = revolve({{0, -1}, {0.8, -1}, {1.0, -0.3}, {0.4, 0.2}, {0.7, 0.9}, {0, 1}}, 12);
  Mat3 shape;
  shape << 1.3, 0.4, 0.0,
           0.0, 0.7, 0.2,
           0.1, 0.0, 1.1;
  for (Vec3& v : mesh.vertices) v = shape * v + Vec3(0.3, -0.2, 0.5);
  return mesh;
}

TEST(MeshInertia, RigidMotionMovesTheComAndRotatesTheTensor) {
  const Mesh mesh = irregular_mesh();
  const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles, 3.0);
  EXPECT_GT(std::abs(p.inertia(0, 2)), 1e-3 * p.inertia.norm()) << "products of inertia present";
  std::mt19937 rng(4);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 R = Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const Vec3 t(10 * g(rng), 10 * g(rng), 10 * g(rng));
    Mesh moved = mesh;
    for (Vec3& v : moved.vertices) v = R * v + t;
    const MeshMassProperties q = inertia_mesh(moved.vertices, moved.triangles, 3.0);
    EXPECT_NEAR(q.volume, p.volume, 1e-13 * p.volume);
    EXPECT_LT((q.com - (R * p.com + t)).norm(), 1e-13 * (1 + t.norm()));
    EXPECT_LT(relative_error(q.inertia, rotate_inertia(p.inertia, R)), 1e-13);
  }
}

TEST(MeshInertia, BoxFarFromTheOriginKeepsFullPrecision) {
  const Vec3 size(1, 2, 3), far(1e5, -2e5, 3e5);
  Mesh mesh = box_mesh(size);
  for (Vec3& v : mesh.vertices) v += far;
  const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles);
  EXPECT_LT((p.com - far).norm(), 1e-10);
  EXPECT_LT(relative_error(p.inertia, inertia_solid_box(6.0, size)), 1e-10);
}

// ---- convergence to the smooth shapes ------------------------------------------------------

// Relative errors of the inscribed polyhedra shrink as 1/segments² (the sagitta of a chord is
// ∝ (segment angle)²): doubling the segments must divide the error by about 4.
void check_convergence(const char* name, Mesh (*make)(int), const Mat3& exact_unit_density,
                       double exact_volume) {
  std::printf("%-8s %9s %9s %13s %13s %7s\n", name, "segments", "triangles", "volume err",
              "inertia err", "ratio");
  double previous = 0;
  for (int segments = 8; segments <= 256; segments *= 2) {
    const Mesh mesh = make(segments);
    const MeshMassProperties p = inertia_mesh(mesh.vertices, mesh.triangles);
    const double error = relative_error(p.inertia, exact_unit_density);
    std::printf("%-8s %9d %9zu %13.4e %13.4e %7.3f\n", "", segments, mesh.triangles.size(),
                std::abs(p.volume - exact_volume) / exact_volume, error,
                previous > 0 ? previous / error : 0.0);
    EXPECT_LT(p.volume, exact_volume) << "an inscribed polyhedron is smaller";
    if (previous > 0 && segments >= 32) {
      EXPECT_GT(previous / error, 3.6) << name << " at " << segments << " segments";
      EXPECT_LT(previous / error, 4.4) << name << " at " << segments << " segments";
    }
    previous = error;
  }
  EXPECT_LT(previous, 1e-3) << "converges to the closed form, not elsewhere";
}

const double r = 0.5, h = 1.2;

TEST(MeshInertia, SphereConvergesAsOneOverSegmentsSquared) {
  const double volume = 4.0 / 3.0 * pi * r * r * r;
  check_convergence("sphere", [](int n) { return sphere_mesh(r, n); },
                    inertia_solid_sphere(volume, r), volume);
}

TEST(MeshInertia, CylinderConvergesAsOneOverSegmentsSquared) {
  const double volume = pi * r * r * h;
  check_convergence("cylinder", [](int n) { return cylinder_mesh(r, h, n); },
                    inertia_solid_cylinder(volume, r, h), volume);
}

TEST(MeshInertia, CapsuleConvergesAsOneOverSegmentsSquared) {
  const double volume = pi * r * r * h + 4.0 / 3.0 * pi * r * r * r;
  check_convergence("capsule", [](int n) { return capsule_mesh(r, h, n); },
                    inertia_capsule(volume, r, h), volume);
}

// ---- refusals ------------------------------------------------------------------------------

std::string refusal(const Mesh& mesh, double density = 1.0) {
  try {
    inertia_mesh(mesh.vertices, mesh.triangles, density);
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(mesh_problem(mesh.vertices, mesh.triangles).empty(), density != 1.0);
    return e.what();
  }
  ADD_FAILURE() << "no refusal";
  return "";
}

Mesh unit_tetrahedron() {
  return tetrahedron(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ());
}

TEST(MeshRefusal, TooSmall) {
  Mesh m = unit_tetrahedron();
  m.triangles.pop_back();
  EXPECT_EQ(refusal(m), "a closed mesh needs at least 4 triangles, got 3");
  m = unit_tetrahedron();
  m.vertices.pop_back();
  EXPECT_EQ(refusal(m), "a closed mesh needs at least 4 vertices, got 3");
}

TEST(MeshRefusal, IndexOutOfRange) {
  Mesh m = unit_tetrahedron();
  m.triangles[2][1] = 4;
  EXPECT_EQ(refusal(m), "triangle 3 refers to vertex 5, but the vertices are numbered 1 to 4");
  m.triangles[2][1] = -1;
  EXPECT_EQ(refusal(m), "triangle 3 refers to vertex 0, but the vertices are numbered 1 to 4");
}

TEST(MeshRefusal, DegenerateTriangles) {
  Mesh m = unit_tetrahedron();
  m.triangles[1] = {0, 0, 3};
  EXPECT_EQ(refusal(m), "triangle 2 (1, 1, 4) is degenerate: it repeats a vertex");
  m = unit_tetrahedron();
  m.vertices[3] = Vec3(0.5, 0.5, 0.0);  // on the hypotenuse of the x-y face: 2, 3, 4 collinear
  EXPECT_NE(refusal(m).find("is degenerate: its vertices are collinear (zero area)"),
            std::string::npos);
  m = unit_tetrahedron();
  m.vertices[2].y() = std::nan("");
  EXPECT_EQ(refusal(m), "vertex 3 is not finite");
}

TEST(MeshRefusal, OpenMeshNamesTheEdge) {
  Mesh m = box_mesh(Vec3(1, 1, 1));
  // Remove the bottom triangle {0, 2, 1}: its diagonal 0-2 (1-3 counting from 1) is left to
  // the other bottom triangle, now the second triangle. The first open edge in triangle
  // order is named.
  m.triangles.erase(m.triangles.begin());
  EXPECT_EQ(refusal(m),
            "the mesh is not closed: edge 1-3 belongs only to triangle 2 (each edge of a closed "
            "surface is shared by exactly two triangles)");
}

TEST(MeshRefusal, EdgeSharedByFourTriangles) {
  // Two tetrahedra sharing the edge from 0 to x: each is closed, but that edge has four
  // triangles. The second tetrahedron's vertices 0, x, −y, −z are m's vertices 1, 2, 5, 6.
  Mesh m = unit_tetrahedron();
  m.vertices.push_back(Vec3(0, -1, 0));
  m.vertices.push_back(Vec3(0, 0, -1));
  const Mesh second = tetrahedron(Vec3::Zero(), Vec3::UnitX(), Vec3(0, -1, 0), Vec3(0, 0, -1));
  ASSERT_EQ(second.vertices[0], Vec3::Zero()) << "positively oriented as given";
  const int index_in_m[4] = {0, 1, 4, 5};
  for (const MeshTriangle& t : second.triangles)
    m.triangles.push_back({index_in_m[t[0]], index_in_m[t[1]], index_in_m[t[2]]});
  EXPECT_EQ(refusal(m),
            "the mesh is not a simple closed surface: edge 1-2 is shared by 4 triangles "
            "(1, 2, 5, 6), not exactly two");
}

TEST(MeshRefusal, InconsistentWinding) {
  Mesh m = box_mesh(Vec3(1, 1, 1));
  std::swap(m.triangles[5][1], m.triangles[5][2]);
  const std::string message = refusal(m);
  EXPECT_NE(message.find("in the same direction, so their windings disagree"), std::string::npos)
      << message;
  EXPECT_NE(message.find("6"), std::string::npos) << "names triangle 6: " << message;
}

TEST(MeshRefusal, InsideOut) {
  Mesh m = box_mesh(Vec3(1, 2, 3));
  for (MeshTriangle& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(refusal(m),
            "the mesh is inside-out (signed volume -6 m³ is negative): its triangles are "
            "clockwise seen from outside; reverse the vertex order of every triangle");
}

TEST(MeshRefusal, ZeroVolume) {
  // A square closed by a top with one diagonal and a bottom with the other: every edge is
  // shared correctly, but the surface encloses nothing.
  const Mesh m{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
               {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}};
  EXPECT_NE(refusal(m).find("the mesh encloses no volume"), std::string::npos) << refusal(m);
}

TEST(MeshRefusal, BadDensity) {
  const Mesh m = unit_tetrahedron();
  EXPECT_EQ(refusal(m, 0.0), "density must be finite and > 0, got 0");
  EXPECT_EQ(refusal(m, -HUGE_VAL), "density must be finite and > 0, got -inf");
}

// ---- several pieces -------------------------------------------------------------------------

// `add`'s vertices and triangles appended to `mesh`, moved by `offset`, optionally inside-out.
void append(Mesh& mesh, const Mesh& add, const Vec3& offset, bool inside_out = false) {
  const int base = static_cast<int>(mesh.vertices.size());
  for (const Vec3& v : add.vertices) mesh.vertices.push_back(v + offset);
  for (MeshTriangle t : add.triangles) {
    if (inside_out) std::swap(t[1], t[2]);
    mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
}

// A 2 × 2 × 2 box with a 1 × 1 × 1 cavity (its surface wound inside-out, counter-clockwise
// seen from inside the cavity) is the big box minus the small one: mass ρ(8 − 1) and, both
// centred at c, I = I_box(8ρ, 2, 2, 2) − I_box(ρ, 1, 1, 1) (the closed forms of a box).
TEST(MeshPieces, ACavityIsSubtracted) {
  const Vec3 c(3, -1, 2);
  Mesh m;
  append(m, box_mesh(Vec3(2, 2, 2)), c);
  append(m, box_mesh(Vec3(1, 1, 1)), c, true);
  const MeshMassProperties p = inertia_mesh(m.vertices, m.triangles, 5.0);
  EXPECT_NEAR(p.volume, 7.0, 1e-13);
  EXPECT_NEAR(p.mass, 35.0, 1e-12);
  EXPECT_LT((p.com - c).norm(), 1e-13);
  const Mat3 want = inertia_solid_box(40.0, Vec3(2, 2, 2)) - inertia_solid_box(5.0, Vec3(1, 1, 1));
  EXPECT_LT(relative_error(p.inertia, want), 1e-14);
}

// Two separate boxes are the composite body: each box's closed form moved to the common COM by
// the parallel axis theorem (here the COM is the midpoint and the offsets are ±(2, 0, 0)).
TEST(MeshPieces, SeparateSolidsAddUp) {
  Mesh m;
  append(m, box_mesh(Vec3(1, 2, 3)), Vec3(-2, 0, 0));
  append(m, box_mesh(Vec3(1, 2, 3)), Vec3(2, 0, 0));
  const MeshMassProperties p = inertia_mesh(m.vertices, m.triangles);
  EXPECT_NEAR(p.mass, 12.0, 1e-13);
  EXPECT_LT(p.com.norm(), 1e-13);
  const Mat3 one = inertia_solid_box(6.0, Vec3(1, 2, 3));
  const Mat3 shift = Vec3(0, 6.0 * 4, 6.0 * 4).asDiagonal();  // m (d·d E − d⊗d), d = (2, 0, 0)
  EXPECT_LT(relative_error(p.inertia, 2.0 * (one + shift)), 1e-14);
}

// As documented, overlapping solid pieces are summed: the exact integrals count the overlap
// once per piece, so two copies of a box are a box of twice the density.
TEST(MeshPieces, OverlappingSolidsAreSummed) {
  Mesh m;
  append(m, box_mesh(Vec3(1, 2, 3)), Vec3::Zero());
  append(m, box_mesh(Vec3(1, 2, 3)), Vec3::Zero());
  const MeshMassProperties p = inertia_mesh(m.vertices, m.triangles);
  EXPECT_NEAR(p.volume, 12.0, 1e-13);
  EXPECT_LT(relative_error(p.inertia, inertia_solid_box(12.0, Vec3(1, 2, 3))), 1e-14);
}

// The audit's case: two separate tetrahedra, the smaller inside-out. The total volume is
// positive (1/6 − 1/48) but the small piece would be negative mass (before, the tensor came
// out with Iyy = Izz < 0).
TEST(MeshPieces, AnInsideOutPieceOutsideTheSolidIsRefused) {
  Mesh m = unit_tetrahedron();
  append(m, tetrahedron(Vec3::Zero(), Vec3(0.5, 0, 0), Vec3(0, 0.5, 0), Vec3(0, 0, 0.5)),
         Vec3(10, 0, 0), true);
  EXPECT_EQ(refusal(m),
            "piece 2 of the mesh's 2 separate closed surfaces (4 triangles, the first is "
            "triangle 5) is inside-out: its signed volume -0.02083333333 m³ is negative, and it "
            "does not lie inside another piece as a cavity would; reverse the vertex order of "
            "its triangles");
  // Flipping the big one instead names it, though the total volume is then negative.
  Mesh big_flipped;
  append(big_flipped, unit_tetrahedron(), Vec3::Zero(), true);
  append(big_flipped, tetrahedron(Vec3::Zero(), Vec3(0.5, 0, 0), Vec3(0, 0.5, 0), Vec3(0, 0, 0.5)),
         Vec3(10, 0, 0));
  EXPECT_NE(refusal(big_flipped).find("piece 1 of the mesh's 2"), std::string::npos)
      << refusal(big_flipped);
}

// A cavity that pokes out of its solid passes the piece test (its first corner is inside the
// cube) but makes a tensor no solid has: the validator of engine/inertia.hpp refuses it.
TEST(MeshPieces, ACavityPokingOutOfTheSolidIsRefusedByTheTensorCheck) {
  Mesh m;
  append(m, box_mesh(Vec3(1, 1, 1)), Vec3(0.5, 0.5, 0.5));         // the cube [0, 1]³
  append(m, box_mesh(Vec3(9.5, 0.2, 0.2)), Vec3(5.25, 0.5, 0.5), true);  // x from 0.5 to 10
  const std::string message = refusal(m);
  EXPECT_EQ(message.rfind("the mesh's pieces give an inertia tensor no solid has (principal "
                          "moments ", 0), 0u) << message;
  EXPECT_NE(message.find("an inside-out piece (a cavity) must lie wholly inside a solid piece"),
            std::string::npos) << message;
}

// ---- scale ---------------------------------------------------------------------------------

// The box's closed form holds from 1e-50 m to 1e50 m (the integrals are of order size⁵).
TEST(MeshScale, BoxesFromTinyToHugeMatchTheClosedForm) {
  for (double s : {1e-50, 1e-20, 1e20, 1e50}) {
    const Vec3 size = s * Vec3(1, 2, 3);
    const Mesh m = box_mesh(size);
    const MeshMassProperties p = inertia_mesh(m.vertices, m.triangles);
    EXPECT_NEAR(p.volume / (s * s * s), 6.0, 1e-13) << s;
    const double s5 = s * s * s * s * s;  // compared at unit scale (their squares would not fit)
    EXPECT_LT(relative_error(p.inertia / s5, inertia_solid_box(p.mass, size) / s5), 1e-13) << s;
  }
}

TEST(MeshScale, TooLargeOrTooSmallSaysSo) {
  for (double s : {1e200, 1e-200}) {
    Mesh m = unit_tetrahedron();
    for (Vec3& v : m.vertices) v *= s;
    const std::string message = refusal(m);
    EXPECT_EQ(message.rfind(s > 1 ? "the mesh is too large to integrate: it spans 1e+200 m"
                                  : "the mesh is too small to integrate: it spans 1e-200 m",
                            0),
              0u)
        << message;
  }
}

}  // namespace
}  // namespace rigidlab
