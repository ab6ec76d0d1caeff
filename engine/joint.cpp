#include "engine/joint.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "engine/format.hpp"

namespace rigidlab {
namespace {

constexpr double two_pi = 2.0 * M_PI;

Jacobian negated(const Jacobian& j) { return {-j.linear, -j.angular_a, -j.angular_b}; }

bool finite_vec(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// The rotation vector (rad, axis times angle in [0, π]) of a unit quaternion.
Vec3 rotation_vector(const Quat& q) {
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vec3 v = sign * q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;  // 2 atan2(s, w)/s → 2 as s → 0
  return (2.0 * std::atan2(s, sign * q.w()) / s) * v;
}

}  // namespace

JointCoordinate driven_coordinate(JointKind type) {
  switch (type) {
    case JointKind::hinge:
    case JointKind::screw:
      return JointCoordinate::angle;
    case JointKind::slider:
    case JointKind::cylindrical:
      return JointCoordinate::offset;
    default:
      return JointCoordinate::none;
  }
}

bool has_angle(JointKind type) {
  return type == JointKind::hinge || type == JointKind::cylindrical ||
         type == JointKind::planar || type == JointKind::screw;
}

bool has_offset(JointKind type) {
  return type == JointKind::slider || type == JointKind::cylindrical || type == JointKind::screw;
}

static bool uses_axis(JointKind type) {
  return type != JointKind::ball && type != JointKind::fixed && type != JointKind::distance;
}

std::string joint_def_problem(const JointDef& def) {
  const std::string name = joint_kind_names[static_cast<int>(def.type)];
  if (!finite_vec(def.anchor)) return "the anchor must be finite";
  if (uses_axis(def.type) && (!finite_vec(def.axis) || def.axis.norm() == 0.0 ||
                              !std::isfinite(def.axis.norm())))
    return "the axis must be a finite non-zero vector, got (" + format_number(def.axis.x()) +
           ", " + format_number(def.axis.y()) + ", " + format_number(def.axis.z()) + ")";
  if (!std::isfinite(def.pitch)) return "the pitch must be finite";
  const bool driven = driven_coordinate(def.type) != JointCoordinate::none;
  const bool has_limits = def.lower != -unbounded || def.upper != unbounded;
  if (!driven && (has_limits || def.spring || def.motor))
    return "a " + name + " joint has no coordinate to limit, spring or drive (hinge, slider, "
           "cylindrical and screw joints have)";
  if (std::isnan(def.lower) || std::isnan(def.upper) || def.lower > def.upper)
    return "the limits must satisfy lower <= upper, got lower = " + format_number(def.lower) +
           ", upper = " + format_number(def.upper);
  if (def.lower == unbounded || def.upper == -unbounded)
    return "the limits must leave some range: lower < inf, upper > -inf";
  if (def.spring) {
    const JointSpring& s = *def.spring;
    if (!(s.hertz > 0.0) || !std::isfinite(s.hertz))
      return "the spring's hertz must be finite and > 0, got " + format_number(s.hertz);
    if (!(s.damping_ratio >= 0.0) || !std::isfinite(s.damping_ratio))
      return "the spring's damping_ratio must be finite and >= 0, got " +
             format_number(s.damping_ratio);
    if (!std::isfinite(s.rest)) return "the spring's rest must be finite";
  }
  if (def.motor) {
    const JointMotor& m = *def.motor;
    if (!(m.kp >= 0.0) || !std::isfinite(m.kp) || !(m.kv >= 0.0) || !std::isfinite(m.kv))
      return "the motor's kp and kv must be finite and >= 0";
    if (!(m.max_force > 0.0)) return "the motor's max_torque must be > 0";
    if (!std::isfinite(m.target) || !std::isfinite(m.target_rate))
      return "the motor's target and target_rate must be finite";
  }
  if (def.type == JointKind::distance) {
    if (!finite_vec(def.a_point) || !finite_vec(def.b_point)) return "the points must be finite";
    const double lo = def.min_length.value_or(0.0), hi = def.max_length.value_or(unbounded);
    if (!(lo >= 0.0) || !std::isfinite(lo))
      return "min must be finite and >= 0, got " + format_number(lo);
    if (std::isnan(hi) || !(hi >= lo) || !(hi > 0.0))
      return "max must be > 0 and >= min, got " + format_number(hi);
  }
  return "";
}

// ---- the joint's frame at the bodies' present poses --------------------------------------------

struct Joint::Frame {
  Quat qa, qb;
  Vec3 xa, xb;  // COMs (the world's origin for the world side)
  Vec3 pa, pb;  // the anchors (distance: the ends) carried by a and by b
  Vec3 ra, rb;  // pa − xa, pb − xb
  Vec3 ua, ub;  // the axis carried by a and by b
  Vec3 p1, p2;  // across b's axis, carried by b
};

Joint::Frame Joint::frame(const Body& a, const Body* b) const {
  Frame f;
  f.qa = a.orientation;
  f.qb = b != nullptr ? b->orientation : Quat(Quat::Identity());
  f.xa = a.position;
  f.xb = b != nullptr ? b->position : Vec3::Zero();
  f.ra = f.qa * local_anchor_a_;
  f.rb = f.qb * local_anchor_b_;
  f.pa = f.xa + f.ra;
  f.pb = f.xb + f.rb;
  f.ua = f.qa * local_axis_a_;
  f.ub = f.qb * local_axis_b_;
  f.p1 = f.qb * local_perp1_b_;
  f.p2 = f.qb * local_perp2_b_;
  return f;
}

Joint::Joint(const JointDef& def, const Body& a, const Body* b)
    : Constraint(def.a, def.b, def.collide), type_(def.type) {
  const std::string problem = joint_def_problem(def);
  if (!problem.empty()) throw std::invalid_argument(problem);
  const Quat qa = a.orientation, qb = b != nullptr ? b->orientation : Quat(Quat::Identity());
  const Vec3 xb = b != nullptr ? b->position : Vec3::Zero();
  if (type_ == JointKind::distance) {
    local_anchor_a_ = def.a_point;
    local_anchor_b_ = def.b_point;
  } else {
    local_anchor_a_ = qa.conjugate() * (def.anchor - a.position);
    local_anchor_b_ = qb.conjugate() * (def.anchor - xb);
  }
  const Vec3 n = uses_axis(type_) ? Vec3(def.axis.normalized()) : Vec3::UnitY();
  local_axis_a_ = qa.conjugate() * n;
  local_axis_b_ = qb.conjugate() * n;
  local_perp1_b_ = local_axis_b_.unitOrthogonal();
  local_perp2_b_ = local_axis_b_.cross(local_perp1_b_);
  reference_ = qb.conjugate() * qa;
  pitch_ = def.pitch;
  lower_ = def.lower, upper_ = def.upper;
  spring_ = def.spring;
  motor_ = def.motor;
  if (type_ == JointKind::distance) {
    const Frame f = frame(a, b);
    length_ = (f.pb - f.pa).norm();
    rope_ = def.min_length.has_value() || def.max_length.has_value();
    min_length_ = def.min_length.value_or(0.0);
    max_length_ = def.max_length.value_or(unbounded);
    if (!rope_ && !(length_ > 0.0))
      throw std::invalid_argument(
          "the ends of a rigid distance joint coincide (length 0): use a ball joint, or give "
          "min or max");
  }
}

// ---- rows -------------------------------------------------------------------------------------

int Joint::coordinate_rows() const {
  if (driven_coordinate(type_) == JointCoordinate::none) return 0;
  return (lower_ != -unbounded) + (upper_ != unbounded) + spring_.has_value() + motor_.has_value();
}

int Joint::row_count() const {
  switch (type_) {
    case JointKind::ball: return 3;
    case JointKind::hinge: return 5 + coordinate_rows();
    case JointKind::slider: return 5 + coordinate_rows();
    case JointKind::cylindrical: return 4 + coordinate_rows();
    case JointKind::planar: return 3;
    case JointKind::screw: return 5 + coordinate_rows();
    case JointKind::fixed: return 6;
    case JointKind::distance:
      return rope_ ? (min_length_ > 0.0) + (max_length_ != unbounded) : 1;
  }
  return 0;
}

namespace {

// C = d·(p_b − p_a) for a direction d carried by b (across an axis, a plane's normal): its
// rate is d·(v_pb − v_pa) + (ω_b × d)·(p_b − p_a), so b's lever arm reaches to p_a.
Jacobian separation_jacobian(const Vec3& d, const Vec3& ra, const Vec3& pa, const Vec3& xb) {
  return {d, ra.cross(d), (pa - xb).cross(d)};
}

JointRow equality(const Jacobian& j, double c) {
  JointRow row;
  row.jacobian = j;
  row.error = c;
  return row;
}

}  // namespace

double Joint::raw_angle(const Frame& f) const {
  // The relative rotation since creation, in b's frame; its twist about b's axis.
  const Quat e = f.qb.conjugate() * f.qa * reference_.conjugate();
  return std::remainder(2.0 * std::atan2(e.vec().dot(local_axis_b_), e.w()), two_pi);
}

// The driven coordinate and its Jacobian (d/dt of it = J v): the angle of a relative to b
// about b's axis, u_b·(ω_a − ω_b); the offset u_b·(p_a − p_b), whose rate has b's lever arm
// reaching to p_a as in separation_jacobian.
void Joint::coordinate(const Frame& f, double& value, Jacobian& jacobian) const {
  if (driven_coordinate(type_) == JointCoordinate::angle) {
    value = tracked_ + std::remainder(raw_angle(f) - tracked_, two_pi);
    jacobian = negated(angular_jacobian(f.ub));
  } else {
    value = f.ub.dot(f.pa - f.pb);
    jacobian = negated(separation_jacobian(f.ub, f.ra, f.pa, f.xb));
  }
}

void Joint::build_rows(const Body& a, const Body* b, JointRow* rows) const {
  const Frame f = frame(a, b);
  int n = 0;
  const Vec3 d = f.pb - f.pa;
  auto point_rows = [&] {  // 000 "Kinematic pair": the anchors coincide
    for (int i = 0; i < 3; ++i) {
      const Vec3 e = Vec3::Unit(i);
      rows[n++] = equality(point_jacobian(e, f.ra, f.rb), e.dot(d));
    }
  };
  auto across_rows = [&] {  // the anchors' separation across the axis is zero
    for (const Vec3& p : {f.p1, f.p2})
      rows[n++] = equality(separation_jacobian(p, f.ra, f.pa, f.xb), p.dot(d));
  };
  auto align_rows = [&] {  // the axes stay parallel: the angle from u_b to u_a is u_b × u_a
    const Vec3 misalignment = f.ub.cross(f.ua);
    for (const Vec3& p : {f.p1, f.p2})
      rows[n++] = equality(angular_jacobian(p), -p.dot(misalignment));
  };
  auto lock_rows = [&] {  // the relative orientation stays as at creation
    const Vec3 theta = rotation_vector(f.qa * reference_.conjugate() * f.qb.conjugate());
    for (int i = 0; i < 3; ++i)
      rows[n++] = equality(angular_jacobian(Vec3::Unit(i)), -theta[i]);
  };
  switch (type_) {
    case JointKind::ball: point_rows(); break;
    case JointKind::hinge: point_rows(); align_rows(); break;
    case JointKind::slider: across_rows(); lock_rows(); break;
    case JointKind::cylindrical: across_rows(); align_rows(); break;
    case JointKind::planar: {
      rows[n++] = equality(separation_jacobian(f.ub, f.ra, f.pa, f.xb), f.ub.dot(d));
      align_rows();
      break;
    }
    case JointKind::screw: {
      across_rows();
      align_rows();
      // offset − pitch·angle/(2π) = 0: one coupled row (000 "Kinematic pair", screw).
      double angle = 0.0;
      Jacobian ja;
      coordinate(f, angle, ja);
      const double c = pitch_ / two_pi;
      const Jacobian jo = negated(separation_jacobian(f.ub, f.ra, f.pa, f.xb));
      rows[n++] = equality({jo.linear, jo.angular_a - c * ja.angular_a,
                            jo.angular_b - c * ja.angular_b},
                           f.ub.dot(f.pa - f.pb) - c * angle);
      break;
    }
    case JointKind::fixed: point_rows(); lock_rows(); break;
    case JointKind::distance: {
      const double length = d.norm();
      const Vec3 dir = length > 1e-12 ? Vec3(d / length) : Vec3::UnitY();
      const Jacobian j = point_jacobian(dir, f.ra, f.rb);
      if (!rope_) {
        rows[n++] = equality(j, length - length_);
        break;
      }
      if (min_length_ > 0.0) {
        rows[n] = equality(j, length - min_length_);
        rows[n++].kind = JointRow::Kind::limit;
      }
      if (max_length_ != unbounded) {
        rows[n] = equality(negated(j), max_length_ - length);
        rows[n++].kind = JointRow::Kind::limit;
      }
      break;
    }
  }
  // The equality rows (all at the start) are solved as one block (engine/solver.cpp).
  if (n > 1 && rows[0].kind == JointRow::Kind::equality) {
    rows[0].block = static_cast<std::uint8_t>(n);
    for (int i = 1; i < n; ++i) rows[i].block = 0;
  }
  if (driven_coordinate(type_) == JointCoordinate::none) return;
  double q = 0.0;
  Jacobian jq;
  coordinate(f, q, jq);
  if (lower_ != -unbounded) {
    rows[n] = equality(jq, q - lower_);
    rows[n++].kind = JointRow::Kind::limit;
  }
  if (upper_ != unbounded) {
    rows[n] = equality(negated(jq), upper_ - q);
    rows[n++].kind = JointRow::Kind::limit;
  }
  if (spring_) {
    JointRow& row = rows[n++];
    row = equality(jq, q - spring_->rest);
    row.kind = JointRow::Kind::spring;
    row.hertz = spring_->hertz;
    row.damping_ratio = spring_->damping_ratio;
  }
  if (motor_) {
    JointRow& row = rows[n++];
    row = equality(jq, q - motor_->target);
    row.kind = JointRow::Kind::motor;
    row.kp = motor_->kp;
    row.kv = motor_->kv;
    row.target_velocity = motor_->target_rate;
    row.max_force = motor_->max_force;
  }
}

void Joint::track(const Body& a, const Body* b) {
  if (has_angle(type_)) tracked_ = angle(a, b);
}

// ---- what the joint reports --------------------------------------------------------------------

double Joint::angle(const Body& a, const Body* b) const {
  if (!has_angle(type_)) return 0.0;
  return tracked_ + std::remainder(raw_angle(frame(a, b)) - tracked_, two_pi);
}

double Joint::offset(const Body& a, const Body* b) const {
  const Frame f = frame(a, b);
  return f.ub.dot(f.pa - f.pb);
}

double Joint::length(const Body& a, const Body* b) const {
  const Frame f = frame(a, b);
  return (f.pb - f.pa).norm();
}

static double jacobian_velocity(const Jacobian& j, const Body& a, const Body* b) {
  const Vec3 vb = b != nullptr ? b->velocity : Vec3::Zero();
  const Vec3 wb = b != nullptr ? b->angular_velocity : Vec3::Zero();
  return j.linear.dot(vb - a.velocity) + j.angular_b.dot(wb) - j.angular_a.dot(a.angular_velocity);
}

double Joint::rate(const Body& a, const Body* b) const {
  const Frame f = frame(a, b);
  if (type_ == JointKind::distance) {
    const Vec3 d = f.pb - f.pa;
    const double length = d.norm();
    if (!(length > 0.0)) return 0.0;
    return jacobian_velocity(point_jacobian(d / length, f.ra, f.rb), a, b);
  }
  if (driven_coordinate(type_) == JointCoordinate::none) return 0.0;
  double q = 0.0;
  Jacobian j;
  coordinate(f, q, j);
  return jacobian_velocity(j, a, b);
}

void Joint::error(const Body& a, const Body* b, double& position, double& angle) const {
  std::array<JointRow, 12> rows;
  build_rows(a, b, rows.data());
  double linear2 = 0.0, angular2 = 0.0;
  for (int i = 0; i < row_count(); ++i) {
    const JointRow& r = rows[static_cast<std::size_t>(i)];
    double c = 0.0;
    if (r.kind == JointRow::Kind::equality) c = r.error;
    else if (r.kind == JointRow::Kind::limit && r.error < 0.0) c = r.error;
    if (r.jacobian.linear.isZero()) angular2 += c * c;
    else linear2 += c * c;
  }
  position = std::sqrt(linear2);
  angle = std::sqrt(angular2);
}

// ½ k C² with the stiffness of the spring row, k = m_eff ω², m_eff = 1/(J W Jᵀ) at the
// present poses (the spring's frequency is per unit effective mass).
double Joint::potential_energy(const Body& a, const Body* b) const {
  if (!spring_ || driven_coordinate(type_) == JointCoordinate::none) return 0.0;
  double q = 0.0;
  Jacobian j;
  coordinate(frame(a, b), q, j);
  const double k = coupling(j, j, a.inverse_mass, inverse_world_inertia(a),
                            b != nullptr ? b->inverse_mass : 0.0,
                            b != nullptr ? inverse_world_inertia(*b) : Mat3::Zero());
  if (!(k > 0.0)) return 0.0;
  const double omega = two_pi * spring_->hertz;
  const double c = q - spring_->rest;
  return 0.5 * omega * omega * c * c / k;
}

Vec3 Joint::world_anchor(const Body& a) const { return to_world(a, local_anchor_a_); }
void Joint::attachment_points(const Body& a, const Body* b, Vec3& on_a, Vec3& on_b) const {
  on_a = to_world(a, local_anchor_a_);
  on_b = b != nullptr ? to_world(*b, local_anchor_b_) : local_anchor_b_;
}
Vec3 Joint::world_axis(const Body* b) const {
  return b != nullptr ? Vec3(b->orientation * local_axis_b_) : local_axis_b_;
}

// Checks a definition of this type that differs from the default only in what changes.
static void check_change(const JointDef& def) {
  const std::string problem = joint_def_problem(def);
  if (!problem.empty()) throw std::invalid_argument(problem);
}

void Joint::set_limits(double lower, double upper) {
  JointDef def;
  def.type = type_;
  def.lower = lower, def.upper = upper;
  check_change(def);
  lower_ = lower, upper_ = upper;
  forget_impulses();
}

void Joint::set_motor(const std::optional<JointMotor>& motor) {
  JointDef def;
  def.type = type_;
  def.motor = motor;
  check_change(def);
  motor_ = motor;
  forget_impulses();
}

void Joint::set_spring(const std::optional<JointSpring>& spring) {
  JointDef def;
  def.type = type_;
  def.spring = spring;
  check_change(def);
  spring_ = spring;
  forget_impulses();
}

// ---- the damped oscillator over one substep -----------------------------------------------------

// With k > 0 about the equilibrium x* = f/k, y = x − x*: (y, y') evolves by e^{Ah},
// A = [[0, 1], [−k, −c]], whose closed form (Cayley–Hamilton for a 2 × 2 matrix with
// eigenvalues −c/2 ± s, s² = c²/4 − k) is
//   e^{Ah} = e^{−ch/2} [cosh(sh) E + sinh(sh)/s (A + c/2 E)],
// cos and sin for s² < 0 (under-damped), the series at s² ≈ 0 (critical). Over-damped, the
// two exponentials are taken separately so that a large c neither overflows nor cancels.
OscillatorState damped_oscillator_step(double x0, double v0, double k, double c, double f,
                                       double h) {
  if (k > 0.0) {
    const double xs = f / k;
    const double y0 = x0 - xs;
    const double s2 = 0.25 * c * c - k;
    double ch = 0.0, sh = 0.0;  // e^{−ch/2} cosh(sh), e^{−ch/2} sinh(sh)/s
    if (std::abs(s2) * h * h < 1e-8) {
      const double decay = std::exp(-0.5 * c * h), q = s2 * h * h;
      ch = decay * (1.0 + q / 2.0 + q * q / 24.0);
      sh = decay * h * (1.0 + q / 6.0 + q * q / 120.0);
    } else if (s2 < 0.0) {
      const double w = std::sqrt(-s2), decay = std::exp(-0.5 * c * h);
      ch = decay * std::cos(w * h);
      sh = decay * std::sin(w * h) / w;
    } else {
      const double r = std::sqrt(s2);
      const double fast = std::exp((-r - 0.5 * c) * h), slow = std::exp(-k / (r + 0.5 * c) * h);
      ch = 0.5 * (slow + fast);
      sh = 0.5 * (slow - fast) / r;
    }
    const double y = ch * y0 + sh * (v0 + 0.5 * c * y0);
    const double v = ch * v0 + sh * (-k * y0 - 0.5 * c * v0);
    return {xs + y, v};
  }
  if (c > 0.0) {  // x'' = f − c x': the velocity relaxes to f/c
    const double terminal = f / c, decayed = -std::expm1(-c * h);  // 1 − e^{−ch}
    return {x0 + terminal * h + (v0 - terminal) * decayed / c, v0 + (v0 - terminal) * -decayed};
  }
  return {x0 + v0 * h + 0.5 * f * h * h, v0 + f * h};
}

}  // namespace rigidlab
