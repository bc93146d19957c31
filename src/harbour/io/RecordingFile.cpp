#include "harbour/io/RecordingFile.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "harbour/core/StateHash.h"

namespace harbour::io {
namespace {

constexpr char kMagic[4] = {'H', 'S', 'R', 'C'};

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
    if (static_cast<std::size_t>(n) * record_size > in_.size() - at_)
      fail(std::string(what) + ": " + std::to_string(n) + " records do not fit in the file (truncated?)");
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

 private:
  void need(std::size_t n, const char* what) const {
    if (n > in_.size() - at_) fail(std::string("truncated in ") + what);
  }
  std::string file_;
  std::vector<unsigned char> in_;
  std::size_t at_ = 0;
};

// step, gantry, trolley, hoist, [boom,] buttons[, spreader size] (v3 added the bracketed fields)
constexpr std::size_t kInputRecord_v2 = 8 + 3 * 8 + 1;
constexpr std::size_t kInputRecord = 8 + 4 * 8 + 1 + 1;

// button bits: lock, unlock, e-stop, horn, then the four flipper switches
std::uint8_t button_bits(const sim::StsControls& c) {
  std::uint8_t bits = (c.lock ? 1 : 0) | (c.unlock ? 2 : 0) | (c.emergency_stop ? 4 : 0) | (c.horn ? 8 : 0);
  for (std::size_t k = 0; k < 4; ++k)
    if (c.flipper_down[k]) bits |= static_cast<std::uint8_t>(16 << k);
  return bits;
}

void set_buttons(sim::StsControls& c, std::uint8_t bits) {
  c.lock = bits & 1;
  c.unlock = bits & 2;
  c.emergency_stop = bits & 4;
  c.horn = bits & 8;
  for (std::size_t k = 0; k < 4; ++k)
    c.flipper_down[k] = bits & (16 << k);
}
constexpr std::size_t kCheckpointRecord = 8 + 8;

std::uint64_t checksum(const std::vector<std::uint8_t>& bytes) {
  core::StateHash h;
  h.add_bytes(bytes.data(), bytes.size());
  return h.value();
}
// step, kind, gust duration and amplitude, corner, value, wind mean, direction, turbulence (v4)
constexpr std::size_t kCommandRecord = 8 + 1 + 2 * 8 + 4 + 4 * 8;

}  // namespace

void write_recording(const std::string& path, const sim::Recording& r) {
  Writer w;
  w.out.insert(w.out.end(), std::begin(kMagic), std::end(kMagic));
  w.put(kRecordingVersion);
  w.put(std::uint16_t{0});
  w.put(r.scenario);
  w.put(r.parent);
  w.put(r.branch_step);
  w.put(r.total_steps);
  w.put(static_cast<std::uint32_t>(r.inputs.size()));
  for (const auto& c : r.inputs) {
    w.put(c.step);
    w.put(c.inputs.sts.gantry);
    w.put(c.inputs.sts.trolley);
    w.put(c.inputs.sts.hoist);
    w.put(c.inputs.sts.boom);
    w.put(button_bits(c.inputs.sts));
    w.put(c.inputs.sts.spreader_size_ft);
  }
  w.put(static_cast<std::uint32_t>(r.checkpoints.size()));
  for (const auto& c : r.checkpoints) {
    w.put(c.step);
    w.put(c.state_hash);
  }
  // keyframes: the simulation's own state bytes (native little-endian doubles, as saved)
  w.put(static_cast<std::uint32_t>(r.keyframes.size()));
  for (const auto& k : r.keyframes) {
    w.put(k.step);
    w.put(static_cast<std::uint32_t>(k.state.size()));
    w.put(checksum(k.state));
    w.out.insert(w.out.end(), k.state.begin(), k.state.end());
  }
  w.put(static_cast<std::uint32_t>(r.commands.size()));
  for (const auto& c : r.commands) {
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
  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(w.out.data()), static_cast<std::streamsize>(w.out.size()));
    if (!out) throw std::runtime_error(temporary + ": cannot be written");
  }
  std::filesystem::rename(temporary, path);
}

