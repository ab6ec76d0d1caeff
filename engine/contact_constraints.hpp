// The contacts of a step as constraints of the shared solver (engine/solver.hpp): found between
// the bodies' shapes and the static planes (engine/contact_finder.cpp: broad phase, narrow
// phase engine/narrow_phase.hpp, speculative contacts and their time of impact), each point three
// rows of engine/constraint_row.hpp (the normal and two friction directions), solved by the
// solver's stages, then stored for warm starting the next step.
//
// Per point: the normal row (001_* Appendix D: λ = −J v/(J W Jᵀ)) with λ ≥ 0, and two friction
// rows whose impulses stay in the disk of radius μ λn (Coulomb's cone; Catto 2005: the
// accumulated impulse is clamped, not each increment). Per sweep, for each manifold: the
// friction of each point, then the normals (as a block, below).
//
// Details, each a named scheme:
// - Patch friction (engine/contact_friction.cpp): a flat manifold (2-4 points, no sphere)
//   holds its friction as one patch instead of two rows per point: two tangent rows at the
//   centre of its points and a twist row about the normal, solved as a 3 x 3 block within μ of
//   the manifold's whole load (PhysX's patch friction). The points keep their share of the
//   patch's impulse for the reports and the warm start.
// - Friction directions: the first tangent along the point's slip (tangential relative
//   velocity) before the solve, the second across it; any orthonormal pair when it does not
//   slip (Duff et al., JCGT 2017). Sliding friction then opposes the slip, as Coulomb's law.
// - Warm starting: a point that touched in the previous step (same bodies or plane, same
//   `feature`, engine/narrow_phase.hpp) starts from the impulses it ended the previous step's
//   sweeps with, scaled by the ratio of the time steps; the friction impulse is kept as a world
//   vector and re-projected on the new tangents. A point whose feature is new continues the
//   nearest point of the previous step within match_distance (the position matching of
//   Bullet's persistent manifolds).
// - Speculative contacts (Catto, "Continuous Collision", GDC 2013; Box2D v3): points with a gap
//   s > 0 are constraints too, v_n ≥ −s/Δt: the bodies may close the gap in this step, not
//   more. Which gaps count: up to speculative_distance always; beyond it, out to what the
//   bodies can travel in the step, only when they really meet in the step: the time of impact
//   τ is found by conservative advancement (engine/time_of_impact.hpp) and the contact is taken
//   at the poses of τ (its normal, points and lever arms where the shapes touch), with s the
//   distance its points close from the start of the step to τ. A body flying past a corner
//   gets no contact (no "ghost" hit) and a fast ball hitting a floor sideways gets the lever
//   arm R of the real contact point.
// - Separation during the step (Box2D v3's contact_solver.c): s = s₀ + n·(Δx_b + Δθ_b × r_b −
//   Δx_a − Δθ_a × r_a), from how far the solver bodies moved (engine/constraint_row.hpp): the
//   relax and restitution stages see the gap the positions left.
// - Soft contacts (soft_step, Box2D v3 b2SolveContact): a touching point (s ≤ 0) is driven by
//   the bias max(massScale·biasRate·s, −push speed) with the soft coefficients of contact_hertz
//   and contact_damping_ratio (engine/constraint_row.hpp make_soft); relax solves it rigidly
//   and without bias. sequential_impulses solves it rigidly and moves the bodies apart after
//   the positions (below).
// - The normal impulses of a manifold are solved as a block (in the spirit of Box2D v2.4's
//   two-point block solver): with K = J W Jᵀ of its points, the accumulated impulses become
//   λ' = P λ − A (J v + bias), where for rigid rows A = K⁺ (the pseudo-inverse) and P = K⁺K,
//   and for soft rows A = (K + Γ)⁻¹ and P = A K, Γ = γ I the softness (the soft constraint
//   K Δλ + J v + bias + Γ λ' = 0 of all points at once). This reaches every point's target at
//   once; the four corners of a face are redundant (three independent normal motions: K has
//   the null vector c of the points' affine dependency, Σ cᵢ = 0, Σ cᵢ pᵢ = 0), and the
//   pseudo-inverse then gives the least-squares impulses: a symmetric load (a box landing flat,
//   a box in a stack) gets equal impulses and no spin, where sequential impulses always leave
//   the first point solved a little more loaded. K⁺ = (K + k c cᵀ)⁻¹ − c cᵀ/k (c unit, k > 0)
//   costs one 4 x 4 inverse. When only some points take part (a corner lifted off, a point
//   with a gap in a manifold that otherwise touches) they are solved as a smaller block,
//   (K_s + Γ_s) λ' = K_s λ − r over them (Γ_ii = 0 for a rigid row), so the manifold stays
//   symmetric where it was. Every answer is checked against the complementarity conditions
//   of its rows (each λ' in [0, cap]; a row at zero does not approach, a loaded row does not
//   separate): the least-squares answer is right only when the targets are consistent (c·r
//   = 0), and a face with one corner above a gap (v_n ≥ −s/Δt) and three touching (v_n ≥ 0)
//   is not, so the block solve sank two touching corners by |c·r|/2 and a stack rocked
//   (tests/engine/perturbed_stack_test.cpp). An answer that fails the check is replaced by
//   the first pattern of free and held rows that passes (contact_blocks.cpp solve_patterns);
//   only when none does are the points solved one by one.
// - Restitution, at the end of the step (Box2D v3's b2ApplyRestitution runs after the substeps
//   too): the positions have landed the bodies on the surface (a point that meets it during
//   the step is brought to it, not through it), and the velocities are then set to the
//   post-impact ones, so the state the step leaves is the end-of-step state (no step with the
//   body at rest on the surface before it bounces). A point bounces when e > 0, it touches at
//   the end of the step and its impact velocity w (< 0: the normal velocity it met the surface
//   with) is faster than the threshold: its target is the velocity whose next step follows the
//   reflected parabola, v_n = −e w − a_n Δt/2. Why: every integrator here moves positions by
//   Δt u with u the velocity the impulses act on, so they follow a parabola on which the
//   velocity at the start of a step is u − a_n Δt/2 and at its end u + a_n Δt/2 (a_n the
//   relative normal acceleration of the point, 0 for a body resting on a support). Reflecting
//   that parabola (w → −e w) keeps its energy, so the rebound apex is e² of the drop height at
//   60 Hz as at 1 kHz; w is that of the parabola at the surface, w = −√(w₀² − 2 a_n s) for a
//   point that closed a gap s during the step (w₀ = u_n − a_n Δt/2 at its start).
//   Impacts are events: the points that bounce solve together with the points that touched
//   already at the start of the step (a ball bouncing on a box that rests on the floor pushes
//   the box against the floor and rebounds as from the floor), each in increments ≥ 0 on top
//   of the sweeps; a point that had a gap at the start and was closed by another impact's
//   push (the next ball of a row) then has its own impact, with the velocity it has after that
//   event, in the next round. So a row of touching-but-apart balls passes the striker's speed
//   to the far ball, and a pair of elastic balls keeps its kinetic energy exactly (each round
//   reflects its normal velocities). A round with a bounce sweeps until it converges, within a
//   budget of manifold solves (contact_restitution.cpp round_work): a round spanning a heap
//   gets the velocity stage's `iterations` sweeps, as a round of landings does.
//   The speculative impulse the sweeps stopped such an impact with (inelastic, and passed on
//   inelastically along a chain of gaps closed in one step) is taken back first, where nothing
//   else pushed its bodies (take_back_speculative).
//   A support is the whole stack under a body, not only the floor: the bodies held by resting
//   contacts are found from the ground and static bodies up, contact by contact
//   (contact_restitution.cpp mark_supported), and taken at the velocities they had before the
//   step's forces (not what the sweeps left, which a soft column still giving way under the
//   impact would put into w); a resting contact between two held bodies that the sweeps opened
//   by a little still holds in the event, closing its gap s and no more (v_n ≥ −s/Δt). So a
//   ball leaves a column of boxes as from the floor (tests/engine/bounce_on_stack_test.cpp).
// - Lever arms after the positions moved: an impulse pair at one point conserves angular
//   momentum, but the relax and restitution impulses act after the bodies moved by Δx_a, Δx_b,
//   and with the arms of the start, x_a + r_a and x_b + r_b are then two points h (u_b − u_a)
//   apart: a bounce of two balls passing each other at 5 m/s would change the angular
//   momentum by that times the impulse. So the arms are moved to one point again, r_a + (1 −
//   w)(Δx_b − Δx_a) and r_b − w (Δx_b − Δx_a), w = m_a⁻¹/(m_a⁻¹ + m_b⁻¹) (the point moves with
//   the lighter body; nothing changes against a plane or a static body), and the rows are
//   prepared again, for the manifolds whose bodies moved apart by more than the landing
//   tolerance in the step (resting contacts keep theirs). Two spheres that moved apart get
//   their contact at the end poses instead: the normal turned to the line of their centres,
//   the arms along it through the centres (engine/contact_constraints.cpp turn_to_centres),
//   so the impulses stay central (no spin from a frictionless bounce) and at one point
//   (angular momentum kept); their bounce target is then the normal velocity that gives the
//   pair the kinetic energy of the reflection, |v₀|² − (1 − e²) w² (contact_restitution.cpp
//   turned_target): an elastic pair keeps its energy exactly.
// - Position correction (sequential_impulses only): non-linear Gauss-Seidel (Box2D v2.4
//   b2ContactSolver::SolvePositionConstraints) on the separation recomputed from each point's
//   anchors, C = clamp(β (s + slop), −max_correction, 0), moving the bodies by −C/K along n.
//   Only positions change, so overlap is removed without adding energy. Within a manifold the
//   correction is first applied at the centroid with the mean separation, then to the points
//   Jacobi-style (all measured at the same poses, each applying 1/count of its correction), so
//   a box sunk evenly rises straight instead of being tipped corner after corner.
//
// Nothing here allocates once the vectors have grown to the largest number of contacts seen.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/body.hpp"
#include "engine/body_store.hpp"
#include "engine/constraint_row.hpp"
#include "engine/contact_pairs.hpp"
#include "engine/narrow_phase.hpp"
#include "engine/plane.hpp"
#include "engine/solver_settings.hpp"
#include "engine/step_poll.hpp"

