// The constraint solver of a world: Box2D v3's solver stages (solver.c: b2SolverStage) over
// ONE array of solver bodies (engine/constraint_row.hpp SolverBody, slot i = the world's body
// i, the last slot the ground the planes belong to) shared by the contacts
// (engine/contact_constraints.hpp) and the joints (engine/constraint.hpp).
//
// The stages of one substep, as World::step runs them (docs/architecture.md has the whole
// pipeline):
//   prepare      find the contacts, build the joints' rows, effective masses, block matrices
//   warm start   apply the impulses each row ended the previous step with (scaled by the ratio
//                of the time steps)
//   solve        `iterations` Gauss-Seidel sweeps over joints then contacts, alternating
//                direction, rigid on the velocities (more on a step where contacts begin
//                without a warm start: the cold start, engine/solver.cpp Solver::solve);
//                soft_step also sweeps its soft position feedback ("with bias", below)
//                each time, and solves the equality rows of the joints that form a forest
//                exactly in each sweep (engine/joint_tree.hpp)
//   integrate    the solver bodies record how far they moved (Δx = h (u + u_push), Δθ the
//   positions    same) while the integrator's position stage moves the bodies
//   relax        soft_step: `relax_iterations` rigid sweeps without position feedback, so the
//                velocity the feedback added does not stay (Catto, "Solver2D": soft step)
//   restitution  the bounces, on the end-of-step velocities (engine/contact_constraints.hpp)
//   correct      sequential_impulses: non-linear Gauss-Seidel position sweeps for contacts and
//                joint rows (Box2D v2.4's position solver)
//   store        the impulses, for the reports and the next step's warm start
//   project      sequential_impulses: the joints' velocities on their rows at the final poses
//                (RATTLE's velocity half; engine/solver.cpp), after the end-of-step velocities
// Box2D v3 runs the prepare stage once per step and its substeps inside the solver; here a
// world substep is a whole pass (forces, collision, all stages), because the integrators
// evaluate forces at every substep and the contacts are found at the substep's poses.
//
// soft_step's position feedback. Box2D v3 sweeps each row once with its soft bias on the body
// velocities and then relaxes: rigid sweeps without bias that take the push-out velocity out
// again. That needs the relax sweeps to converge, which Box2D gets from its 4 substeps; at one
// substep a column of 20 boxes keeps a part of each step's push-out and bounces ever higher
// (measured here: the top 4 cm up and down within a second, then falling). So the soft rows
// act on separate push velocities (the split impulses of E. Catto, "Modeling and Solving
// Constraints", GDC 2009, and Bullet's split impulse), which move the positions in this
// substep and are then dropped: the body velocities never carry the push-out, and relax is
// left with what it is for, the velocities at the moved positions. The soft rows are Box2D's
// own (make_soft with contact_hertz / joint_hertz and their damping ratios, the push-out
// speed bounded by contact_push_speed); as they carry no load (the velocity rows do), a
// stack does not sag by load/(m ω²) as Box2D's does (1.7 cm for eight unit boxes at 30 Hz).
#pragma once

#include <cstddef>
#include <vector>

#include "engine/body.hpp"
#include "engine/constraint.hpp"
#include "engine/constraint_row.hpp"
#include "engine/contact_constraints.hpp"
#include "engine/integrators.hpp"
#include "engine/joint_blocks.hpp"
#include "engine/joint_tree.hpp"
#include "engine/solver_settings.hpp"
#include "engine/step_poll.hpp"

namespace rigidlab {

class Solver {
 public:
  SolverKind kind = SolverKind::soft_step;
  ContactSettings settings;
  StepPoll* poll = nullptr;  // World::step's stop check during a step, else null
  // What the integrator's velocity stage left for its position stage (engine/integrators.hpp),
  // by which the joints' look-ahead (build_rows_ahead) finds the pose the position stage
  // reaches for given velocities; null: orientations turn by exp(h ω).
  const StageWorkspace* stages = nullptr;

  // ---- the shared arrays (sized by begin; slot ground() is the planes' ground) ----
  void begin(std::size_t body_count);
  SolverBody* bodies() { return bodies_.data(); }
  const SolverBody* bodies() const { return bodies_.data(); }
  // soft_step's push velocities (zero for sequential_impulses), by slot: the positions move
  // with bodies() + pushes().
  const SolverBody* pushes() const { return pushes_.data(); }
  Acceleration* accelerations() { return accelerations_.data(); }
  std::size_t ground() const { return bodies_.size() - 1; }

  // ---- the stages of a substep of length h ----
  // `joints` with the indices of their bodies (no_body for the world), resolved by the world.
  struct JointRef {
    Constraint* constraint;
    std::size_t a, b;
  };
  void prepare(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
               const std::vector<Plane>& planes, const std::vector<JointRef>& joints, double h);
  void warm_start();
  void solve();
  void integrate_positions();
  void relax();
  void restitution();
  // sequential_impulses only; returns the first body whose state is not finite, or all_finite.
  std::size_t correct_positions(std::vector<Body>& bodies);
  void store();
  // sequential_impulses only, after the end-of-step velocities are written: the joints'
  // velocity rows at the final poses (RATTLE's velocity half, engine/solver.cpp).
  void project_velocities(std::vector<Body>& bodies);

  // ---- results ----
  const std::vector<ContactInfo>& contacts() const { return contacts_.contacts(); }
  std::size_t contact_point_count() const { return contacts_.point_count(); }
  // The largest constraint velocity error (m/s or rad/s) seen by each sweep of the solve stage
  // of the last substep (w:solver_report()).
  const std::vector<double>& report() const { return report_; }
  ContactConstraints& contact_constraints() { return contacts_; }

