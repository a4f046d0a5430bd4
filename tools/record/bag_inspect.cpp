#include "bag_inspect.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "cdr_decoder.h"
#include "mechsim/record/mcap_reader.h"
#include "mechsim/transport/raw.h"

namespace mechsim::recorder {

namespace {

namespace fs = std::filesystem;

// Steps seen per run of one data topic, for the gap check.
using StepsByRun = std::map<std::uint64_t, std::vector<std::uint64_t>>;

void count_steps(const StepsByRun& runs, BagTopic& t) {
  bool first = true;
  for (auto [run, steps] : runs) {
    std::sort(steps.begin(), steps.end());
    const auto distinct = static_cast<std::uint64_t>(std::unique(steps.begin(), steps.end()) - steps.begin());
    t.duplicate_steps += steps.size() - distinct;
    t.missing_steps += (steps[distinct - 1] - steps[0] + 1) - distinct;
    t.step_first = first ? steps[0] : std::min(t.step_first, steps[0]);
    t.step_last = first ? steps[distinct - 1] : std::max(t.step_last, steps[distinct - 1]);
    first = false;
  }
}

std::string seconds_text(std::uint64_t ns) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f s", static_cast<double>(ns) * 1e-9);
  return buf;
}

std::string utc_text(std::uint64_t ns) {
  const std::time_t s = static_cast<std::time_t>(ns / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03uZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<unsigned>(ns / 1'000'000 % 1000));
  return buf;
}

std::string size_text(std::uint64_t bytes) {
  char buf[32];
  if (bytes < 10 * 1024)
    std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else if (bytes < 10 * 1024 * 1024)
    std::snprintf(buf, sizeof buf, "%.1f KiB", static_cast<double>(bytes) / 1024);
  else
    std::snprintf(buf, sizeof buf, "%.1f MiB", static_cast<double>(bytes) / (1024 * 1024));
  return buf;
}

std::string hex_id(std::uint64_t id) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(id));
  return buf;
}

std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string csv_quoted(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csv_cell(const FieldValue& v) {
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "1" : "0";
  if (const auto* s = std::get_if<std::string>(&v)) return csv_quoted(*s);
  return to_text(v);
}

}  // namespace

namespace {

record::McapReader open_bag(const std::string& path, const BagReadOptions& options) {
  record::ReaderOptions ro;
  ro.limits = options.limits;
  ro.strict = options.strict;
  return record::McapReader(path, ro);
}

// --strict: a file with any problem (McapReader::verify()) is refused, naming the first.
void refuse_if_damaged(const std::string& path, const std::vector<std::string>& problems) {
  if (!problems.empty())
    throw record::McapError("'" + path + "' is damaged (" + std::to_string(problems.size()) +
                            " problems; without --strict the sound chunks are read): " + problems.front());
}

}  // namespace

