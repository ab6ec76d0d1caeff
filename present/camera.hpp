// A perspective camera and the projection of world points onto a canvas's dots: the pinhole
// model of computer graphics (Foley, van Dam et al., "Computer Graphics", section 6.3), with
// the view basis of gluLookAt and a vertical field of view, clipped at a near plane.
#pragma once

#include <string>

#include "present/scene.hpp"

namespace rigidlab::present {

struct Camera {
  Point3 eye = Point3(0, 0, 5);   // m, world
  Point3 target = Point3::Zero(); // m, the point at the centre of the frame
  Point3 up = Point3::UnitY();    // the direction that shows upwards
  double fov = 40.0;              // degrees, vertical field of view
};

// Why `camera` cannot be used, or "": eye and target must differ, up must not be parallel to
// the line of sight (nor zero), fov between 1 and 170 degrees, everything finite.
std::string camera_problem(const Camera& camera);

// A camera that frames the scene: looking at the centre of the bodies (and overlays) from
// the front, to the right and above (azimuth 30°, elevation 20°), far enough that their
// bounding sphere fits the frame of `columns` x `rows` cells of aspect `cell_aspect`.
Camera fit_camera(const Scene& scene, double fov, int columns, int rows, double cell_aspect = 2.0);

// The camera moved on a sphere about its target: `azimuth` radians about the up direction
// (positive: the eye goes to the right), `elevation` radians towards up; the elevation stays
// within 85 degrees of the horizon, so up never lines up with the line of sight.
Camera orbit(const Camera& camera, double azimuth, double elevation);

// The centre and radius of a sphere holding every body (its bounding sphere), curve point,
// marker, ellipsoid and arrow (the sphere it sweeps as it turns) of the scene; radius 0 for
// an empty scene.
void scene_bounds(const Scene& scene, Point3& center, double& radius);

class Projection {
 public:
  // Dots across and down, and a dot's height over its width (Canvas::dot_aspect()).
  Projection(const Camera& camera, int dots_x, int dots_y, double dot_aspect);

  // The dot coordinates of a world point; false when it lies behind the near plane.
  bool point(const Point3& p, double& x, double& y) const;
  // A world segment clipped to the near plane and projected; false when nothing is in front.
  bool segment(Point3 a, Point3 b, double& x0, double& y0, double& x1, double& y1) const;
  // Dots per metre of a length across the line of sight at p's depth (0 behind the near plane):
  // for choosing how finely to draw a curve.
  double dots_per_metre(const Point3& p) const {
    const double z = depth(p);
    return z >= near_ ? focal_y_ / z : 0.0;
  }
  // Distance in front of the eye along the line of sight.
  double depth(const Point3& p) const { return (p - eye_).dot(forward_); }
  const Point3& forward() const { return forward_; }
  const Point3& eye() const { return eye_; }

 private:
  Point3 eye_, right_, up_, forward_;
  double focal_x_, focal_y_, center_x_, center_y_, near_;
};

}  // namespace rigidlab::present
