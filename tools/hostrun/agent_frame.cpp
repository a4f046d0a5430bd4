#include "agent_frame.h"

#include <cstdint>
#include <cstring>

namespace mechsim::hostrun {

namespace {

constexpr char kMagic[4] = {'M', 'S', 'A', '1'};

template <typename T>
void put(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xff));
}

void put_bytes(std::string& out, const void* bytes, std::size_t n) {
  put<std::uint32_t>(out, static_cast<std::uint32_t>(n));
  out.append(static_cast<const char*>(bytes), n);
}

// Reads fields from a frame's body; every read is checked against its end.
class BodyReader {
 public:
  BodyReader(const char* p, std::size_t n) : p_(p), end_(p + n) {}
  template <typename T>
  T get() {
    need(sizeof(T), "an integer");
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(p_[i])) << (8 * i);
    p_ += sizeof(T);
    return static_cast<T>(v);
  }
  std::string bytes(const char* what) {
    const auto n = get<std::uint32_t>();
    need(n, what);
    std::string out(p_, n);
    p_ += n;
    return out;
  }
  bool at_end() const { return p_ == end_; }

 private:
  void need(std::size_t n, const char* what) const {
    if (static_cast<std::size_t>(end_ - p_) < n) throw FrameError(std::string("a frame whose ") + what + " overruns its body");
  }
  const char* p_;
  const char* end_;
};

}  // namespace

std::string encode_frame(const transport::AgentMessage& m) {
  std::string body;
  put<std::uint64_t>(body, m.run_id);
  put<std::uint64_t>(body, m.sequence);
  put<std::uint32_t>(body, static_cast<std::uint32_t>(m.kind));
  put_bytes(body, m.host.data(), m.host.size());
  put_bytes(body, m.node.data(), m.node.size());
  put_bytes(body, m.text.data(), m.text.size());
  put_bytes(body, m.data.data(), m.data.size());
  std::string frame(kMagic, sizeof kMagic);
  put<std::uint32_t>(frame, static_cast<std::uint32_t>(body.size()));
  return frame + body;
}

std::optional<transport::AgentMessage> FrameReader::next() {
  if (buffer_.size() < 8) return std::nullopt;
  if (std::memcmp(buffer_.data(), kMagic, sizeof kMagic) != 0)
    throw FrameError("bytes that are not a mechsim agent frame (no \"MSA1\" at the start of a frame)");
  std::uint32_t length = 0;
  for (int i = 0; i < 4; ++i) length |= static_cast<std::uint32_t>(static_cast<unsigned char>(buffer_[4 + i])) << (8 * i);
  if (length > max_)
    throw FrameError("a frame of " + std::to_string(length) + " bytes, over the limit of " + std::to_string(max_) + " bytes");
  if (buffer_.size() < 8 + static_cast<std::size_t>(length)) return std::nullopt;
  BodyReader r(buffer_.data() + 8, length);
  transport::AgentMessage m;
  m.run_id = r.get<std::uint64_t>();
  m.sequence = r.get<std::uint64_t>();
  m.kind = static_cast<std::int32_t>(r.get<std::uint32_t>());
  m.host = r.bytes("host");
  m.node = r.bytes("node");
  m.text = r.bytes("text");
  const std::string data = r.bytes("data");
  if (!r.at_end()) throw FrameError("a frame with bytes after its last field");
  const auto* p = reinterpret_cast<const std::byte*>(data.data());
  m.data.assign(p, p + data.size());
  buffer_.erase(0, 8 + static_cast<std::size_t>(length));
  return m;
}

}  // namespace mechsim::hostrun
