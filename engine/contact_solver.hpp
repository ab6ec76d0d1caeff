// The contact step of a world: finds the contacts between the bodies' shapes and the static
// planes (engine/contacts.hpp), then solves all of them together with sequential impulses
// (E. Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005; "Fast and Simple
// Physics using Sequential Impulses", GDC 2006; Box2D v2.4's b2ContactSolver), and finally
// pushes overlapping bodies apart by moving them (non-linear Gauss-Seidel, Box2D's
// SolvePositionConstraints), which changes no velocity.
//
// /work/shared/seeds/000_* "Sequential impulses": 1. integrate applied forces to tentative
// velocities, 2. apply impulses sequentially for all constraints to correct the velocity
// errors, 3. use the new velocities to update the positions. Each contact point has three
// constraints: along the normal (001_* Appendix D: λ = −J v / (J W Jᵀ), with the effective
// mass J W Jᵀ = m_a⁻¹ + m_b⁻¹ + (r_a×n)·I_a⁻¹(r_a×n) + (r_b×n)·I_b⁻¹(r_b×n), which is n·K n
// for 002_* "Inverse Mass Matrix" K) and along two tangents (Coulomb friction). Per sweep,
// for each manifold: the friction of each point, then the normals (as a block, below), as
// Box2D does friction before the normal. Impulses are accumulated over the
// sweeps and the accumulated value is clamped, not each increment (Catto 2005): normal
// λn ≥ 0, friction (λt1, λt2) inside the disk of radius μ λn (the Coulomb cone).
//
// Details, each a named scheme:
// - Friction directions: the first tangent along the point's slip (tangential relative
//   velocity) before the solve, the second across it; any orthonormal pair when it does not
//   slip (Duff et al., JCGT 2017). Sliding friction then opposes the slip, as Coulomb's law.
// - Warm starting: a point that touched in the previous step (same bodies or plane, same
//   `feature`, engine/contacts.hpp) starts from the impulses it ended with, scaled by the ratio
//   of the time steps; the friction impulse is kept as a world vector and re-projected on the
//   new tangents. A point whose feature is new continues the nearest point of the previous
//   step within match_distance (the position matching of Bullet's persistent manifolds).
// - Speculative contacts (Catto, "Continuous Collision", GDC 2013; Box2D v3): points with a gap
//   s > 0 are constraints too, v_n ≥ −s/Δt: the bodies may close the gap in this step, not
//   more. A falling body lands on the surface instead of sinking into it, and a resting one
//   stays. Which gaps count: up to speculative_distance always (Box2D v3: resting and stacked
//   bodies keep their contacts); beyond it, out to what the bodies can travel in the step, only
//   when they really meet in the step: the time of impact τ is found by conservative
//   advancement (engine/time_of_impact.hpp) and the contact is taken at the poses of τ (its
//   normal, points and lever arms where the shapes touch), with s the distance its points
//   close from the start of the step to τ. A body flying past a corner gets no contact (no
//   "ghost" hit) and a fast ball hitting a floor sideways gets the lever arm R of the real
//   contact point, not that of a point in the gap.
// - Restitution (the restitution pass of Box2D v3's b2ApplyRestitution, over all contacts):
//   after the sweeps, every point is solved again along its normal, with the target
//   v_n ≥ −s/Δt as before except at bouncing points, v_n = −e w + a_n Δt/2. w is the
//   normal velocity at the instant of impact, a_n the relative normal acceleration of the
//   contact point under the applied forces and gravity, and a point bounces when it touches at
//   the start of the step, e > 0 and −w > restitution_threshold. Because the non-bouncing
//   points are solved in the same pass, a ball bouncing on a box that rests on the floor
//   pushes the box against the floor instead of into it, and rebounds as from the floor.
//   Why w and a_n: the positions of every integrator here follow a parabola exactly (x' = x +
//   Δt u, with u the velocity the impulses act on, see below), on which the velocity at the
//   start of the step is w₀ = u_n − a_n Δt/2 and at the end u_n + a_n Δt/2. Reflecting that
//   parabola at the surface (w → −e w) keeps the "shadow" energy ½w² − a_n x of the discrete
//   motion, so the rebound apex is e² of the drop height at 60 Hz as at 1 kHz; using the
//   velocity with this step's gravity already in it (u_n) adds e g Δt per bounce, and a ball
//   with e ≥ 0.85 then bounces forever at 60 Hz on the limit cycle v* = e g Δt/(1 − e). A
//   speculative point that lands in the step (its gap closes, with impact velocity
//   w = −√(w₀² − 2 a_n s), the parabola's at the gap) is only brought to the surface, and
//   bounces in the next step, when it touches, with the w it landed with (ContactInfo::impact):
//   a bounce from inside the gap would start above the surface.
// - Position correction: non-linear Gauss-Seidel (Box2D v2.4 b2ContactSolver::
//   SolvePositionConstraints) on the separation recomputed from each point's anchors,
//   C = clamp(β (s + slop), −max_correction, 0), moving the bodies by −C/K along n. Only
//   positions change, so overlap is removed without adding energy (Baumgarte's velocity
//   bias would throw stacked bodies up). Within a manifold the correction is first applied at
//   the centroid with the mean separation, then to the points Jacobi-style (all measured at
//   the same poses, each applying 1/count of its correction), so a box sunk evenly rises
//   straight instead of being tipped corner after corner.
// - The normal impulses of a manifold are solved as a block (in the spirit of Box2D v2.4's
//   two-point block solver): with K = J W Jᵀ of its points, the accumulated impulses become
//   λ' = P λ − K⁺(v_n − target), K⁺ the pseudo-inverse and P = K⁺K, which reaches every
//   point's target at once; the four corners of a face are redundant (three independent
//   normal motions), and the pseudo-inverse then gives the least-squares impulses: a
//   symmetric load (a box landing flat, a box in a stack) gets equal impulses and no spin,
//   where sequential impulses always leave the first point solved a little more loaded. When
//   a block would need a negative impulse somewhere its points are solved one by one.
//
// When it runs (World::step): with the Euler integrators the impulses are computed against the
// velocities the integrator is about to produce (semi-implicit: v + Δt(F/m + g) and
// ω + Δt I⁻¹τ; explicit Euler, whose positions move with the old velocities: v and ω), applied
// to the bodies, then the integrator runs, then positions are corrected: for semi-implicit
// Euler this is exactly the order above (the gyroscopic term, second order in Δt, is left to
// the integrator). RK4 moves positions by x' = x + Δt v + Δt²/2 a (constant forces), so its
// contacts are solved before its step too, once, on the mean velocity of the step,
// v + Δt/2 (F/m + g): positions then stay on the surface exactly, where solving after the
// step (at the new positions, on the new velocities) lets RK4 sink a resting body by
// g Δt²/2 every step that only position correction pulls back (1 cm at 60 Hz, a stack of
// three 3 cm). The price: between steps, a body resting on a contact shows v = −g Δt/2 (the
// impulse acted at the start of the step, gravity during it); with explicit Euler, whose
// positions move with the velocity before the step, −g Δt for the same reason. Both are
// inherent to one impulse per step acting before the positions move (removing them after
// the step would leave the next step's contact without the load that sets its friction
// limit), and neither moves the body: positions stay on the surface. Springs and force
// callbacks are evaluated at RK4's stages, after the contacts: the prediction uses gravity
// and the forces applied before the step, and position correction takes up the difference.
//
// Nothing here allocates once the vectors have grown to the largest number of contacts seen.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/body.hpp"
#include "engine/contacts.hpp"
#include "engine/forces.hpp"
#include "engine/plane.hpp"
#include "engine/step_poll.hpp"