BagInfo inspect_bag(const std::string& path, const BagReadOptions& options) {
  const record::McapReader reader = open_bag(path, options);
  BagInfo info;
  info.path = path;
  info.file_size = reader.file_size();
  info.truncated = reader.truncated();
  info.readable_bytes = reader.truncated() ? reader.scan_end() : reader.file_size();
  if (reader.truncated()) info.stop_reason = reader.stop_reason();
  std::set<std::string> compressions;
  for (const auto& c : reader.chunks()) {
    compressions.insert(c.compression.empty() ? "none" : c.compression);
    info.compressed_bytes += c.compressed_size;
    info.uncompressed_bytes += c.uncompressed_size;
  }
  info.compressions.assign(compressions.begin(), compressions.end());
  info.chunks = reader.chunks().size();

  std::map<std::uint16_t, BagTopic> topics;
  std::map<std::uint16_t, const MessageLayout*> layouts;
  std::map<std::uint16_t, StepsByRun> steps;
  for (const auto& [id, ch] : reader.channels()) {
    BagTopic t;
    t.topic = ch.topic;
    t.message_encoding = ch.message_encoding;
    t.metadata = ch.metadata;
    auto schema = reader.schemas().find(ch.schema_id);
    if (schema != reader.schemas().end()) t.type = schema->second.name;
    topics[id] = t;
    layouts[id] = ch.message_encoding == "cdr" ? find_layout(t.type) : nullptr;
  }
  bool first_message = true;
  reader.for_each_message([&](const record::MessageView& m) {
    auto it = topics.find(m.channel_id);
    if (it == topics.end()) return;  // a message of an unknown channel: the reader already refuses those
    BagTopic& t = it->second;
    if (t.messages == 0) {
      t.publish_first_ns = t.publish_last_ns = m.publish_time;
      t.log_first_ns = t.log_last_ns = m.log_time;
    }
    ++t.messages;
    t.bytes += m.data.size();
    t.publish_first_ns = std::min(t.publish_first_ns, m.publish_time);
    t.publish_last_ns = std::max(t.publish_last_ns, m.publish_time);
    t.log_first_ns = std::min(t.log_first_ns, m.log_time);
    t.log_last_ns = std::max(t.log_last_ns, m.log_time);
    if (first_message) {
      info.log_start_ns = info.log_end_ns = m.log_time;
      info.publish_start_ns = info.publish_end_ns = m.publish_time;
      first_message = false;
    }
    info.log_start_ns = std::min(info.log_start_ns, m.log_time);
    info.log_end_ns = std::max(info.log_end_ns, m.log_time);
    info.publish_start_ns = std::min(info.publish_start_ns, m.publish_time);
    info.publish_end_ns = std::max(info.publish_end_ns, m.publish_time);
    ++info.messages;
    if (!layouts[m.channel_id]) {
      ++t.undecodable;
      return;
    }
    try {
      const transport::SampleHeader h = decode_header(m.data);
      if (std::find(t.run_ids.begin(), t.run_ids.end(), h.run_id) == t.run_ids.end()) t.run_ids.push_back(h.run_id);
      if (transport::topic_kind(t.topic) == transport::TopicKind::data) steps[m.channel_id][h.run_id].push_back(h.step);
    } catch (const CdrError&) {
      ++t.undecodable;
    }
  });
  for (auto& [id, t] : topics) {
    count_steps(steps[id], t);
    info.topics.push_back(std::move(t));
  }
  std::sort(info.topics.begin(), info.topics.end(), [](const BagTopic& a, const BagTopic& b) { return a.topic < b.topic; });
  info.problems = reader.verify();
  if (options.strict) refuse_if_damaged(path, info.problems);
  info.chunks_skipped = reader.damaged().size();
  info.damaged = !info.problems.empty();
  info.complete = reader.complete() && !info.damaged;
  info.accounting = reader.accounting();
  return info;
}

int exit_code(const BagInfo& info) { return info.damaged ? kBagDamagedExitCode : 0; }
int exit_code(const BagExport& result) { return result.skipped_chunks.empty() ? 0 : kBagDamagedExitCode; }

