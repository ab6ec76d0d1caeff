#include "engine/narrow_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rigidlab {
namespace {

// Combines feature numbers into one (boost::hash_combine's mixing): equal inputs give equal
// ids from step to step, which is all warm starting needs.
std::uint32_t mix(std::uint32_t seed, std::uint32_t value) {
  return seed ^ (value + 0x9e3779b9u + (seed << 6) + (seed >> 2));
}

double sign_of(double x) { return x < 0.0 ? -1.0 : 1.0; }

// Half the length of the projection of a box onto the unit axis n (m): Σ h_k |n·u_k|.
double radius_along(const Pose& box, const Vec3& half, const Vec3& n) {
  return half.x() * std::abs(n.dot(box.rotation.col(0))) +
         half.y() * std::abs(n.dot(box.rotation.col(1))) +
         half.z() * std::abs(n.dot(box.rotation.col(2)));
}

// Appends a point given its gap (= −depth) and the point of b's surface measured from a's
// surface along n: the midpoint lies half the gap back towards a.
void add_point(Manifold& m, const Vec3& surface_point_b, double gap, std::uint32_t feature) {
  m.points[m.count++] = {surface_point_b - 0.5 * gap * m.normal, -gap, feature};
}

// ---- box–box helpers --------------------------------------------------------------------

struct ClipVertex {
  Vec3 p;
  std::uint32_t id;
};
constexpr int max_clip_vertices = max_face_points;

// Sutherland–Hodgman against one plane: keeps the part of the convex polygon `in` where
// dir·p ≤ limit. Returns the number of vertices written to `out`. A vertex within `tolerance`
// of the plane counts as on it (kept, no cut next to it): the side faces of equal boxes
// stacked edge on edge coincide, and rounding must not cut their corners into near-duplicate
// points of which only some are kept (a stack would then be held unevenly and topple).
int clip_polygon(const ClipVertex* in, int count, ClipVertex* out, const Vec3& dir, double limit,
                 double tolerance, std::uint32_t plane_id) {
  // Each vertex's signed distance once (it is the next edge's start as well as this one's end).
  double distance[max_clip_vertices];
  for (int k = 0; k < count; ++k) {
    const double d = dir.dot(in[k].p) - limit;
    distance[k] = std::abs(d) <= tolerance ? 0.0 : d;
  }
  int written = 0;
  for (int k = 0; k < count; ++k) {
    const int before = k == 0 ? count - 1 : k - 1;
    const ClipVertex& prev = in[before];
    const ClipVertex& cur = in[k];
    const double dp = distance[before], dc = distance[k];
    if ((dp < 0.0 && dc > 0.0) || (dp > 0.0 && dc < 0.0))
      out[written++] = {prev.p + (dp / (dp - dc)) * (cur.p - prev.p),
                        mix(mix(plane_id, prev.id), cur.id)};
    if (dc <= 0.0) out[written++] = cur;
  }
  return written;
}

// Removes the vertices of a clipped face (in the polygon's order) where its boundary turns by
// less than 1e-6 rad: such a vertex lies on the segment between its neighbours (to rounding)
// and holds nothing they do not (the gap is linear along an edge, so it is never deeper than
// both). They arise where an incident edge crosses a reference side plane at a tiny angle:
// two equal boxes stacked face on face with a yaw θ between them overlap in an octagon whose
// four extra vertices lie mid-edge, turning by θ. With θ ~ 1e-8 (rounding), which of a
// corner and its edge's mid point is "deepest" is decided by rounding, and reduce_to_four,
// starting from the deepest, kept a mid-edge point instead of a corner: the box above rested
// on three corners and a mid point, lost the warm start of the fourth, and a column of 20
// boxes under sequential_impulses toppled. Returns the number left (all of them when fewer
// than three would be: a degenerate sliver is left to reduce_to_four as it is).
int drop_straight_vertices(ContactPoint* points, int count, const Vec3& n) {
  bool straight[max_clip_vertices] = {};
  for (int k = 0; k < count; ++k) {
    const Vec3& prev = points[(k + count - 1) % count].point;
    const Vec3& next = points[(k + 1) % count].point;
    const Vec3 in = points[k].point - prev, out = next - points[k].point;
    straight[k] = std::abs(in.cross(out).dot(n)) <= 1e-6 * in.norm() * out.norm();
  }
  int written = 0;
  for (int k = 0; k < count; ++k)
    if (!straight[k]) points[written++] = points[k];
  return written >= 3 ? written : count;
}

// Keeps at most four of the `count` points of one face contact, in this order: the deepest,
// the one farthest from it across the face, the one making the largest triangle with those
// two, and the one making the largest triangle on the other side of their edge (Gregorius,
// GDC 2015). Distances and areas are measured in the contact plane. On four points of a
// convex quad it keeps all four (ordered so), on three a triangle.
// Four of the points, grown from `first` (Gregorius, GDC 2015): the point farthest from it,
// the one making the largest triangle with those two, and the one adding the largest triangle
// outside it. Returns twice the area of the quad (in the contact plane) they span.
double grow_four(const ContactPoint* points, int count, const Vec3& n, int first, int chosen[4]) {
  auto in_plane = [&n](const Vec3& v) -> Vec3 { return v - n.dot(v) * n; };
  const Vec3& p0 = points[first].point;
  int second = first;
  double farthest = -1.0;
  for (int k = 0; k < count; ++k) {
    const double d2 = in_plane(points[k].point - p0).squaredNorm();
    if (d2 > farthest) farthest = d2, second = k;
  }
  // Twice the signed area of the triangle (i, j, k) in the contact plane.
  auto area = [&](int i, int j, int k) {
    return (points[j].point - points[i].point).cross(points[k].point - points[i].point).dot(n);
  };
  int third = first;
  double largest = -1.0;
  for (int k = 0; k < count; ++k)
    if (std::abs(area(first, second, k)) > largest)
      largest = std::abs(area(first, second, k)), third = k;
  const double side = sign_of(area(first, second, third));
  // The fourth: the largest triangle outside the edge first-second; when first-second is an
  // edge of the polygon (a point adjacent to the deepest can be the farthest, in a kite),
  // outside the triangle's other two edges instead, so that a quad keeps its four corners.
  int fourth = -1;
  double opposite = 0.0;
  for (const auto& [i, j] : {std::pair{first, second}, {second, third}, {third, first}}) {
    for (int k = 0; k < count; ++k)
      if (-side * area(i, j, k) > opposite) opposite = -side * area(i, j, k), fourth = k;
    if (fourth >= 0) break;
  }
  chosen[0] = first, chosen[1] = second, chosen[2] = third, chosen[3] = fourth;
  return largest + opposite;
}

void reduce_to_four(const ContactPoint* points, int count, Manifold& m) {
  const Vec3& n = m.normal;
  int first = 0;
  for (int k = 1; k < count; ++k)
    if (points[k].depth > points[first].depth) first = k;
  int chosen[4];
  const double area = grow_four(points, count, n, first, chosen);
  // Grown from the deepest point, the quad keeps the largest penetration; but when the points
  // are about as deep (a face resting flat on a face: depths within a thousandth of the
  // patch's size), which of them is deepest is chance, and a point in the middle of an edge
  // can start it. Two unit boxes twisted by 0.1 rad about their common normal overlap in an
  // octagon whose four corners turn by 84 degrees and four mid-edge vertices by 6; grown from
  // a mid-edge vertex the quad keeps three corners and that vertex, and a stack of five boxes
  // with yaws 0, 0.1, 0, ... crept 223 mm in 10 s at 60 Hz (eight fell). So among the points
  // as deep as the deepest, the quad is also grown from the one farthest from their centroid
  // (a corner), and kept when it spans more than 10 % more area. Otherwise the quad is the
  // deepest point's, as before: a choice that gains little is not made (issue 13's pyramid
  // depends on its contacts' point order to within its 5 mm).
  Vec3 centroid = Vec3::Zero();
  for (int k = 0; k < count; ++k) centroid += points[k].point;
  centroid /= count;
  auto from_centroid = [&](int k) {
    const Vec3 d = points[k].point - centroid;
    return (d - n.dot(d) * n).squaredNorm();
  };
  double extent = 0.0;
  for (int k = 0; k < count; ++k) extent = std::max(extent, from_centroid(k));
  const double flat = 1e-3 * std::sqrt(extent);
  int corner = first;
  for (int k = 0; k < count; ++k)
    if (points[k].depth >= points[first].depth - flat && from_centroid(k) > from_centroid(corner))
      corner = k;
  if (corner != first) {
    int other[4];
    if (grow_four(points, count, n, corner, other) > 1.1 * area) std::copy(other, other + 4, chosen);
  }
  m.count = 0;
  for (int k : chosen)
    if (k >= 0) m.points[m.count++] = points[k];
}

// The contact of a face of `ref` (axis `axis`, outward unit normal ref_normal pointing at
// `inc`) with the face of `inc` that faces it: the incident face is clipped against the four
// side planes of the reference face; the clipped vertices within the margin below the
// reference face are the points. The manifold normal is ref_normal (flipped by the caller
// when ref is b).
Manifold face_contact(const Pose& ref, const Vec3& ref_half, int axis, const Vec3& ref_normal,
                      const Pose& inc, const Vec3& inc_half, double margin,
                      std::uint32_t feature_seed) {
  int face = 0;
  double best = -1.0;
  for (int k = 0; k < 3; ++k) {
    const double alignment = std::abs(inc.rotation.col(k).dot(ref_normal));
    if (alignment > best) best = alignment, face = k;
  }
  const double face_sign = -sign_of(inc.rotation.col(face).dot(ref_normal));
  const Vec3 face_center = inc.position + face_sign * inc_half[face] * inc.rotation.col(face);
  const int f1 = (face + 1) % 3, f2 = (face + 2) % 3;
  const Vec3 e1 = inc_half[f1] * inc.rotation.col(f1), e2 = inc_half[f2] * inc.rotation.col(f2);
  ClipVertex buffer_a[max_clip_vertices] = {{face_center + e1 + e2, 0},
                                            {face_center - e1 + e2, 1},
                                            {face_center - e1 - e2, 2},
                                            {face_center + e1 - e2, 3}};
  ClipVertex buffer_b[max_clip_vertices];
  ClipVertex* polygon = buffer_a;
  ClipVertex* scratch = buffer_b;
  int count = 4;
  const int s1 = (axis + 1) % 3, s2 = (axis + 2) % 3;
  for (int plane = 0; plane < 4 && count > 0; ++plane) {
    const int side_axis = plane < 2 ? s1 : s2;
    const Vec3 dir = (plane % 2 == 0 ? 1.0 : -1.0) * ref.rotation.col(side_axis);
    const double limit = ref_half[side_axis] + dir.dot(ref.position);
    // Rounding of positions and of a unit axis times a size, with room to spare.
    const double tolerance = 1e-9 * (ref_half.maxCoeff() + inc_half.maxCoeff()) +
                             1e-12 * std::abs(limit);
    count = clip_polygon(polygon, count, scratch, dir, limit, tolerance,
                         static_cast<std::uint32_t>(plane));
    std::swap(polygon, scratch);
  }
  const std::uint32_t seed =
      mix(feature_seed, static_cast<std::uint32_t>(2 * face + (face_sign > 0)));
  const Vec3 ref_center = ref.position + ref_half[axis] * ref_normal;
  auto keep = [&](ContactPoint* kept, int& kept_count) {
    for (int k = 0; k < count; ++k) {
      const double gap = ref_normal.dot(polygon[k].p - ref_center);
      if (gap <= margin)
        kept[kept_count++] = {polygon[k].p - 0.5 * gap * ref_normal, -gap,
                              mix(seed, polygon[k].id)};
    }
  };
  if (count <= max_manifold_points) {  // kept as they are (reduce_face_points): made in place
    Manifold m;
    m.normal = ref_normal;
    keep(m.points.data(), m.count);
    return m;
  }
  ContactPoint kept[max_clip_vertices];
  int kept_count = 0;
  keep(kept, kept_count);
  return reduce_face_points(kept, kept_count, ref_normal);
}

// One point where edge `edge_a` of a crosses edge `edge_b` of b, n the separating axis from a
// to b: the midpoint of the closest points of the two edges that support the boxes along n.
Manifold edge_contact(const Pose& a, const Vec3& ha, int edge_a, const Pose& b, const Vec3& hb,
                      int edge_b, const Vec3& n) {
  Vec3 pa = a.position, pb = b.position;
  for (int k = 0; k < 3; ++k) {
    if (k != edge_a) pa += ha[k] * sign_of(n.dot(a.rotation.col(k))) * a.rotation.col(k);
    if (k != edge_b) pb -= hb[k] * sign_of(n.dot(b.rotation.col(k))) * b.rotation.col(k);
  }
  // Closest points of pa + s u and pb + t v (Ericson 5.1.9 for unit directions), clamped to
  // the edges: s = t (u·v) − u·w, t = s (u·v) + v·w with w = pa − pb.
  const Vec3 u = a.rotation.col(edge_a), v = b.rotation.col(edge_b), w = pa - pb;
  const double uv = u.dot(v), uw = u.dot(w), vw = v.dot(w), denom = 1.0 - uv * uv;
  double s = denom > 1e-12 ? (uv * vw - uw) / denom : 0.0;
  s = std::clamp(s, -ha[edge_a], ha[edge_a]);
  double t = s * uv + vw;
  if (std::abs(t) > hb[edge_b]) {
    t = std::clamp(t, -hb[edge_b], hb[edge_b]);
    s = std::clamp(t * uv - uw, -ha[edge_a], ha[edge_a]);
  }
  const Vec3 qa = pa + s * u, qb = pb + t * v;
  Manifold m;
  m.normal = n;
  add_point(m, qb, n.dot(qb - qa), 0x80000000u | static_cast<std::uint32_t>(3 * edge_a + edge_b));
  return m;
}

Manifold flipped(Manifold m) {
  m.normal = -m.normal;
  return m;
}

}  // namespace

