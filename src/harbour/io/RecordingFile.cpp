#include "harbour/io/RecordingFile.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>

#include "harbour/core/StateHash.h"
#include "harbour/core/Text.h"
#include "harbour/io/BoundedFile.h"

namespace harbour::io {
namespace {

constexpr char kMagic[4] = {'H', 'S', 'R', 'C'};
constexpr std::uint16_t kFlagRopesSettled = 1;   // the run's hoist ropes started stretched under their load
constexpr std::uint16_t kFlagRopesCurved = 2;    // its ropes stretched along their curved length
constexpr std::uint16_t kFlagEndStopsClear = 4;  // its end stops lay beyond its drives' travel
constexpr std::uint16_t kFlagStartSettled = 8;   // its machine was brought to rest before its first step
constexpr std::uint16_t kFlagRopeDampingInternal = 16;  // its ropes' transverse damping acted on their ends
constexpr std::uint16_t kFlagSheaveBendingLoss =
    32;  // its ropes lost to bending where they turned on sheaves
constexpr std::uint16_t kFlagMachineStateHashed = 64;  // its checkpoints hash everything the machine saves
constexpr std::uint16_t kFlagRunningSheaves = 128;     // its sheaves ran with loss, by the transfer's change
constexpr std::uint16_t kFlagSlackRopesKeepSag = 256;  // a slack rope kept the shape it had

class Writer {
 public:
  template <typename T>
  void put(T v) {
    auto bytes = std::bit_cast<std::array<unsigned char, sizeof(T)>>(v);
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes.begin(), bytes.end());
    out.insert(out.end(), bytes.begin(), bytes.end());
  }
  void put(const std::string& s) {
    put(static_cast<std::uint32_t>(s.size()));
    out.insert(out.end(), s.begin(), s.end());
  }
  std::vector<unsigned char> out;
};

/// The file ends inside a record (a RecordingFileError unless it is the torn tail of a v6 stream).
struct Truncated : RecordingFileError {
  explicit Truncated(const RecordingFileError& e) : RecordingFileError(e) {}
};

class Reader {
 public:
  Reader(std::string file, std::vector<unsigned char> bytes)
      : file_(std::move(file)), in_(std::move(bytes)) {}
  template <typename T>
  T get(const char* what) {
    need(sizeof(T), what);
    std::array<unsigned char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), &in_[at_], sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes.begin(), bytes.end());
    at_ += sizeof(T);
    return std::bit_cast<T>(bytes);
  }
  /// `n` raw bytes appended to `out`.
  void bytes(std::size_t n, std::vector<std::uint8_t>& out, const char* what) {
    need(n, what);
    out.insert(out.end(), in_.begin() + static_cast<std::ptrdiff_t>(at_),
               in_.begin() + static_cast<std::ptrdiff_t>(at_ + n));
    at_ += n;
  }
  std::string text(const char* what) {
    const auto n = get<std::uint32_t>(what);
    need(n, what);
    std::string s(reinterpret_cast<const char*>(&in_[at_]), n);
    at_ += n;
    return s;
  }
  /// A count of records of `record_size` bytes each, checked against what is left.
  std::uint32_t count(std::size_t record_size, const char* what) {
    const auto n = get<std::uint32_t>(what);
    // more than the file holds: cut short there (a torn last record of a stream reads as such)
    if (static_cast<std::size_t>(n) * record_size > in_.size() - at_)
      throw Truncated(RecordingFileError(
          file_, at_,
          std::string(what) + ": " + std::to_string(n) + " records do not fit in the file (truncated?)"));
    return n;
  }
  /// A control lever's position: finite, within [-1, 1].
  double lever(const char* what) {
    const auto v = get<double>(what);
    if (!(v >= -1.0 && v <= 1.0))
      fail(std::string(what) + " lever " + std::to_string(v) + " is outside [-1, 1]");
    return v;
  }
  [[noreturn]] void fail(const std::string& problem) const { throw RecordingFileError(file_, at_, problem); }
  std::size_t offset() const { return at_; }
  bool done() const { return at_ == in_.size(); }
  void rewind(std::size_t offset) { at_ = offset; }

 private:
  void need(std::size_t n, const char* what) const {
    if (n > in_.size() - at_)
      throw Truncated(RecordingFileError(file_, at_, std::string("truncated in ") + what));
  }
  std::string file_;
  std::vector<unsigned char> in_;
  std::size_t at_ = 0;
};