namespace rigidlab {

inline constexpr std::size_t no_plane = static_cast<std::size_t>(-1);

// One contact point of the last step, for reports and for warm starting the next step.
struct ContactInfo {
  BodyId a;                      // body a; no_body_id when a is a plane
  BodyId b;                      // body b
  std::size_t plane = no_plane;  // index of the plane, when a is a plane
  std::uint32_t feature = 0;
  Vec3 point = Vec3::Zero();             // m, world, midway between the surfaces when found
  Vec3 normal = Vec3::UnitY();           // unit, from a to b (a plane's own normal)
  double depth = 0.0;                    // m, overlap when found (< 0: a gap the step could close)
  double normal_impulse = 0.0;           // N s over the step: b received normal_impulse·normal
  Vec3 friction_impulse = Vec3::Zero();  // N s, tangential, on b (a the opposite)
  double restitution = 0.0;              // the mixed material of the pair (engine/plane.hpp)
  double friction = 0.0;
  double sweep_impulse = 0.0;            // N s: the normal impulse before restitution (the
                                         // load the next step is warm started with)
};

// A point that touched (depth ≥ 0) or pushed (normal impulse > 0) in the step: the contacts
// worth reporting. The others were speculative and stayed apart.
inline bool touched(const ContactInfo& c) { return c.depth >= 0.0 || c.normal_impulse > 0.0; }

// How a sweep treats the normal rows (see the header comment):
//   velocity  before the positions move, rigid: a touching point may not approach (v_n ≥ 0), a
//             point with a gap s may close it within the substep and no more (v_n ≥ −s/Δt);
//   push      soft_step's position feedback on the push velocities: an overlap is pushed out
//             by the soft row of contact_hertz and contact_damping_ratio (Box2D v3's soft
//             contact), the push then moving the positions but never the velocities;
//   relax     after the positions moved: a point touching now may not approach (v_n ≥ 0); a
//             point with a gap now only gives back what the sweeps pushed with, down to
//             v_n = −gap/Δt (Box2D v3's relax), and never pushes: a body still coming in is
//             left to the next step.
enum class NormalMode { velocity, push, relax };

// One round of the restitution stage of the last substep, as it ran (for tests and reports):
// how many manifolds it swept, the sweeps it was allowed and did, and the manifold solves it
// spent (counted where round_sweep solves one).
struct RestitutionRound {
  std::uint32_t manifolds = 0;
  int allowed_sweeps = 0, sweeps = 0;
  long solves = 0;
  bool bounces = false;  // some target > 0 (a bounce), else landings only
};

class ContactConstraints {
 public:
  // A point's flag after the restitution stage: it was in an impact round.
  static constexpr std::uint8_t took_part_flag = 16;
  // The body pairs that never collide (ContactPairs::excluded), set by the world.
  std::vector<std::pair<std::uint64_t, std::uint64_t>>& excluded_pairs() {
    return pairs_.excluded();
  }