Manifold reduce_face_points(ContactPoint* points, int count, const Vec3& normal) {
  Manifold m;
  m.normal = normal;
  if (count <= max_manifold_points) {
    for (int k = 0; k < count; ++k) m.points[k] = points[k];
    m.count = count;
  } else {
    // The straight vertices go before the reduction, which then orders what is left as it
    // would have among all (a solver sweeping the points in that order sees the same order
    // whether or not a mid-edge point was there: issue 13's pyramid stands as before).
    reduce_to_four(points, drop_straight_vertices(points, count, normal), m);
  }
  return m;
}

double bounding_radius(const Shape& shape) {
  switch (shape.kind) {
    case ShapeKind::sphere:
      return shape.radius;
    case ShapeKind::box:
      return shape.half_extents.norm();
    case ShapeKind::none:
      break;
  }
  return 0.0;
}

Manifold collide_sphere_plane(const Vec3& center, double radius, const Plane& plane,
                              double margin) {
  Manifold m;
  m.normal = plane.normal;
  const double gap = signed_distance(plane, center) - radius;
  if (gap <= margin) add_point(m, center - radius * plane.normal, gap, 0);
  return m;
}

Manifold collide_box_plane(const Pose& box, const Vec3& half, const Plane& plane, double margin) {
  struct Corner {
    double gap;
    std::uint32_t index;
    Vec3 p;
  };
  Corner corners[8];
  int count = 0;
  for (std::uint32_t i = 0; i < 8; ++i) {
    const Vec3 local((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                     (i & 4) ? half.z() : -half.z());
    const Vec3 p = box.position + box.rotation * local;
    const double gap = signed_distance(plane, p);
    if (gap <= margin) corners[count++] = {gap, i, p};
  }
  // The deepest four (a face lying on the plane gives exactly its four corners): insertion
  // sort by gap, ties by corner number.
  for (int k = 1; k < count; ++k)
    for (int j = k; j > 0 && corners[j].gap < corners[j - 1].gap; --j)
      std::swap(corners[j], corners[j - 1]);
  Manifold m;
  m.normal = plane.normal;
  for (int k = 0; k < std::min(count, max_manifold_points); ++k)
    add_point(m, corners[k].p, corners[k].gap, corners[k].index);
  return m;
}

Manifold collide_sphere_sphere(const Vec3& center_a, double radius_a, const Vec3& center_b,
                               double radius_b, double margin) {
  Manifold m;
  const Vec3 d = center_b - center_a;
  const double distance = d.norm();
  const double gap = distance - radius_a - radius_b;
  if (gap > margin) return m;
  m.normal = distance > 0.0 ? Vec3(d / distance) : Vec3::UnitY();
  add_point(m, center_b - radius_b * m.normal, gap, 0);
  return m;
}

Manifold collide_box_sphere(const Pose& box, const Vec3& half, const Vec3& center, double radius,
                            double margin) {
  Manifold m;
  const Vec3 local = box.rotation.transpose() * (center - box.position);
  Vec3 surface = local.cwiseMax(-half).cwiseMin(half);  // the closest point of the box
  Vec3 normal_local;
  double gap;
  if (surface != local) {  // centre outside: along the line from the closest point
    const Vec3 offset = local - surface;
    const double distance = offset.norm();
    gap = distance - radius;
    if (gap > margin) return m;
    normal_local = offset / distance;
  } else {  // centre inside: out through the nearest face
    int axis = 0;
    const Vec3 inside = half - local.cwiseAbs();
    inside.minCoeff(&axis);
    normal_local = sign_of(local[axis]) * Vec3::Unit(axis);
    surface[axis] = normal_local[axis] * half[axis];
    gap = -inside[axis] - radius;
  }
  m.normal = box.rotation * normal_local;
  add_point(m, center - radius * m.normal, gap, 0);
  return m;
}

namespace {

// The separating-axis test of two boxes over the 15 candidate axes (faces of a, faces of b,
// edge pairs), each oriented from a to b; the separation along an axis is the distance between
// the projections of the boxes (negative: overlap). Keeps the best axis of each kind. Stops
// early (separated = true) as soon as an axis separates by more than `margin`.
//
// With tolerance ≥ 0, the caller (collide_box_box) takes an edge pair only when it beats the
// face it prefers by more than `tolerance`: an edge axis whose separation is sure to be no
// more than that (nor than the margin) is not computed (edge_bounded_below). The edges that
// can be taken are all computed, so the answer is the same: same axis, same separations. The face axes' dot
// products are taken once (a_i·b_j serves the faces of both boxes), each the same products
// summed in the same order as before, so every separation is the same to the bit.
struct SeparatingAxes {
  double best[3];  // face of a, face of b, edge pair; m
  int index[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  Vec3 normal[3];
  bool separated = false;
};

// The dot products of two boxes' axes and centre offset d = b − a: c[i][j] = a_i·b_j,
// ga[i][k] = a_i·a_k, gb[j][k] = b_j·b_k, da[i] = a_i·d, db[j] = b_j·d.
struct AxisProducts {
  double c[3][3], ga[3][3], gb[3][3], da[3], db[3];
  AxisProducts(const Mat3& ra, const Mat3& rb, const Vec3& d) {
    for (int i = 0; i < 3; ++i) {
      da[i] = ra.col(i).dot(d);
      db[i] = rb.col(i).dot(d);
      for (int k = 0; k < 3; ++k) c[i][k] = ra.col(i).dot(rb.col(k));
      for (int k = i; k < 3; ++k) {
        ga[i][k] = ga[k][i] = ra.col(i).dot(ra.col(k));
        gb[i][k] = gb[k][i] = rb.col(i).dot(rb.col(k));
      }
    }
  }
  // Both rotations orthonormal to 1e-12: what edge_bounded_below's identities need.
  bool orthonormal() const {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        const double unit = i == k ? 1.0 : 0.0;
        if (!(std::abs(ga[i][k] - unit) <= 1e-12 && std::abs(gb[i][k] - unit) <= 1e-12))
          return false;
      }
    return true;
  }
};

// True when the separation along the edge axis a_i × b_j, as separating_axes computes it, is
// surely at most `floor`. With orthonormal rotations the axis is L = c[i1][j] a_i2 − c[i2][j]
// a_i1 = c[i][j2] b_j1 − c[i][j1] b_j2 (i1, i2 and j1, j2 the next axes in cyclic order), so
// (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996, table 1; Ericson, "Real-Time Collision
// Detection" 4.4.1) |L| times the separation is |L·d| − (ha_i1 |c[i2][j]| + ha_i2 |c[i1][j]|)
// − (hb_j1 |c[i][j2]| + hb_j2 |c[i][j1]|), up to roundings of some 1e-15 of `scale` (the
// offset and the boxes' sizes), which the 1e-9 slack dwarfs. Also true for an axis the test
// skips as too short.
bool edge_bounded_below(const AxisProducts& p, const Vec3& ha, const Vec3& hb, int i, int j,
                        double floor, double scale) {
  const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const double along_d = std::abs(p.c[i1][j] * p.da[i2] - p.c[i2][j] * p.da[i1]);
  const double radii = ha[i1] * std::abs(p.c[i2][j]) + ha[i2] * std::abs(p.c[i1][j]) +
                       hb[j1] * std::abs(p.c[i][j2]) + hb[j2] * std::abs(p.c[i][j1]);
  const double scaled = along_d - radii + 1e-9 * scale;  // ≥ |L| times the separation
  if (floor >= 0.0 && scaled <= 0.0) return true;
  const double length = std::sqrt(p.c[i1][j] * p.c[i1][j] + p.c[i2][j] * p.c[i2][j]);
  // Edges this close to parallel (|L| < 1e-6 less the roundings) are skipped by the test too.
  return length < 0.5e-6 || scaled <= floor * length;
}

SeparatingAxes separating_axes(const Pose& a, const Vec3& ha, const Pose& b, const Vec3& hb,
                               double margin, double tolerance = -1.0) {
  constexpr double minus_infinity = -std::numeric_limits<double>::infinity();
  SeparatingAxes r;
  r.best[0] = r.best[1] = r.best[2] = minus_infinity;
  const Vec3 d = b.position - a.position;
  const AxisProducts p(a.rotation, b.rotation, d);
  // A face axis n of a or b: its separation |n·d| − Σ ha_k |n·a_k| − Σ hb_k |n·b_k|.
  auto consider_face = [&](int kind, int i, const Vec3& axis, double distance,
                           const double* dots_a, const double* dots_b) {
    const bool flip = distance < 0.0;
    if (flip) distance = -distance;
    const double radius_a = ha.x() * std::abs(dots_a[0]) + ha.y() * std::abs(dots_a[1]) +
                            ha.z() * std::abs(dots_a[2]);
    const double radius_b = hb.x() * std::abs(dots_b[0]) + hb.y() * std::abs(dots_b[1]) +
                            hb.z() * std::abs(dots_b[2]);
    const double separation = distance - radius_a - radius_b;
    if (separation > r.best[kind]) {
      r.best[kind] = separation;
      r.index[kind][0] = i, r.index[kind][1] = 0;
      r.normal[kind] = flip ? Vec3(-axis) : axis;
    }
    r.separated = separation > margin;
    return !r.separated;
  };
  for (int i = 0; i < 3; ++i)
    if (!consider_face(0, i, a.rotation.col(i), p.da[i], p.ga[i], p.c[i])) return r;
  for (int j = 0; j < 3; ++j) {
    const double dots_a[3] = {p.c[0][j], p.c[1][j], p.c[2][j]};
    if (!consider_face(1, j, b.rotation.col(j), p.db[j], dots_a, p.gb[j])) return r;
  }
  // collide_box_box's preferred face: b's only when clearly better than a's.
  const double best_face = r.best[1] > r.best[0] + tolerance ? r.best[1] : r.best[0];
  const double floor = std::min(best_face + tolerance, margin);
  const bool bounded = tolerance >= 0.0 && floor > minus_infinity && p.orthonormal();
  const double scale = d.norm() + ha.sum() + hb.sum();
  auto consider_edge = [&](int i, int j, Vec3 n) {
    double distance = n.dot(d);
    if (distance < 0.0) n = -n, distance = -distance;
    const double separation = distance - radius_along(a, ha, n) - radius_along(b, hb, n);
    if (separation > r.best[2]) {
      r.best[2] = separation;
      r.index[2][0] = i, r.index[2][1] = j;
      r.normal[2] = n;
    }
    r.separated = separation > margin;
    return !r.separated;
  };
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (bounded && edge_bounded_below(p, ha, hb, i, j, floor, scale)) continue;
      const Vec3 axis = a.rotation.col(i).cross(b.rotation.col(j));
      const double length = axis.norm();  // sin of the angle between the edges
      if (length > 1e-6 && !consider_edge(i, j, axis / length)) return r;
    }
  return r;
}

}  // namespace

