#include "compression.h"

#include <lz4frame.h>
#include <zstd.h>

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

void zstd_decompress(std::span<const uint8_t> data, Buffer& out, const std::string& where) {
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
  if (ZSTD_isError(n))
    throw McapError(where + ": zstd decompression failed: " + ZSTD_getErrorName(n));
  if (n != out.size())
    throw McapError(where + ": zstd data holds " + std::to_string(n) + " bytes, chunk says " +
                    std::to_string(out.size()));
}

void lz4_decompress(std::span<const uint8_t> data, Buffer& out, const std::string& where) {
  LZ4F_dctx* raw_ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw_ctx, LZ4F_VERSION)))
    throw std::runtime_error("lz4: cannot create a decompression context");
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw_ctx, &LZ4F_freeDecompressionContext);
  std::size_t in_pos = 0, out_pos = 0;
  std::size_t hint = 1;
  while (hint != 0) {
    std::size_t in_size = data.size() - in_pos;
    std::size_t out_size = out.size() - out_pos;
    if (in_size == 0) throw McapError(where + ": lz4 frame ends early");
    hint = LZ4F_decompress(ctx.get(), out.data() + out_pos, &out_size, data.data() + in_pos,
                           &in_size, nullptr);
    if (LZ4F_isError(hint))
      throw McapError(where + ": lz4 decompression failed: " + LZ4F_getErrorName(hint));
    in_pos += in_size;
    out_pos += out_size;
    // No progress with input left means the output buffer is full but the frame goes on.
    if (hint != 0 && in_size == 0 && out_size == 0)
      throw McapError(where + ": lz4 data is larger than the chunk says");
  }
  if (out_pos != out.size())
    throw McapError(where + ": lz4 data holds " + std::to_string(out_pos) + " bytes, chunk says " +
                    std::to_string(out.size()));
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
  Buffer out(static_cast<std::size_t>(uncompressed_size));
  if (compression == "zstd")
    zstd_decompress(data, out, where);
  else if (compression == "lz4")
    lz4_decompress(data, out, where);
  else
    throw McapError(where + ": unsupported compression '" + compression + "'");
  return out;
}

}  // namespace mechsim::record::detail