  // ---- the stages (engine/solver.cpp calls them) ----
  // Finds the contacts at the bodies' present poses (slot i of `solver` is body i; slot
  // bodies.size() is the ground, for planes) and prepares their rows. `ids` names the bodies.
  void find(const std::vector<Body>& bodies, const std::vector<BodyId>& ids,
            const std::vector<Plane>& planes, const SolverBody* solver,
            const Acceleration* acceleration, const ContactSettings& settings, double h);
  void warm_start(SolverBody* solver);
  // After the solver bodies recorded how far they moved: each point's gap now, and the lever
  // arms moved to one point again for the relax and restitution impulses (see below).
  void positions_moved(SolverBody* solver);
  // One sweep over all manifolds; returns the largest normal velocity error seen. With `push`,
  // each manifold's push rows (NormalMode::push on those velocities) are solved right after
  // its `mode` rows: the two sets of velocities are apart, so this is the same as a sweep of
  // `mode` followed by a push sweep, with one pass over the contacts' memory instead of two.
  double sweep(SolverBody* solver, NormalMode mode, bool forward, SolverBody* push = nullptr);
  void restitution(SolverBody* solver, const Acceleration* acceleration, StepPoll* poll);
  // sequential_impulses' position sweeps at the bodies' present poses; returns the index of
  // the first body in a contact whose state is not finite, or all_finite.
  std::size_t correct_positions(std::vector<Body>& bodies, StepPoll* poll);
  void store(double h);