// step, gantry, trolley, hoist, [boom,] buttons[, spreader size] (v3 added the bracketed fields)
constexpr std::size_t kInputRecord_v2 = 8 + 3 * 8 + 1;
constexpr std::size_t kInputRecord = 8 + 4 * 8 + 1 + 1;

// button bits (before v7): lock, unlock, e-stop, horn, then the four flipper switches
constexpr std::uint8_t kLegacyButtons[] = {4, 5, 6, 7, 11, 12, 13, 14};  // their legacy label slots
constexpr std::size_t kCheckpointRecord = 8 + 8;

std::uint64_t checksum(const std::vector<std::uint8_t>& bytes) {
  core::StateHash h;
  h.add_bytes(bytes.data(), bytes.size());
  return h.value();
}
// step, kind, gust duration and amplitude, corner, value, wind mean, direction, turbulence (v4)
constexpr std::size_t kCommandRecord = 8 + 1 + 2 * 8 + 4 + 4 * 8;

// v6 record tags
constexpr std::uint8_t kTagInput = 'I', kTagCheckpoint = 'C', kTagKeyframe = 'K', kTagCommand = 'M',
                       kTagEnd = 'E';
constexpr std::uint8_t kTagTeam = 'T';  // v9

// v7: the step, then the values that changed since the previous input record (slot, value)
void put_input(Writer& w, const sim::Recording::InputChange& c, const scene::Controls& previous,
               std::size_t controls) {
  w.put(c.step);
  std::uint8_t changed = 0;
  for (std::size_t n = 0; n < controls; ++n)
    if (c.controls.value[n] != previous.value[n]) ++changed;
  w.put(changed);
  for (std::size_t n = 0; n < controls; ++n)
    if (c.controls.value[n] != previous.value[n]) {
      w.put(static_cast<std::uint8_t>(n));
      w.put(c.controls.value[n]);
    }
}

void put_command(Writer& w, const sim::Recording::Command& c) {
  w.put(c.step);
  w.put(static_cast<std::uint8_t>(c.command.kind));
  w.put(c.command.gust.duration_s);
  w.put(c.command.gust.amplitude_mps);
  w.put(static_cast<std::int32_t>(c.command.corner));
  w.put(c.command.value);
  w.put(c.command.wind_mean_mps);
  w.put(c.command.wind_from_rad);
  w.put(c.command.turbulence);
}

// step, kind, slot, position, rotation (its matrix by rows: exactly what was applied), velocity, angular
// velocity, mass
constexpr std::size_t kTeamValues = 3 + 9 + 3 + 3 + 1;
void put_team(Writer& w, const sim::Recording::TeamEvent& e) {
  const sim::TeamInput& t = e.input;
  w.put(e.step);
  w.put(static_cast<std::uint8_t>(t.kind));
  w.put(static_cast<std::int32_t>(t.slot));
  for (const double v : {t.pose.position.x, t.pose.position.y, t.pose.position.z})
    w.put(v);
  for (const auto& row : t.pose.rotation.m)
    for (const double v : row)
      w.put(v);
  for (const double v : {t.velocity_mps.x, t.velocity_mps.y, t.velocity_mps.z, t.angular_velocity_radps.x,
                         t.angular_velocity_radps.y, t.angular_velocity_radps.z, t.mass_kg})
    w.put(v);
  if (t.kind == sim::TeamInput::Kind::kObstacleAt)  // v10: and its size
    for (const double v : {t.half_extents_m.x, t.half_extents_m.y, t.half_extents_m.z})
      w.put(v);
  if (t.kind == sim::TeamInput::Kind::kLoadOn) {  // v11: and the box's name
    const std::string item = t.item_name();
    w.put(static_cast<std::uint8_t>(item.size()));
    w.out.insert(w.out.end(), item.begin(), item.end());
  }
}

}  // namespace

