// Tests for present/camera.cpp and present/wireframe.cpp. The reference projection is built
// here the way OpenGL's gluLookAt and gluPerspective matrices do it (4 x 4 homogeneous
// matrices, normalised device coordinates, then the viewport), not with the code under test;
// a unit cube's edges and a sphere's outline must light the cells it predicts (within one
// cell), overlays must point where their vectors do, and ASCII frames must stay ASCII.
#include "present/wireframe.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

namespace rigidlab::present {
namespace {

constexpr double pi = 3.14159265358979323846;

// gluLookAt * gluPerspective and the viewport transform, for a canvas of dots_x x dots_y dots
// each dot_aspect times taller than wide.
struct GluReference {
  Eigen::Matrix4d matrix;
  int dots_x, dots_y;

  GluReference(const Camera& c, int dx, int dy, double dot_aspect) : dots_x(dx), dots_y(dy) {
    const Eigen::Vector3d f = (c.target - c.eye).normalized();
    const Eigen::Vector3d s = f.cross(c.up.normalized()).normalized();
    const Eigen::Vector3d u = s.cross(f);
    Eigen::Matrix4d look = Eigen::Matrix4d::Identity();
    look.block<1, 3>(0, 0) = s.transpose();
    look.block<1, 3>(1, 0) = u.transpose();
    look.block<1, 3>(2, 0) = -f.transpose();
    Eigen::Matrix4d translate = Eigen::Matrix4d::Identity();
    translate.block<3, 1>(0, 3) = -c.eye;
    const double aspect = dx / (dy * dot_aspect);  // the frame's width over its height
    const double cot = 1.0 / std::tan(c.fov * pi / 360), zn = 0.01, zf = 100;
    Eigen::Matrix4d perspective = Eigen::Matrix4d::Zero();
    perspective(0, 0) = cot / aspect;
    perspective(1, 1) = cot;
    perspective(2, 2) = (zf + zn) / (zn - zf);
    perspective(2, 3) = 2 * zf * zn / (zn - zf);
    perspective(3, 2) = -1;
    matrix = perspective * look * translate;
  }
  // Dot coordinates (dot centres at integers, y down) of a world point.
  Eigen::Vector2d operator()(const Eigen::Vector3d& p) const {
    const Eigen::Vector4d clip = matrix * p.homogeneous();
    const double nx = clip.x() / clip.w(), ny = clip.y() / clip.w();
    return {(nx + 1) / 2 * dots_x - 0.5, (1 - ny) / 2 * dots_y - 0.5};
  }
};

Camera camera_at(Point3 eye, Point3 target = Point3::Zero(), double fov = 40) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fov = fov;
  return c;
}

bool lit_near(const Canvas& c, int column, int row) {
  for (int r = row - 1; r <= row + 1; ++r)
    for (int k = column - 1; k <= column + 1; ++k)
      if (c.lit(k, r)) return true;
  return false;
}

TEST(Projection, AgreesWithTheGluMatrices) {
  const Camera cam = camera_at(Point3(3, 2, 5), Point3(0.2, -0.1, 0), 35);
  const Projection view(cam, 160, 120, 1.0);
  const GluReference glu(cam, 160, 120, 1.0);
  for (const Point3& p : {Point3(0, 0, 0), Point3(1, 0.5, -0.3), Point3(-0.7, 1.2, 0.4)}) {
    double x, y;
    ASSERT_TRUE(view.point(p, x, y));
    EXPECT_NEAR(x, glu(p).x(), 1e-9);
    EXPECT_NEAR(y, glu(p).y(), 1e-9);
  }
  double x, y;
  EXPECT_FALSE(view.point(Point3(6, 4, 10), x, y));  // behind the eye
}

TEST(Wireframe, AUnitCubeLightsTheCellsOfItsProjectedEdges) {
  Scene scene;
  SceneBody cube;
  cube.shape = BodyShape::box;
  cube.position = Point3(0.3, -0.2, 0.1);
  cube.rotation = Eigen::AngleAxisd(0.7, Point3(1, 2, 3).normalized()).toRotationMatrix();
  cube.half_extents = Point3(0.5, 0.5, 0.5);
  scene.bodies.push_back(cube);
  const Camera cam = camera_at(Point3(2.5, 1.8, 3.5));
  for (bool braille : {true, false}) {
    SCOPED_TRACE(braille ? "braille" : "ascii");
    const TextStyle style{braille, false};
    const Canvas canvas = draw_scene(scene, cam, 70, 30, style);
    const GluReference glu(cam, canvas.dots_x(), canvas.dots_y(), canvas.dot_aspect());
    const int dx = braille ? 2 : 1, dy = braille ? 4 : 1;
    std::vector<bool> near_edge(70 * 30, false);
    int checked = 0;
    for (int i = 0; i < 8; ++i) {
      for (int bit = 1; bit < 8; bit <<= 1) {
        if (i & bit) continue;
        auto corner = [&](int k) {
          return Point3(cube.position + cube.rotation * Point3(k & 1 ? 0.5 : -0.5,
                                                                k & 2 ? 0.5 : -0.5,
                                                                k & 4 ? 0.5 : -0.5));
        };
        for (int s = 0; s <= 40; ++s) {
          const Eigen::Vector2d d = glu(corner(i) + s / 40.0 * (corner(i | bit) - corner(i)));
          const int column = static_cast<int>(std::floor((d.x() + 0.5) / dx));
          const int row = static_cast<int>(std::floor((d.y() + 0.5) / dy));
          EXPECT_TRUE(lit_near(canvas, column, row)) << "edge point at cell " << column << ", " << row;
          ++checked;
          for (int r = row - 1; r <= row + 1; ++r)
            for (int k = column - 1; k <= column + 1; ++k)
              if (r >= 0 && r < 30 && k >= 0 && k < 70) near_edge[r * 70 + k] = true;
        }
      }
    }
    EXPECT_EQ(checked, 12 * 41);
    for (int r = 0; r < 30; ++r)  // and nothing lit away from the edges
      for (int k = 0; k < 70; ++k)
        if (canvas.lit(k, r)) EXPECT_TRUE(near_edge[r * 70 + k]) << "stray cell " << k << ", " << r;
  }
}

TEST(Wireframe, ASphereOutlineIsWhereTheTangentLinesFromTheEyeMeetTheCanvas) {
  Scene scene;
  SceneBody ball;
  ball.shape = BodyShape::sphere;
  ball.radius = 1.0;
  scene.bodies.push_back(ball);
  const double d = 5.0;
  const Camera cam = camera_at(Point3(0, 0, d));
  const Canvas canvas = draw_scene(scene, cam, 60, 30, TextStyle{true, false});
  // The tangent lines make the angle asin(r / d) with the line of sight.
  const double half_angle = std::asin(1.0 / d);
  const double focal = 0.5 * canvas.dots_y() / std::tan(20 * pi / 180);
  const double cx = 0.5 * (canvas.dots_x() - 1), cy = 0.5 * (canvas.dots_y() - 1);
  const double extent = focal * std::tan(half_angle);  // dots, square dots in braille
  for (double angle = 0; angle < 2 * pi; angle += pi / 8) {
    const double x = cx + extent * std::cos(angle), y = cy + extent * std::sin(angle);
    EXPECT_TRUE(lit_near(canvas, static_cast<int>((x + 0.5) / 2), static_cast<int>((y + 0.5) / 4)))
        << "outline at angle " << angle;
  }
}

TEST(Wireframe, OverlaysPointWhereTheirVectorsDo) {
  Scene scene;
  scene.bodies.push_back(SceneBody{});  // a point mass at the origin
  scene.arrows.push_back(SceneArrow{Overlay::omega, Point3::Zero(), Point3(1, 0, 0)});
  scene.arrows.push_back(SceneArrow{Overlay::momentum, Point3::Zero(), Point3(0, 1, 0)});
  const Camera cam = camera_at(Point3(0, 0, 5));  // looking down -z: x right, y up
  const Canvas canvas = draw_scene(scene, cam, 60, 30, TextStyle{true, false});
  const int center_column = 30, center_row = 15;
  int omega_cells = 0, momentum_cells = 0;
  for (int r = 0; r < 30; ++r) {
    for (int k = 0; k < 60; ++k) {
      if (canvas.has_ink(k, r, overlay_ink(Overlay::omega))) {
        ++omega_cells;
        EXPECT_GE(k, center_column - 1);
        EXPECT_NEAR(r, center_row, 1.5);
      }
      if (canvas.has_ink(k, r, overlay_ink(Overlay::momentum))) {
        ++momentum_cells;
        EXPECT_LE(r, center_row + 1);
        EXPECT_NEAR(k, center_column, 2.5);
      }
    }
  }
  // 1 m at 5 m with a 40° field: 0.2 / tan 20° of the half height, 30 * 0.27 = about 8 cells
  // across (square dots, 2 per cell) and about 4 rows up.
  EXPECT_GE(omega_cells, 6);
  EXPECT_GE(momentum_cells, 3);
  // Labels just past the tips: ω to the right, L above.
  const std::vector<std::string> lines = canvas.lines();
  const std::size_t omega_at = lines[center_row].find("ω");
  ASSERT_NE(omega_at, std::string::npos);
  int label_row = -1;
  for (int r = 0; r < center_row; ++r)
    if (lines[r].find("L") != std::string::npos) label_row = r;
  EXPECT_GE(label_row, 0);
  EXPECT_LT(label_row, center_row - 2);
}

TEST(Wireframe, LabelsOfParallelArrowsAreBothShown) {
  Scene scene;
  scene.bodies.push_back(SceneBody{});
  scene.arrows.push_back(SceneArrow{Overlay::omega, Point3::Zero(), Point3(1, 0, 0)});
  scene.arrows.push_back(SceneArrow{Overlay::momentum, Point3::Zero(), Point3(1, 0, 0)});
  const Canvas canvas = draw_scene(scene, camera_at(Point3(0, 0, 5)), 60, 30, TextStyle{true, false});
  const std::string row = canvas.lines()[15];
  EXPECT_NE(row.find("ωL"), std::string::npos) << row;
}

TEST(Wireframe, DefaultFramingKeepsTheSceneInside) {
  Scene scene;
  for (int i = 0; i < 5; ++i) {
    SceneBody b;
    b.shape = BodyShape::box;
    b.position = Point3(3.0 * i - 6, 0.5 * i, -2.0 * i);
    b.half_extents = Point3(0.5, 0.2, 0.3);
    scene.bodies.push_back(b);
  }
  const Camera cam = fit_camera(scene, 40, 80, 24);
  EXPECT_EQ(camera_problem(cam), "");
  const Projection view(cam, 160, 96, 1.0);
  for (const SceneBody& b : scene.bodies) {
    for (int k = 0; k < 8; ++k) {
      const Point3 corner = b.position + Point3(k & 1 ? 0.5 : -0.5, k & 2 ? 0.2 : -0.2, k & 4 ? 0.3 : -0.3);
      double x, y;
      ASSERT_TRUE(view.point(corner, x, y));
      EXPECT_TRUE(x >= 0 && x <= 159 && y >= 0 && y <= 95) << x << ", " << y;
    }
  }
}

TEST(Camera, OrbitKeepsTheDistanceAndTurnsAboutUp) {
  const Camera c = camera_at(Point3(0, 0, 5));
  const Camera right = orbit(c, pi / 2, 0);
  EXPECT_NEAR((right.eye - Point3(5, 0, 0)).norm(), 0, 1e-12);  // a quarter turn about +y
  const Camera high = orbit(c, 0, pi / 6);
  EXPECT_NEAR(high.eye.norm(), 5, 1e-12);
  EXPECT_NEAR(high.eye.y(), 5 * std::sin(pi / 6), 1e-12);
  const Camera top = orbit(c, 0, 3.0);  // clamped at 85 degrees
  EXPECT_NEAR(std::asin(top.eye.y() / 5), 85 * pi / 180, 1e-12);
  EXPECT_EQ(camera_problem(top), "");
}

TEST(Wireframe, CameraProblemsAreNamed) {
  EXPECT_EQ(camera_problem(camera_at(Point3::Zero())), "eye and target must differ");
  Camera c = camera_at(Point3(0, 5, 0));
  EXPECT_EQ(camera_problem(c), "up must not be parallel to the line from eye to target");
  c = camera_at(Point3(0, 0, 5), Point3::Zero(), 0.5);
  EXPECT_EQ(camera_problem(c), "fov must be from 1 to 170 degrees");
  c.fov = NAN;
  EXPECT_EQ(camera_problem(c), "must be finite");
}

Scene everything() {
  Scene scene;
  SceneBody box, ball, point;
  box.shape = BodyShape::box;
  box.half_extents = Point3(0.5, 0.2, 0.3);
  box.name = "box ω²";
  ball.shape = BodyShape::sphere;
  ball.radius = 0.4;
  ball.position = Point3(1.5, 0, 0);
  ball.name = "sphere";
  point.position = Point3(-1.5, 0.5, 0);
  scene.bodies = {box, ball, point};
  scene.planes.push_back(ScenePlane{Point3::UnitY(), -1});
  for (Overlay k : {Overlay::axis_x, Overlay::axis_y, Overlay::axis_z, Overlay::omega,
                    Overlay::momentum, Overlay::impulse})
    scene.arrows.push_back(SceneArrow{k, Point3::Zero(), Point3(0.3 * int(k), 1, 0.2)});
  scene.ellipsoids.push_back(SceneEllipsoid{Point3::Zero(), Basis3::Identity(), Point3(0.2, 0.5, 0.3)});
  scene.markers.push_back(SceneMarker{Overlay::contact, Point3(1.5, -0.4, 0)});
  scene.curves.push_back(SceneCurve{Overlay::trail, {Point3(0, 0, 0), Point3(1, 1, 1), Point3(2, 0, 1)}});
  scene.notes.push_back(SceneNote{Overlay::omega, "2.31 rad/s — ω²", ""});
  scene.notes.push_back(SceneNote{Overlay::momentum, "ωᵀIω", "w.I.w"});
  return scene;
}

TEST(Wireframe, AsciiFramesHaveNoByteAbove127) {
  RenderOptions options;
  options.style = TextStyle{false, false};
  const Scene scene = everything();
  options.camera = fit_camera(scene, 40, options.width, options.height);
  const std::string frame = render_scene(scene, options);
  for (char c : frame) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c <= 0x7E)) << int(c);
  EXPECT_NE(frame.find("angular velocity"), std::string::npos);
  EXPECT_NE(frame.find("w.I.w"), std::string::npos);  // the note's ASCII form
}