  // ---- bookkeeping ----
  std::size_t point_count() const { return points_.size(); }
  // The restitution rounds of the last substep that had any (at most 32).
  const std::vector<RestitutionRound>& restitution_rounds() const { return rounds_; }
  // The manifolds the last find made, as the pairs of solver slots (a is the ground slot for a
  // plane): the world's sleep stage wakes an island a pair reaches (engine/islands.hpp).
  std::size_t manifold_count() const { return manifolds_.size(); }
  std::pair<std::uint32_t, std::uint32_t> manifold_slots(std::size_t m) const {
    return {manifolds_[m].a, manifolds_[m].b};
  }
  // How many points of this step warm_start found no previous point for (new contacts).
  std::size_t cold_points() const { return cold_points_; }
  // The longest chain of new touching points in series under a body, down to what holds it:
  // a fixed body, the ground, or a body with a touching point that was warm started (0: no new
  // touching point rests on anything held). A new point with a gap carries no load yet and is
  // no link. The pyramid of 210 on its first step: 20; a box landing on the floor or on a
  // resting stack: 1; a settling heap of spheres: at most 2 (measured, settle/256 to 4096).
  std::size_t cold_chain() const { return cold_chain_; }
  // soft_step: no point of the substep is sunk beyond the push's slop, so the push sweeps have
  // nothing to do (their velocities stay 0).
  bool push_idle() {
    if (!push_rows_.ready) prepare_mode(NormalMode::push);
    return push_rows_.idle;
  }
  // Every point of the last step (touched and speculative), ordered by body a, then body b or
  // plane, then feature.
  const std::vector<ContactInfo>& contacts() const { return contacts_; }
  // The body left the world: its contacts are forgotten.
  void body_removed(BodyId id);
  // The state a step reads (the previous step's points and time step), for the world's undo
  // and its saved states.
  struct Cache {
    std::vector<ContactInfo> contacts;
    double last_dt = 0.0;
  };
  void save(Cache& to) const {
    to.contacts = contacts_;
    to.last_dt = last_dt_;
  }
  void restore(const Cache& from) {
    contacts_ = from.contacts;
    last_dt_ = from.last_dt;
  }
  // The world's undo of one step, without copying the points (World::save_step): begin_step
  // marks the points the step starts from; the step's first store() sets them aside (a swap of
  // buffers) instead of reusing their memory, and undo_step() puts them back as they were.
  void begin_step() {
    undo_open_ = true;
    undo_kept_ = false;
    undo_dt_ = last_dt_;
  }
  void undo_step() {
    if (undo_kept_) contacts_.swap(undo_contacts_);
    last_dt_ = undo_dt_;
    undo_open_ = undo_kept_ = false;
  }

