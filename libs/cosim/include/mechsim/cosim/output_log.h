// The time series a node writes into the run folder: every block output at every macro
// step, as raw doubles, so that logging costs nothing next to a DDS round trip. The
// launcher reads it back to compare with the reference.
//
// File layout: the line "mechsim-outputs 1\n", one line of comma-separated column names
// ("t,<output>,...\n"), then rows of native little-endian doubles.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <thread>
#include <span>
#include <string>
#include <vector>

namespace mechsim::cosim {

class OutputLogWriter {
 public:
  // direct: append() writes through stdio in the calling thread. background: append()
  // copies the row into a preallocated ring that a thread of its own (SCHED_OTHER, whatever
  // the node's policy) writes out, so that a paced node never waits for the disk in a step
  // (a write() can block for milliseconds while the file system commits; seen here).
  enum class Mode { direct, background };
  OutputLogWriter(const std::string& path, const std::vector<std::string>& columns, Mode mode = Mode::direct);
  // A node resumed from a checkpoint (checkpoint.h): reopens the existing log and keeps its
  // first `rows` rows, dropping what was written after the checkpoint. Direct mode only.
  struct Resume {
    std::uint64_t rows;
  };
  OutputLogWriter(const std::string& path, const std::vector<std::string>& columns, Resume resume);
  ~OutputLogWriter();
  void append(double t, std::span<const double> values);
  // Rows appended so far (resumed rows included).
  std::uint64_t rows() const { return rows_; }
  // Direct mode: writes the buffered rows to the file (a checkpoint needs them there).
  void flush();
  // Direct mode: drops every row after the first `rows` (a rollback to a checkpoint).
  void truncate_rows(std::uint64_t rows);
  // Writes what is left and closes the file (joins the writer thread). Throws on a write error.
  void close();
  // Appends that found the ring full and waited for the writer thread (background mode).
  long ring_full_waits() const { return ring_full_waits_; }

 private:
  void write_rows_until(std::size_t head);  // writer thread: ring rows [tail, head) to the file
  void writer_loop();
  std::FILE* file_ = nullptr;
  std::string path_;
  std::size_t width_;
  Mode mode_;
  long header_bytes_ = 0;
  std::uint64_t rows_ = 0;
  // background mode: single producer (append), single consumer (the writer thread)
  static constexpr std::size_t kRingRows = 16384;
  std::vector<double> ring_;
  std::atomic<std::size_t> head_{0}, tail_{0};  // rows appended / rows written, ever
  std::atomic<bool> stop_{false};
  std::thread writer_;
  long ring_full_waits_ = 0;
};

struct OutputLog {
  std::vector<std::string> columns;          // "t" first
  std::vector<std::vector<double>> data;     // data[column][row]
  int column(const std::string& name) const; // -1 when absent
  std::size_t rows() const { return data.empty() ? 0 : data[0].size(); }
};

// Throws std::runtime_error naming the file when it is missing or malformed. A truncated
// last row (a node killed while writing) is dropped.
OutputLog read_output_log(const std::string& path);

// max - min of a column's finite values (0 when it holds fewer than two distinct ones): the
// range an adaptive step's scale is compared with (time.scales).
double finite_range(std::span<const double> column);

}  // namespace mechsim::cosim