nlohmann::json to_json(const BagInfo& info) {
  nlohmann::json topics = nlohmann::json::array();
  for (const auto& t : info.topics) {
    nlohmann::json runs = nlohmann::json::array();
    for (auto r : t.run_ids) runs.push_back(hex_id(r));
    nlohmann::json j{{"topic", t.topic},
                     {"type", t.type},
                     {"message_encoding", t.message_encoding},
                     {"metadata", t.metadata},
                     {"messages", t.messages},
                     {"bytes", t.bytes},
                     {"publish_time_s", {static_cast<double>(t.publish_first_ns) * 1e-9, static_cast<double>(t.publish_last_ns) * 1e-9}},
                     {"log_time_ns", {t.log_first_ns, t.log_last_ns}},
                     {"run_ids", runs},
                     {"undecodable", t.undecodable}};
    if (transport::topic_kind(t.topic) == transport::TopicKind::data)
      j["steps"] = {{"first", t.step_first}, {"last", t.step_last}, {"missing", t.missing_steps}, {"duplicates", t.duplicate_steps}};
    topics.push_back(j);
  }
  return {{"file", info.path},
          {"file_size", info.file_size},
          {"complete", info.complete},
          {"damaged", info.damaged},
          {"chunks_skipped", info.chunks_skipped},
          {"truncated", info.truncated},
          {"stop_reason", info.stop_reason},
          {"readable_bytes", info.readable_bytes},
          {"compression", info.compressions},
          {"chunks", info.chunks},
          {"compressed_bytes", info.compressed_bytes},
          {"uncompressed_bytes", info.uncompressed_bytes},
          {"messages", info.messages},
          {"log_time_ns", {info.log_start_ns, info.log_end_ns}},
          {"publish_time_s", {static_cast<double>(info.publish_start_ns) * 1e-9, static_cast<double>(info.publish_end_ns) * 1e-9}},
          {"topics", topics},
          {"problems", info.problems}};
}

std::string format_bag_info(const BagInfo& info) {
  std::ostringstream o;
  o << "file:         " << info.path << "\n";
  o << "state:        "
    << (info.complete    ? "complete"
        : info.truncated ? "TRUNCATED (not closed; `mechsim record --recover` rebuilds it)"
        : info.damaged   ? "DAMAGED (problems below; `mechsim record --recover` keeps the sound chunks)"
                         : "complete data section without a summary")
    << "\n";
  if (info.damaged && info.chunks_skipped > 0)
    o << "              " << info.chunks_skipped << " damaged chunks skipped: their messages are not counted\n";
  if (info.truncated) o << "              read up to byte " << info.readable_bytes << ": " << info.stop_reason << "\n";
  std::string comp;
  for (const auto& c : info.compressions) comp += (comp.empty() ? "" : ", ") + c;
  o << "size:         " << size_text(info.file_size) << " (" << info.file_size << " bytes); " << info.chunks << " chunks, "
    << size_text(info.compressed_bytes) << " compressed from " << size_text(info.uncompressed_bytes)
    << (comp.empty() ? "" : " (" + comp + ")") << "\n";
  o << "messages:     " << info.messages << "\n";
  if (info.messages > 0) {
    o << "log time:     " << utc_text(info.log_start_ns) << " .. " << utc_text(info.log_end_ns) << " ("
      << seconds_text(info.log_end_ns - info.log_start_ns) << " wall)\n";
    o << "publish time: " << seconds_text(info.publish_start_ns) << " .. " << seconds_text(info.publish_end_ns)
      << " (simulated)\n";
  }
  std::size_t width = 5;
  for (const auto& t : info.topics) width = std::max(width, t.topic.size());
  o << "topics:\n";
  for (const auto& t : info.topics) {
    char line[512];
    std::snprintf(line, sizeof line, "  %-*s  %-28s %8llu msgs  %10s  t %.6f .. %.6f s", static_cast<int>(width),
                  t.topic.c_str(), t.type.c_str(), static_cast<unsigned long long>(t.messages), size_text(t.bytes).c_str(),
                  static_cast<double>(t.publish_first_ns) * 1e-9, static_cast<double>(t.publish_last_ns) * 1e-9);
    o << line;
    if (transport::topic_kind(t.topic) == transport::TopicKind::data && t.messages > 0) {
      o << "  steps " << t.step_first << ".." << t.step_last;
      if (t.missing_steps || t.duplicate_steps)
        o << " (" << t.missing_steps << " missing, " << t.duplicate_steps << " duplicated)";
    }
    if (t.run_ids.size() > 1) o << "  " << t.run_ids.size() << " runs";
    if (t.undecodable) o << "  " << t.undecodable << " undecodable";
    o << "\n";
    // An FMU participant's topic: its variable names, as the recorder wrote them.
    if (auto it = t.metadata.find(kFieldsMetadataKey); it != t.metadata.end())
      o << "  " << std::string(static_cast<std::size_t>(width), ' ') << "  fields: " << it->second << "\n";
  }
  for (const auto& p : info.problems) o << "problem:      " << p << "\n";
  return o.str();
}