 private:
  // A point is kept in three arrays by what reads it (the sweeps visit each point some 24
  // times a step; a 700-byte point streamed most of itself from L2/L3 each time, and settle/4096
  // missed L2 35 times as often per contact as settle/256):
  // - NormalRow (normals_): what the normal sweeps and the block solves read, two cache lines.
  //   Its row's linear part is the manifold's normal, shared by its points:
  //   J = [−n, −angular_a, n, angular_b] (engine/constraint_row.hpp).
  // - FrictionRows (frictions_): the point's two friction rows (read by the sweeps only for a
  //   manifold without a patch: engine/contact_friction.cpp).
  // - Point (points_): the rest, read once or twice a step (arms, witnesses, gaps, restitution).
  // The arrays are not zeroed when a point is made (DefaultInit): add_manifold sets every field
  // of NormalRow and Point (a field added here must be set there too).
  // Its first cache line is what a sweep needs to find the row's velocity and impulse (a
  // manifold whose rows carry nothing and do not approach is left alone: solve_normals), the
  // second what it needs to change them.
  struct alignas(64) NormalRow {
    Vec3 angular_a, angular_b;    // r_a × n, r_b × n
    double impulse;               // N s: the sweeps' accumulated λ (≥ 0)
    double push_impulse;          // N s: soft_step's position feedback (on the push velocities)
    Vec3 weighted_a, weighted_b;  // I_a⁻¹ angular_a, I_b⁻¹ angular_b
    double mass;                  // 1/(J W Jᵀ); 0 when neither body can move along n
    double relax_cap;             // N s: relax may only take back impulse from a point with a gap
  };
  struct FrictionRows {
    ConstraintRow tangent1, tangent2;
  };
  struct Point {
    Vec3 r_a, r_b;            // m, from each COM to the point (at the poses of the start;
                              // moved to the end poses by positions_moved)
    Vec3 start_r_a, start_r_b;  // m, the arms at the start (the impact velocity's)
    Vec3 anchor_a, anchor_b;  // witness points in body coordinates (a plane's: world)
    Vec3 point;               // m, world, when found
    double separation;        // m: the gap at the start of the substep (< 0 overlap)
    double end_separation;    // m: the gap after the positions moved
    double approach;          // m/s: J v before the solve
    double slop;              // m: the overlap sequential_impulses' position sweeps leave
    double restitution_impulse;  // N s: added by the restitution rounds
    double round_impulse;     // N s: this restitution round's increment
    double target;            // m/s: J v the restitution round drives toward
    std::uint32_t feature;
    std::uint8_t flags;       // of the restitution stage (contact_restitution.cpp)
    bool turned;              // a sphere pair taken at the end poses (positions_moved)
  };
  // The normal row of point k (of manifold m) as the sweeps use it: its velocity J v, the
  // impulse λ applied along it (Δv = W Jᵀ λ): row_velocity/apply_row of
  // engine/constraint_row.hpp with linear = m.normal.
  double normal_velocity(const Vec3& normal, std::uint32_t k, const SolverBody& a,
                         const SolverBody& b) const {
    const NormalRow& row = normals_[k];
    return velocity_along(normal, row.angular_a, row.angular_b, b.velocity - a.velocity,
                          a.angular_velocity, b.angular_velocity);
  }
  void apply_normal(const Vec3& normal, std::uint32_t k, SolverBody& a, SolverBody& b,
                    double lambda) const {
    const NormalRow& row = normals_[k];
    apply_parts(normal, row.weighted_a, row.weighted_b, a, b, lambda);
  }
  // Sets point k's normal row for arms r_a, r_b (prepare_row of engine/constraint_row.hpp).
  void prepare_normal(std::uint32_t k, const Vec3& normal, const Vec3& r_a, const Vec3& r_b,
                      const SolverBody& a, const SolverBody& b);
  // What the sweeps read of a manifold is its first cache line (the rest is read once or twice
  // a step).
  struct alignas(64) Manifold {
    std::uint32_t a, b;          // solver slots
    std::uint32_t first, count;  // points
    Vec3 normal;
    double friction;
    double compliance;           // γ of the soft block, 1/kg
    bool block;                  // the block matrices below are usable (once prepared)
    bool patch;                  // its friction is a patch (patches_, prepare_patch)
    std::uint8_t block_state;    // BlockState: the block matrices made, or how they will be
    BodyId id_a, id_b;
    std::size_t plane;
    Vec3 start_normal;           // the normal found (positions_moved may turn `normal`)
    double restitution;
    double radius_a, radius_b;   // m, of a sphere (its witness is recomputed), else 0
    Softness softness;
  };
  using Mat4 = Eigen::Matrix<double, 4, 4, Eigen::DontAlign>;
  using Vec4 = Eigen::Matrix<double, 4, 1, Eigen::DontAlign>;
  // A subset's matrix made ready to solve (contact_blocks.cpp), for the rows `key` names:
  // bits 0-3 the free rows, 4-7 the rows taking part.
  struct SubsetFactor {
    static constexpr std::uint16_t none = 0xffff;
    Eigen::Matrix4d data;
    std::uint16_t key = none;
    int n = 0;
    bool ok = false;
    void make(const Eigen::Matrix4d& matrix, int size, double threshold);
    void solve(const Eigen::Vector4d& right, Eigen::Vector4d& solved) const;
  };
  // On cache lines: a sweep's block solve reads one inverse (two lines) and c.
  struct alignas(64) Block {
    Mat4 rigid_inverse;  // K⁺
    Mat4 soft_inverse;   // (K + Γ)⁻¹ on the range of K
    Vec4 null;           // c, the unit null vector of K of four points (else zero)
    Mat4 k;              // J W Jᵀ of the normal rows
    SubsetFactor subset[2][2];  // the last subsets solved, rigid and soft (solve_subset)
  };

