#include "present/wireframe.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "present/chart.hpp"
#include "present/text.hpp"

namespace rigidlab::present {
namespace {

constexpr double pi = 3.14159265358979323846;
constexpr int overlay_count = static_cast<int>(Overlay::joint) + 1;

const char* const body_colors[] = {"\x1b[34m", "\x1b[32m", "\x1b[36m",
                                   "\x1b[35m", "\x1b[33m", "\x1b[37m"};
// By Overlay: axes x, y, z, ω, L, impulse, contact, ellipsoid, trail, joint.
const char* const overlay_colors[] = {"\x1b[91m", "\x1b[92m", "\x1b[94m", "\x1b[93m", "\x1b[95m",
                                      "\x1b[91m", "\x1b[91m", "\x1b[96m", "\x1b[90m", "\x1b[97m"};

struct Painter {
  Canvas& canvas;
  const Projection& view;
  const TextStyle& style;

  int segment(const Point3& a, const Point3& b, const Stroke& s, int phase = 0) const {
    double x0, y0, x1, y1;
    if (!view.segment(a, b, x0, y0, x1, y1)) return phase;
    return canvas.line(x0, y0, x1, y1, s, phase);
  }

  // The ellipse c + cos t u + sin t v, in as many segments as its size on screen needs.
  void ellipse(const Point3& c, const Point3& u, const Point3& v, const Stroke& s) const {
    const double size = std::max(u.norm(), v.norm()) * view.dots_per_metre(c);
    const int n = std::clamp(static_cast<int>(size), 12, 72);
    int phase = 0;
    Point3 previous = c + u;
    for (int i = 1; i <= n; ++i) {
      const double t = 2 * pi * i / n;
      const Point3 next = c + std::cos(t) * u + std::sin(t) * v;
      phase = segment(previous, next, s, phase);
      previous = next;
    }
  }

