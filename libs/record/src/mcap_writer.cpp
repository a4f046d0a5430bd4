#include "mechsim/record/mcap_writer.h"

#include <algorithm>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "compression.h"
#include "crc32.h"
#include "file_sink.h"
#include "records.h"

namespace mechsim::record {

using namespace detail;
using Clock = std::chrono::steady_clock;

struct McapWriter::Impl {
  Impl(const std::string& path, WriterOptions opts)
      : options(std::move(opts)),
        sink(path, HeaderRecord{options.profile, options.library},
             options.sync == SyncMode::data_sync) {}

  bool chunk_due(Clock::time_point now) const {
    return !chunk.empty() && now - chunk_opened >= options.max_chunk_interval;
  }

  // Compresses and writes the open chunk (if any) with its message indexes.
  void finish_chunk() {
    if (chunk.empty()) return;
    ChunkHeader header;
    header.message_start_time = chunk_start_time;
    header.message_end_time = chunk_end_time;
    header.uncompressed_size = chunk.size();
    header.uncompressed_crc = crc32_update(0, chunk);
    header.compression = compression_name(options.compression);
    const Buffer compressed = compress(options.compression, chunk);
    header.records = compressed;
    Buffer record;
    record.reserve(compressed.size() + 64);
    encode_chunk(record, header);
    sink.write_chunk(record, header, index);
    chunk.clear();
    index.clear();
  }

  void require_open() const {
    if (closed) throw std::logic_error("McapWriter: already closed");
  }

  std::mutex mutex;
  WriterOptions options;
  McapFileSink sink;
  bool closed = false;

  Buffer chunk;  // uncompressed records of the open chunk
  MessageIndex index;
  uint64_t chunk_start_time = 0;
  uint64_t chunk_end_time = 0;
  Clock::time_point chunk_opened;

  uint32_t next_schema_id = 1;
  uint32_t next_channel_id = 1;
  uint64_t message_count = 0;
  std::map<uint16_t, uint64_t> channel_message_counts;
};

McapWriter::McapWriter(const std::string& path, WriterOptions options)
    : impl_(std::make_unique<Impl>(path, std::move(options))) {
  if (impl_->options.chunk_size == 0) throw std::invalid_argument("McapWriter: chunk_size is 0");
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (...) {
    // A destructor must not throw; close() explicitly to see I/O errors.
  }
}

uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                const std::string& data) {
  std::lock_guard lock(impl_->mutex);
  impl_->require_open();
  if (impl_->next_schema_id > std::numeric_limits<uint16_t>::max())
    throw std::length_error("McapWriter: more than 65535 schemas");
  Schema schema{static_cast<uint16_t>(impl_->next_schema_id++), name, encoding, data};
  impl_->sink.write_schema(schema);
  return schema.id;
}

uint16_t McapWriter::add_channel(uint16_t schema_id, const std::string& topic,
                                 const std::string& message_encoding,
                                 const std::map<std::string, std::string>& metadata) {
  std::lock_guard lock(impl_->mutex);
  impl_->require_open();
  if (schema_id != 0 && !impl_->sink.has_schema(schema_id))
    throw std::invalid_argument("McapWriter: unknown schema id " + std::to_string(schema_id) +
                                " for topic '" + topic + "'");
  if (impl_->next_channel_id > std::numeric_limits<uint16_t>::max())
    throw std::length_error("McapWriter: more than 65535 channels");
  Channel channel{static_cast<uint16_t>(impl_->next_channel_id++), schema_id, topic,
                  message_encoding, metadata};
  impl_->sink.write_channel(channel);
  return channel.id;
}

void McapWriter::write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns,
                       uint64_t publish_time_ns, std::span<const std::byte> data) {
  std::lock_guard lock(impl_->mutex);
  Impl& w = *impl_;
  w.require_open();
  if (!w.sink.has_channel(channel_id))
    throw std::invalid_argument("McapWriter: unknown channel id " + std::to_string(channel_id));
  const Clock::time_point now = Clock::now();
  if (w.chunk.empty()) {
    w.chunk_opened = now;
    w.chunk_start_time = log_time_ns;
    w.chunk_end_time = log_time_ns;
  }
  w.index[channel_id].push_back({log_time_ns, w.chunk.size()});
  encode_message(w.chunk, channel_id, sequence, log_time_ns, publish_time_ns, as_u8(data));
  w.chunk_start_time = std::min(w.chunk_start_time, log_time_ns);
  w.chunk_end_time = std::max(w.chunk_end_time, log_time_ns);
  ++w.message_count;
  ++w.channel_message_counts[channel_id];
  if (w.chunk.size() >= w.options.chunk_size || w.chunk_due(now)) w.finish_chunk();
}

void McapWriter::flush() {
  std::lock_guard lock(impl_->mutex);
  impl_->require_open();
  impl_->finish_chunk();
}

bool McapWriter::flush_if_due() {
  std::lock_guard lock(impl_->mutex);
  impl_->require_open();
  if (!impl_->chunk_due(Clock::now())) return false;
  impl_->finish_chunk();
  return true;
}

void McapWriter::close() {
  std::lock_guard lock(impl_->mutex);
  if (impl_->closed) return;
  impl_->closed = true;  // even if finishing fails: a half-written tail is not retried
  impl_->finish_chunk();
  impl_->sink.finish();
}

uint64_t McapWriter::message_count() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->message_count;
}

std::map<uint16_t, uint64_t> McapWriter::channel_message_counts() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->channel_message_counts;
}

uint64_t McapWriter::chunk_count() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->sink.chunk_count();
}

uint64_t McapWriter::bytes_written() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->sink.position();
}

}  // namespace mechsim::record