  // contact_finder.cpp
  void add_pair(const std::vector<Body>& bodies, const rigidlab::Manifold& m, std::size_t a,
                std::size_t b, std::size_t plane, const Plane* plane_material);
  void add_manifold(const std::vector<Body>& bodies, const rigidlab::Manifold& m, std::size_t a,
                    std::size_t b, std::size_t plane, const Plane* plane_material, double toi,
                    const Pose& pose_a, const Pose& pose_b);
  void central_sphere_point(Manifold& m, Point& p, const Vec3& centre_a,
                            const Vec3& centre_b) const;
  double touch_tolerance() const { return touch_tolerance_; }
  // The largest gap at which a point counts as touching after the positions moved: a point the
  // sweeps brought to the surface lands there up to rounding.
  double landed_tolerance() const { return 1e-3 * touch_tolerance_; }

  // contact_constraints.cpp
  std::pair<const ContactInfo*, const ContactInfo*> previous_points(const Manifold& m,
                                                                    const ContactInfo* hint) const;
  const ContactInfo* previous_point(const Point& p, const ContactInfo* first,
                                    const ContactInfo* last) const;
  double current_separation(const Manifold& m, const Point& p) const;
  void turn_to_centres(Manifold& m, const Vec3& apart);
  void take_back_speculative();
  bool normal_bias(const Manifold& m, std::uint32_t k, NormalMode mode, double& bias,
                   Softness& soft) const;
  // normal_bias of every point for `mode`, as the block form takes it (below), made once per
  // stage instead of once per sweep: the biases depend on the gaps, fixed within a stage.
  void prepare_mode(NormalMode mode);
  void solve_friction(Manifold& m, bool forward);
  template <NormalMode mode>
  double solve_normals(std::size_t manifold);
  template <NormalMode mode>
  double sweep_as(SolverBody* solver, bool forward, SolverBody* push);
  // How many manifolds ahead a sweep asks for the solver bodies (sweep_as), and the request.
  static constexpr std::size_t prefetch_distance = 6;
  static void prefetch_bodies(const SolverBody* solver, const Manifold& m) {
    __builtin_prefetch(solver + m.a, 1);
    __builtin_prefetch(solver + m.b, 1);
  }
  // Which impulse of a point a block solve accumulates.
  enum class Impulse { sweep, round, push };

