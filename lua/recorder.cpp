#include "lua/recorder.hpp"

#include <new>

#include "engine/body.hpp"

namespace rigidlab::lua {
namespace {

// The layout of a sample. World: kinetic, potential, total energy, linear momentum, angular
// momentum about the origin. Body: position, orientation (w, x, y, z), velocity, angular
// velocity (world), kinetic energy, angular momentum about the COM (world). Body-frame
// values are Rᵀ times the world ones, computed when read, from the orientation recorded.
enum WorldSlot { kinetic = 0, potential = 1, total = 2, momentum = 3, angular = 6, world_stride = 9 };
enum BodySlot { position = 0, orientation = 3, velocity = 7, omega = 10, body_kinetic = 13,
                body_angular = 14, body_stride = 17 };

// Where a series lives: its slot, and whether it is a world-frame vector read in the body frame.
struct Layout {
  int slot;
  bool body_frame;
};

Layout layout(const SeriesInfo& s) {
  const std::string name = s.name;
  if (!s.per_body) {
    if (name == "kinetic_energy") return {kinetic, false};
    if (name == "potential_energy") return {potential, false};
    if (name == "energy") return {total, false};
    if (name == "linear_momentum") return {momentum, false};
    return {angular, false};
  }
  if (name == "position") return {position, false};
  if (name == "orientation") return {orientation, false};
  if (name == "velocity") return {velocity, false};
  if (name == "angular_velocity") return {omega, false};
  if (name == "velocity_body") return {velocity, true};
  if (name == "angular_velocity_body") return {omega, true};
  if (name == "kinetic_energy") return {body_kinetic, false};
  if (name == "angular_momentum") return {body_angular, false};
  return {body_angular, true};  // angular_momentum_body
}

void put(std::vector<double>& out, const Vec3& v) { out.insert(out.end(), {v.x(), v.y(), v.z()}); }

}  // namespace

const std::vector<SeriesInfo>& series_list() {
  static const std::vector<SeriesInfo> list = {
      {"t", false, SeriesKind::number, "time (s)"},
      {"kinetic_energy", false, SeriesKind::number, "the world's kinetic energy (J)"},
      {"potential_energy", false, SeriesKind::number, "gravity and springs (J)"},
      {"energy", false, SeriesKind::number, "kinetic + potential (J)"},
      {"linear_momentum", false, SeriesKind::vector, "total (kg m/s)"},
      {"angular_momentum", false, SeriesKind::vector, "total, about the world origin (kg m²/s)"},
      {"position", true, SeriesKind::vector, "the COM, world (m)"},
      {"orientation", true, SeriesKind::rotation, "body -> world (quat)"},
      {"velocity", true, SeriesKind::vector, "of the COM, world (m/s)"},
      {"angular_velocity", true, SeriesKind::vector, "world (rad/s)"},
      {"velocity_body", true, SeriesKind::vector, "of the COM, body frame (m/s)"},
      {"angular_velocity_body", true, SeriesKind::vector, "body frame (rad/s)"},
      {"kinetic_energy", true, SeriesKind::number, "of the body (J)"},
      {"angular_momentum", true, SeriesKind::vector, "about the COM, world (kg m²/s)"},
      {"angular_momentum_body", true, SeriesKind::vector, "about the COM, body frame (kg m²/s)"},
  };
  return list;
}

const SeriesInfo* find_series(const std::string& name, bool per_body) {
  for (const SeriesInfo& s : series_list())
    if (name == s.name && (s.per_body == per_body || name == "t")) return &s;
  return nullptr;
}

Recorder::Recorder(const World& world, std::vector<BodyStore::Id> ids, long every)
    : ids_(std::move(ids)), every_(every < 1 ? 1 : every) {
  sample(world);
}

void Recorder::sample(const World& world) {
  times_.push_back(world.time());
  world_.insert(world_.end(), {world.kinetic_energy(), world.potential_energy(), world.energy()});
  put(world_, world.linear_momentum());
  put(world_, world.angular_momentum());
  const BodyStore& store = *world.shared_store();
  for (const BodyStore::Id id : ids_) {
    const Body& b = store.get(id);
    put(bodies_, b.position);
    bodies_.insert(bodies_.end(), {b.orientation.w(), b.orientation.x(), b.orientation.y(),
                                   b.orientation.z()});
    put(bodies_, b.velocity);
    put(bodies_, b.angular_velocity);
    const bool moves = !is_static(b);
    bodies_.push_back(moves ? kinetic_energy(b) : 0.0);
    put(bodies_, moves ? Vec3(world_inertia(b) * b.angular_velocity) : Vec3::Zero());
  }
}

void Recorder::after_step(const World& world) noexcept {
  if (!recording_ || ++steps_ % every_ != 0) return;
  const BodyStore& store = *world.shared_store();
  for (std::size_t k = 0; k < ids_.size(); ++k)
    if (!store.contains(ids_[k]))
      return stop("recorded body " + std::to_string(k + 1) + " left the world at t = " +
                  present::csv_number(world.time()) + " s");
  const std::size_t sizes[3] = {times_.size(), world_.size(), bodies_.size()};
  try {
    sample(world);
  } catch (const std::bad_alloc&) {  // keep whole samples only
    times_.resize(sizes[0]);
    world_.resize(sizes[1]);
    bodies_.resize(sizes[2]);
    stop("not enough memory for more samples");
  }
}

void Recorder::stop(const std::string& reason) {
  if (!recording_) return;
  recording_ = false;
  stop_reason_ = reason;
}

std::vector<double> Recorder::numbers(const SeriesInfo& series, std::size_t body) const {
  if (std::string(series.name) == "t") return times_;
  const Layout where = layout(series);
  std::vector<double> out(samples());
  for (std::size_t i = 0; i < samples(); ++i)
    out[i] = series.per_body ? bodies_[(i * ids_.size() + body) * body_stride + where.slot]
                             : world_[i * world_stride + where.slot];
  return out;
}

std::vector<Vec3> Recorder::vectors(const SeriesInfo& series, std::size_t body) const {
  const Layout where = layout(series);
  std::vector<Vec3> out(samples());
  for (std::size_t i = 0; i < samples(); ++i) {
    const double* p = series.per_body ? &bodies_[(i * ids_.size() + body) * body_stride]
                                      : &world_[i * world_stride];
    out[i] = Vec3(p[where.slot], p[where.slot + 1], p[where.slot + 2]);
    if (where.body_frame) {
      const Quat q(p[orientation], p[orientation + 1], p[orientation + 2], p[orientation + 3]);
      out[i] = q.conjugate() * out[i];
    }
  }
  return out;
}

std::vector<Quat> Recorder::rotations(const SeriesInfo& series, std::size_t body) const {
  const int slot = layout(series).slot;
  std::vector<Quat> out(samples());
  for (std::size_t i = 0; i < samples(); ++i) {
    const double* p = &bodies_[(i * ids_.size() + body) * body_stride + slot];
    out[i] = Quat(p[0], p[1], p[2], p[3]);
  }
  return out;
}

std::vector<present::Column> Recorder::columns() const {
  std::vector<present::Column> out;
  for (std::size_t body = 0; body < (ids_.empty() ? 1 : ids_.size() + 1); ++body) {
    for (const SeriesInfo& s : series_list()) {
      if (s.per_body != (body > 0) || (body > 0 && std::string(s.name) == "t")) continue;
      const std::string prefix = body > 0 ? "body" + std::to_string(body) + "." + s.name : s.name;
      if (s.kind == SeriesKind::number) {
        out.push_back({prefix, numbers(s, body - (body > 0))});
      } else if (s.kind == SeriesKind::vector) {
        const std::vector<Vec3> v = vectors(s, body - (body > 0));
        for (int k = 0; k < 3; ++k) {
          out.push_back({prefix + "." + "xyz"[k], {}});
          for (const Vec3& x : v) out.back().values.push_back(x[k]);
        }
      } else {
        const std::vector<Quat> q = rotations(s, body - 1);
        const char* parts[4] = {".w", ".x", ".y", ".z"};
        for (int k = 0; k < 4; ++k) {
          out.push_back({prefix + parts[k], {}});
          for (const Quat& x : q) out.back().values.push_back(k == 0 ? x.w() : x.vec()[k - 1]);
        }
      }
    }
  }
  return out;
}

}  // namespace rigidlab::lua
