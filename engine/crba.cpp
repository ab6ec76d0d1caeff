#include "engine/crba.hpp"

namespace rigidlab {
namespace {

// I^c_i = I_i + Σ over children of λ_X_c* I^c_c c_X_λ, leaves first (RBDA Table 6.2).
void composite_inertias(const ArticulationModel& model, ArticulationWorkspace& ws) {
  ws.IC[0].setZero();
  for (int i = 1; i <= model.link_count(); ++i) ws.IC[i] = model.links()[i - 1].inertia;
  for (int i = model.link_count(); i >= 1; --i) {
    const int parent = model.links()[i - 1].spec.parent + 1;
    if (parent > 0 || model.free_base())
      ws.IC[parent] += inertia_to_parent(ws.X_up[i], ws.IC[i]);
  }
}

// The force F (at body `i`, its coordinates) carried to the root: M_ij = S_jᵀ F at each
// ancestor joint j, and a free base's block row S_baseᵀ F at the end.
void fill_ancestors(const ArticulationModel& model, const ArticulationWorkspace& ws, int i,
                    int column, Vec6 F, Eigen::MatrixXd& M) {
  while (i > 0) {
    F = ws.X_up[i].transpose_force(F);
    i = model.links()[i - 1].spec.parent + 1;
    const int row = i > 0 ? model.links()[i - 1].v_index : -1;
    if (row >= 0) M(row, column) = M(column, row) = ws.S[i].dot(F);
  }
  if (model.free_base()) {  // S_baseᵀ F = (R f, R n)
    const Eigen::Matrix<double, 6, 1> base_row = ws.S_base.transpose() * F;
    M.block<6, 1>(0, column) = base_row;
    M.block<1, 6>(column, 0) = base_row.transpose();
  }
}

}  // namespace

void composite_rigid_body(const ArticulationModel& model, const Eigen::VectorXd& q,
                          ArticulationWorkspace& ws, Eigen::MatrixXd& mass_matrix) {
  forward_kinematics(model, q, ws);
  composite_inertias(model, ws);
  mass_matrix.setZero(model.nv(), model.nv());
  for (int i = 1; i <= model.link_count(); ++i) {
    const int column = model.links()[i - 1].v_index;
    if (column < 0) continue;
    const Vec6 F = ws.IC[i] * ws.S[i];
    mass_matrix(column, column) = ws.S[i].dot(F);
    fill_ancestors(model, ws, i, column, F, mass_matrix);
  }
  if (model.free_base())  // the whole articulation as one rigid body about the base
    mass_matrix.topLeftCorner<6, 6>() = ws.S_base.transpose() * ws.IC[0] * ws.S_base;
}

}  // namespace rigidlab
