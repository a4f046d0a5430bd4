#include "compression.h"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace mechsim::record {

std::string compression_name(Compression compression) {
  switch (compression) {
    case Compression::none: return "";
    case Compression::zstd: return "zstd";
    case Compression::lz4: return "lz4";
  }
  throw std::invalid_argument("unknown Compression value");
}

}  // namespace mechsim::record

namespace mechsim::record::detail {
namespace {

// A corrupt chunk header could claim any size; refuse before allocating it. 4 GiB is far
// beyond any chunk a recorder writes (1 MiB by default).
constexpr uint64_t kMaxChunkSize = uint64_t(1) << 32;

// zstd level 1: recordings are written while the simulation runs, so speed matters more
// than the last percent of size (measured in docs/recording.md).
constexpr int kZstdLevel = 1;

Buffer zstd_compress(std::span<const uint8_t> data) {
  Buffer out(ZSTD_compressBound(data.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), data.data(), data.size(), kZstdLevel);
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

Buffer lz4_compress(std::span<const uint8_t> data) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.contentSize = data.size();  // lets readers size their buffer
  Buffer out(LZ4F_compressFrameBound(data.size(), &prefs));
  const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), &prefs);
  if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(n));
  out.resize(n);
  return out;
}

// Decompressed output grows as the decoder produces it, up to the size the chunk claims: a
// corrupt header claiming gigabytes costs only what the data really holds (found by the mcap
// fuzzer: a shuffled uncompressed_size of 3.6 GB was allocated before decoding).
class GrowingOutput {
 public:
  GrowingOutput(uint64_t claimed, std::size_t compressed_size)
      : claimed_(static_cast<std::size_t>(claimed)) {
    constexpr std::size_t kFirstGuess = std::size_t(1) << 16;
    buffer_.resize(std::min(claimed_, std::max(kFirstGuess, compressed_size * 16)));
  }
  uint8_t* free_space() { return buffer_.data() + used_; }
  std::size_t free_size() const { return buffer_.size() - used_; }
  void produced(std::size_t n) { used_ += n; }
  // False when the buffer already holds the claimed size (the data is larger than claimed).
  bool grow() {
    if (buffer_.size() >= claimed_) return false;
    buffer_.resize(std::min(claimed_, std::max<std::size_t>(buffer_.size() * 2, 1)));
    return true;
  }
  std::size_t used() const { return used_; }
  Buffer take() {
    buffer_.resize(used_);
    return std::move(buffer_);
  }

 private:
  std::size_t claimed_;
  std::size_t used_ = 0;
  Buffer buffer_;
};

std::string sizes_differ(const std::string& where, const char* codec, std::size_t held,
                         uint64_t claimed) {
  return where + ": " + codec + " data holds " + std::to_string(held) + " bytes, chunk says " +
         std::to_string(claimed);
}

// The decoder made no progress: it needs more room (grow, unless the claimed size is
// reached) or more input (the frame ends early).
void stalled(GrowingOutput& out, const std::string& where, const char* codec, uint64_t claimed) {
  if (out.free_size() > 0) throw McapError(where + ": " + codec + " frame ends early");
  if (!out.grow())
    throw McapError(where + ": " + codec + " data is larger than the chunk says (" +
                    std::to_string(claimed) + " bytes)");
}

Buffer zstd_decompress(std::span<const uint8_t> data, uint64_t claimed, const std::string& where) {
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  if (!ctx) throw std::runtime_error("zstd: cannot create a decompression context");
  GrowingOutput out(claimed, data.size());
  ZSTD_inBuffer in{data.data(), data.size(), 0};
  std::size_t hint = 1;  // 0 once a frame is complete
  while (hint != 0 || in.pos < in.size) {  // concatenated frames continue the output
    ZSTD_outBuffer chunk{out.free_space(), out.free_size(), 0};
    const std::size_t in_before = in.pos;
    hint = ZSTD_decompressStream(ctx.get(), &chunk, &in);
    if (ZSTD_isError(hint))
      throw McapError(where + ": zstd decompression failed: " + ZSTD_getErrorName(hint));
    out.produced(chunk.pos);
    if (chunk.pos == 0 && in.pos == in_before) stalled(out, where, "zstd", claimed);
  }
  if (out.used() != claimed) throw McapError(sizes_differ(where, "zstd", out.used(), claimed));
  return out.take();
}

Buffer lz4_decompress(std::span<const uint8_t> data, uint64_t claimed, const std::string& where) {
  LZ4F_dctx* raw_ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw_ctx, LZ4F_VERSION)))
    throw std::runtime_error("lz4: cannot create a decompression context");
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw_ctx, &LZ4F_freeDecompressionContext);
  GrowingOutput out(claimed, data.size());
  std::size_t in_pos = 0;
  std::size_t hint = 1;  // 0 once the frame is complete
  while (hint != 0) {
    std::size_t in_size = data.size() - in_pos;
    std::size_t out_size = out.free_size();
    hint = LZ4F_decompress(ctx.get(), out.free_space(), &out_size, data.data() + in_pos,
                           &in_size, nullptr);
    if (LZ4F_isError(hint))
      throw McapError(where + ": lz4 decompression failed: " + LZ4F_getErrorName(hint));
    in_pos += in_size;
    out.produced(out_size);
    if (hint != 0 && in_size == 0 && out_size == 0) stalled(out, where, "lz4", claimed);
  }
  if (out.used() != claimed) throw McapError(sizes_differ(where, "lz4", out.used(), claimed));
  return out.take();
}

}  // namespace

Buffer compress(Compression compression, std::span<const uint8_t> data) {
  switch (compression) {
    case Compression::none: return Buffer(data.begin(), data.end());
    case Compression::zstd: return zstd_compress(data);
    case Compression::lz4: return lz4_compress(data);
  }
  throw std::invalid_argument("unknown Compression value");
}

Buffer decompress(const std::string& compression, std::span<const uint8_t> data,
                  uint64_t uncompressed_size, const std::string& where) {
  if (uncompressed_size > kMaxChunkSize)
    throw McapError(where + ": uncompressed size " + std::to_string(uncompressed_size) +
                    " is implausible");
  if (compression.empty()) {
    if (data.size() != uncompressed_size)
      throw McapError(where + ": uncompressed chunk holds " + std::to_string(data.size()) +
                      " bytes, chunk says " + std::to_string(uncompressed_size));
    return Buffer(data.begin(), data.end());
  }
  if (compression == "zstd") return zstd_decompress(data, uncompressed_size, where);
  if (compression == "lz4") return lz4_decompress(data, uncompressed_size, where);
  throw McapError(where + ": unsupported compression '" + compression + "'");
}

}  // namespace mechsim::record::detail
