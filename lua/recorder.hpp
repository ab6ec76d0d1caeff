// A recording of a world's motion: at the start and after every `every`-th completed step,
// the time, energies and momenta of the world and the pose and velocities of each recorded
// body, as the world's own accessors give them. No Lua here; lua/record.cpp binds it
// (w:record, rec:series, rec:csv) and the world calls after_step.
//
// Cost: nothing when no recorder is attached; when one is, a sample is a few dozen doubles
// per body appended to flat arrays (amortised growth, no allocation per step otherwise).
#pragma once

#include <string>
#include <vector>

#include "engine/world.hpp"
#include "present/csv.hpp"

namespace rigidlab::lua {

// What a series holds: one number, a vec3 or a quaternion per sample.
enum class SeriesKind { number, vector, rotation };

struct SeriesInfo {
  const char* name;
  bool per_body;    // needs a body
  SeriesKind kind;
  const char* doc;  // unit and frame
};

// Every series, world ones first; names as the world's and body's accessors are named.
const std::vector<SeriesInfo>& series_list();
// The series called `name` for a world (per_body false) or a body (true), or nullptr.
const SeriesInfo* find_series(const std::string& name, bool per_body);

class Recorder : public StepObserver {
 public:
  // Records the bodies `ids` of `world` (in that order) every `every` >= 1 steps, starting
  // with a sample of the state now.
  Recorder(const World& world, std::vector<BodyStore::Id> ids, long every);

  // Called after each completed step. Every `every`-th step appends a sample; when a recorded
  // body has left the world, or memory runs out, recording stops and stop_reason() says why.
  void after_step(const World& world) noexcept override;
  void stop(const std::string& reason);

  bool recording() const { return recording_; }
  const std::string& stop_reason() const { return stop_reason_; }
  long every() const { return every_; }
  std::size_t samples() const { return times_.size(); }
  std::size_t body_count() const { return ids_.size(); }
  const std::vector<BodyStore::Id>& ids() const { return ids_; }
  const std::vector<double>& times() const { return times_; }

  // The values of a series (kind as SeriesInfo says) at each sample; `body` is the position in
  // ids() for per-body series.
  std::vector<double> numbers(const SeriesInfo& series, std::size_t body) const;
  std::vector<Vec3> vectors(const SeriesInfo& series, std::size_t body) const;
  std::vector<Quat> rotations(const SeriesInfo& series, std::size_t body) const;

  // Every series as CSV columns: t, the world's, then "body1.position.x" and so on.
  std::vector<present::Column> columns() const;

 private:
  void sample(const World& world);

  std::vector<BodyStore::Id> ids_;
  long every_;
  long steps_ = 0;
  bool recording_ = true;
  std::string stop_reason_;
  std::vector<double> times_;
  std::vector<double> world_;   // per sample: world_stride values
  std::vector<double> bodies_;  // per sample and body: body_stride values
};

}  // namespace rigidlab::lua