namespace rigidlab {

struct ContactSettings {
  static constexpr int max_iterations = 1000;
  int iterations = 10;                 // velocity sweeps per step (1 .. max_iterations)
  int position_iterations = 3;         // position-correction sweeps per step (Box2D: 3)
  double restitution_threshold = 1.0;  // m/s: slower impacts do not bounce (Box2D: 1 m/s)
  double linear_slop = 0.005;          // m: overlap left uncorrected, keeps contacts (Box2D);
                                       // at most 1 % of the smaller body's smallest size
  double baumgarte = 0.2;              // fraction of the overlap removed per sweep (Box2D)
  double max_correction = 0.2;         // m: largest move per point per sweep (Box2D)
  double speculative_distance = 0.02;  // m: gaps up to this are contacts (Box2D v3: 4 slops)
  double match_distance = 0.02;        // m: a point this close to one of the previous step
                                       // (same pair) continues it, when the features differ
};

// "" or the rule broken: "iterations must be an integer from 1 to 1000, got 0", ...
std::string contact_settings_problem(const ContactSettings& settings);

// Which velocities the impulses are computed against (see above): the velocities that move the
// positions in the integrator's step, v + h (F/m + g) and ω + h I_world⁻¹ τ.
enum class ContactVelocities {
  after_forces,  // h = Δt: semi-implicit Euler (x' = x + Δt v')
  mid_step,      // h = Δt/2: RK4 with constant forces (x' = x + Δt v + Δt²/2 a)
  current,       // h = 0: explicit Euler (x' = x + Δt v)
};

inline constexpr std::size_t no_plane = static_cast<std::size_t>(-1);

// One contact point of the last step, for reports and for warm starting the next step.
struct ContactInfo {
  std::size_t a = no_body;       // index of body a in the world; no_body when a is a plane
  std::size_t b = no_body;       // index of body b
  std::size_t plane = no_plane;  // index of the plane, when a is a plane
  std::uint32_t feature = 0;
  Vec3 point = Vec3::Zero();             // m, world, midway between the surfaces when found
  Vec3 normal = Vec3::UnitY();           // unit, from a to b (a plane's own normal)
  double depth = 0.0;                    // m, overlap when found (< 0: a gap the step could close)
  double normal_impulse = 0.0;           // N s: b received normal_impulse·normal, a the opposite
  Vec3 friction_impulse = Vec3::Zero();  // N s, tangential, on b (a the opposite)
  double restitution = 0.0;              // the mixed material of the pair (engine/plane.hpp)
  double friction = 0.0;
  double impact = 0.0;  // m/s, < 0 when the point landed in the step (a speculative contact
                        // whose gap closed): the normal velocity it met the surface with,
                        // bounced on in the next step
};

// A point that touched (depth ≥ 0) or pushed (normal impulse > 0) in the step: the contacts
// worth reporting. The others were speculative and stayed apart.
inline bool touched(const ContactInfo& c) { return c.depth >= 0.0 || c.normal_impulse > 0.0; }

class ContactSolver {
 public:
  ContactSettings settings;
  // World::step's stop check, ticked once per sweep with the points solved (null outside a
  // step); what it throws leaves the solver consistent for the world's undo.
  StepPoll* poll = nullptr;

