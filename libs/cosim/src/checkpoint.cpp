#include "mechsim/cosim/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <thread>

namespace mechsim::cosim {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMagic = "mechsim-checkpoint 1 ";
constexpr const char* kTrailer = "end\n";

class Bytes {
 public:
  void u64(std::uint64_t v) { raw(&v, sizeof v); }
  void i64(std::int64_t v) { raw(&v, sizeof v); }
  void f64(double v) { raw(&v, sizeof v); }
  void vec(const std::vector<double>& v) {
    u64(v.size());
    raw(v.data(), v.size() * sizeof(double));
  }
  void text(const std::string& s) { out_.append(s); }
  const std::string& str() const { return out_; }

 private:
  void raw(const void* p, std::size_t n) { out_.append(static_cast<const char*>(p), n); }
  std::string out_;
};

class Reader {
 public:
  Reader(std::string data, std::string path) : data_(std::move(data)), path_(std::move(path)) {}
  std::uint64_t u64() { return scalar<std::uint64_t>(); }
  std::int64_t i64() { return scalar<std::int64_t>(); }
  double f64() { return scalar<double>(); }
  std::vector<double> vec() {
    const std::uint64_t n = u64();
    if (n > (data_.size() - pos_) / sizeof(double)) damaged("a vector longer than the file");
    std::vector<double> v(n);
    std::memcpy(v.data(), data_.data() + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
    return v;
  }
  void expect(const std::string& s, const char* what) {
    if (data_.compare(pos_, s.size(), s) != 0) damaged(what);
    pos_ += s.size();
  }
  bool at_end() const { return pos_ == data_.size(); }
  [[noreturn]] void damaged(const std::string& what) const {
    throw std::runtime_error(path_ + ": not a usable checkpoint: " + what);
  }

 private:
  template <class T>
  T scalar() {
    if (data_.size() - pos_ < sizeof(T)) damaged("it ends early");
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::string data_, path_;
  std::size_t pos_ = 0;
};

std::string encode(const std::string& node, const NodeCheckpoint& c) {
  Bytes b;
  b.text(std::string(kMagic) + node + "\n");
  const StepperSnapshot& s = c.stepper;
  b.u64(s.step);
  b.vec(s.state);
  b.vec(s.discrete);
  b.vec(s.outputs);
  b.u64(s.channels.size());
  for (const auto& channel : s.channels) {
    b.u64(channel.size());
    for (const auto& [step, values] : channel) {
      b.u64(step);
      b.vec(values);
    }
  }
  b.f64(s.assumed_torque);
  b.vec(c.guard);
  b.u64(c.output_rows);
  b.i64(c.events_bytes);
  b.text(kTrailer);
  return b.str();
}

void write_all(int fd, const char* p, std::size_t n, const std::string& path) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw std::runtime_error(path + ": cannot write the checkpoint: " + std::strerror(errno));
    p += w;
    n -= static_cast<std::size_t>(w);
  }
}

// "<node>.<step>.ckpt" -> step, for this node's complete checkpoints.
std::optional<std::uint64_t> step_of(const std::string& file, const std::string& node) {
  const std::string prefix = node + ".", suffix = ".ckpt";
  if (file.size() <= prefix.size() + suffix.size() || file.compare(0, prefix.size(), prefix) != 0 ||
      file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  const std::string digits = file.substr(prefix.size(), file.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::strtoull(digits.c_str(), nullptr, 10);
}

}  // namespace

std::string checkpoint_path(const std::string& run_dir, const std::string& node, std::uint64_t step) {
  return run_dir + "/checkpoints/" + node + "." + std::to_string(step) + ".ckpt";
}

void write_checkpoint(const std::string& run_dir, const std::string& node, const NodeCheckpoint& checkpoint, int keep,
                      double pause_halfway_s) {
  const std::string path = checkpoint_path(run_dir, node, checkpoint.stepper.step);
  const std::string temp = path + ".tmp";
  std::error_code ec;
  fs::create_directories(run_dir + "/checkpoints", ec);
  const std::string bytes = encode(node, checkpoint);
  const bool temp_was_left = fs::exists(temp, ec);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(temp + ": cannot create the checkpoint: " + std::strerror(errno));
  try {
    const std::size_t half = bytes.size() / 2;
    write_all(fd, bytes.data(), half, temp);
    // The test seam: once, not when the temporary file of a killed writer is left.
    if (pause_halfway_s > 0 && !temp_was_left) std::this_thread::sleep_for(std::chrono::duration<double>(pause_halfway_s));
    write_all(fd, bytes.data() + half, bytes.size() - half, temp);
    // No fdatasync: what a restart survives is the death of a process, whose writes are in
    // the kernel's page cache and whose rename below is atomic; a crash of the machine ends
    // the run (the launcher dies too). A sync would stall every node of the lock-step
    // run whenever the disk is busy (measured: docs/faults.md).
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  if (std::rename(temp.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot put the checkpoint in place: " + std::strerror(errno));
  const auto steps = checkpoint_steps(run_dir, node);
  for (std::size_t i = 0; i + static_cast<std::size_t>(keep) < steps.size(); ++i)
    fs::remove(checkpoint_path(run_dir, node, steps[i]), ec);
}

NodeCheckpoint read_checkpoint(const std::string& run_dir, const std::string& node, std::uint64_t step) {
  const std::string path = checkpoint_path(run_dir, node, step);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": no checkpoint of node '" + node + "' at step " + std::to_string(step));
  Reader r(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), path);
  r.expect(std::string(kMagic) + node + "\n", "its header names no checkpoint of this node");
  NodeCheckpoint c;
  StepperSnapshot& s = c.stepper;
  s.step = r.u64();
  if (s.step != step) r.damaged("it holds step " + std::to_string(s.step));
  s.state = r.vec();
  s.discrete = r.vec();
  s.outputs = r.vec();
  s.channels.resize(r.u64());
  for (auto& channel : s.channels) {
    const std::uint64_t n = r.u64();
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::uint64_t k = r.u64();
      channel.emplace_back(k, r.vec());
    }
  }
  s.assumed_torque = r.f64();
  c.guard = r.vec();
  c.output_rows = r.u64();
  c.events_bytes = r.i64();
  r.expect(kTrailer, "no end mark");
  if (!r.at_end()) r.damaged("bytes after the end mark");
  return c;
}

std::vector<std::uint64_t> checkpoint_steps(const std::string& run_dir, const std::string& node) {
  std::vector<std::uint64_t> steps;
  std::error_code ec;
  for (fs::directory_iterator it(run_dir + "/checkpoints", ec), end; !ec && it != end; it.increment(ec))
    if (auto k = step_of(it->path().filename().string(), node)) steps.push_back(*k);
  std::sort(steps.begin(), steps.end());
  return steps;
}

std::optional<std::uint64_t> common_checkpoint(const std::string& run_dir, const std::vector<std::string>& nodes) {
  if (nodes.empty()) return std::nullopt;
  std::map<std::uint64_t, std::size_t> holders;
  for (const auto& n : nodes)
    for (std::uint64_t k : checkpoint_steps(run_dir, n)) ++holders[k];
  for (auto it = holders.rbegin(); it != holders.rend(); ++it)
    if (it->second == nodes.size()) return it->first;
  return std::nullopt;
}

int checkpoints_to_keep(long checkpoint_every, std::size_t nodes) {
  // Nodes of a lock-step run are at most ~2 steps apart per node between them.
  const long spread = 2 * static_cast<long>(nodes) + 2;
  return 2 + static_cast<int>((spread + checkpoint_every - 1) / checkpoint_every);
}

std::string rolled_back_message(std::uint64_t step, std::int32_t generation) {
  return "rolled back to step " + std::to_string(step) + " (generation " + std::to_string(generation) + ")";
}

}  // namespace mechsim::cosim