RecordingWriter::RecordingWriter(const std::string& path, const sim::Recording& prefix) : path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot be written (" + std::strerror(errno) + ")");
  Writer w;
  w.out.insert(w.out.end(), std::begin(kMagic), std::end(kMagic));
  w.put(kRecordingVersion);
  w.put(static_cast<std::uint16_t>(
      (prefix.ropes_settled ? kFlagRopesSettled : 0) | (prefix.ropes_curved ? kFlagRopesCurved : 0) |
      (prefix.end_stops_clear ? kFlagEndStopsClear : 0) | (prefix.start_settled ? kFlagStartSettled : 0) |
      (prefix.rope_damping_internal ? kFlagRopeDampingInternal : 0) |
      (prefix.sheave_bending_loss ? kFlagSheaveBendingLoss : 0) |
      (prefix.machine_state_hashed ? kFlagMachineStateHashed : 0) |
      (prefix.running_sheaves ? kFlagRunningSheaves : 0) |
      (prefix.slack_ropes_keep_sag ? kFlagSlackRopesKeepSag : 0)));
  w.put(prefix.scenario);
  w.put(prefix.parent);
  w.put(prefix.branch_step);
  if (prefix.control_labels.size() > static_cast<std::size_t>(scene::kMaxControls))
    throw std::runtime_error(path + ": more than " + std::to_string(scene::kMaxControls) + " controls");
  control_count_ = prefix.control_labels.size();
  w.put(static_cast<std::uint8_t>(control_count_));
  for (const std::string& label : prefix.control_labels)
    w.put(label);
  write(w.out, true);
  // the prefix merged in the order a run streams it: before step s the commands of s, after it the input
  // change applied at s and the checkpoint and keyframe of s + 1 (each list is written in its own order)
  // (the team inputs of s after its commands)
  const std::size_t sizes[] = {prefix.commands.size(), prefix.team.size(), prefix.inputs.size(),
                               prefix.checkpoints.size(), prefix.keyframes.size()};
  constexpr std::size_t kKinds = std::size(sizes);
  std::size_t next[kKinds] = {};
  const auto streamed_at = [&](std::size_t kind) -> std::pair<std::int64_t, std::size_t> {
    switch (kind) {
      case 0:
        return {prefix.commands[next[0]].step, 0};
      case 1:
        return {prefix.team[next[1]].step, 1};
      case 2:
        return {prefix.inputs[next[2]].step, 2};
      case 3:
        return {prefix.checkpoints[next[3]].step - 1, 3};
      default:
        return {prefix.keyframes[next[4]].step - 1, 4};
    }
  };
  for (;;) {
    std::size_t first = kKinds;
    for (std::size_t kind = 0; kind < kKinds; ++kind)
      if (next[kind] < sizes[kind] && (first == kKinds || streamed_at(kind) < streamed_at(first)))
        first = kind;
    if (first == kKinds) break;
    const std::size_t n = next[first]++;
    if (first == 0) on_command(prefix.commands[n]);
    if (first == 1) on_team(prefix.team[n]);
    if (first == 2) on_input(prefix.inputs[n]);
    if (first == 3) on_checkpoint(prefix.checkpoints[n]);
    if (first == 4) on_keyframe(prefix.keyframes[n]);
  }
}

RecordingWriter::~RecordingWriter() {
  if (file_) std::fclose(file_);  // unfinished: what was written stays a readable, incomplete recording
}

void RecordingWriter::write(const std::vector<unsigned char>& bytes, bool flush) {
  if (!file_) throw std::runtime_error(path_ + ": the recording is already finished");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size() || (flush && std::fflush(file_) != 0))
    throw std::runtime_error(path_ + ": cannot be written (" + std::strerror(errno) + ")");
}

void RecordingWriter::on_input(const sim::Recording::InputChange& change) {
  Writer w;
  w.put(kTagInput);
  put_input(w, change, last_input_, control_count_);
  last_input_ = change.controls;
  write(w.out, false);
}

void RecordingWriter::on_checkpoint(const sim::Recording::Checkpoint& checkpoint) {
  Writer w;
  w.put(kTagCheckpoint);
  w.put(checkpoint.step);
  w.put(checkpoint.state_hash);
  write(w.out, true);  // every simulated second reaches the file: a crash loses at most one
}

void RecordingWriter::on_keyframe(const sim::Recording::Keyframe& k) {
  // the simulation's own state bytes (native little-endian doubles, as saved)
  Writer w;
  w.put(kTagKeyframe);
  w.put(k.step);
  w.put(static_cast<std::uint32_t>(k.state.size()));
  w.put(checksum(k.state));
  w.out.insert(w.out.end(), k.state.begin(), k.state.end());
  write(w.out, true);
}