  // A mark of a few dots around the projection of p: a cross ('x'), a plus ('+') or a ring
  // ('o'); in ASCII the one character.
  void mark(const Point3& p, Ink ink, char shape) const {
    double x, y;
    if (!view.point(p, x, y)) return;
    Stroke s = solid_stroke(ink);
    s.glyph = shape;
    if (!canvas.braille()) {
      canvas.line(x, y, x, y, s);
      return;
    }
    const double r = 2.0;
    if (shape == 'x') {
      canvas.line(x - r, y - r, x + r, y + r, s);
      canvas.line(x - r, y + r, x + r, y - r, s);
    } else if (shape == '+') {
      canvas.line(x - r, y, x + r, y, s);
      canvas.line(x, y - r, x, y + r, s);
    } else {
      for (int k = 0; k < 8; ++k)
        canvas.line(x + r * std::cos(k * pi / 4), y + r * std::sin(k * pi / 4),
                    x + r * std::cos((k + 1) * pi / 4), y + r * std::sin((k + 1) * pi / 4), s);
    }
  }
};

void draw_body(const Painter& p, const SceneBody& b, const Stroke& s) {
  const Basis3& R = b.rotation;
  if (b.shape == BodyShape::box) {
    Point3 corner[8];
    for (int i = 0; i < 8; ++i)
      corner[i] = b.position + R * Point3((i & 1 ? 1 : -1) * b.half_extents.x(),
                                          (i & 2 ? 1 : -1) * b.half_extents.y(),
                                          (i & 4 ? 1 : -1) * b.half_extents.z());
    for (int i = 0; i < 8; ++i)
      for (int bit = 1; bit < 8; bit <<= 1)
        if (!(i & bit)) p.segment(corner[i], corner[i | bit], s);
  } else if (b.shape == BodyShape::sphere) {
    const double r = b.radius;
    for (int k = 0; k < 3; ++k)  // great circles in the body frame: they turn with the body
      p.ellipse(b.position, r * R.col((k + 1) % 3), r * R.col((k + 2) % 3), s);
    // The outline: the circle where the lines from the eye touch the sphere.
    const Point3 w = b.position - p.view.eye();
    const double d = w.norm();
    if (d > r) {
      const Point3 n = w / d;
      const Point3 u = n.cross(std::fabs(n.y()) < 0.9 ? Point3::UnitY() : Point3::UnitX()).normalized();
      const double rho = r * std::sqrt(d * d - r * r) / d;
      p.ellipse(b.position - (r * r / d) * n, rho * u, rho * n.cross(u), s);
    }
  } else {
    int phase = 0;
    for (const auto& [from, to] : b.segments) phase = p.segment(from, to, s, phase);
    p.mark(b.position, s.ink, '+');
  }
}

// A grid on the plane, centred where the scene's centre projects onto it, with lines at
// round multiples of a spacing, so it does not slide as the scene moves.
void draw_plane(const Painter& p, const ScenePlane& plane, const Point3& center, double radius) {
  const Point3 n = plane.normal.normalized();
  const Point3 u = n.cross(std::fabs(n.x()) < 0.9 ? Point3::UnitX() : Point3::UnitZ()).normalized();
  const Point3 v = n.cross(u);
  const double half = std::max(1.5 * radius, 1.0);
  const double spacing = nice_number(half / 3, true);
  if (!(spacing > 0.0)) return;
  const Point3 origin = plane.offset * n;
  const double a0 = center.dot(u), b0 = center.dot(v);
  Stroke s = patterned_stroke(plane_ink(), 2, p.canvas.braille());
  s.glyph = '.';  // in ASCII a floor of dots, not of the strokes bodies are drawn with
  const double a_lo = std::ceil((a0 - half) / spacing), a_hi = std::floor((a0 + half) / spacing);
  const double b_lo = std::ceil((b0 - half) / spacing), b_hi = std::floor((b0 + half) / spacing);
  for (double k = a_lo; k <= a_hi && k - a_lo < 64; ++k)
    p.segment(origin + k * spacing * u + (b0 - half) * v, origin + k * spacing * u + (b0 + half) * v, s);
  for (double k = b_lo; k <= b_hi && k - b_lo < 64; ++k)
    p.segment(origin + (a0 - half) * u + k * spacing * v, origin + (a0 + half) * u + k * spacing * v, s);
}

// An arrow: the shaft, in braille a head of two short strokes at the tip, and the label in the
// cell just past the tip.
void draw_arrow(const Painter& p, const SceneArrow& arrow) {
  if (!(arrow.vector.norm() > 0.0)) return;
  const Stroke s = solid_stroke(overlay_ink(arrow.kind));
  double x0, y0, x1, y1;
  if (!p.view.segment(arrow.origin, arrow.origin + arrow.vector, x0, y0, x1, y1)) return;
  p.canvas.line(x0, y0, x1, y1, s);
  const double aspect = p.canvas.dot_aspect();
  double ux = x1 - x0, uy = (y1 - y0) * aspect;  // in units of a dot's width
  const double length = std::hypot(ux, uy);
  if (length > 0.0) {
    ux /= length;
    uy /= length;
  } else {
    ux = 1.0;
    uy = 0.0;
  }
  if (p.canvas.braille() && length >= 3.0) {
    const double head = std::min(4.0, 0.4 * length), c = std::cos(0.45), sn = std::sin(0.45);
    for (double sign : {-1.0, 1.0}) {
      const double hx = -(ux * c - sign * uy * sn), hy = -(sign * ux * sn + uy * c);
      p.canvas.line(x1, y1, x1 + head * hx, y1 + head * hy / aspect, s);
    }
  }
  const int dx = p.canvas.dots_x() / p.canvas.columns(), dy = p.canvas.dots_y() / p.canvas.rows();
  // One cell past the tip along the arrow (a cell is `aspect` dots' widths tall per dot row).
  const double cx = (x1 + 0.5) / dx + ux, cy = (y1 + 0.5) / dy + uy * dx / (dy * aspect);
  int column = static_cast<int>(std::floor(cx));
  const int row = static_cast<int>(std::floor(cy));
  // Parallel vectors (ω and L of a body spinning about a principal axis) end at one cell: the
  // later label goes beside the earlier one.
  for (int tries = 0; tries < 3 && p.canvas.has_text(column, row); ++tries) ++column;
  p.canvas.text(column, row, overlay_label(arrow.kind, p.style.unicode), s.ink);
}

void draw_overlays(const Painter& p, const Scene& scene) {
  for (const SceneEllipsoid& e : scene.ellipsoids) {
    const Stroke s = patterned_stroke(overlay_ink(Overlay::ellipsoid), 1, p.canvas.braille());
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      p.ellipse(e.center, e.semi_axes[i] * e.axes.col(i), e.semi_axes[j] * e.axes.col(j), s);
    }
  }
  for (const SceneCurve& curve : scene.curves) {
    Stroke s = patterned_stroke(overlay_ink(curve.kind), curve.kind == Overlay::trail ? 2 : 0,
                                p.canvas.braille());
    if (curve.kind == Overlay::trail) s.glyph = ':';
    int phase = 0;
    for (std::size_t i = 1; i < curve.points.size(); ++i)
      phase = p.segment(curve.points[i - 1], curve.points[i], s, phase);
  }
  for (const SceneMarker& m : scene.markers)
    p.mark(m.position, overlay_ink(m.kind), m.kind == Overlay::contact ? 'x' : 'o');
  for (const SceneArrow& a : scene.arrows) draw_arrow(p, a);
}

Stroke body_stroke(std::size_t i, const TextStyle& style) {
  return style.color ? solid_stroke(body_ink(i))
                     : patterned_stroke(body_ink(i), static_cast<int>(i % 4), style.unicode);
}

std::vector<std::string> palette() {
  std::vector<std::string> colors(1 + overlay_ink(Overlay::joint));
  for (int i = 0; i < 6; ++i) colors[body_ink(i)] = body_colors[i];
  colors[plane_ink()] = "\x1b[90m";
  for (int k = 0; k < overlay_count; ++k) colors[overlay_ink(Overlay(k))] = overlay_colors[k];
  return colors;
}

// A short line drawn with `stroke`, as the legend shows a body's colour or dash pattern.
std::string sample(const Stroke& stroke, const TextStyle& style, int cells) {
  Canvas c(cells, 1, style.unicode);
  Stroke s = stroke;
  if (!style.unicode && s.glyph == 0) s.glyph = '-';
  c.line(0, c.dots_y() / 2, c.dots_x() - 1, c.dots_y() / 2, s);
  return c.lines(style.color ? palette() : std::vector<std::string>{})[0];
}

const char* overlay_name(Overlay kind) {
  static const char* const names[] = {"body axes", "", "", "angular velocity",
                                      "angular momentum", "contact impulse", "contact point",
                                      "inertia ellipsoid", "trail", "joint"};
  return names[static_cast<int>(kind)];
}

// Entries separated by three spaces, wrapped at `width` columns.
void add_entries(std::vector<std::string>& lines, const std::vector<std::pair<std::string, std::size_t>>& entries,
                 std::size_t width) {
  std::string line;
  std::size_t used = 0;
  for (const auto& [text, columns] : entries) {
    if (used > 0 && used + 3 + columns > width) {
      lines.push_back(line);
      line.clear();
      used = 0;
    }
    if (used > 0) line += "   ", used += 3;
    line += text;
    used += columns;
  }
  if (used > 0) lines.push_back(line);
}

std::vector<std::string> legend(const Scene& scene, const TextStyle& style, int width) {
  std::vector<std::pair<std::string, std::size_t>> bodies, overlays;
  const std::size_t shown = std::min<std::size_t>(scene.bodies.size(), 8);
  for (std::size_t i = 0; i < shown; ++i) {
    const std::string text = std::to_string(i + 1) + " " + printable(scene.bodies[i].name, style.unicode);
    bodies.emplace_back(sample(body_stroke(i, style), style, 5) + " " + text, 6 + display_width(text));
  }
  if (scene.bodies.size() > shown) {
    const std::string more = "and " + std::to_string(scene.bodies.size() - shown) + " more";
    bodies.emplace_back(more, more.size());
  }
  bool present[overlay_count] = {false};
  for (const SceneArrow& a : scene.arrows) present[static_cast<int>(a.kind)] = true;
  for (const SceneMarker& m : scene.markers) present[static_cast<int>(m.kind)] = true;
  if (!scene.ellipsoids.empty()) present[static_cast<int>(Overlay::ellipsoid)] = true;
  for (const SceneCurve& c : scene.curves) present[static_cast<int>(c.kind)] = true;
  for (const SceneNote& note : scene.notes) present[static_cast<int>(note.kind)] = true;
  for (int k = 0; k < overlay_count; ++k) {
    if (!present[k] || k == 1 || k == 2) continue;  // the three axes share one entry
    const Overlay kind = Overlay(k);
    std::string key = kind == Overlay::axis_x ? "" : overlay_label(kind, style.unicode);
    if (kind == Overlay::axis_x) {
      for (Overlay axis : {Overlay::axis_x, Overlay::axis_y, Overlay::axis_z}) {
        const std::string l = overlay_label(axis, style.unicode);
        key += style.color ? palette()[overlay_ink(axis)] + l + "\x1b[0m" : l;
      }
    } else if (style.color) {
      key = palette()[overlay_ink(kind)] + key + "\x1b[0m";
    }
    std::string text = std::string(" ") + overlay_name(kind);
    for (const SceneNote& note : scene.notes)
      if (note.kind == kind)
        text += " " + printable(style.unicode || note.ascii.empty() ? note.text : note.ascii,
                                style.unicode);
    const std::size_t key_width = kind == Overlay::axis_x ? 3 : display_width(overlay_label(kind, style.unicode));
    overlays.emplace_back(key + text, key_width + display_width(text));
  }
  std::vector<std::string> lines;
  add_entries(lines, bodies, static_cast<std::size_t>(width));
  add_entries(lines, overlays, static_cast<std::size_t>(width));
  return lines;
}

}  // namespace

