#include "present/html.hpp"

#include <cmath>
#include <cstdio>

#include "present/text.hpp"
#include "present/wireframe.hpp"

namespace rigidlab::present {

// The player's markup and script (present/html_script.cpp).
extern const char* const html_head;
extern const char* const html_script;

namespace {

// JSON numbers with 6 significant digits: a millionth of the scene is below a pixel.
void number(std::string& out, double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", std::isfinite(x) ? x + 0.0 : 0.0);
  out += buffer;
}

void numbers(std::string& out, const double* x, int n) {
  for (int i = 0; i < n; ++i) {
    if (i) out += ',';
    number(out, x[i]);
  }
}

void point(std::string& out, const Point3& p) { numbers(out, p.data(), 3); }

// A JSON string: the text made printable (so valid UTF-8 without controls), then escaped;
// "</" is written "<\/" so no text can end the script element.
std::string json_string(const std::string& text) {
  std::string out = "\"";
  const std::string clean = printable(text, true);
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const char c = clean[i];
    if (c == '"' || c == '\\') out += '\\';
    if (c == '/' && i > 0 && clean[i - 1] == '<') out += '\\';
    out += c;
  }
  return out + "\"";
}

void scene_json(std::string& out, const HtmlFrame& f) {
  const Scene& s = f.scene;
  out += "{\"t\":";
  number(out, f.time);
  out += ",\"status\":" + json_string(f.status) + ",\"b\":[";
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const SceneBody& b = s.bodies[i];
    out += i ? ",[" : "[";
    out += std::to_string(static_cast<int>(b.shape)) + ",";
    point(out, b.position);
    out += ',';
    const Basis3 R = b.rotation.transpose();  // rows of R, so R(i, j) at 3 i + j
    numbers(out, R.data(), 9);
    out += ',';
    point(out, b.half_extents);
    out += ',';
    number(out, b.radius);
    for (const auto& [from, to] : b.segments) {  // then the segments' ends, six numbers each
      out += ',';
      point(out, from);
      out += ',';
      point(out, to);
    }
    out += "]";
  }
  out += "],\"a\":[";
  for (std::size_t i = 0; i < s.arrows.size(); ++i) {
    out += i ? ",[" : "[";
    out += std::to_string(static_cast<int>(s.arrows[i].kind)) + ",";
    point(out, s.arrows[i].origin);
    out += ',';
    point(out, s.arrows[i].vector);
    out += "]";
  }
  out += "],\"e\":[";
  for (std::size_t i = 0; i < s.ellipsoids.size(); ++i) {
    const SceneEllipsoid& e = s.ellipsoids[i];
    out += i ? ",[" : "[";
    point(out, e.center);
    out += ',';
    const Basis3 A = e.axes.transpose();
    numbers(out, A.data(), 9);
    out += ',';
    point(out, e.semi_axes);
    out += "]";
  }
  out += "],\"m\":[";
  for (std::size_t i = 0; i < s.markers.size(); ++i) {
    out += i ? ",[" : "[";
    out += std::to_string(static_cast<int>(s.markers[i].kind)) + ",";
    point(out, s.markers[i].position);
    out += "]";
  }
  out += "],\"c\":[";
  for (std::size_t i = 0; i < s.curves.size(); ++i) {
    out += i ? ",[" : "[";
    for (std::size_t k = 0; k < s.curves[i].points.size(); ++k) {
      if (k) out += ',';
      point(out, s.curves[i].points[k]);
    }
    out += "]";
  }
  out += "],\"n\":[";
  for (std::size_t i = 0; i < s.notes.size(); ++i) {
    out += i ? ",[" : "[";
    out += std::to_string(static_cast<int>(s.notes[i].kind)) + "," + json_string(s.notes[i].text);
    out += "]";
  }
  out += "]}";
}

}  // namespace

namespace {
// Every body, arrow and ellipsoid of every frame, for framing the whole sequence.
Scene all_frames(const std::vector<HtmlFrame>& frames) {
  Scene all;
  for (const HtmlFrame& f : frames) {
    all.bodies.insert(all.bodies.end(), f.scene.bodies.begin(), f.scene.bodies.end());
    all.arrows.insert(all.arrows.end(), f.scene.arrows.begin(), f.scene.arrows.end());
    all.ellipsoids.insert(all.ellipsoids.end(), f.scene.ellipsoids.begin(), f.scene.ellipsoids.end());
  }
  return all;
}
}  // namespace

Camera fit_camera_to_frames(const std::vector<HtmlFrame>& frames, double fov, double aspect) {
  // fit_camera takes cells of aspect 2; a picture `aspect` wide per unit of height is
  // 2 * aspect cells per row.
  return fit_camera(all_frames(frames), fov, static_cast<int>(std::lround(200 * aspect)), 100, 2.0);
}

std::string html_player(const std::vector<HtmlFrame>& frames, const Camera& camera,
                        const std::string& title) {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
                    xml_text(title) + "</title>\n" + html_head + "<h1>" + xml_text(title) +
                    "</h1>\n";
  out += "<canvas id=\"view\" width=\"800\" height=\"500\"></canvas>\n"
         "<div id=\"controls\"><button id=\"play\" type=\"button\">play</button>\n"
         "<input id=\"slider\" type=\"range\" min=\"0\" max=\"" +
         std::to_string(frames.empty() ? 0 : frames.size() - 1) +
         "\" value=\"0\" aria-label=\"time\">\n<span id=\"clock\"></span></div>\n"
         "<div id=\"status\"></div>\n<div id=\"legend\"></div>\n"
         "<p class=\"hint\">Drag the picture to turn the camera; the slider moves in time.</p>\n"
         "<script>\n\"use strict\";\nconst DATA = {\"camera\":{\"eye\":[";
  point(out, camera.eye);
  out += "],\"target\":[";
  point(out, camera.target);
  out += "],\"up\":[";
  point(out, camera.up);
  out += "],\"fov\":";
  number(out, camera.fov);
  Point3 center;
  double radius;
  scene_bounds(all_frames(frames), center, radius);
  out += "},\"center\":[";
  point(out, center);
  out += "],\"radius\":";
  number(out, radius);
  out += ",\"names\":[";
  const std::vector<SceneBody>& bodies = frames.empty() ? std::vector<SceneBody>{} : frames[0].scene.bodies;
  for (std::size_t i = 0; i < bodies.size() && i < 8; ++i)
    out += (i ? "," : "") + json_string(bodies[i].name);
  out += "],\"planes\":[";
  const std::vector<ScenePlane>& planes = frames.empty() ? std::vector<ScenePlane>{} : frames[0].scene.planes;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    out += i ? ",[" : "[";
    point(out, planes[i].normal);
    out += ',';
    number(out, planes[i].offset);
    out += "]";
  }
  out += "],\"frames\":[\n";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i) out += ",\n";
    scene_json(out, frames[i]);
  }
  out += "]};\n";
  out += html_script;
  out += "</script>\n</body></html>\n";
  return out;
}

}  // namespace rigidlab::present
