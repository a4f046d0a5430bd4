// Plain POSIX file access: positioned reads for the reader, unbuffered appends (each call
// hands the bytes to the kernel at once) for the writer.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "byte_io.h"

namespace mechsim::record::detail {

class InputFile {
 public:
  explicit InputFile(const std::string& path);  // throws McapError naming the path
  ~InputFile();
  InputFile(InputFile&& other) noexcept;
  InputFile& operator=(InputFile&& other) noexcept;
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  uint64_t size() const { return size_; }
  // Reads exactly n bytes at `offset`; throws McapError if the file is shorter.
  Buffer read(uint64_t offset, uint64_t n) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

class OutputFile {
 public:
  explicit OutputFile(const std::string& path);  // creates/truncates; throws runtime_error
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void append(std::span<const uint8_t> bytes);  // write(2) until done; throws on failure
  void data_sync();                             // fdatasync(2)
  void close();                                 // throws if close(2) reports an error
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const char* what) const;
  std::string path_;
  int fd_ = -1;
};

}  // namespace mechsim::record::detail
