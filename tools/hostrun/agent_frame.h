// The agent conversation (agent_protocol.h) on a byte stream: the SSH session of
// `mechsim agent --stdio` (requests on its stdin, replies on its stdout). One frame per
// message, all integers little-endian:
//
//   "MSA1"  u32 body length  |  u64 run_id  u64 sequence  i32 kind
//                            |  u32 n + host  u32 n + node  u32 n + text  u32 n + data
//
// A reader takes bytes as they come and yields whole messages; a frame that does not parse,
// or whose body exceeds the reader's limit, ends the stream (FrameError): a peer that sends
// one is not speaking this protocol, and nothing after it can be trusted to be aligned.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include "mechsim/transport/messages.h"

namespace mechsim::hostrun {

// The largest body a reader accepts by default: a file chunk (kAgentChunkBytes) or a start
// request with its scene text, with room to spare; a 33-participant scene is ~40 kB.
inline constexpr std::size_t kMaxFrameBytes = 4u << 20;

struct FrameError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string encode_frame(const transport::AgentMessage& m);

class FrameReader {
 public:
  explicit FrameReader(std::size_t max_body_bytes = kMaxFrameBytes) : max_(max_body_bytes) {}
  void feed(const char* bytes, std::size_t n) { buffer_.append(bytes, n); }
  // The next whole message, or nothing until more bytes come. Throws FrameError for a frame
  // without the magic, with a body over the limit, or whose fields overrun its body.
  std::optional<transport::AgentMessage> next();
  std::size_t buffered() const { return buffer_.size(); }

 private:
  std::size_t max_;
  std::string buffer_;
};

}  // namespace mechsim::hostrun