  // Finds the contacts at the bodies' current poses, solves their velocities and applies the
  // change of velocity to the bodies (static bodies and planes never move). Δt in s. Returns
  // the index of the first body in a contact whose velocity became non-finite, or all_finite.
  std::size_t solve_velocities(std::vector<Body>& bodies, const std::vector<Plane>& planes,
                               const Vec3& gravity, double dt, ContactVelocities velocities);
  // Position correction of the contacts found by the last solve_velocities, at the bodies'
  // present poses (after the integrator moved them). Returns the first non-finite body index.
  std::size_t correct_positions(std::vector<Body>& bodies);

  // Every point of the last solve (touched and speculative), ordered by body a, then body b or
  // plane, then feature.
  const std::vector<ContactInfo>& contacts() const { return contacts_; }

  // Body `index` left the world: its contacts are forgotten, later indices drop by one.
  void body_removed(std::size_t index);
  // The world's undo: remember the contacts now, and put them back after a failed step.
  void save();
  void restore();

 private:
  // A body in contact, with the velocities being solved (slot 0 is the ground: planes and
  // static bodies, velocity 0 and inverse mass 0).
  struct SolverBody {
    Vec3 velocity, angular_velocity;              // m/s, rad/s, world
    Vec3 start_velocity, start_angular_velocity;  // before the solve
    Vec3 acceleration, angular_acceleration;      // free: F/m + g, I⁻¹τ (m/s², rad/s²)
    Mat3 inverse_inertia;                         // world, 1/(kg m²)
    double inverse_mass;                          // 1/kg
    std::size_t index;                            // in the world
  };
  // One contact point: its three constraints and their accumulated impulses.
  struct Constraint {
    std::size_t a, b, plane;
    std::uint32_t slot_a, slot_b, feature;
    Vec3 normal, tangent1, tangent2;  // unit, orthogonal
    Vec3 point;                       // m, world, when found
    Vec3 r_a, r_b;                    // m, from each COM to the point
    Vec3 anchor_a, anchor_b;          // witness points in body coordinates (a plane's: world)
    double radius_a, radius_b;        // m, of a sphere (its witness is recomputed), else 0
    double separation;                // m, −depth
    double normal_mass, tangent_mass1, tangent_mass2;  // kg: 1/(J W Jᵀ)
    double normal_impulse, tangent_impulse1, tangent_impulse2;  // N s
    double bias;          // m/s: gap/Δt of a speculative point, else 0
    double approach;      // m/s: v_n before the solve (the velocity the positions move with)
    double slop;          // m: the overlap position correction leaves (see add_manifold)
    double acceleration;  // m/s²: a_n, relative normal acceleration of the point, free
    double impact;        // m/s: w, normal velocity at the impact in this step, else 0
    double target;        // m/s: v_n after the restitution pass at a bouncing point
    bool bounces;         // touches, and bounces in this step (see prepare_restitution)
    bool landed;          // pushed after the sweeps while its impact lies in the step
    double restitution, friction;
  };
  // A shape in the broad phase: its extent along x (sweep and prune).
  struct Proxy {
    double min_x, max_x;  // m
    std::size_t index;
    double radius;  // m, bounding sphere
    double sweep;   // m: how far the shape's points can move in the step
  };

