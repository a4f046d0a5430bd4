#include "mechsim/cosim/output_log.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mechsim::cosim {

namespace {
constexpr const char* kMagic = "mechsim-outputs 1";
}

OutputLogWriter::OutputLogWriter(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), width_(columns.size() + 1) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  std::string header = std::string(kMagic) + "\nt";
  for (const auto& c : columns) header += "," + c;
  header += "\n";
  std::fwrite(header.data(), 1, header.size(), file_);
}

OutputLogWriter::~OutputLogWriter() { close(); }

void OutputLogWriter::append(double t, std::span<const double> values) {
  std::fwrite(&t, sizeof t, 1, file_);
  std::fwrite(values.data(), sizeof(double), values.size(), file_);
}

void OutputLogWriter::close() {
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

}  // namespace mechsim::cosim
