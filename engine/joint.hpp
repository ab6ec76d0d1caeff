// Joints in maximal coordinates: the kinematic pairs of document 000 ("Kinematic pair":
// revolute, prismatic, screw, cylindrical, spherical, planar) plus a fixed joint and a
// distance joint (rigid rod or rope), each written as the rows of engine/constraint.hpp and
// solved by the world's one constraint solver (engine/solver.hpp; document 000 "Sequential
// impulses").
//
// Frames. At creation the joint takes a world anchor point and a world axis and stores them
// in each body's frame (the world's frame for the world side), with the relative orientation
// of the two bodies. From then on the joint holds that relation:
//   anchor   the point carried by a and the point carried by b coincide (their separation
//            along the free directions is the `offset`);
//   axis     the axis carried by a stays parallel to the axis carried by b (hinge, slider,
//            cylindrical, screw; the normal of the plane for planar);
//   angle    of a relative to b about b's axis, right hand, 0 at creation, counted in turns
//            past ±π (tracked at every substep: a body turning less than π per substep);
//   offset   of a's anchor relative to b's along b's axis, m, 0 at creation.
//
// Degrees of freedom (free coordinates) and the rows that remove the others:
//   ball         3 rot.          3 point rows
//   hinge        1 rot. (angle)  3 point rows, 2 angular rows across the axis
//   slider       1 transl.       2 point rows across the axis, 3 angular rows
//   cylindrical  1 + 1           2 point rows across the axis, 2 angular rows across it
//   planar       2 transl. + 1   1 point row along the normal, 2 angular rows across it
//   screw        1 coupled       as cylindrical, plus offset − pitch·angle/(2π) = 0
//   fixed        0               3 point rows, 3 angular rows
//   distance     2 + 3           |p_b − p_a| = length (or min ≤ |p_b − p_a| ≤ max: a rope)
// The driven coordinate (limits, spring, motor) is the angle for hinge and screw, the offset
// for slider and cylindrical; ball, planar, fixed and distance take none (distance has min
// and max).
#pragma once

#include <optional>
#include <string>

#include "engine/body.hpp"
#include "engine/body_store.hpp"
#include "engine/constraint.hpp"

namespace rigidlab {

enum class JointKind { ball, hinge, slider, cylindrical, planar, screw, fixed, distance };
inline constexpr const char* joint_kind_names[] = {"ball",   "hinge", "slider", "cylindrical",
                                                   "planar", "screw", "fixed",  "distance"};
inline constexpr int joint_kind_count = 8;

// What a type's driven coordinate is, if any.
enum class JointCoordinate { none, angle, offset };
JointCoordinate driven_coordinate(JointKind type);
// Whether the type has an angle (hinge, cylindrical, planar, screw) or an offset along its
// axis (slider, cylindrical, screw) to report.
bool has_angle(JointKind type);
bool has_offset(JointKind type);

// A soft drive of the coordinate toward `rest` (rad or m): a damped oscillator of `hertz` and
// `damping_ratio` per unit effective mass, as Box2D's joint springs.
struct JointSpring {
  double hertz = 0.0;  // > 0
  double damping_ratio = 0.0;
  double rest = 0.0;
};

// Document 000 "PD controller": τ = kp (θd − θ) + kv (θ̇d − θ̇), clamped to ±max_force
// (N m for an angle, N for an offset).
struct JointMotor {
  double target = 0.0;       // θd (rad or m)
  double target_rate = 0.0;  // θ̇d (rad/s or m/s)
  double kp = 0.0;           // N m/rad or N/m, >= 0
  double kv = 0.0;           // N m s/rad or N s/m, >= 0
  double max_force = unbounded;
};

struct JointDef {
  JointKind type = JointKind::ball;
  BodyId a, b;                      // b = no_body_id: the world
  Vec3 anchor = Vec3::Zero();       // world point (not distance)
  Vec3 axis = Vec3::UnitY();        // world direction, non-zero (normalised here)
  double pitch = 0.0;               // screw: m of offset per turn of angle
  Vec3 a_point = Vec3::Zero();      // distance: a's end, a's frame
  Vec3 b_point = Vec3::Zero();      // distance: b's end, b's frame (a world point for the world)
  // distance: without min and max a rigid rod of the length at creation; with either a rope
  // or a limit: min <= length <= max (min default 0, max default infinite).
  std::optional<double> min_length, max_length;
  double lower = -unbounded, upper = unbounded;  // limits of the driven coordinate
  std::optional<JointSpring> spring;
  std::optional<JointMotor> motor;
  bool collide = false;  // whether a and b still collide with each other
};

// "" or the rule the definition breaks ("the axis must be a non-zero vector", "a ball joint
// takes no limits, spring or motor", ...). Bodies are checked by the world.
std::string joint_def_problem(const JointDef& def);

class Joint final : public Constraint {
 public:
  // `a` and `b` are the bodies of def.a and def.b (b nullptr for the world) as they are now.
  // Throws std::invalid_argument with joint_def_problem's message.
  Joint(const JointDef& def, const Body& a, const Body* b);