  std::uint32_t slot_for(const std::vector<Body>& bodies, std::size_t index, const Vec3& gravity,
                         double dt, ContactVelocities velocities);
  void build_proxies(const std::vector<Body>& bodies, const Vec3& gravity, double dt,
                     ContactVelocities velocities);
  void find_contacts(std::vector<Body>& bodies, const std::vector<Plane>& planes,
                     const Vec3& gravity, double dt, ContactVelocities velocities);
  // One pair's contact: the manifold at the start poses, or at the time of impact, or none.
  void add_pair(const std::vector<Body>& bodies, const Manifold& m, std::size_t a, std::size_t b,
                std::size_t plane, const Plane* plane_material, double dt, std::uint32_t slot_a,
                std::uint32_t slot_b);
  // The constraints of manifold m, found at time toi of the step with the bodies at
  // pose_a, pose_b (pose_a unused for a plane).
  void add_manifold(const std::vector<Body>& bodies, const Manifold& m, std::size_t a,
                    std::size_t b, std::size_t plane, const Plane* plane_material, double dt,
                    std::uint32_t slot_a, std::uint32_t slot_b, double toi, const Pose& pose_a,
                    const Pose& pose_b);
  double touch_tolerance() const;
  const ContactInfo* previous_point(const Constraint& c) const;
  void warm_start(Constraint& c, double dt);
  void prepare_restitution(Constraint& c, const ContactInfo* previous, double dt) const;
  double target_of(const Constraint& c, bool restitution) const {
    return restitution && c.bounces ? c.target : -c.bias;
  }
  // Calls f(begin, end) for the constraint range of each manifold.
  template <class F>
  void for_each_manifold(F&& f) {
    for (std::size_t i = 0; i < manifold_begin_.size(); ++i)
      f(manifold_begin_[i],
        i + 1 < manifold_begin_.size() ? manifold_begin_[i + 1] : constraints_.size());
  }
  void solve_friction(Constraint& c);
  double solve_normal(Constraint& c, bool restitution);
  double solve_normals(std::size_t manifold, bool restitution);
  void prepare_blocks();
  // Calls f(constraint) for each point of manifold m.
  template <class F>
  void for_manifold(std::size_t m, F&& f) {
    const std::size_t end =
        m + 1 < manifold_begin_.size() ? manifold_begin_[m + 1] : constraints_.size();
    for (std::size_t k = manifold_begin_[m]; k < end; ++k) f(constraints_[k]);
  }
  void apply_impulse(Constraint& c, const Vec3& impulse);
  void apply_restitution();
  void store_results(double dt);
  std::size_t write_back(std::vector<Body>& bodies);
  void witnesses(const std::vector<Body>& bodies, const Constraint& c, Vec3& pa, Vec3& pb) const;
  void move_apart(std::vector<Body>& bodies, const Constraint& c, const Vec3& point,
                  double correction);

  std::vector<SolverBody> solver_bodies_;  // slot 0: the ground (planes, static bodies)
  std::vector<std::uint32_t> slot_of_;     // by body index; 0 when not in a contact yet
  std::vector<Proxy> proxies_;             // broad phase, sorted along x
  std::vector<Constraint> constraints_;
  std::vector<std::size_t> manifold_begin_;  // the first constraint of each manifold
  // The block solve of a manifold's normal impulses: K⁺ and P = K⁺K (4 x 4, the unused rows
  // and columns of a smaller manifold zero).
  using Mat4 = Eigen::Matrix<double, 4, 4, Eigen::DontAlign>;
  using Vec4 = Eigen::Matrix<double, 4, 1, Eigen::DontAlign>;
  struct Block {
    Mat4 inverse, projector;
    bool usable;
  };
  std::vector<Block> blocks_;  // by manifold
  std::vector<ContactInfo> contacts_;        // the last step's, sorted (warm starting)
  std::vector<ContactInfo> next_contacts_;
  std::vector<ContactInfo> saved_contacts_;
  double last_dt_ = 0.0;
  double saved_dt_ = 0.0;
};

}  // namespace rigidlab
