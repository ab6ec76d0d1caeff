#include "engine/articulation_model.hpp"

#include <cmath>
#include <stdexcept>

#include "engine/format.hpp"
#include "engine/inertia.hpp"

namespace rigidlab {
namespace {

// A quaternion given for an orientation may be off unit length by rounding in the digits a
// user typed (0.7071); anything further is a mistake, not a rotation.
constexpr double unit_quaternion_tolerance = 1e-6;

std::string number(double x) { return format_number(x); }

std::string vec3_text(const Vec3& v) {
  return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
}

std::string quaternion_problem(const Quat& q) {
  if (!is_finite(q)) return "must be finite";
  const double norm = stable_norm(q);
  if (!(std::abs(norm - 1.0) <= unit_quaternion_tolerance))
    return "must be a unit quaternion, got length " + number(norm);
  return {};
}

// The rules of one link spec, checked against the links already in the model.
std::string link_problem(const LinkSpec& spec, const std::vector<Link>& links) {
  const int count = static_cast<int>(links.size());
  if (spec.parent < -1 || spec.parent >= count)
    return count == 0 ? "parent must be the base (nil): the articulation has no links yet"
                      : "parent must be the base (nil) or one of the links 1 to " +
                            std::to_string(count) + " of this articulation, got link " +
                            std::to_string(spec.parent + 1);
  if (!is_finite(spec.axis)) return "axis must be finite, got " + vec3_text(spec.axis);
  if (spec.joint != JointType::fixed && is_zero(spec.axis))
    return "axis must be non-zero for a " + std::string(joint_type_names[int(spec.joint)]) +
           " joint, got (0, 0, 0)";
  if (!is_finite(spec.origin)) return "origin must be finite, got " + vec3_text(spec.origin);
  if (!is_finite(spec.com)) return "com must be finite, got " + vec3_text(spec.com);
  if (!std::isfinite(spec.mass) || spec.mass < 0.0)
    return "mass must be finite and >= 0, got " + number(spec.mass);
  const std::string inertia = inertia_tensor_problem(spec.inertia, InertiaRules::idealized);
  if (!inertia.empty()) return "inertia is not a valid tensor: " + inertia;
  if (!spec.name.empty())
    for (int k = 0; k < count; ++k)
      if (links[k].spec.name == spec.name)
        return "name must be unique: link " + std::to_string(k + 1) + " is already called '" +
               spec.name + "'";
  return {};
}

}  // namespace

std::optional<JointType> parse_joint_type(std::string_view name) {
  for (int k = 0; k < 3; ++k)
    if (name == joint_type_names[k]) return static_cast<JointType>(k);
  return std::nullopt;
}

std::optional<BaseType> parse_base_type(std::string_view name) {
  for (int k = 0; k < 2; ++k)
    if (name == base_type_names[k]) return static_cast<BaseType>(k);
  return std::nullopt;
}

ArticulationModel::ArticulationModel(BaseType base, const Vec3& base_position,
                                     const Quat& base_orientation)
    : base_(base), base_position_(base_position), base_orientation_(base_orientation) {
  if (!is_finite(base_position))
    throw std::invalid_argument("position must be finite, got " + vec3_text(base_position));
  const std::string orientation = quaternion_problem(base_orientation);
  if (!orientation.empty()) throw std::invalid_argument("orientation " + orientation);
  base_orientation_ = unit(base_orientation);
  nq_ = base_coordinates();
  nv_ = base_velocities();
}

int ArticulationModel::add_link(const LinkSpec& spec) {
  const std::string problem = link_problem(spec, links_);
  if (!problem.empty()) throw std::invalid_argument(problem);
  Link link;
  link.spec = spec;
  if (spec.joint != JointType::fixed) {
    link.spec.axis = unit(spec.axis);
    link.q_index = nq_++;
    link.v_index = nv_++;
  } else if (!is_zero(spec.axis)) {
    link.spec.axis = unit(spec.axis);  // unused by a fixed joint, kept tidy for display
  }
  link.inertia = rigid_body_inertia(spec.mass, spec.com, spec.inertia);
  links_.push_back(std::move(link));
  return link_count() - 1;
}

int ArticulationModel::find_link(std::string_view name) const {
  for (int k = 0; k < link_count(); ++k)
    if (links_[k].spec.name == name) return k;
  return -1;
}

void ArticulationModel::set_gravity(const Vec3& g) {
  if (!is_finite(g)) throw std::invalid_argument("gravity must be finite, got " + vec3_text(g));
  gravity_ = g;
}

std::string ArticulationModel::state_problem(const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& v) const {
  if (q.size() != nq_)
    return "q must have " + std::to_string(nq_) + " entries (" +
           (free_base() ? "7 for the free base and " : std::string()) + "one per moving joint)" +
           ", got " + std::to_string(q.size());
  if (v.size() != nv_)
    return "qd must have " + std::to_string(nv_) + " entries (" +
           (free_base() ? "6 for the free base and " : std::string()) + "one per moving joint)" +
           ", got " + std::to_string(v.size());
  for (int k = 0; k < nq_; ++k)
    if (!std::isfinite(q[k]))
      return "q[" + std::to_string(k + 1) + "] must be finite, got " + number(q[k]);
  for (int k = 0; k < nv_; ++k)
    if (!std::isfinite(v[k]))
      return "qd[" + std::to_string(k + 1) + "] must be finite, got " + number(v[k]);
  if (free_base()) {
    const Quat orientation(q[3], q[4], q[5], q[6]);
    const std::string problem = quaternion_problem(orientation);
    if (!problem.empty()) return "q[4..7] (the base orientation w, x, y, z) " + problem;
  }
  return {};
}

Eigen::VectorXd ArticulationModel::neutral_q() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(nq_);
  if (free_base()) {
    q.head<3>() = base_position_;
    q.segment<4>(3) << base_orientation_.w(), base_orientation_.x(), base_orientation_.y(),
        base_orientation_.z();
  }
  return q;
}

PluckerTransform ArticulationModel::joint_transform(int link, double q_joint) const {
  const LinkSpec& spec = links_[link].spec;
  switch (spec.joint) {
    case JointType::revolute:  // X_J = rot(E(axis, q)), X_T = xlt(origin)
      return {rotation_coordinates(spec.axis, q_joint), spec.origin};
    case JointType::prismatic:  // X_J = xlt(axis q)
      return {Mat3::Identity(), spec.origin + q_joint * spec.axis};
    case JointType::fixed:
      break;
  }
  return plucker_translation(spec.origin);
}

Mat3 base_rotation(const ArticulationModel& model, const Eigen::VectorXd& q) {
  if (!model.free_base()) return model.base_orientation().toRotationMatrix();
  return unit(Quat(q[3], q[4], q[5], q[6])).toRotationMatrix();
}

Vec3 base_position(const ArticulationModel& model, const Eigen::VectorXd& q) {
  return model.free_base() ? Vec3(q.head<3>()) : model.base_position();
}

}  // namespace rigidlab
