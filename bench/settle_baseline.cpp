// The sphere-heap baseline of bench/settle_baseline.hpp (the steps are described there).
#include "bench/settle_baseline.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace baseline {

namespace {

int clamp_cell(double x, int dim) {
  const int c = static_cast<int>(x);
  return c < 0 ? 0 : (c >= dim ? dim - 1 : c);
}

// An orthonormal pair spanning the plane normal to the unit n (Box2D / Bullet
// btPlaneSpace1: drop the smallest component so the cross product stays well conditioned).
void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
  if (std::abs(n.x()) >= 0.57735) t1 = Vec3(n.y(), -n.x(), 0.0).normalized();
  else t1 = Vec3(0.0, n.z(), -n.y()).normalized();
  t2 = n.cross(t1);
}

}  // namespace

SphereHeap::SphereHeap(std::vector<Sphere> spheres, std::vector<Wall> walls,
                       const Settings& settings)
    : spheres_(std::move(spheres)), walls_(std::move(walls)), settings_(settings) {
  double largest = 0.0;
  for (const Sphere& s : spheres_) largest = std::max(largest, s.radius);
  cell_ = 2.0 * largest + settings_.speculative_distance;
  bodies_.resize(spheres_.size() + 1);
  bodies_.back() = SolverBody{Vec3::Zero(), 0.0, Vec3::Zero(), 0.0};  // the world
}

void SphereHeap::step() {
  const Vec3 dv = settings_.dt * settings_.gravity;
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    const Sphere& s = spheres_[i];
    bodies_[i] = SolverBody{s.velocity + dv, s.inverse_mass, s.angular_velocity,
                            s.inverse_inertia};
  }
  build_grid();
  find_contacts();
  prepare_and_warm_start();
  for (int k = 0; k < settings_.iterations; ++k) solve_sweep();
  integrate_and_remember();
}

// Bounding box of the centres, cells of edge cell_ (larger when the box would need more than
// 4 cells per sphere, so that a sphere thrown far does not grow the grid), counting sort.
void SphereHeap::build_grid() {
  const std::size_t n = spheres_.size();
  Vec3 lower = Vec3::Constant(1e300), upper = Vec3::Constant(-1e300);
  for (const Sphere& s : spheres_) {
    lower = lower.cwiseMin(s.position);
    upper = upper.cwiseMax(s.position);
  }
  lower_ = lower;
  double cell = cell_;
  const double cap = 4.0 * static_cast<double>(n) + 64.0;
  for (;;) {
    double count = 1.0;
    for (int k = 0; k < 3; ++k) {
      dims_[k] = static_cast<int>((upper[k] - lower[k]) / cell) + 1;
      count *= dims_[k];
    }
    if (count <= cap) break;
    cell *= 1.25;
  }
  const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  cell_start_.assign(cells + 1, 0);
  cell_of_.resize(n);
  by_cell_.resize(n);
  const double inv = 1.0 / cell;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = (spheres_[i].position - lower) * inv;
    const std::uint32_t c = static_cast<std::uint32_t>(
        clamp_cell(p.x(), dims_[0]) +
        dims_[0] * (clamp_cell(p.y(), dims_[1]) + dims_[1] * clamp_cell(p.z(), dims_[2])));
    cell_of_[i] = c;
    ++cell_start_[c + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    by_cell_[cell_cursor_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
}

// Sphere i against the spheres j > i of its 27 cells (each row of three cells along x is one
// run of by_cell_), then against the walls: contacts come out sorted by key.
void SphereHeap::find_contacts() {
  const std::uint32_t n = static_cast<std::uint32_t>(spheres_.size());
  const double spec = settings_.speculative_distance;
  contacts_.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    const Sphere& si = spheres_[i];
    const int c = static_cast<int>(cell_of_[i]);
    const int cx = c % dims_[0], cy = (c / dims_[0]) % dims_[1], cz = c / (dims_[0] * dims_[1]);
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, dims_[0] - 1);
    neighbours_.clear();
    for (int z = std::max(cz - 1, 0); z <= std::min(cz + 1, dims_[2] - 1); ++z)
      for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, dims_[1] - 1); ++y) {
        const int row = dims_[0] * (y + dims_[1] * z);
        for (std::uint32_t k = cell_start_[row + x0]; k < cell_start_[row + x1 + 1]; ++k) {
          const std::uint32_t j = by_cell_[k];
          if (j <= i) continue;
          const double reach = si.radius + spheres_[j].radius + spec;
          if ((si.position - spheres_[j].position).squaredNorm() <= reach * reach)
            neighbours_.push_back(j);
        }
      }
    std::sort(neighbours_.begin(), neighbours_.end());
    for (const std::uint32_t j : neighbours_) {
      const Sphere& sj = spheres_[j];
      const Vec3 d = si.position - sj.position;
      const double distance = d.norm();
      const Vec3 normal = distance > 1e-12 ? Vec3(d / distance) : Vec3(Vec3::UnitY());
      add_contact(i, j, (std::uint64_t{i} << 32) | j, normal,
                  distance - si.radius - sj.radius, std::sqrt(si.friction * sj.friction));
    }
    for (std::uint32_t w = 0; w < walls_.size(); ++w) {
      const Wall& wall = walls_[w];
      const double gap = wall.normal.dot(si.position) - wall.offset - si.radius;
      if (gap <= spec)
        add_contact(i, n, (std::uint64_t{i} << 32) | (n + w), wall.normal, gap,
                    std::sqrt(si.friction * wall.friction));
    }
  }
}