Manifold collide_box_box(const Pose& a, const Vec3& ha, const Pose& b, const Vec3& hb,
                         double margin) {
  // Prefer a's faces, then b's, then edges, unless the next is clearly better: with nearly
  // equal separations (a box resting on another) the choice then stays the same from step
  // to step, and so do the feature ids warm starting relies on. So an edge pair no better
  // than the faces' best plus the tolerance is never taken: separating_axes need not compute it.
  const double tolerance = std::min(1e-3, 0.01 * std::min(ha.minCoeff(), hb.minCoeff()));
  const SeparatingAxes axes = separating_axes(a, ha, b, hb, margin, tolerance);
  if (axes.separated) return {};
  const double* best = axes.best;
  const auto& index = axes.index;
  const Vec3* normal = axes.normal;
  const bool face_of_b = best[1] > best[0] + tolerance;
  const double best_face = face_of_b ? best[1] : best[0];
  if (best[2] > best_face + tolerance)
    return edge_contact(a, ha, index[2][0], b, hb, index[2][1], normal[2]);
  if (!face_of_b)
    return face_contact(a, ha, index[0][0], normal[0], b, hb, margin,
                        static_cast<std::uint32_t>(index[0][0]));
  return flipped(face_contact(b, hb, index[1][0], -normal[1], a, ha, margin,
                              static_cast<std::uint32_t>(8 + index[1][0])));
}

