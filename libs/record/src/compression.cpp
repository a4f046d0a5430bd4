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

std::string sizes_differ(const std::string& where, const char* codec, std::size_t held,
                         uint64_t claimed) {
  return where + ": " + codec + " data holds " + std::to_string(held) + " bytes, chunk says " +
         std::to_string(claimed);
}

[[noreturn]] void larger_than_claimed(const std::string& where, const char* codec, uint64_t claimed) {
  throw McapError(where + ": " + codec + " data is larger than the chunk says (" +
                  std::to_string(claimed) + " bytes); decompression stopped there");
}

// The decoders' output: exactly the claimed size (already bounded by ChunkLimits), never
// grown. Once it is full the decoder gets a one-byte probe instead: a byte there means the
// chunk lied, and decoding stops.
class ExactOutput {
 public:
  explicit ExactOutput(uint64_t claimed) : buffer_(static_cast<std::size_t>(claimed)) {}
  uint8_t* space() { return full() ? &probe_ : buffer_.data() + used_; }
  std::size_t space_size() const { return full() ? 1 : buffer_.size() - used_; }
  // The decoder wrote `n` bytes to space(); adds them to `produced`.
  void wrote(std::size_t n, uint64_t& produced, const std::string& where, const char* codec) {
    produced += n;
    if (n > 0 && full()) larger_than_claimed(where, codec, buffer_.size());
    used_ += n;
  }
  // The whole output, after checking that the decoder filled it.
  Buffer take(const std::string& where, const char* codec) {
    if (!full()) throw McapError(sizes_differ(where, codec, used_, buffer_.size()));
    return std::move(buffer_);
  }

 private:
  bool full() const { return used_ == buffer_.size(); }
  Buffer buffer_;
  std::size_t used_ = 0;
  uint8_t probe_ = 0;
};

Buffer zstd_decompress(std::span<const uint8_t> data, uint64_t claimed, const std::string& where,
                       uint64_t& produced) {
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  if (!ctx) throw std::runtime_error("zstd: cannot create a decompression context");
  ExactOutput out(claimed);
  ZSTD_inBuffer in{data.data(), data.size(), 0};
  std::size_t hint = 1;  // 0 once a frame is complete
  while (hint != 0 || in.pos < in.size) {  // concatenated frames continue the output
    ZSTD_outBuffer o{out.space(), out.space_size(), 0};
    const std::size_t in_before = in.pos;
    hint = ZSTD_decompressStream(ctx.get(), &o, &in);
    if (ZSTD_isError(hint))
      throw McapError(where + ": zstd decompression failed: " + ZSTD_getErrorName(hint));
    out.wrote(o.pos, produced, where, "zstd");
    if (o.pos == 0 && in.pos == in_before)  // no progress with room left: input ends early
      throw McapError(where + ": zstd frame ends early");
  }
  return out.take(where, "zstd");
}

Buffer lz4_decompress(std::span<const uint8_t> data, uint64_t claimed, const std::string& where,
                      uint64_t& produced) {
  LZ4F_dctx* raw_ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw_ctx, LZ4F_VERSION)))
    throw std::runtime_error("lz4: cannot create a decompression context");
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw_ctx, &LZ4F_freeDecompressionContext);
  ExactOutput out(claimed);
  std::size_t in_pos = 0;
  std::size_t hint = 1;  // 0 once the frame is complete
  while (hint != 0) {
    std::size_t in_size = data.size() - in_pos;
    std::size_t out_size = out.space_size();
    hint = LZ4F_decompress(ctx.get(), out.space(), &out_size, data.data() + in_pos, &in_size, nullptr);
    if (LZ4F_isError(hint))
      throw McapError(where + ": lz4 decompression failed: " + LZ4F_getErrorName(hint));
    out.wrote(out_size, produced, where, "lz4");
    in_pos += in_size;
    if (hint != 0 && in_size == 0 && out_size == 0) throw McapError(where + ": lz4 frame ends early");
  }
  return out.take(where, "lz4");
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

void check_claim(const std::string& compression, std::size_t compressed, uint64_t claimed,
                 const ChunkLimits& limits, const std::string& where) {
  if (claimed > limits.max_chunk_size)
    throw McapError(where + ": claims " + std::to_string(claimed) +
                    " bytes uncompressed, more than the reader's limit of " +
                    std::to_string(limits.max_chunk_size) + " bytes per chunk");
  if (!compression.empty() && claimed > limits.expansion_floor &&
      claimed / limits.max_expansion >= std::max<uint64_t>(compressed, 1))
    throw McapError(where + ": claims " + std::to_string(claimed) + " bytes uncompressed from " +
                    std::to_string(compressed) + " compressed bytes, an expansion beyond the " +
                    "reader's limit of " + std::to_string(limits.max_expansion) + ":1");
}

Buffer decompress(const std::string& compression, std::span<const uint8_t> data,
                  uint64_t uncompressed_size, const std::string& where, const ChunkLimits& limits,
                  uint64_t& produced) {
  check_claim(compression, data.size(), uncompressed_size, limits, where);
  if (compression.empty()) {
    if (data.size() != uncompressed_size)
      throw McapError(where + ": uncompressed chunk holds " + std::to_string(data.size()) +
                      " bytes, chunk says " + std::to_string(uncompressed_size));
    return Buffer(data.begin(), data.end());
  }
  if (compression == "zstd") return zstd_decompress(data, uncompressed_size, where, produced);
  if (compression == "lz4") return lz4_decompress(data, uncompressed_size, where, produced);
  throw McapError(where + ": unsupported compression '" + compression + "'");
}

}  // namespace mechsim::record::detail