void RecordingWriter::on_command(const sim::Recording::Command& command) {
  Writer w;
  w.put(kTagCommand);
  put_command(w, command);
  write(w.out, true);
}

void RecordingWriter::on_team(const sim::Recording::TeamEvent& event) {
  Writer w;
  w.put(kTagTeam);
  put_team(w, event);
  write(w.out, true);
}

void RecordingWriter::finish(std::int64_t total_steps) {
  Writer w;
  w.put(kTagEnd);
  w.put(total_steps);
  write(w.out, true);
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!closed) throw std::runtime_error(path_ + ": cannot be written (" + std::strerror(errno) + ")");
}

void write_recording(const std::string& path, const sim::Recording& r) {
  RecordingWriter writer(path, r);
  writer.finish(r.total_steps);
}

namespace {

// before v7: the STS cab's fields, stored by the legacy labels (sim::legacy_sts_control_labels)
sim::Recording::InputChange read_legacy_input(Reader& r, std::uint16_t version) {
  sim::Recording::InputChange c;
  c.step = r.get<std::int64_t>("input step");
  auto& v = c.controls.value;
  v[0] = r.lever("gantry");
  v[1] = r.lever("trolley");
  v[2] = r.lever("hoist");
  if (version >= 3) v[3] = r.lever("boom");
  const auto bits = r.get<std::uint8_t>("buttons");
  for (std::size_t k = 0; k < std::size(kLegacyButtons); ++k)
    v[kLegacyButtons[k]] = (bits >> k) & 1 ? 1.0 : 0.0;
  if (version >= 3) {
    const auto size = r.get<std::uint8_t>("spreader size");
    if (size != 0 && size != 20 && size != 40 && size != 45)
      r.fail("spreader size button is not 0, 20, 40 or 45");
    v[8] = size == 20;
    v[9] = size == 40;
    v[10] = size == 45;
  }
  return c;
}

sim::Recording::InputChange read_input(Reader& r, const sim::Recording& rec) {
  sim::Recording::InputChange c;
  c.step = r.get<std::int64_t>("input step");
  c.controls = rec.inputs.empty() ? scene::Controls{} : rec.inputs.back().controls;
  const auto changed = r.get<std::uint8_t>("changed controls");
  for (std::uint8_t k = 0; k < changed; ++k) {
    const auto slot = r.get<std::uint8_t>("control");
    if (slot >= rec.control_labels.size())
      r.fail("input control " + std::to_string(slot) + " of " + std::to_string(rec.control_labels.size()));
    const double value = r.get<double>("control value");
    if (!std::isfinite(value)) r.fail("control '" + rec.control_labels[slot] + "' is not a finite value");
    c.controls.value[slot] = value;
  }
  return c;
}

sim::Recording::Keyframe read_keyframe(Reader& r, std::uint16_t version, std::size_t n) {
  sim::Recording::Keyframe k;
  k.step = r.get<std::int64_t>("keyframe step");
  const std::uint32_t size = r.count(1, "keyframe state");
  const std::uint64_t sum = version >= 5 ? r.get<std::uint64_t>("keyframe checksum") : 0;
  r.bytes(size, k.state, "keyframe state");
  if (version >= 5 && checksum(k.state) != sum)
    r.fail("keyframe " + std::to_string(n) + " is damaged (its checksum does not match its bytes)");
  return k;
}

sim::Recording::Command read_command(Reader& r, std::size_t n) {
  sim::Recording::Command c;
  c.step = r.get<std::int64_t>("command step");
  const auto kind = r.get<std::uint8_t>("command kind");
  if (kind >= sim::InstructorCommand::kKinds)
    r.fail("instructor command kind " + std::to_string(kind) + " unknown");
  c.command.kind = static_cast<sim::InstructorCommand::Kind>(kind);
  c.command.gust.duration_s = r.get<double>("gust duration");
  c.command.gust.amplitude_mps = r.get<double>("gust amplitude");
  c.command.corner = r.get<std::int32_t>("corner");
  c.command.value = r.get<double>("command value");
  c.command.wind_mean_mps = r.get<double>("wind mean");
  c.command.wind_from_rad = r.get<double>("wind direction");
  c.command.turbulence = r.get<double>("turbulence");
  if (const std::string why = sim::why_invalid(c.command); !why.empty())
    r.fail("instructor command " + std::to_string(n) + ": " + why);
  return c;
}

sim::Recording::TeamEvent read_team(Reader& r, std::size_t n, std::uint16_t version) {
  sim::Recording::TeamEvent e;
  e.step = r.get<std::int64_t>("team input step");
  const auto kind = r.get<std::uint8_t>("team input kind");
  const std::uint8_t kinds = version >= 10 ? sim::TeamInput::kKinds : 3;
  if (kind >= kinds) r.fail("team input kind " + std::to_string(kind) + " unknown");
  sim::TeamInput& t = e.input;
  t.kind = static_cast<sim::TeamInput::Kind>(kind);
  t.slot = r.get<std::int32_t>("team input slot");
  double v[kTeamValues];
  for (double& x : v)
    x = r.get<double>("team input value");
  t.pose.position = {v[0], v[1], v[2]};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      t.pose.rotation.m[row][col] = v[3 + 3 * row + col];
  // a rotation: its rows unit and square to one another (what a replay applies must be one)
  const core::Mat3& m = t.pose.rotation;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double dot = m.m[a][0] * m.m[b][0] + m.m[a][1] * m.m[b][1] + m.m[a][2] * m.m[b][2];
      if (!(std::abs(dot - (a == b ? 1.0 : 0.0)) < 1e-6))
        r.fail("team input " + std::to_string(n) + ": a rotation that is not one");
    }
  t.velocity_mps = {v[12], v[13], v[14]};
  t.angular_velocity_radps = {v[15], v[16], v[17]};
  t.mass_kg = v[18];
  if (t.kind == sim::TeamInput::Kind::kObstacleAt)
    for (double* side : {&t.half_extents_m.x, &t.half_extents_m.y, &t.half_extents_m.z})
      *side = r.get<double>("team obstacle size");
  if (t.kind == sim::TeamInput::Kind::kLoadOn && version >= 11) {
    const auto length = r.get<std::uint8_t>("team load's name length");
    if (length > sim::TeamInput::kMostItemChars)
      r.fail("team input " + std::to_string(n) + ": a load's name of " + std::to_string(length) +
             " characters");
    std::vector<std::uint8_t> name;
    r.bytes(length, name, "team load's name");
    std::copy(name.begin(), name.end(), t.item.begin());
  }
  if (const std::string why = sim::why_invalid(t); !why.empty())
    r.fail("team input " + std::to_string(n) + ": " + why);
  return e;
}

