// The time series a node writes into the run folder: every block output at every macro
// step, as raw doubles, so that logging costs nothing next to a DDS round trip. The
// launcher reads it back to compare with the reference.
//
// File layout: the line "mechsim-outputs 1\n", one line of comma-separated column names
// ("t,<output>,...\n"), then rows of native little-endian doubles.
#pragma once

#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace mechsim::cosim {

class OutputLogWriter {
 public:
  OutputLogWriter(const std::string& path, const std::vector<std::string>& columns);
  ~OutputLogWriter();
  void append(double t, std::span<const double> values);
  void close();

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::size_t width_;
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

}  // namespace mechsim::cosim