Manifold collide_shapes(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
                        double margin) {
  const bool sphere_a = a.kind == ShapeKind::sphere, sphere_b = b.kind == ShapeKind::sphere;
  if (a.kind == ShapeKind::none || b.kind == ShapeKind::none) return {};
  if (sphere_a && sphere_b)
    return collide_sphere_sphere(pose_a.position, a.radius, pose_b.position, b.radius, margin);
  if (sphere_a)
    return flipped(collide_box_sphere(pose_b, b.half_extents, pose_a.position, a.radius, margin));
  if (sphere_b)
    return collide_box_sphere(pose_a, a.half_extents, pose_b.position, b.radius, margin);
  return collide_box_box(pose_a, a.half_extents, pose_b, b.half_extents, margin);
}

double separation(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  if (a.kind == ShapeKind::box && b.kind == ShapeKind::box) {
    const SeparatingAxes axes =
        separating_axes(pose_a, a.half_extents, pose_b, b.half_extents, infinity);
    return std::max({axes.best[0], axes.best[1], axes.best[2]});
  }
  // With a sphere the closest points are exact (engine/narrow_phase.hpp): the gap of the point.
  const Manifold m = collide_shapes(a, pose_a, b, pose_b, infinity);
  return m.count > 0 ? -m.points[0].depth : infinity;
}

double separation(const Shape& shape, const Pose& pose, const Plane& plane) {
  const Manifold m =
      collide_shape_plane(shape, pose, plane, std::numeric_limits<double>::infinity());
  return m.count > 0 ? -m.points[0].depth : std::numeric_limits<double>::infinity();
}

Manifold collide_shape_plane(const Shape& shape, const Pose& pose, const Plane& plane,
                             double margin) {
  switch (shape.kind) {
    case ShapeKind::sphere:
      return collide_sphere_plane(pose.position, shape.radius, plane, margin);
    case ShapeKind::box:
      return collide_box_plane(pose, shape.half_extents, plane, margin);
    case ShapeKind::none:
      break;
  }
  Manifold m;
  m.normal = plane.normal;
  return m;
}

}  // namespace rigidlab