  JointKind type() const { return type_; }
  int row_count() const override;
  void build_rows(const Body& a, const Body* b, JointRow* rows) const override;
  void track(const Body& a, const Body* b) override;
  double potential_energy(const Body& a, const Body* b) const override;

  // The present coordinates (need the bodies as they are now).
  double angle(const Body& a, const Body* b) const;   // rad, counted in turns
  double offset(const Body& a, const Body* b) const;  // m
  double length(const Body& a, const Body* b) const;  // distance: m
  // d/dt of the driven coordinate (rad/s or m/s; distance: of the length).
  double rate(const Body& a, const Body* b) const;
  // The position error (m) and angle error (rad) of the rows that hold (equality rows and
  // violated limits), each the root sum of squares.
  void error(const Body& a, const Body* b, double& position, double& angle) const;
  Vec3 world_anchor(const Body& a) const;
  void attachment_points(const Body& a, const Body* b, Vec3& on_a, Vec3& on_b) const override;
  Vec3 world_axis(const Body* b) const;

  // Changes take effect at the next step; they forget the impulses the next step would be
  // warm started from (the rows change).
  void set_limits(double lower, double upper);  // std::invalid_argument unless lower <= upper
  void set_motor(const std::optional<JointMotor>& motor);
  void set_spring(const std::optional<JointSpring>& spring);
  double lower() const { return lower_; }
  double upper() const { return upper_; }
  const std::optional<JointMotor>& motor() const { return motor_; }
  const std::optional<JointSpring>& spring() const { return spring_; }
  double pitch() const { return pitch_; }

 private:
  struct Frame;  // the world-frame quantities of one evaluation
  Frame frame(const Body& a, const Body* b) const;
  double raw_angle(const Frame& f) const;  // in (−π, π]
  int coordinate_rows() const;
  void coordinate(const Frame& f, double& value, Jacobian& jacobian) const;

  JointKind type_;
  Vec3 local_anchor_a_, local_anchor_b_;  // body frames (world frame for the world side)
  Vec3 local_axis_a_, local_axis_b_;      // unit
  Vec3 local_perp1_b_, local_perp2_b_;    // unit, across b's axis
  Quat reference_;                        // q_b⁻¹ q_a at creation
  double pitch_ = 0.0;
  double length_ = 0.0;                   // distance: at creation
  bool rope_ = false;
  double min_length_ = 0.0, max_length_ = unbounded;
  double lower_ = -unbounded, upper_ = unbounded;
  std::optional<JointSpring> spring_;
  std::optional<JointMotor> motor_;
};

// The exact solution over h of the damped, driven oscillator
//   x'' + c x' + k x = f     (k >= 0, c >= 0, f constant)
// from x(0) = x0, x'(0) = v0: x(h) and x'(h). The joint springs and PD motors are integrated
// with it (engine/solver.cpp, "spring and motor rows").
struct OscillatorState {
  double x, v;
};
OscillatorState damped_oscillator_step(double x0, double v0, double k, double c, double f,
                                       double h);

}  // namespace rigidlab