  // contact_blocks.cpp
  // The rigid block matrices, and the soft ones (push sweeps) with soft_too.
  void prepare_block(std::size_t manifold, bool soft_too = true);
  // A manifold's block matrices are made when a solve first needs them (block_usable): a
  // third of a pyramid's manifolds (boxes side by side, no load, not approaching) never do.
  // Made from the rows as they are then, which are those the eager order used: the rows change
  // only in positions_moved, which re-made a prepared block without its soft part (the push
  // sweeps are over), as a block first needed after it is made (rigid_only).
  enum BlockState : std::uint8_t { unprepared = 0, rigid_only = 1, prepared = 2 };
  bool block_usable(std::size_t manifold) {
    Manifold& m = manifolds_[manifold];
    if (m.block_state != prepared) prepare_block(manifold, m.block_state == unprepared);
    return m.block;
  }
  template <Impulse which>
  double& impulse_of(std::uint32_t k) {
    if constexpr (which == Impulse::sweep) return normals_[k].impulse;
    else if constexpr (which == Impulse::round) return points_[k].round_impulse;
    else return normals_[k].push_impulse;
  }
  bool solve_block(std::size_t manifold, const Mat4& inverse, double gamma,
                   const double* residual, const double* cap, Impulse which, Vec4* result);
  bool solve_subset(std::size_t manifold, const bool* active, const double* residual,
                    const double* gamma, const double* cap, Impulse which, const Vec4* first);
  // The same as templates on `which` (the sweeps' calls: the impulse is known where they are
  // compiled); the two above call these.
  template <Impulse which>
  bool solve_block(std::size_t manifold, const Mat4& inverse, double gamma,
                   const double* residual, const double* cap, Vec4* result);
  template <Impulse which>
  bool solve_subset(std::size_t manifold, const bool* active, const double* residual,
                    const double* gamma, const double* cap, const Vec4* first);
  static bool complementary(const Mat4& k, const int* taking, int taken, const Vec4& old,
                            const Vec4& next, const Vec4& residual, const double* gamma,
                            const double* cap);
  static bool solve_patterns(const Mat4& k, const int* taking, int taken, const Vec4& old,
                             const Vec4& residual, const double* gamma, const double* cap,
                             Vec4& next);

  // contact_restitution.cpp
  void mark_supported(const Acceleration* acceleration);
  double impact_velocity(const Manifold& m, const Point& p) const;
  double turned_target(const Manifold& m, double w, double a_n) const;
  double normal_acceleration(const Manifold& m, const Point& p) const;
  bool start_round(bool first);
  void end_round(Point& p);
  void link_bodies();
  void gather_round(int hops);
  double round_sweep(bool forward, double& peak);

  // contact_friction.cpp: the friction of a flat manifold as one patch (see there).
  struct Patch {
    ConstraintRow rows[3];  // the two tangents at the centre, the twist about the normal
    Eigen::Matrix<double, 3, 3, Eigen::DontAlign> inverse;  // (J W Jᵀ)⁻¹ of the rows
    Vec3 r_a, r_b;          // m, the centre's lever arms
    double distance[max_manifold_points];  // m, each point's from the centre, in the plane
    double spread;          // m², Σ distance²
  };                        // (Manifold::patch says whether it is used)
  void prepare_patch(std::size_t manifold, const SolverBody& a, const SolverBody& b);
  // Whether prepare_patch can make m a patch (its points' friction rows are then prepared only
  // when it does not: prepare_friction).
  static bool may_be_patch(const Manifold& m) {
    return !(m.count < 2 || !(m.friction > 0.0) || m.radius_a > 0.0 || m.radius_b > 0.0);
  }
  // The friction rows of m's points at their present arms.
  void prepare_friction(const Manifold& m, const SolverBody& a, const SolverBody& b);
  void warm_start_patch(std::size_t manifold);
  void solve_patch(std::size_t manifold);
  void spread_patch(std::size_t manifold);
  std::vector<Patch> patches_;  // by manifold

  // contact_positions.cpp
  void witnesses(const std::vector<Body>& bodies, const Manifold& m, const Point& p, Vec3& pa,
                 Vec3& pb) const;
  void move_apart(std::vector<Body>& bodies, const Manifold& m, const Point& p, const Vec3& point,
                  double correction);

