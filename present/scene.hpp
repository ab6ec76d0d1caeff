// What a 3-D frame shows, in world coordinates (m, right-handed, y up), without any engine
// type: bodies with their shapes and poses, planes, and the overlays (vectors, ellipsoids,
// markers, trails), already scaled to lengths in the world. A binding builds it from a world
// (lua/render_scene.cpp); present/wireframe draws it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace rigidlab::present {

using Point3 = Eigen::Vector3d;
using Basis3 = Eigen::Matrix3d;  // columns: unit axes (a rotation, body -> world)

// A link of an articulation is drawn as `segments` (from its joint to its COM and to its
// children's joints) with a cross at its COM.
enum class BodyShape { point, sphere, box, segments };

struct SceneBody {
  BodyShape shape = BodyShape::point;
  Point3 position = Point3::Zero();              // m, the COM
  Basis3 rotation = Basis3::Identity();          // body -> world
  Point3 half_extents = Point3::Zero();          // box, m
  double radius = 0.0;                           // sphere, m
  std::vector<std::pair<Point3, Point3>> segments;  // segments, world
  std::string name;                              // for the legend: "box 0.5×0.15×1"
};

// A static half-space boundary n·x = offset (n unit), drawn as a grid.
struct ScenePlane {
  Point3 normal = Point3::UnitY();
  double offset = 0.0;
};

// What an arrow, a marker or a curve stands for: its ink, its label and its legend entry.
enum class Overlay { axis_x, axis_y, axis_z, omega, momentum, impulse, contact, ellipsoid, trail,
                     joint };

struct SceneArrow {
  Overlay kind = Overlay::omega;
  Point3 origin = Point3::Zero();  // m, world
  Point3 vector = Point3::Zero();  // m, world: the quantity times its scale
};

// An ellipsoid drawn as its three principal ellipses.
struct SceneEllipsoid {
  Point3 center = Point3::Zero();
  Basis3 axes = Basis3::Identity();     // columns: the principal directions
  Point3 semi_axes = Point3::Zero();    // m, along each column
};

struct SceneMarker {
  Overlay kind = Overlay::contact;
  Point3 position = Point3::Zero();
};

struct SceneCurve {
  Overlay kind = Overlay::trail;
  std::vector<Point3> points;
};

// Legend text for an overlay shown ("(2.31 rad/s)"), with an ASCII form for ASCII frames
// (empty: the text is ASCII already).
struct SceneNote {
  Overlay kind = Overlay::omega;
  std::string text, ascii;
};

struct Scene {
  std::vector<SceneBody> bodies;
  std::vector<ScenePlane> planes;
  std::vector<SceneArrow> arrows;
  std::vector<SceneEllipsoid> ellipsoids;
  std::vector<SceneMarker> markers;
  std::vector<SceneCurve> curves;
  std::vector<SceneNote> notes;
};

}  // namespace rigidlab::present