TEST(Wireframe, WithoutColourBodiesHaveDistinctPatternsAndTheLegendSaysWhich) {
  RenderOptions options;
  const Scene scene = everything();
  options.camera = fit_camera(scene, 40, options.width, options.height);
  const std::string plain = render_scene(scene, options);
  EXPECT_EQ(plain.find('\x1b'), std::string::npos);
  EXPECT_NE(plain.find("1 box ω²"), std::string::npos);
  EXPECT_NE(plain.find("2 sphere"), std::string::npos);
  EXPECT_NE(plain.find("L angular momentum ωᵀIω"), std::string::npos);
  options.style.color = true;
  const std::string colored = render_scene(scene, options);
  EXPECT_NE(colored.find("\x1b[34m"), std::string::npos);  // body 1
  EXPECT_NE(colored.find("\x1b[93m"), std::string::npos);  // ω
}

TEST(Wireframe, APictureHasTheSizeAsked) {
  RenderOptions options;
  options.width = 33;
  options.height = 11;
  options.legend = false;
  const Scene scene = everything();
  options.camera = fit_camera(scene, 40, 33, 11);
  const std::string frame = render_scene(scene, options);
  int lines = 1;
  for (char c : frame) lines += c == '\n';
  EXPECT_EQ(lines, 11);
  const std::string first = frame.substr(0, frame.find('\n'));
  int columns = 0;
  for (char c : first) columns += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  EXPECT_EQ(columns, 33);
}

}  // namespace
}  // namespace rigidlab::present
