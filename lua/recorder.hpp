// Recordings of motion: at the start and after every `every`-th completed step, the quantities
// a world's or an articulation's own accessors give, in flat arrays. No Lua here; lua/record.cpp
// binds them (w:record, art:record, rec:series, rec:csv) and the world or articulation calls
// after_step (World::add_step_observer, Articulation::add_step_observer).
//
// Cost: nothing when no recorder is attached; when one is, a sample is a few dozen doubles
// per body or link appended to flat arrays (amortised growth, no allocation per step otherwise).
#pragma once

#include <string>
#include <vector>

#include "engine/articulation.hpp"
#include "engine/world.hpp"
#include "present/csv.hpp"

namespace rigidlab::lua {

// What a series holds: one number, a vec3 or a quaternion per sample.
enum class SeriesKind { number, vector, rotation };

struct SeriesInfo {
  const char* name;
  bool indexed;     // of a body, a link or a coordinate: needs which
  SeriesKind kind;
  const char* doc;  // unit and frame
};

// What is common to every recording: the times, when it samples, whether it still does.
class Recording {
 public:
  virtual ~Recording() = default;

  // Every series this recording offers, unindexed ones first.
  virtual const std::vector<SeriesInfo>& series() const = 0;
  // How many of the things an indexed series is about (bodies, links, coordinates).
  virtual std::size_t index_count(const SeriesInfo& series) const = 0;
  // The values of a series at each sample; `index` picks the body, link or coordinate.
  virtual std::vector<double> numbers(const SeriesInfo& series, std::size_t index) const = 0;
  virtual std::vector<Vec3> vectors(const SeriesInfo& series, std::size_t index) const = 0;
  virtual std::vector<Quat> rotations(const SeriesInfo& series, std::size_t index) const = 0;

  // The series called `name`, indexed or not, or nullptr.
  const SeriesInfo* find(const std::string& name, bool indexed) const;
  // Every series as CSV columns: "t", the unindexed ones, then "body1.position.x" and so on
  // (`prefix` names what an index counts: "body", "link", "q").
  std::vector<present::Column> columns() const;

  void stop(const std::string& reason);
  bool recording() const { return recording_; }
  const std::string& stop_reason() const { return stop_reason_; }
  long every() const { return every_; }
  std::size_t samples() const { return times_.size(); }
  const std::vector<double>& times() const { return times_; }

 protected:
  explicit Recording(long every) : every_(every < 1 ? 1 : every) {}
  // Counts a completed step; true when it is one to sample.
  bool due() { return recording_ && ++steps_ % every_ == 0; }
  // A step that ends at or before the last sample's time (a live view quit after a rewind
  // left the world at an earlier state, and it steps on from there): the samples from that
  // time on are dropped, so the times stay increasing and the recording is the motion as it
  // now went; sampling counts `every` steps from the state it went back to. `arrays` hold whole samples each.
  void drop_samples_from(double time, std::vector<std::vector<double>*> arrays);
  // Runs `sample` keeping whole samples only: on std::bad_alloc the arrays are cut back to
  // their sizes before it and recording stops.
  template <class Sample>
  void sample_or_stop(std::vector<std::vector<double>*> arrays, Sample&& sample) noexcept;
  virtual const char* index_name(const SeriesInfo& series) const = 0;  // "body", "link", "q"

  std::vector<double> times_;

 private:
  long every_;
  long steps_ = 0;
  bool recording_ = true;
  std::string stop_reason_;
};

// A world: time, energies, momenta; per body its pose and velocities (world and body frame),
// kinetic energy and angular momentum about its COM.
class WorldRecorder : public Recording, public StepObserver {
 public:
  WorldRecorder(const World& world, std::vector<BodyStore::Id> ids, long every);
  void after_step(const World& world) noexcept override;

  const std::vector<SeriesInfo>& series() const override;
  std::size_t index_count(const SeriesInfo&) const override { return ids_.size(); }
  std::vector<double> numbers(const SeriesInfo& series, std::size_t body) const override;
  std::vector<Vec3> vectors(const SeriesInfo& series, std::size_t body) const override;
  std::vector<Quat> rotations(const SeriesInfo& series, std::size_t body) const override;
  const std::vector<BodyStore::Id>& ids() const { return ids_; }

 private:
  const char* index_name(const SeriesInfo&) const override { return "body"; }
  void sample(const World& world);

  std::vector<BodyStore::Id> ids_;
  std::vector<double> world_;   // per sample: 9 values
  std::vector<double> bodies_;  // per sample and body: 17 values
};

// An articulation: time, energies; q and q̇ per coordinate; per link the pose of its frame (the
// joint), its COM and its angular velocity (world).
class ArticulationRecorder : public Recording, public ArticulationObserver {
 public:
  ArticulationRecorder(Articulation& art, long every);
  void after_step(Articulation& art) noexcept override;

  const std::vector<SeriesInfo>& series() const override;
  std::size_t index_count(const SeriesInfo& series) const override;
  std::vector<double> numbers(const SeriesInfo& series, std::size_t index) const override;
  std::vector<Vec3> vectors(const SeriesInfo& series, std::size_t link) const override;
  std::vector<Quat> rotations(const SeriesInfo& series, std::size_t link) const override;
  std::size_t links() const { return links_; }

 private:
  const char* index_name(const SeriesInfo& series) const override;
  void sample(Articulation& art);
  std::size_t stride() const { return 3 + nq_ + nv_; }

  std::size_t links_, nq_, nv_;
  std::vector<double> state_;  // per sample: kinetic, potential, total energy, q, q̇
  std::vector<double> poses_;  // per sample and link: position, orientation, COM, ω (13)
};

}  // namespace rigidlab::lua