// records in order, every checkpoint second covered, everything within the recording
void check_recording(const sim::Recording& rec, Reader& r) {
  if (rec.total_steps < 0 || rec.total_steps > kMaxRecordingSteps)
    r.fail("length of " + std::to_string(rec.total_steps) + " steps is outside 0-" +
           std::to_string(kMaxRecordingSteps) + " (24 h)");
  if (rec.branch_step < 0 || rec.branch_step > rec.total_steps) r.fail("branch step outside the recording");
  if (rec.parent.empty() && rec.branch_step != 0) r.fail("a branch step without a parent recording");
  for (std::size_t n = 1; n < rec.inputs.size(); ++n)
    if (rec.inputs[n].step < rec.inputs[n - 1].step) r.fail("input steps out of order");
  // a checkpoint every simulated second: fewer means the header claims more than the data holds
  const std::int64_t seconds = rec.total_steps / sim::Recorder::kCheckpointEvery;
  if (static_cast<std::int64_t>(rec.checkpoints.size()) != seconds)
    r.fail(std::to_string(rec.checkpoints.size()) + " checkpoints for " + std::to_string(seconds) +
           " recorded seconds (a truncated or altered recording)");
  for (std::size_t n = 0; n < rec.checkpoints.size(); ++n)
    if (rec.checkpoints[n].step != static_cast<std::int64_t>(n + 1) * sim::Recorder::kCheckpointEvery)
      r.fail("checkpoint " + std::to_string(n) + " is not at second " + std::to_string(n + 1));
  for (std::size_t n = 0; n < rec.keyframes.size(); ++n) {
    const std::int64_t step = rec.keyframes[n].step;
    if (step < 0 || step > rec.total_steps) r.fail("keyframe step outside the recording");
    if (n > 0 && step <= rec.keyframes[n - 1].step) r.fail("keyframes out of order");
  }
  for (std::size_t n = 0; n < rec.commands.size(); ++n) {
    const std::int64_t step = rec.commands[n].step;
    if (step < 0 || step > rec.total_steps) r.fail("instructor command step outside the recording");
    if (n > 0 && step < rec.commands[n - 1].step) r.fail("instructor commands out of order");
  }
  for (std::size_t n = 0; n < rec.team.size(); ++n) {
    const std::int64_t step = rec.team[n].step;
    if (step < 0 || step > rec.total_steps) r.fail("team input step outside the recording");
    if (n > 0 && step < rec.team[n - 1].step) r.fail("team inputs out of order");
  }
}

