#include "mechsim/cosim/output_log.h"

#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace mechsim::cosim {

namespace {
constexpr const char* kMagic = "mechsim-outputs 1";
}

OutputLogWriter::OutputLogWriter(const std::string& path, const std::vector<std::string>& columns, Mode mode)
    : path_(path), width_(columns.size() + 1), mode_(mode) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  std::string header = std::string(kMagic) + "\nt";
  for (const auto& c : columns) header += "," + c;
  header += "\n";
  header_bytes_ = static_cast<long>(header.size());
  std::fwrite(header.data(), 1, header.size(), file_);
  if (mode_ == Mode::background) {
    ring_.assign(kRingRows * width_, 0.0);
    writer_ = std::thread([this] { writer_loop(); });
  }
}

OutputLogWriter::OutputLogWriter(const std::string& path, const std::vector<std::string>& columns, Resume resume)
    : path_(path), width_(columns.size() + 1), mode_(Mode::direct) {
  std::string header = std::string(kMagic) + "\nt";
  for (const auto& c : columns) header += "," + c;
  header += "\n";
  header_bytes_ = static_cast<long>(header.size());
  file_ = std::fopen(path.c_str(), "r+b");
  if (!file_) throw std::runtime_error(path + ": cannot reopen to resume: " + std::strerror(errno));
  try {
    std::string found(header.size(), '\0');
    if (std::fread(found.data(), 1, found.size(), file_) != found.size() || found != header)
      throw std::runtime_error(path + ": not this node's output log (its header differs), cannot resume it");
    truncate_rows(resume.rows);
  } catch (...) {
    std::fclose(std::exchange(file_, nullptr));
    throw;
  }
}

void OutputLogWriter::flush() {
  if (mode_ != Mode::direct) throw std::logic_error(path_ + ": flush of a background output log");
  if (std::fflush(file_) != 0) throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
}

void OutputLogWriter::truncate_rows(std::uint64_t rows) {
  if (mode_ != Mode::direct) throw std::logic_error(path_ + ": truncate of a background output log");
  flush();
  const long size = header_bytes_ + static_cast<long>(rows * width_ * sizeof(double));
  std::fseek(file_, 0, SEEK_END);
  if (std::ftell(file_) < size)
    throw std::runtime_error(path_ + ": holds fewer than the " + std::to_string(rows) + " rows of the checkpoint");
  if (::ftruncate(::fileno(file_), size) != 0 || std::fseek(file_, size, SEEK_SET) != 0)
    throw std::runtime_error(path_ + ": cannot truncate to the checkpoint: " + std::strerror(errno));
  rows_ = rows;
}

OutputLogWriter::~OutputLogWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // a destructor does not throw; close() explicitly to see the error
  }
}

void OutputLogWriter::append(double t, std::span<const double> values) {
  ++rows_;
  if (mode_ == Mode::direct) {
    std::fwrite(&t, sizeof t, 1, file_);
    std::fwrite(values.data(), sizeof(double), values.size(), file_);
    return;
  }
  const std::size_t head = head_.load(std::memory_order_relaxed);
  if (head - tail_.load(std::memory_order_acquire) >= kRingRows) {
    ++ring_full_waits_;  // the disk is 16 384 rows behind: wait rather than lose a row
    while (head - tail_.load(std::memory_order_acquire) >= kRingRows) std::this_thread::yield();
  }
  double* row = ring_.data() + (head % kRingRows) * width_;
  row[0] = t;
  std::copy(values.begin(), values.end(), row + 1);
  head_.store(head + 1, std::memory_order_release);
}

void OutputLogWriter::write_rows_until(std::size_t head) {
  std::size_t tail = tail_.load(std::memory_order_relaxed);
  while (tail < head) {
    // Contiguous rows up to the ring's end in one fwrite.
    const std::size_t first = tail % kRingRows;
    const std::size_t n = std::min(head - tail, kRingRows - first);
    std::fwrite(ring_.data() + first * width_, sizeof(double), n * width_, file_);
    tail += n;
    tail_.store(tail, std::memory_order_release);
  }
}

void OutputLogWriter::writer_loop() {
  // Not the node's real-time policy: this thread may wait for the disk.
  sched_param normal{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  while (!stop_.load(std::memory_order_acquire)) {
    write_rows_until(head_.load(std::memory_order_acquire));
    std::fflush(file_);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  write_rows_until(head_.load(std::memory_order_acquire));
}

void OutputLogWriter::close() {
  if (writer_.joinable()) {
    stop_.store(true, std::memory_order_release);
    writer_.join();
  }
  if (file_) {
    if (std::fclose(file_) != 0) {
      file_ = nullptr;
      throw std::runtime_error(path_ + ": write failed: " + std::strerror(errno));
    }
    file_ = nullptr;
  }
}

int OutputLog::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return static_cast<int>(i);
  return -1;
}

OutputLog read_output_log(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the node's output log");
  std::string magic, names;
  std::getline(in, magic);
  std::getline(in, names);
  if (magic != kMagic) throw std::runtime_error(path + ": not a mechsim output log");
  OutputLog log;
  std::stringstream ss(names);
  for (std::string c; std::getline(ss, c, ',');) log.columns.push_back(c);
  log.data.resize(log.columns.size());
  std::vector<double> row(log.columns.size());
  const auto bytes = static_cast<std::streamsize>(row.size() * sizeof(double));
  while (in.read(reinterpret_cast<char*>(row.data()), bytes))
    for (std::size_t i = 0; i < row.size(); ++i) log.data[i].push_back(row[i]);
  return log;
}

double finite_range(std::span<const double> column) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double v : column)
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  return hi > lo ? hi - lo : 0.0;
}

}  // namespace mechsim::cosim