sim::Recording read_recording(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordingFileError(path, 0, "cannot be opened");
  Reader r(path, std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {}));
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
  r.get<std::uint16_t>("reserved");
  sim::Recording rec;
  rec.scenario = r.text("scenario name");
  rec.parent = r.text("parent");
  rec.branch_step = r.get<std::int64_t>("branch step");
  rec.total_steps = r.get<std::int64_t>("total steps");
  const std::uint32_t inputs = r.count(version >= 3 ? kInputRecord : kInputRecord_v2, "inputs");
  for (std::uint32_t n = 0; n < inputs; ++n) {
    sim::Recording::InputChange c;
    c.step = r.get<std::int64_t>("input step");
    c.inputs.sts.gantry = r.lever("gantry");
    c.inputs.sts.trolley = r.lever("trolley");
    c.inputs.sts.hoist = r.lever("hoist");
    if (version >= 3) c.inputs.sts.boom = r.lever("boom");
    set_buttons(c.inputs.sts, r.get<std::uint8_t>("buttons"));
    if (version >= 3) {
      c.inputs.sts.spreader_size_ft = r.get<std::uint8_t>("spreader size");
      const auto size = c.inputs.sts.spreader_size_ft;
      if (size != 0 && size != 20 && size != 40 && size != 45)
        r.fail("spreader size button is not 0, 20, 40 or 45");
    }
    if (!rec.inputs.empty() && c.step < rec.inputs.back().step) r.fail("input steps out of order");
    rec.inputs.push_back(c);
  }
  const std::uint32_t checkpoints = r.count(kCheckpointRecord, "checkpoints");
  for (std::uint32_t n = 0; n < checkpoints; ++n) {
    sim::Recording::Checkpoint c;
    c.step = r.get<std::int64_t>("checkpoint step");
    c.state_hash = r.get<std::uint64_t>("checkpoint hash");
    if (c.step <= 0 || c.step > rec.total_steps) r.fail("checkpoint step outside the recording");
    if (!rec.checkpoints.empty() && c.step <= rec.checkpoints.back().step) r.fail("checkpoints out of order");
    rec.checkpoints.push_back(c);
  }
  if (version >= 2) {
    const std::uint32_t keyframes = r.count(version >= 5 ? 8 + 4 + 8 : 8 + 4, "keyframes");
    for (std::uint32_t n = 0; n < keyframes; ++n) {
      sim::Recording::Keyframe k;
      k.step = r.get<std::int64_t>("keyframe step");
      const std::uint32_t size = r.count(1, "keyframe state");
      const std::uint64_t sum = version >= 5 ? r.get<std::uint64_t>("keyframe checksum") : 0;
      r.bytes(size, k.state, "keyframe state");
      if (version >= 5 && checksum(k.state) != sum)
        r.fail("keyframe " + std::to_string(n) + " is damaged (its checksum does not match its bytes)");
      if (k.step < 0 || k.step > rec.total_steps) r.fail("keyframe step outside the recording");
      if (!rec.keyframes.empty() && k.step <= rec.keyframes.back().step) r.fail("keyframes out of order");
      rec.keyframes.push_back(std::move(k));
    }
  }
  if (version >= 4) {
    const std::uint32_t commands = r.count(kCommandRecord, "instructor commands");
    for (std::uint32_t n = 0; n < commands; ++n) {
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
      if (c.step < 0 || c.step > rec.total_steps) r.fail("instructor command step outside the recording");
      if (!rec.commands.empty() && c.step < rec.commands.back().step)
        r.fail("instructor commands out of order");
      if (const std::string why = sim::why_invalid(c.command); !why.empty())
        r.fail("instructor command " + std::to_string(n) + ": " + why);
      rec.commands.push_back(c);
    }
  }
  if (!r.done()) r.fail("unexpected bytes after the last record");
  return rec;
}

}  // namespace harbour::io