Ink body_ink(std::size_t body) { return static_cast<Ink>(1 + body % 6); }
Ink plane_ink() { return 7; }
Ink overlay_ink(Overlay kind) { return static_cast<Ink>(8 + static_cast<int>(kind)); }

std::string overlay_label(Overlay kind, bool unicode) {
  switch (kind) {
    case Overlay::axis_x: return "x";
    case Overlay::axis_y: return "y";
    case Overlay::axis_z: return "z";
    case Overlay::omega: return unicode ? "ω" : "w";
    case Overlay::momentum: return "L";
    case Overlay::impulse: return "J";
    case Overlay::contact: return unicode ? "×" : "x";
    case Overlay::ellipsoid: return unicode ? "◯" : "O";
    case Overlay::trail: return unicode ? "┄" : ".";
    case Overlay::joint: return unicode ? "●" : "o";
  }
  return "?";
}

Canvas draw_scene(const Scene& scene, const Camera& camera, int width, int height,
                  const TextStyle& style) {
  Canvas canvas(width, height, style.unicode);
  if (!camera_problem(camera).empty()) return canvas;
  const Projection view(camera, canvas.dots_x(), canvas.dots_y(), canvas.dot_aspect());
  const Painter painter{canvas, view, style};
  Point3 center;
  double radius;
  scene_bounds(scene, center, radius);
  for (const ScenePlane& plane : scene.planes) draw_plane(painter, plane, center, radius);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    draw_body(painter, scene.bodies[i], body_stroke(i, style));
  draw_overlays(painter, scene);
  return canvas;
}

std::string render_scene(const Scene& scene, const RenderOptions& options) {
  const int width = std::max(options.width, 1), height = std::max(options.height, 1);
  const Canvas canvas = draw_scene(scene, options.camera, width, height, options.style);
  std::vector<std::string> lines = canvas.lines(options.style.color ? palette() : std::vector<std::string>{});
  if (options.legend)
    for (const std::string& line : legend(scene, options.style, width)) lines.push_back(line);
  std::string text;
  for (std::size_t i = 0; i < lines.size(); ++i) text += (i ? "\n" : "") + lines[i];
  return text;
}

}  // namespace rigidlab::present
