#include "engine/articulation_kinematics.hpp"

namespace rigidlab {
namespace {

int body_of(int link) { return link + 1; }
int parent_body(const Link& link) { return link.spec.parent + 1; }

// Rotates the body-coordinate angular velocity of `body` into the world.
Vec3 world_angular(const ArticulationWorkspace& ws, int body) {
  return ws.rotation[body] * top(ws.v[body]);
}

}  // namespace

void ArticulationWorkspace::resize(const ArticulationModel& model) {
  const std::size_t n = static_cast<std::size_t>(model.link_count()) + 1;
  X_up.resize(n);
  rotation.resize(n);
  position.resize(n);
  S.assign(n, Vec6::Zero());
  v.assign(n, Vec6::Zero());
  c.assign(n, Vec6::Zero());
  p.assign(n, Vec6::Zero());
  IA.assign(n, Mat6::Zero());
  pA.assign(n, Vec6::Zero());
  U.assign(n, Vec6::Zero());
  D.assign(n, 0.0);
  u.assign(n, 0.0);
  a.assign(n, Vec6::Zero());
  f.assign(n, Vec6::Zero());
  IC.assign(n, Mat6::Zero());
}

void forward_kinematics(const ArticulationModel& model, const Eigen::VectorXd& q,
                        ArticulationWorkspace& ws) {
  const Mat3 base_to_world = base_rotation(model, q);
  ws.rotation[0] = base_to_world;
  ws.position[0] = base_position(model, q);
  ws.X_up[0] = {base_to_world.transpose(), ws.position[0]};
  if (model.free_base()) {
    ws.S_base.setZero();
    ws.S_base.topRightCorner<3, 3>() = base_to_world.transpose();
    ws.S_base.bottomLeftCorner<3, 3>() = base_to_world.transpose();
  }
  const std::vector<Link>& links = model.links();
  for (int k = 0; k < model.link_count(); ++k) {
    const Link& link = links[k];
    const int i = body_of(k), parent = parent_body(link);
    const double q_joint = link.q_index >= 0 ? q[link.q_index] : 0.0;
    const PluckerTransform X = model.joint_transform(k, q_joint);
    ws.X_up[i] = X;
    ws.rotation[i] = ws.rotation[parent] * X.E.transpose();
    ws.position[i] = ws.position[parent] + ws.rotation[parent] * X.r;
    // Motion subspace S (RBDA Table 4.1): [axis; 0] revolute, [0; axis] prismatic.
    switch (link.spec.joint) {
      case JointType::revolute: ws.S[i] = spatial(link.spec.axis, Vec3::Zero()); break;
      case JointType::prismatic: ws.S[i] = spatial(Vec3::Zero(), link.spec.axis); break;
      case JointType::fixed: ws.S[i].setZero(); break;
    }
  }
}

void forward_velocities(const ArticulationModel& model, const Eigen::VectorXd& v,
                        ArticulationWorkspace& ws) {
  if (model.free_base()) {
    // v_0 = S_base (v, ω); S_base depends on q, so c_0 = Ṡ_base q̇ = [Ṙᵀω; Ṙᵀv] =
    // [0; −ω_b × v_b] (Ṙᵀ = −Rᵀω̂): the spatial acceleration of a body whose origin moves at
    // constant world velocity is not zero.
    ws.v[0] = ws.S_base * v.head<6>();
    ws.c[0] = spatial(Vec3::Zero(), -top(ws.v[0]).cross(bottom(ws.v[0])));
  } else {
    ws.v[0].setZero();
    ws.c[0].setZero();
  }
  const std::vector<Link>& links = model.links();
  for (int k = 0; k < model.link_count(); ++k) {
    const Link& link = links[k];
    const int i = body_of(k);
    const Vec6 vJ = link.v_index >= 0 ? Vec6(ws.S[i] * v[link.v_index]) : Vec6(Vec6::Zero());
    ws.v[i] = ws.X_up[i].apply_motion(ws.v[parent_body(link)]) + vJ;  // v_i = X v_λ + S q̇
    ws.c[i] = crm(ws.v[i], vJ);                                        // c_i = v_i × S q̇
  }
}

Vec6 gravity_force(const ArticulationModel& model, const ArticulationWorkspace& ws, int body) {
  const Vec3 g_body = ws.rotation[body].transpose() * model.gravity();
  return model.links()[body - 1].inertia * spatial(Vec3::Zero(), g_body);
}

Vec3 link_point_position(const ArticulationWorkspace& ws, int link, const Vec3& point) {
  const int i = body_of(link);
  return ws.position[i] + ws.rotation[i] * point;
}

Vec3 link_point_velocity(const ArticulationWorkspace& ws, int link, const Vec3& point) {
  const int i = body_of(link);
  const Vec3 origin_velocity = ws.rotation[i] * bottom(ws.v[i]);
  return origin_velocity + world_angular(ws, i).cross(ws.rotation[i] * point);
}

Vec3 link_angular_velocity(const ArticulationWorkspace& ws, int link) {
  return world_angular(ws, body_of(link));
}

void point_jacobian(const ArticulationModel& model, const ArticulationWorkspace& ws, int link,
                    const Vec3& point, Eigen::MatrixXd& jacobian) {
  jacobian.setZero(6, model.nv());
  const Vec3 p = link_point_position(ws, link, point);
  const std::vector<Link>& links = model.links();
  for (int i = body_of(link); i > 0; i = parent_body(links[i - 1])) {
    const Link& joint = links[i - 1];
    if (joint.v_index < 0) continue;
    const Vec3 axis = ws.rotation[i] * joint.spec.axis;  // same in parent and link frames
    if (joint.spec.joint == JointType::revolute)
      jacobian.col(joint.v_index) << axis.cross(p - ws.position[i]), axis;
    else
      jacobian.col(joint.v_index) << axis, Vec3::Zero();
  }
  if (model.free_base()) {
    jacobian.block<3, 3>(0, 0).setIdentity();
    jacobian.block<3, 3>(0, 3) = -skew(p - ws.position[0]);
    jacobian.block<3, 3>(3, 3).setIdentity();
  }
}

void virtual_force(const ArticulationModel& model, const ArticulationWorkspace& ws, int link,
                   const Vec3& point, const Vec3& force, const Vec3& torque,
                   Eigen::VectorXd& tau) {
  tau.setZero(model.nv());
  const Vec3 p = link_point_position(ws, link, point);
  const std::vector<Link>& links = model.links();
  for (int i = body_of(link); i > 0; i = parent_body(links[i - 1])) {
    const Link& joint = links[i - 1];
    if (joint.v_index < 0) continue;
    const Vec3 axis = ws.rotation[i] * joint.spec.axis;
    // Column j of J dotted with (F, n): â·((p − o) × F + n) for a revolute joint, â·F for a
    // prismatic one.
    tau[joint.v_index] = joint.spec.joint == JointType::revolute
                             ? axis.dot((p - ws.position[i]).cross(force) + torque)
                             : axis.dot(force);
  }
  if (model.free_base()) {
    tau.head<3>() = force;
    tau.segment<3>(3) = (p - ws.position[0]).cross(force) + torque;
  }
}

double kinetic_energy(const ArticulationModel& model, const ArticulationWorkspace& ws) {
  double twice = 0.0;
  for (int k = 0; k < model.link_count(); ++k) {
    const Vec6& v = ws.v[body_of(k)];
    twice += v.dot(model.links()[k].inertia * v);
  }
  return 0.5 * twice;
}

double potential_energy(const ArticulationModel& model, const ArticulationWorkspace& ws) {
  double energy = 0.0;
  for (int k = 0; k < model.link_count(); ++k) {
    const LinkSpec& spec = model.links()[k].spec;
    energy -= spec.mass * model.gravity().dot(link_point_position(ws, k, spec.com));
  }
  return energy;
}

void momentum(const ArticulationModel& model, const ArticulationWorkspace& ws, Vec3& linear,
              Vec3& angular) {
  linear.setZero();
  angular.setZero();
  for (int k = 0; k < model.link_count(); ++k) {
    const LinkSpec& spec = model.links()[k].spec;
    const Mat3& R = ws.rotation[body_of(k)];
    const Vec3 com = link_point_position(ws, k, spec.com);
    const Vec3 com_velocity = link_point_velocity(ws, k, spec.com);
    const Vec3 omega = link_angular_velocity(ws, k);
    linear += spec.mass * com_velocity;
    angular += spec.mass * com.cross(com_velocity) + R * (spec.inertia * (R.transpose() * omega));
  }
}

double center_of_mass(const ArticulationModel& model, const ArticulationWorkspace& ws,
                      Vec3& com) {
  double mass = 0.0;
  Vec3 moment = Vec3::Zero();
  for (int k = 0; k < model.link_count(); ++k) {
    const LinkSpec& spec = model.links()[k].spec;
    mass += spec.mass;
    moment += spec.mass * link_point_position(ws, k, spec.com);
  }
  com = mass > 0.0 ? Vec3(moment / mass) : ws.position[0];
  return mass;
}

}  // namespace rigidlab
