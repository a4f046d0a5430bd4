// Shared helpers for the record tests: scratch files and a reproducible sample recording
// (3 channels on 2 schemas, CDR-like payloads of slowly varying doubles).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_writer.h"

namespace mechsim::record::test {

// A fresh directory per test, removed by the caller's ScratchDir destructor.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "." + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    path_ = std::filesystem::temp_directory_path() / "mechsim_record_test" /
            (name + "." + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

inline std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::string& path, const uint8_t* data, std::size_t n) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n));
}

inline uint64_t le_u64(const std::vector<uint8_t>& b, std::size_t at) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(b.at(at + i)) << (8 * i);
  return v;
}
inline uint32_t le_u32(const std::vector<uint8_t>& b, std::size_t at) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t(b.at(at + i)) << (8 * i);
  return v;
}
inline uint16_t le_u16(const std::vector<uint8_t>& b, std::size_t at) {
  return static_cast<uint16_t>(b.at(at) | b.at(at + 1) << 8);
}

inline const std::vector<uint8_t> kMcapMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

inline const char* kCamStateIdl = R"(module mechsim { module msg {
struct CamState { double time; double angle; double speed; double torque; };
}; };)";
inline const char* kFollowerStateIdl = R"(module mechsim { module msg {
struct FollowerState { double time; double lift; double velocity; double contact_force;
  unsigned long step; };
}; };)";

// A CDR-like payload: encapsulation header then `n_doubles` slowly varying doubles, as a
// node's state sample would look (so compression ratios are realistic, not best case).
inline std::vector<std::byte> sample_payload(uint64_t i, uint16_t channel, std::size_t n_doubles) {
  std::vector<std::byte> out(4 + 8 * n_doubles);
  out[1] = std::byte{0x01};  // CDR little endian
  for (std::size_t k = 0; k < n_doubles; ++k) {
    const double v = std::sin(1e-3 * double(i) * double(k + 1) + channel) * (k + 1.5);
    std::memcpy(out.data() + 4 + 8 * k, &v, 8);
  }
  return out;
}

struct SampleRecording {
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
  std::vector<Message> messages;  // in write order (log times strictly increasing)
};

// Writes `count` messages round-robin on 3 channels (payload sizes 36, 44 and 100 bytes),
// log time 1 ms apart from 1.7e18 ns, publish time = simulated time 100 us apart.
inline SampleRecording write_sample(const std::string& path, const WriterOptions& options,
                                    std::size_t count) {
  SampleRecording rec;
  McapWriter writer(path, options);
  const uint16_t cam = writer.add_schema("mechsim::msg::CamState", "omgidl", kCamStateIdl);
  const uint16_t follower =
      writer.add_schema("mechsim::msg::FollowerState", "omgidl", kFollowerStateIdl);
  rec.schemas = {{cam, "mechsim::msg::CamState", "omgidl", kCamStateIdl},
                 {follower, "mechsim::msg::FollowerState", "omgidl", kFollowerStateIdl}};
  const std::map<std::string, std::string> meta{{"offered_qos_profiles", "reliable"}};
  struct Topic { const char* name; uint16_t schema; std::size_t doubles; };
  const Topic topics[] = {{"cam_shaft/state", cam, 4}, {"follower/state", follower, 5},
                          {"cam_shaft/detail", cam, 12}};
  for (const Topic& t : topics) {
    const uint16_t id = writer.add_channel(t.schema, t.name, "cdr", meta);
    rec.channels.push_back({id, t.schema, t.name, "cdr", meta});
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t k = i % 3;
    Message m{rec.channels[k].id, static_cast<uint32_t>(i / 3),
              1'700'000'000'000'000'000ull + 1'000'000ull * i, 100'000ull * i,
              sample_payload(i, rec.channels[k].id, topics[k].doubles)};
    writer.write(m.channel_id, m.sequence, m.log_time, m.publish_time, m.data);
    rec.messages.push_back(std::move(m));
  }
  writer.close();
  return rec;
}

}  // namespace mechsim::record::test