// v6: tagged records until the end record; a file without one is what a killed run left
void read_records(Reader& r, sim::Recording& rec, std::uint16_t version) {
  bool ended = false;
  while (!r.done()) {
    const std::size_t at = r.offset();
    try {
      const auto tag = r.get<std::uint8_t>("record tag");
      if (tag == kTagInput) {
        rec.inputs.push_back(version >= 7 ? read_input(r, rec) : read_legacy_input(r, version));
      } else if (tag == kTagCheckpoint) {
        sim::Recording::Checkpoint c;
        c.step = r.get<std::int64_t>("checkpoint step");
        c.state_hash = r.get<std::uint64_t>("checkpoint hash");
        rec.checkpoints.push_back(c);
      } else if (tag == kTagKeyframe) {
        rec.keyframes.push_back(read_keyframe(r, kRecordingVersion, rec.keyframes.size()));
      } else if (tag == kTagCommand) {
        rec.commands.push_back(read_command(r, rec.commands.size()));
      } else if (tag == kTagTeam && version >= 9) {
        rec.team.push_back(read_team(r, rec.team.size(), version));
      } else if (tag == kTagEnd) {
        rec.total_steps = r.get<std::int64_t>("total steps");
        ended = true;
        break;
      } else {
        r.fail("unknown record tag " + std::to_string(tag));
      }
    } catch (const Truncated&) {
      r.rewind(at);  // the torn last record of a killed run
      break;
    }
  }
  if (ended) {
    if (!r.done()) r.fail("unexpected bytes after the end record");
    return;
  }
  // incomplete: it replays up to its last checkpoint, with what came before it
  rec.complete = false;
  rec.total_steps = rec.checkpoints.empty() ? rec.branch_step : rec.checkpoints.back().step;
  rec.total_steps = std::max(rec.total_steps, rec.branch_step);
  std::erase_if(rec.inputs, [&](const auto& c) { return c.step >= rec.total_steps; });
  std::erase_if(rec.keyframes, [&](const auto& k) { return k.step > rec.total_steps; });
  std::erase_if(rec.commands, [&](const auto& c) { return c.step >= rec.total_steps; });
  std::erase_if(rec.team, [&](const auto& e) { return e.step >= rec.total_steps; });
  std::erase_if(rec.checkpoints, [&](const auto& c) { return c.step > rec.total_steps; });
}

}  // namespace

sim::Recording read_recording(const std::string& path) {
  std::string why;
  std::optional<std::string> bytes = read_bounded_file(path, kMaxRecordingBytes, why);
  if (!bytes) throw RecordingFileError(path, 0, why);
  return parse_recording(path, std::move(*bytes));
}

std::string recording_copy(const std::string& path, std::size_t most) {
  std::string why;
  return read_bounded_file(path, most, why).value_or(std::string{});
}