std::string csv_file_name(const std::string& topic) {
  std::string name = topic;
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_')) c = '_';
  return name + ".csv";
}

BagExport export_csv(const std::string& bag, const std::string& dir, const BagReadOptions& options) {
  const record::McapReader reader = open_bag(bag, options);
  if (options.strict) refuse_if_damaged(bag, reader.verify());  // a lie the index reads past (a record length)
  fs::create_directories(dir);
  struct Output {
    ExportedTopic topic;
    std::optional<MessageLayout> layout;
    bool unnamed = false;  // FmuOutputs without its names in the channel: named from the first sample
    std::unique_ptr<std::ofstream> file;
  };
  const auto write_header = [](Output& out) {
    *out.file << "t,step,run_id";
    for (const auto& f : out.layout->fields) *out.file << "," << csv_quoted(f.name);
    *out.file << "\n";
  };
  std::map<std::uint16_t, Output> outputs;
  std::set<std::string> used_names;
  for (const auto& [id, ch] : reader.channels()) {
    Output out;
    out.topic.topic = ch.topic;
    auto schema = reader.schemas().find(ch.schema_id);
    if (schema != reader.schemas().end() && ch.message_encoding == "cdr") {
      try {
        out.layout = channel_layout(schema->second.name, ch.metadata);
      } catch (const CdrError&) {
        out.layout.reset();  // metadata that is not a field list: the topic is skipped, as undecodable
      }
    }
    out.unnamed = out.layout && out.layout->sequences && out.layout->fields.empty();
    if (out.layout) {
      std::string name = csv_file_name(ch.topic);
      // Two topics that differ only in replaced characters must not share a file.
      for (int k = 2; used_names.count(name); ++k) name = csv_file_name(ch.topic + "-" + std::to_string(k));
      used_names.insert(name);
      out.topic.file = (fs::path(dir) / name).string();
      out.file = std::make_unique<std::ofstream>(out.topic.file);
      if (!*out.file) throw std::runtime_error("cannot write " + out.topic.file);
      if (!out.unnamed) write_header(out);
    }
    outputs.emplace(id, std::move(out));
  }
  std::string row;
  reader.for_each_message([&](const record::MessageView& m) {
    auto it = outputs.find(m.channel_id);
    if (it == outputs.end()) return;
    Output& out = it->second;
    if (!out.layout) {
      ++out.topic.skipped;
      return;
    }
    DecodedSample s;
    try {
      if (out.unnamed) {
        out.layout = unnamed_fmu_layout(m.data);
        out.unnamed = false;
        write_header(out);
      }
      s = decode_sample(m.data, *out.layout);
    } catch (const CdrError&) {
      ++out.topic.skipped;
      return;
    }
    row = number_text(s.header.t) + "," + std::to_string(s.header.step) + "," + std::to_string(s.header.run_id);
    for (const auto& v : s.values) row += "," + csv_cell(v);
    row += "\n";
    *out.file << row;
    ++out.topic.rows;
  });
  BagExport result;
  for (auto& [id, out] : outputs) {
    if (out.file) {
      out.file->close();
      if (!*out.file) throw std::runtime_error("cannot write " + out.topic.file);
    }
    result.topics.push_back(out.topic);
  }
  std::sort(result.topics.begin(), result.topics.end(),
            [](const ExportedTopic& a, const ExportedTopic& b) { return a.topic < b.topic; });
  result.skipped_chunks = reader.damaged();
  return result;
}

}  // namespace mechsim::recorder