  // ---- what the next step reads from the last (for the world's undo and saved states) ----
  void save(ContactConstraints::Cache& contacts, double& last_substep) const {
    contacts_.save(contacts);
    last_substep = last_h_;
  }
  void restore(const ContactConstraints::Cache& contacts, double last_substep) {
    contacts_.restore(contacts);
    last_h_ = last_substep;
  }
  // The undo of one step without copying (ContactConstraints::begin_step): what the step
  // started from is kept as it is replaced.
  void begin_step() {
    contacts_.begin_step();
    undo_h_ = last_h_;
  }
  void undo_step() {
    contacts_.undo_step();
    last_h_ = undo_h_;
  }
  // The joints' row impulses, flattened in order (Constraint::impulses), and back.
  // Per joint: the row count, the state it tracks (a hinge's turns), the impulses.
  template <class Joints>
  static void save_impulses(const Joints& joints, std::vector<double>& to) {
    to.clear();
    for (const auto& joint : joints) {
      to.push_back(static_cast<double>(joint->impulses_.size()));
      to.push_back(joint->tracked_);
      to.insert(to.end(), joint->impulses_.begin(), joint->impulses_.end());
    }
  }
  template <class Joints>
  static void restore_impulses(Joints& joints, const std::vector<double>& from) {
    std::size_t next = 0;
    for (auto& joint : joints) {
      const std::size_t count = static_cast<std::size_t>(from[next++]);
      joint->tracked_ = from[next++];
      joint->impulses_.assign(from.begin() + next, from.begin() + next + count);
      next += count;
    }
  }
  const ContactConstraints& contact_constraints() const { return contacts_; }

 private:
  // soft_step: whether the velocity sweeps have converged (engine/solver.cpp).
  bool settled();
  struct Row {
    ConstraintRow row;
    double push_impulse;  // on the push velocities
    Softness soft;        // soft_step's position feedback of equality rows and limits
    double error;         // C
    double bias;          // equality rows: R/h (curvature); springs and motors: −(the oscillator's
                          // end velocity)
    double push_target;   // springs and motors: the push velocity J v_push they reach
    double start_rate;    // springs and motors: C' at the start of the substep
    bool pushes;          // springs and motors: whether the push applies
    std::uint32_t a, b;   // solver slots
    JointRow::Kind kind;
    bool tree;            // in tree_ (engine/joint_tree.hpp)
    std::uint32_t block;  // the row's block in blocks_ (JointBlocks::none: swept alone); the
                          // block holds its impulses, and the bias the sweeps read
    int block_row;        // its row in that block
  };
  static constexpr int max_block = JointBlocks::max_size;
  struct Group {  // rows solved together: one row, or a block of 2 to 6 equality rows
    std::uint32_t first;
    std::uint8_t size;
    std::uint32_t block;  // index in blocks_ when size > 1
    bool tree = false;    // solved by tree_ (while its factor is valid)
  };
  Row make_row(const JointRow& spec, std::uint32_t a, std::uint32_t b) const;
  double sweep_joints(bool forward, bool push = false);
  double sweep_group(const Group& g);
  void push_group(const Group& g, bool feedback);
  void group_rows(std::size_t first);
  void push_joints(bool forward, bool feedback);
  double& impulse(Row& r, bool push);
  void offer_to_tree(const Group& g);
  void refresh_curvature();
  void build_tree(double compliance);
  double solve_tree(const JointTree::Factor& f, bool push);
  double joint_bias(const Row& r) const;
  void prepare_oscillator(Row& r, const JointRow& spec) const;
  void build_rows_ahead(Constraint& joint, const Body& a, const Body* b, std::uint32_t a_slot,
                        std::uint32_t b_slot);
  Quat orientation_ahead(const Body& body, std::uint32_t slot) const;
  void correct_joint_positions(std::vector<Body>& bodies, const std::vector<JointRef>& joints);
  void correct_block(const JointRow* rows, int size, Body& a, Body* b, const SolverBody& sa,
                     const SolverBody& sb) const;
  static void move_apart(const Jacobian& j, double lambda, Body& a, Body* b, const SolverBody& sa,
                         const SolverBody& sb);

  std::vector<SolverBody> bodies_;
  std::vector<SolverBody> pushes_;
  std::vector<Acceleration> accelerations_;
  ContactConstraints contacts_;
  std::vector<Row> rows_;
  std::vector<JointRow> scratch_;
  std::vector<JointRow> ahead_;
  std::vector<Group> groups_;
  // The joints' equality blocks that form a forest over the dynamic bodies, solved exactly in
  // one pass (engine/joint_tree.hpp): factored for the rigid velocity rows and for soft_step's
  // soft position rows; tree_rows_ maps the tree's rows to rows_.
  JointTree tree_;
  JointTree::Factor rigid_factor_, soft_factor_;
  std::vector<std::uint32_t> tree_rows_;
  std::vector<std::uint32_t> tree_offers_;  // the group of each offer
  std::vector<double> tree_bias_, tree_impulse_;
  JointBlocks blocks_;      // the groups of more than one row, as the sweeps read them
  bool fuse_pushes_ = false;  // no motor rows: sweep the velocity and push rows in one pass
  const std::vector<JointRef>* joints_ = nullptr;
  const std::vector<Body>* bodies_in_ = nullptr;
  std::vector<double> report_;
  double h_ = 0.0;
  double last_h_ = 0.0;
  double undo_h_ = 0.0;  // last_h_ when the step began (begin_step)
};

}  // namespace rigidlab