sim::Recording parse_recording(const std::string& path, std::string bytes) {
  if (bytes.size() > kMaxRecordingBytes)
    throw RecordingFileError(path, 0, "larger than " + std::to_string(kMaxRecordingBytes) + " bytes");
  Reader r(path, std::vector<unsigned char>(bytes.begin(), bytes.end()));
  bytes.clear();
  bytes.shrink_to_fit();
  char magic[4];
  for (char& m : magic)
    m = static_cast<char>(r.get<std::uint8_t>("magic"));
  if (std::memcmp(magic, kMagic, 4) != 0)
    throw RecordingFileError(path, 0, "not a harboursim recording (no HSRC magic)");
  const auto version = r.get<std::uint16_t>("version");
  if (version < 1 || version > kRecordingVersion)
    throw RecordingFileError(path, 4,
                             "recording version " + std::to_string(version) +
                                 " is not supported (this build reads " + std::to_string(kRecordingVersion) +
                                 ")");
  const auto flags = r.get<std::uint16_t>("flags");  // reserved (0) before version 8
  sim::Recording rec;
  rec.ropes_settled = version >= 8 && (flags & kFlagRopesSettled) != 0;
  rec.ropes_curved = version >= 8 && (flags & kFlagRopesCurved) != 0;
  rec.end_stops_clear = version >= 8 && (flags & kFlagEndStopsClear) != 0;
  rec.start_settled = version >= 8 && (flags & kFlagStartSettled) != 0;
  rec.rope_damping_internal = version >= 8 && (flags & kFlagRopeDampingInternal) != 0;
  rec.sheave_bending_loss = version >= 8 && (flags & kFlagSheaveBendingLoss) != 0;
  rec.machine_state_hashed = version >= 8 && (flags & kFlagMachineStateHashed) != 0;
  rec.running_sheaves = version >= 8 && (flags & kFlagRunningSheaves) != 0;
  rec.slack_ropes_keep_sag = version >= 8 && (flags & kFlagSlackRopesKeepSag) != 0;
  constexpr std::uint16_t kKnown = kFlagRopesSettled | kFlagRopesCurved | kFlagEndStopsClear |
                                   kFlagStartSettled | kFlagRopeDampingInternal | kFlagSheaveBendingLoss |
                                   kFlagMachineStateHashed | kFlagRunningSheaves | kFlagSlackRopesKeepSag;
  if (version >= 8 && (flags & ~kKnown) != 0) r.fail("unknown header flags " + std::to_string(flags));
  rec.scenario = r.text("scenario name");
  if (const std::string bad = core::why_bad_name(rec.scenario); !bad.empty())
    r.fail("the scenario name " + bad);
  rec.parent = r.text("parent");
  if (const std::string bad = core::why_bad_name(rec.parent, 4096); !rec.parent.empty() && !bad.empty())
    r.fail("the parent recording's name " + bad);
  rec.branch_step = r.get<std::int64_t>("branch step");
  if (version >= 7) {
    const auto controls = r.get<std::uint8_t>("control count");
    if (controls > scene::kMaxControls) r.fail(std::to_string(controls) + " controls (at most 32)");
    for (std::uint8_t n = 0; n < controls; ++n) {
      std::string label = r.text("control label");
      if (const std::string bad = core::why_bad_name(label, 64); !bad.empty())
        r.fail("a control label " + bad);
      if (std::find(rec.control_labels.begin(), rec.control_labels.end(), label) != rec.control_labels.end())
        r.fail("control '" + label + "' is listed twice");
      rec.control_labels.push_back(std::move(label));
    }
  } else {
    rec.control_labels = sim::legacy_sts_control_labels();
  }
  if (version >= 6) {
    read_records(r, rec, version);
    check_recording(rec, r);
    return rec;
  }
  rec.total_steps = r.get<std::int64_t>("total steps");
  const std::uint32_t inputs = r.count(version >= 3 ? kInputRecord : kInputRecord_v2, "inputs");
  for (std::uint32_t n = 0; n < inputs; ++n)
    rec.inputs.push_back(read_legacy_input(r, version));
  const std::uint32_t checkpoints = r.count(kCheckpointRecord, "checkpoints");
  for (std::uint32_t n = 0; n < checkpoints; ++n) {
    sim::Recording::Checkpoint c;
    c.step = r.get<std::int64_t>("checkpoint step");
    c.state_hash = r.get<std::uint64_t>("checkpoint hash");
    rec.checkpoints.push_back(c);
  }
  if (version >= 2) {
    const std::uint32_t keyframes = r.count(version >= 5 ? 8 + 4 + 8 : 8 + 4, "keyframes");
    for (std::uint32_t n = 0; n < keyframes; ++n)
      rec.keyframes.push_back(read_keyframe(r, version, n));
  }
  if (version >= 4) {
    const std::uint32_t commands = r.count(kCommandRecord, "instructor commands");
    for (std::uint32_t n = 0; n < commands; ++n)
      rec.commands.push_back(read_command(r, n));
  }
  if (!r.done()) r.fail("unexpected bytes after the last record");
  check_recording(rec, r);
  return rec;
}

}  // namespace harbour::io
