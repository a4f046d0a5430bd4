// Recording a DDS domain into an MCAP file (docs/recording.md): every selected mechsim
// topic is read raw (the CDR bytes as on the wire) and written as one MCAP channel, with
// one schema per IDL type. A Recorder runs on a thread of its own, so `mechsim record`
// and the launcher (a scene's `record:` section) use it alike:
//
//   auto rec = start_recording(domain, options);  // readers exist when this returns
//   ... start the nodes, wait until they are ready ...
//   rec->wait_matched(topics, 5s);                // every expected writer is matched
//   ... send start, run ...
//   RecordingReport report = rec->stop();         // drains, closes the file, counts
//
// Topics are found through DDS discovery (a topic is subscribed to as soon as a writer of
// a known type appears on it); topics given with their type in `topic_types` get their
// reader at once, before any writer exists, which is what a launcher wants.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "mechsim/record/mcap_writer.h"

namespace mechsim::recorder {

// Which topics to record. With no names and no regex: every topic whose type is a mechsim
// type (the data types of transport/topic_types.h, Control and Status).
struct TopicSelection {
  std::vector<std::string> names;  // exact topic names
  std::string regex;               // ECMAScript; must match the whole topic name
  // Throws std::invalid_argument for a malformed regex or both names and a regex.
  void validate() const;
  bool all() const { return names.empty() && regex.empty(); }
  bool selects(const std::string& topic) const;
};

struct RecordOptions {
  std::string file;  // the MCAP file to write (created, truncated)
  TopicSelection topics;
  // Topic -> IDL type (scoped or short name) of topics to subscribe to at start, before
  // their writers exist. Every entry must also be selected.
  std::map<std::string, std::string> topic_types;
  // FmuOutputs topics' field lists (cdr_decoder.h fields_text), written into their
  // channels' metadata as "mechsim.fields", so that bag and third-party readers know the
  // FMU's variable names.
  std::map<std::string, std::string> topic_fields;
  record::Compression compression = record::Compression::zstd;
  // How often the recording thread wakes without data to close a due chunk
  // (McapWriter::flush_if_due) and look at discovery.
  std::chrono::milliseconds flush_period{100};
  // After taking what its readers held, the recording thread rests this long before it
  // looks again, so that it wakes a few hundred times a second rather than once per
  // sample (the samples wait in the readers' history meanwhile: reliable keep-all loses
  // nothing, and DDS acknowledges them on arrival, so the writers are not held up).
  std::chrono::microseconds batch_period{2000};
  std::chrono::milliseconds max_chunk_interval{1000};  // bounds what a crash can lose
  record::SyncMode sync = record::SyncMode::flush;
  std::string vendor = "cyclone";
};

struct TopicCount {
  std::string topic;
  std::string type;               // fully scoped IDL type
  bool reliable = true;           // data and control topics; status is best effort
  std::uint64_t samples = 0;      // recorded
  std::uint64_t lost = 0;         // DDS SAMPLE_LOST count (only a best-effort topic has any)
  // Data topics: samples of a (run, step) the file holds already, not written again: the
  // steps a run repeats after a rollback to a checkpoint (docs/faults.md).
  std::uint64_t repeated = 0;
  int matched_writers = 0;        // at the time of the count
};

struct RecordingReport {
  std::string file;
  std::vector<TopicCount> topics;  // sorted by topic name
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;         // file size after close
  double wall_time_s = 0.0;        // start_recording() to stop()
  std::string error;               // what stopped the recording early ("" if nothing did)
};

class Recorder {
 public:
  virtual ~Recorder() = default;
  // Blocks until the reader of each topic in `topics` is matched with at least one writer
  // (the topic must be selected; with discovery, its reader appears with its first
  // writer). Returns false on timeout, naming nothing; counts() shows which are missing.
  // Safe from any thread.
  virtual bool wait_matched(const std::vector<std::string>& topics, std::chrono::milliseconds timeout) = 0;
  // Samples recorded so far, per topic (safe from any thread).
  virtual std::vector<TopicCount> counts() const = 0;
  // Takes what the readers still hold, writes the summary and closes the file. Idempotent
  // (a second call returns the first report). Never throws: failures go to `error`.
  virtual RecordingReport stop() = 0;
  virtual const std::string& file() const = 0;
};

// Creates the participant, the MCAP file and the readers of `options.topic_types`, then
// starts the recording thread. Throws std::invalid_argument for bad options (selection,
// unknown type) and std::runtime_error when DDS or the file refuse.
std::unique_ptr<Recorder> start_recording(int domain_id, const RecordOptions& options);

// "zstd", "lz4", "none" -> Compression; throws std::invalid_argument otherwise.
record::Compression parse_compression(const std::string& name);

}  // namespace mechsim::recorder
