#include "lua/recorder.hpp"

#include <algorithm>
#include <new>

#include "engine/body.hpp"

namespace rigidlab::lua {
namespace {

void put(std::vector<double>& out, const Vec3& v) { out.insert(out.end(), {v.x(), v.y(), v.z()}); }
void put(std::vector<double>& out, const Quat& q) {
  out.insert(out.end(), {q.w(), q.x(), q.y(), q.z()});
}
Vec3 vec_at(const double* p) { return Vec3(p[0], p[1], p[2]); }
Quat quat_at(const double* p) { return Quat(p[0], p[1], p[2], p[3]); }

// The layout of a world's sample. World: kinetic, potential, total energy, linear momentum,
// angular momentum about the origin. Body: position, orientation (w, x, y, z), velocity,
// angular velocity (world), kinetic energy, angular momentum about the COM (world). Body-frame
// values are Rᵀ times the world ones, computed when read from the orientation recorded.
enum WorldSlot { kinetic = 0, potential = 1, total = 2, momentum = 3, angular = 6, world_stride = 9 };
enum BodySlot { position = 0, orientation = 3, velocity = 7, omega = 10, body_kinetic = 13,
                body_angular = 14, body_stride = 17 };
// An articulation's link: position, orientation, COM, angular velocity.
enum LinkSlot { link_position = 0, link_orientation = 3, link_com = 7, link_omega = 10,
                link_stride = 13 };

// Where a series lives: its slot, and whether it is a world-frame vector read in the body frame.
struct Layout {
  int slot;
  bool body_frame;
};

Layout world_layout(const SeriesInfo& s) {
  const std::string name = s.name;
  if (!s.indexed) {
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

int link_slot(const SeriesInfo& s) {
  const std::string name = s.name;
  return name == "position" ? link_position : name == "orientation" ? link_orientation
         : name == "com"    ? link_com : link_omega;
}

}  // namespace

// ---- Recording ---------------------------------------------------------------------------------

const SeriesInfo* Recording::find(const std::string& name, bool indexed) const {
  for (const SeriesInfo& s : series())
    if (name == s.name && (s.indexed == indexed || name == "t")) return &s;
  return nullptr;
}

std::vector<present::Column> Recording::columns() const {
  std::vector<present::Column> out;
  auto add = [&](const std::string& prefix, const SeriesInfo& s, std::size_t index) {
    if (s.kind == SeriesKind::number) {
      out.push_back({prefix, numbers(s, index)});
    } else if (s.kind == SeriesKind::vector) {
      const std::vector<Vec3> v = vectors(s, index);
      for (int k = 0; k < 3; ++k) {
        out.push_back({prefix + "." + "xyz"[k], {}});
        for (const Vec3& x : v) out.back().values.push_back(x[k]);
      }
    } else {
      const std::vector<Quat> q = rotations(s, index);
      const char* parts[4] = {".w", ".x", ".y", ".z"};
      for (int k = 0; k < 4; ++k) {
        out.push_back({prefix + parts[k], {}});
        for (const Quat& x : q) out.back().values.push_back(k == 0 ? x.w() : x.vec()[k - 1]);
      }
    }
  };
  for (const SeriesInfo& s : series())
    if (!s.indexed) add(s.name, s, 0);
  // Indexed series by what they count, in the order they are listed: all the series of body 1
  // (or link 1), then of body 2; a coordinate's series q1, q2, ...
  std::vector<std::string> groups;
  for (const SeriesInfo& s : series())
    if (s.indexed && std::find(groups.begin(), groups.end(), index_name(s)) == groups.end())
      groups.push_back(index_name(s));
  for (const std::string& group : groups) {
    const SeriesInfo* first = nullptr;
    for (const SeriesInfo& s : series())
      if (s.indexed && group == index_name(s) && first == nullptr) first = &s;
    for (std::size_t i = 0; i < index_count(*first); ++i)
      for (const SeriesInfo& s : series()) {
        if (!s.indexed || group != index_name(s)) continue;
        const std::string head = group + std::to_string(i + 1);
        add(group == s.name ? head : head + "." + s.name, s, i);
      }
  }
  return out;
}

void Recording::stop(const std::string& reason) {
  if (!recording_) return;
  recording_ = false;
  stop_reason_ = reason;
}

void Recording::drop_samples_from(double time, std::vector<std::vector<double>*> arrays) {
  if (times_.empty() || time > times_.back()) return;
  const std::size_t samples = times_.size();
  const std::size_t kept = static_cast<std::size_t>(
      std::lower_bound(times_.begin(), times_.end(), time) - times_.begin());
  for (std::vector<double>* a : arrays) a->resize(a->size() / samples * kept);
  times_.resize(kept);
  steps_ = 0;  // `every` steps from the state the world went back to
}

template <class Sample>
void Recording::sample_or_stop(std::vector<std::vector<double>*> arrays, Sample&& sample) noexcept {
  std::vector<std::size_t> sizes;
  try {
    sizes.reserve(arrays.size() + 1);
    sizes.push_back(times_.size());
    for (const std::vector<double>* a : arrays) sizes.push_back(a->size());
    sample();
  } catch (const std::bad_alloc&) {  // keep whole samples only
    if (sizes.size() == arrays.size() + 1) {
      times_.resize(sizes[0]);
      for (std::size_t k = 0; k < arrays.size(); ++k) arrays[k]->resize(sizes[k + 1]);
    }
    stop("not enough memory for more samples");
  }
}

// ---- WorldRecorder -------------------------------------------------------------------------------

const std::vector<SeriesInfo>& WorldRecorder::series() const {
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

WorldRecorder::WorldRecorder(const World& world, std::vector<BodyStore::Id> ids, long every)
    : Recording(every), ids_(std::move(ids)) {
  sample(world);
}

void WorldRecorder::sample(const World& world) {
  times_.push_back(world.time());
  world_.insert(world_.end(), {world.kinetic_energy(), world.potential_energy(), world.energy()});
  put(world_, world.linear_momentum());
  put(world_, world.angular_momentum());
  const BodyStore& store = *world.shared_store();
  for (const BodyStore::Id id : ids_) {
    const Body& b = store.get(id);
    put(bodies_, b.position);
    put(bodies_, b.orientation);
    put(bodies_, b.velocity);
    put(bodies_, b.angular_velocity);
    const bool moves = !is_static(b);
    bodies_.push_back(moves ? kinetic_energy(b) : 0.0);
    put(bodies_, moves ? Vec3(world_inertia(b) * b.angular_velocity) : Vec3::Zero());
  }
}

void WorldRecorder::after_step(const World& world) noexcept {
  if (recording()) drop_samples_from(world.time(), {&world_, &bodies_});
  if (!due()) return;
  const BodyStore& store = *world.shared_store();
  for (std::size_t k = 0; k < ids_.size(); ++k)
    if (!store.contains(ids_[k]))
      return stop("recorded body " + std::to_string(k + 1) + " left the world at t = " +
                  present::csv_number(world.time()) + " s");
  sample_or_stop({&world_, &bodies_}, [&] { sample(world); });
}

std::vector<double> WorldRecorder::numbers(const SeriesInfo& series, std::size_t body) const {
  if (std::string(series.name) == "t") return times_;
  const Layout where = world_layout(series);
  std::vector<double> out(samples());
  for (std::size_t i = 0; i < samples(); ++i)
    out[i] = series.indexed ? bodies_[(i * ids_.size() + body) * body_stride + where.slot]
                            : world_[i * world_stride + where.slot];
  return out;
}

std::vector<Vec3> WorldRecorder::vectors(const SeriesInfo& series, std::size_t body) const {
  const Layout where = world_layout(series);
  std::vector<Vec3> out(samples());
  for (std::size_t i = 0; i < samples(); ++i) {
    const double* p = series.indexed ? &bodies_[(i * ids_.size() + body) * body_stride]
                                     : &world_[i * world_stride];
    out[i] = vec_at(p + where.slot);
    if (where.body_frame) out[i] = quat_at(p + orientation).conjugate() * out[i];
  }
  return out;
}

std::vector<Quat> WorldRecorder::rotations(const SeriesInfo& series, std::size_t body) const {
  const int slot = world_layout(series).slot;
  std::vector<Quat> out(samples());
  for (std::size_t i = 0; i < samples(); ++i)
    out[i] = quat_at(&bodies_[(i * ids_.size() + body) * body_stride + slot]);
  return out;
}

// ---- ArticulationRecorder ------------------------------------------------------------------------

const std::vector<SeriesInfo>& ArticulationRecorder::series() const {
  static const std::vector<SeriesInfo> list = {
      {"t", false, SeriesKind::number, "time (s)"},
      {"kinetic_energy", false, SeriesKind::number, "the articulation's kinetic energy (J)"},
      {"potential_energy", false, SeriesKind::number, "gravity (J)"},
      {"energy", false, SeriesKind::number, "kinetic + potential (J)"},
      {"q", true, SeriesKind::number, "a joint coordinate (rad or m; a free base's first 7)"},
      {"qd", true, SeriesKind::number, "a joint rate (rad/s or m/s; a free base's first 6)"},
      {"position", true, SeriesKind::vector, "the link frame's origin (its joint), world (m)"},
      {"orientation", true, SeriesKind::rotation, "link -> world (quat)"},
      {"com", true, SeriesKind::vector, "the link's COM, world (m)"},
      {"angular_velocity", true, SeriesKind::vector, "the link's, world (rad/s)"},
  };
  return list;
}

const char* ArticulationRecorder::index_name(const SeriesInfo& series) const {
  const std::string name = series.name;
  return name == "q" ? "q" : name == "qd" ? "qd" : "link";
}

std::size_t ArticulationRecorder::index_count(const SeriesInfo& series) const {
  const std::string name = series.name;
  return name == "q" ? nq_ : name == "qd" ? nv_ : links_;
}

ArticulationRecorder::ArticulationRecorder(Articulation& art, long every)
    : Recording(every),
      links_(static_cast<std::size_t>(art.model().link_count())),
      nq_(static_cast<std::size_t>(art.model().nq())),
      nv_(static_cast<std::size_t>(art.model().nv())) {
  sample(art);
}

void ArticulationRecorder::sample(Articulation& art) {
  times_.push_back(art.time());
  const double kinetic_energy = art.kinetic_energy(), potential_energy = art.potential_energy();
  state_.insert(state_.end(), {kinetic_energy, potential_energy, kinetic_energy + potential_energy});
  state_.insert(state_.end(), art.q().data(), art.q().data() + art.q().size());
  state_.insert(state_.end(), art.v().data(), art.v().data() + art.v().size());
  for (std::size_t k = 0; k < links_; ++k) {
    const int link = static_cast<int>(k);
    put(poses_, art.link_position(link));
    put(poses_, Quat(art.link_rotation(link)));
    put(poses_, art.link_com(link));
    put(poses_, art.angular_velocity(link));
  }
}

void ArticulationRecorder::after_step(Articulation& art) noexcept {
  if (recording()) drop_samples_from(art.time(), {&state_, &poses_});
  if (!due()) return;
  if (static_cast<std::size_t>(art.model().link_count()) != links_)
    return stop("a link was added at t = " + present::csv_number(art.time()) + " s");
  sample_or_stop({&state_, &poses_}, [&] { sample(art); });
}

std::vector<double> ArticulationRecorder::numbers(const SeriesInfo& series,
                                                  std::size_t index) const {
  const std::string name = series.name;
  if (name == "t") return times_;
  const std::size_t slot = name == "kinetic_energy" ? 0 : name == "potential_energy" ? 1
                           : name == "energy"       ? 2
                           : name == "q"            ? 3 + index : 3 + nq_ + index;
  std::vector<double> out(samples());
  for (std::size_t i = 0; i < samples(); ++i) out[i] = state_[i * stride() + slot];
  return out;
}

std::vector<Vec3> ArticulationRecorder::vectors(const SeriesInfo& series, std::size_t link) const {
  const int slot = link_slot(series);
  std::vector<Vec3> out(samples());
  for (std::size_t i = 0; i < samples(); ++i)
    out[i] = vec_at(&poses_[(i * links_ + link) * link_stride + slot]);
  return out;
}

std::vector<Quat> ArticulationRecorder::rotations(const SeriesInfo& series, std::size_t link) const {
  const int slot = link_slot(series);
  std::vector<Quat> out(samples());
  for (std::size_t i = 0; i < samples(); ++i)
    out[i] = quat_at(&poses_[(i * links_ + link) * link_stride + slot]);
  return out;
}

}  // namespace rigidlab::lua
