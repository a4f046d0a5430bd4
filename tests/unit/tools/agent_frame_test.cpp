// The agent frames of an SSH session (tools/hostrun/agent_frame.h): a message comes back
// whole however the stream cuts it, and bytes that are not a frame, a frame over the limit or
// a frame whose fields overrun its body end the stream with a FrameError naming the fault.
#include <gtest/gtest.h>

#include "agent_frame.h"

namespace mechsim::hostrun {
namespace {

transport::AgentMessage sample() {
  transport::AgentMessage m;
  m.run_id = 0x0123456789abcdefull;
  m.sequence = 7;
  m.kind = 104;
  m.host = "10.77.0.2";
  m.node = "servo";
  m.text = R"({"offset":0})";
  for (int i = 0; i < 300; ++i) m.data.push_back(static_cast<std::byte>(i & 0xff));
  return m;
}

void expect_same(const transport::AgentMessage& a, const transport::AgentMessage& b) {
  EXPECT_EQ(a.run_id, b.run_id);
  EXPECT_EQ(a.sequence, b.sequence);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.host, b.host);
  EXPECT_EQ(a.node, b.node);
  EXPECT_EQ(a.text, b.text);
  EXPECT_TRUE(a.data == b.data);
}

// The FrameError the reader's next frame raises ("" when it raises none).
std::string frame_error(FrameReader& reader) {
  try {
    reader.next();
  } catch (const FrameError& e) {
    return e.what();
  }
  return "";
}

TEST(AgentFrame, MessagesComeBackWholeWhenTheStreamArrivesByteByByte) {
  const std::string two = encode_frame(sample()) + encode_frame(transport::AgentMessage{});
  FrameReader reader;
  std::vector<transport::AgentMessage> got;
  for (char c : two) {
    reader.feed(&c, 1);
    while (auto m = reader.next()) got.push_back(*m);
  }
  ASSERT_EQ(got.size(), 2u);
  expect_same(got[0], sample());
  expect_same(got[1], transport::AgentMessage{});
  EXPECT_EQ(reader.buffered(), 0u);
}

TEST(AgentFrame, BytesThatAreNotAFrameAreRefused) {
  FrameReader reader;
  const std::string junk = "GET / HTTP/1.1\r\n";
  reader.feed(junk.data(), junk.size());
  const std::string error = frame_error(reader);
  EXPECT_NE(error.find("not a mechsim agent frame"), std::string::npos) << "junk parsed as a frame: '" << error << "'";
}

TEST(AgentFrame, AFrameOverTheLimitIsRefusedBeforeItsBodyArrives) {
  FrameReader reader(1000);
  const std::string frame = encode_frame(sample());  // 300 bytes of data and ~80 of fields: under 1000
  reader.feed(frame.data(), frame.size());
  EXPECT_TRUE(reader.next().has_value());
  FrameReader small(100);
  small.feed(frame.data(), 8);  // the header only: refused on the length it announces
  const std::string error = frame_error(small);
  EXPECT_NE(error.find("over the limit of 100 bytes"), std::string::npos) << "a frame over the limit: '" << error << "'";
}

TEST(AgentFrame, AFieldThatOverrunsTheBodyIsRefused) {
  std::string frame = encode_frame(sample());
  // The host field's length (after magic, length, run id, sequence, kind: byte 28) made huge.
  frame[28] = static_cast<char>(0xff);
  frame[29] = static_cast<char>(0xff);
  FrameReader reader;
  reader.feed(frame.data(), frame.size());
  const std::string error = frame_error(reader);
  EXPECT_NE(error.find("host overruns its body"), std::string::npos) << "an overrunning field: '" << error << "'";
}

}  // namespace
}  // namespace mechsim::hostrun