// The point halfway across the gap (or overlap) between the two surfaces.
void SphereHeap::add_contact(std::uint32_t a, std::uint32_t b, std::uint64_t key,
                             const Vec3& normal, double gap, double friction) {
  Contact c;
  c.key = key;
  c.a = a;
  c.b = b;
  c.normal = normal;
  tangents(normal, c.tangent1, c.tangent2);
  const Sphere& sa = spheres_[a];
  c.arm_a = -(sa.radius + 0.5 * gap) * normal;
  const Vec3 point = sa.position + c.arm_a;
  c.arm_b = b < spheres_.size() ? Vec3(point - spheres_[b].position) : point;
  c.gap = gap;
  c.friction = friction;
  contacts_.push_back(c);
}

// Effective masses, targets, and the warm start: the cache is sorted by key like contacts_.
void SphereHeap::prepare_and_warm_start() {
  const double inv_dt = 1.0 / settings_.dt;
  std::size_t p = 0;
  for (Contact& c : contacts_) {
    SolverBody& a = bodies_[c.a];
    SolverBody& b = bodies_[c.b];
    auto row_mass = [&](const Vec3& dir) {
      const double k = a.inverse_mass + b.inverse_mass +
                       a.inverse_inertia * c.arm_a.cross(dir).squaredNorm() +
                       b.inverse_inertia * c.arm_b.cross(dir).squaredNorm();
      return 1.0 / k;
    };
    c.normal_mass = row_mass(c.normal);
    c.tangent_mass1 = row_mass(c.tangent1);
    c.tangent_mass2 = row_mass(c.tangent2);
    c.target = c.gap > 0.0
                   ? -c.gap * inv_dt
                   : settings_.baumgarte * inv_dt * std::max(-c.gap - settings_.linear_slop, 0.0);
    while (p < cache_.size() && cache_[p].key < c.key) ++p;
    if (p < cache_.size() && cache_[p].key == c.key) {
      c.normal_impulse = cache_[p].normal_impulse;
      c.tangent_impulse1 = cache_[p].friction_impulse.dot(c.tangent1);
      c.tangent_impulse2 = cache_[p].friction_impulse.dot(c.tangent2);
      const Vec3 impulse = c.normal_impulse * c.normal + c.tangent_impulse1 * c.tangent1 +
                           c.tangent_impulse2 * c.tangent2;
      a.velocity += a.inverse_mass * impulse;
      a.angular_velocity += a.inverse_inertia * c.arm_a.cross(impulse);
      b.velocity -= b.inverse_mass * impulse;
      b.angular_velocity -= b.inverse_inertia * c.arm_b.cross(impulse);
    } else {
      c.normal_impulse = c.tangent_impulse1 = c.tangent_impulse2 = 0.0;
    }
  }
}

// One Gauss-Seidel sweep: per contact the friction disk (with the current normal impulse),
// then the normal row, so the normal row has the last word.
void SphereHeap::solve_sweep() {
  for (Contact& c : contacts_) {
    SolverBody& a = bodies_[c.a];
    SolverBody& b = bodies_[c.b];
    auto apply = [&](const Vec3& impulse) {
      a.velocity += a.inverse_mass * impulse;
      a.angular_velocity += a.inverse_inertia * c.arm_a.cross(impulse);
      b.velocity -= b.inverse_mass * impulse;
      b.angular_velocity -= b.inverse_inertia * c.arm_b.cross(impulse);
    };
    Vec3 relative = a.velocity + a.angular_velocity.cross(c.arm_a) - b.velocity -
                    b.angular_velocity.cross(c.arm_b);
    const double old1 = c.tangent_impulse1, old2 = c.tangent_impulse2;
    double t1 = old1 - c.tangent_mass1 * relative.dot(c.tangent1);
    double t2 = old2 - c.tangent_mass2 * relative.dot(c.tangent2);
    const double limit = c.friction * c.normal_impulse;
    const double magnitude2 = t1 * t1 + t2 * t2;
    if (magnitude2 > limit * limit) {
      const double scale = limit / std::sqrt(magnitude2);
      t1 *= scale;
      t2 *= scale;
    }
    c.tangent_impulse1 = t1;
    c.tangent_impulse2 = t2;
    apply((t1 - old1) * c.tangent1 + (t2 - old2) * c.tangent2);

    relative = a.velocity + a.angular_velocity.cross(c.arm_a) - b.velocity -
               b.angular_velocity.cross(c.arm_b);
    const double old = c.normal_impulse;
    c.normal_impulse = std::max(old + c.normal_mass * (c.target - relative.dot(c.normal)), 0.0);
    apply((c.normal_impulse - old) * c.normal);
  }
}

void SphereHeap::integrate_and_remember() {
  const double dt = settings_.dt;
  for (std::size_t i = 0; i < spheres_.size(); ++i) {
    Sphere& s = spheres_[i];
    const SolverBody& b = bodies_[i];
    s.velocity = b.velocity;
    s.angular_velocity = b.angular_velocity;
    s.position += dt * s.velocity;
    const Quat spin(0.0, s.angular_velocity.x(), s.angular_velocity.y(),
                    s.angular_velocity.z());
    s.orientation.coeffs() += 0.5 * dt * (spin * s.orientation).coeffs();
    s.orientation.normalize();
  }
  cache_.resize(contacts_.size());
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& c = contacts_[k];
    cache_[k] = Remembered{c.key, c.normal_impulse,
                           c.tangent_impulse1 * c.tangent1 + c.tangent_impulse2 * c.tangent2};
  }
}

double SphereHeap::max_overlap() const {
  double deepest = 0.0;
  for (const Contact& c : contacts_) deepest = std::max(deepest, -c.gap);
  return deepest;
}

void SphereHeap::save(State& to) const {
  to.spheres = spheres_;
  to.cache = cache_;
}

void SphereHeap::restore(const State& from) {
  spheres_ = from.spheres;
  cache_ = from.cache;
}

}  // namespace baseline
