#include "file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace mechsim::record::detail {

InputFile::InputFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw McapError("cannot open '" + path + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int err = errno;
    ::close(fd_);
    throw McapError("cannot stat '" + path + "': " + std::strerror(err));
  }
  size_ = static_cast<uint64_t>(st.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

InputFile::InputFile(InputFile&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)), size_(other.size_) {}

InputFile& InputFile::operator=(InputFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    size_ = other.size_;
  }
  return *this;
}

Buffer InputFile::read(uint64_t offset, uint64_t n) const {
  if (offset > size_ || n > size_ - offset)
    throw McapError("'" + path_ + "': reading " + std::to_string(n) + " bytes at offset " +
                    std::to_string(offset) + " runs past the end of the file (" +
                    std::to_string(size_) + " bytes)");
  Buffer out(static_cast<std::size_t>(n));
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t got = ::pread(fd_, out.data() + done, out.size() - done,
                                static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0)
      throw McapError("'" + path_ + "': read failed at offset " + std::to_string(offset + done) +
                      (got < 0 ? std::string(": ") + std::strerror(errno) : ": file shrank"));
    done += static_cast<std::size_t>(got);
  }
  return out;
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create");
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::fail(const char* what) const {
  throw std::runtime_error(std::string("mcap: ") + what + " '" + path_ + "': " +
                           std::strerror(errno));
}

void OutputFile::append(std::span<const uint8_t> bytes) {
  if (fd_ < 0) throw std::logic_error("mcap: write to closed file '" + path_ + "'");
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("write to");
    done += static_cast<std::size_t>(n);
  }
}

void OutputFile::data_sync() {
  if (fd_ >= 0 && ::fdatasync(fd_) != 0) fail("fdatasync");
}

void OutputFile::close() {
  if (fd_ < 0) return;
  const int rc = ::close(std::exchange(fd_, -1));
  if (rc != 0) fail("close");
}

}  // namespace mechsim::record::detail