  // The step being solved.
  const ContactSettings* settings_ = nullptr;
  double h_ = 0.0;
  double touch_tolerance_ = 1e-6;  // of settings_ (contact_finder.cpp find), read per point
  std::size_t ground_ = 0;
  SolverBody* solver_ = nullptr;  // during a stage
  const SolverBody* found_with_ = nullptr;
  const std::vector<BodyId>* ids_ = nullptr;
  const Acceleration* acceleration_ = nullptr;
  ContactPairs pairs_;  // the broad phase, kept from step to step
  std::vector<Manifold> manifolds_;
  // An allocator that default-initialises (std::allocator value-initialises: emplace_back()
  // zeroed a point's bytes before add_manifold wrote them all again).
  template <class T>
  struct DefaultInit : std::allocator<T> {
    template <class U>
    struct rebind {
      using other = DefaultInit<U>;
    };
    DefaultInit() = default;
    template <class U>
    DefaultInit(const DefaultInit<U>&) noexcept {}
    template <class U>
    void construct(U* at) noexcept(std::is_nothrow_default_constructible<U>::value) {
      ::new (static_cast<void*>(at)) U;
    }
    template <class U, class... Args>
    void construct(U* at, Args&&... args) {
      ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
    }
  };
  std::vector<Point, DefaultInit<Point>> points_;
  std::vector<NormalRow, DefaultInit<NormalRow>> normals_;       // by point (see Point)
  std::vector<FrictionRows, DefaultInit<FrictionRows>> frictions_;  // by point
  std::vector<Block> blocks_;  // by manifold
  // Per NormalMode, per point (prepare_mode): whether its normal row takes part, and its
  // residual offset bias/mass_scale (r = J v + offset, engine/contact_constraints.cpp
  // solve_normals). Valid while `ready`: find and positions_moved change the gaps.
  struct ModeRow {
    double offset;
    bool active;
  };
  struct ModeRows {
    std::vector<ModeRow> rows;
    bool ready = false;
    bool idle = true;  // no active row has a bias (push: no overlap beyond the push's slop)
  };
  ModeRows velocity_rows_, push_rows_, relax_rows_;
  ModeRows& mode_rows(NormalMode mode) {
    return mode == NormalMode::velocity ? velocity_rows_
                                        : mode == NormalMode::push ? push_rows_ : relax_rows_;
  }
  // Restitution: per body, whether a resting contact supports it; its velocity then.
  std::vector<unsigned char> supported_;
  std::vector<unsigned char> held_;  // per body: pushed by a contact that keeps its impulse
  std::vector<std::uint32_t> round_manifolds_;  // the manifolds a restitution round sweeps
  bool bounces_ = false;  // the present round has a bounce (a target > 0)
  std::vector<RestitutionRound> rounds_;  // of the last restitution stage
  // A later round of landings sweeps the manifolds near its impacts (gather_round): each
  // body's manifolds (body_manifolds_ from body_first_[slot]), and marks for the search.
  std::vector<std::uint32_t> body_first_, body_manifolds_, frontier_, next_frontier_;
  std::vector<unsigned char> body_reached_, manifold_taken_;
  long round_solves_ = 0;                 // counted by round_sweep
  std::vector<Vec3> start_velocity_, start_angular_velocity_;  // u before warm starting
  // The last step's points, sorted (warm starting), and the one being built.
  std::vector<ContactInfo> contacts_;
  std::vector<ContactInfo> next_contacts_;
  std::vector<ContactInfo> undo_contacts_;  // the points the step started from (begin_step)
  double undo_dt_ = 0.0;
  bool undo_open_ = false, undo_kept_ = false;
  std::vector<std::uint32_t> order_, merged_;  // store's order of the manifolds
  double last_dt_ = 0.0;
  std::size_t cold_points_ = 0;
  std::size_t cold_chain_ = 0;
  // Per slot: the new touching points in series down to what holds it (unreached: none);
  // the manifolds with a new touching point (measure_cold_chain).
  static constexpr std::uint32_t unreached = 0xffffff00u;
  std::vector<std::uint32_t> chain_, cold_manifolds_;
  void measure_cold_chain();
};

}  // namespace rigidlab
