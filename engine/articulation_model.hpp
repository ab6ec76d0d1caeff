// The model of an articulated body in reduced coordinates (document 000 "Coordinate
// simulation"): a tree of rigid links joined by revolute, prismatic or fixed joints to a base
// that is either fixed in the world or free-floating. Only the joints' own coordinates are
// state; no constraint forces are computed or needed.
//
// Frames. The base has a frame (fixed: at `base_position`, `base_orientation` in the world;
// free: its pose is the first part of q). Every link has a frame whose pose relative to its
// parent's frame is set by its joint (RBDA 4.1-4.4, tree model): at q = 0 the link frame is the
// parent frame moved to `origin` (parent coordinates), axes parallel; a revolute joint then
// turns it by q (rad, right-handed) about `axis`, a prismatic joint slides it by q (m) along
// `axis`; a fixed joint keeps it there. The axis is the same vector in parent and link
// coordinates. Mass properties are in the link frame: `com` the centre of mass, `inertia` the
// rotational inertia about the COM.
//
// Coordinates (q) and velocities (q̇, "v" below). Each revolute or prismatic joint adds one of
// each, in the order the links are added. A free base adds first
//   q: base position (3, m, world) and orientation (4, unit quaternion w, x, y, z: base frame to
//      world), then the joints;
//   v: velocity of the base frame's origin (3, m/s, world) and angular velocity (3, rad/s,
//      world), then the joint rates.
// So nq = nv + 1 with a free base and nq = nv otherwise. The generalised forces τ pair with v:
// a free base's are the world force (N) at its origin and the world torque (N·m) about it.
//
// The algorithms (engine/aba, rnea, crba, articulation_kinematics) number bodies as RBDA does:
// body 0 is the base, link k (0-based) is body k + 1, and every parent precedes its children (a
// parent must exist before a child is added).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "engine/spatial.hpp"

namespace rigidlab {

enum class JointType { revolute, prismatic, fixed };
enum class BaseType { fixed, free };
inline constexpr const char* joint_type_names[] = {"revolute", "prismatic", "fixed"};
inline constexpr const char* base_type_names[] = {"fixed", "free"};
std::optional<JointType> parse_joint_type(std::string_view name);
std::optional<BaseType> parse_base_type(std::string_view name);

// What a user gives for one link (units: m, kg, kg·m²; frames as above).
struct LinkSpec {
  int parent = -1;  // index of the parent link (0-based), −1 for the base
  JointType joint = JointType::revolute;
  Vec3 axis = Vec3::UnitZ();     // parent frame; any non-zero length (normalised)
  Vec3 origin = Vec3::Zero();    // the joint's position in the parent's frame
  double mass = 1.0;             // >= 0
  Mat3 inertia = Mat3::Zero();   // about the COM, link frame (a point mass by default)
  Vec3 com = Vec3::Zero();       // link frame
  std::string name;              // optional; unique when given
};

struct Link {
  LinkSpec spec;        // axis normalised
  Mat6 inertia;         // spatial inertia about the link origin, link coordinates (RBDA 2.63)
  int q_index = -1;     // its coordinate in q, −1 for a fixed joint
  int v_index = -1;     // its rate in v and its force in τ, −1 for a fixed joint
};

class ArticulationModel {
 public:
  // Throws std::invalid_argument for a non-finite position or a non-unit orientation.
  explicit ArticulationModel(BaseType base = BaseType::fixed,
                             const Vec3& base_position = Vec3::Zero(),
                             const Quat& base_orientation = Quat::Identity());

  // Adds a link and returns its index. Throws std::invalid_argument naming the rule a bad
  // spec breaks (parent not an existing link, zero or non-finite axis, negative mass, an
  // inertia that no body has, a repeated name); the model is then unchanged.
  int add_link(const LinkSpec& spec);

  BaseType base() const { return base_; }
  bool free_base() const { return base_ == BaseType::free; }
  const Vec3& base_position() const { return base_position_; }        // fixed base, world
  const Quat& base_orientation() const { return base_orientation_; }  // fixed base, world
  const std::vector<Link>& links() const { return links_; }
  int link_count() const { return static_cast<int>(links_.size()); }
  int nq() const { return nq_; }
  int nv() const { return nv_; }
  int base_coordinates() const { return free_base() ? 7 : 0; }  // leading entries of q
  int base_velocities() const { return free_base() ? 6 : 0; }   // leading entries of v
  // The index of the link called `name`, or −1.
  int find_link(std::string_view name) const;

  // m/s², world; default (0, −9.81, 0) as a world's. Throws for a non-finite vector.
  const Vec3& gravity() const { return gravity_; }
  void set_gravity(const Vec3& g);

  // Empty when q (length nq) and v (length nv) are a valid state, else why not: wrong length,
  // a non-finite entry, a free base's quaternion not of unit length (within 1e-6).
  std::string state_problem(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // The q of the zero pose: joints at 0, a free base at the model's base pose.
  Eigen::VectorXd neutral_q() const;

  // i_X_λ(i): from the parent's coordinates to link `link`'s at its joint coordinate
  // `q_joint` (ignored for a fixed joint): X_J X_T, RBDA eq. 4.1 and Table 4.1.
  PluckerTransform joint_transform(int link, double q_joint) const;

 private:
  BaseType base_;
  Vec3 base_position_;
  Quat base_orientation_;
  Vec3 gravity_{0.0, -9.81, 0.0};
  std::vector<Link> links_;
  int nq_ = 0, nv_ = 0;
};

// The base's rotation (base to world) and position for state q: the fixed base's pose, or the
// free base's first seven coordinates.
Mat3 base_rotation(const ArticulationModel& model, const Eigen::VectorXd& q);
Vec3 base_position(const ArticulationModel& model, const Eigen::VectorXd& q);

}  // namespace rigidlab
