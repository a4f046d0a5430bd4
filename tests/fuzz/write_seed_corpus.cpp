// Writes the seed corpora of mcap_fuzz and cdr_fuzz from real recordings (a scene run with
// `record: true`), so that the seeds hold what DDS actually delivers:
//   write_seed_corpus OUT_DIR RECORDING.mcap...
// OUT_DIR/mcap_fuzz: small MCAP files made by McapWriter from the first messages of each
// channel (zstd, lz4, none; several chunks), and one cut short inside a chunk (recovery);
// OUT_DIR/cdr_fuzz: one file per recorded type, the layout's index in all_layouts() as the
// first byte and then the recorded sample. Not run by the tests; the output is committed.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cdr_decoder.h"
#include "mechsim/record/mcap_reader.h"
#include "mechsim/record/mcap_writer.h"

namespace fs = std::filesystem;
using namespace mechsim;

namespace {

struct Picked {
  record::Schema schema;
  record::Channel channel;
  std::vector<record::Message> messages;
};

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  std::printf("%s (%zu bytes)\n", path.c_str(), bytes.size());
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_mcap(const fs::path& path, const std::vector<Picked>& picked, record::Compression compression) {
  record::WriterOptions options;
  options.compression = compression;
  options.chunk_size = 300;  // a few messages per chunk
  {
    record::McapWriter writer(path.string(), options);
    for (const Picked& p : picked) {
      const uint16_t schema = writer.add_schema(p.schema.name, p.schema.encoding, p.schema.data);
      const uint16_t channel = writer.add_channel(schema, p.channel.topic, p.channel.message_encoding, p.channel.metadata);
      for (const auto& m : p.messages) writer.write(channel, m.sequence, m.log_time, m.publish_time, m.data);
    }
    writer.close();
  }
  std::printf("%s (%ju bytes)\n", path.c_str(), static_cast<std::uintmax_t>(fs::file_size(path)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: write_seed_corpus OUT_DIR RECORDING.mcap...\n");
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out / "mcap_fuzz");
  fs::create_directories(out / "cdr_fuzz");
  const auto& layouts = recorder::all_layouts();
  for (int i = 2; i < argc; ++i) {
    const record::McapReader reader(argv[i]);
    // The run folder's name without its run id: "cam_press-1f53d6fc" -> "cam_press".
    std::string stem = fs::path(argv[i]).parent_path().filename().string();
    stem = stem.substr(0, stem.rfind('-'));
    std::map<uint16_t, Picked> picked;  // by channel id: the first two messages
    for (const auto& m : reader.read_messages()) {
      Picked& p = picked[m.channel_id];
      if (p.messages.size() >= 2) continue;
      p.channel = reader.channels().at(m.channel_id);
      p.schema = reader.schemas().at(p.channel.schema_id);
      p.messages.push_back(m);
    }
    std::vector<Picked> all;
    for (auto& [id, p] : picked) {
      all.push_back(p);
      const recorder::MessageLayout* layout = recorder::find_layout(p.schema.name);
      if (!layout) continue;
      std::string seed(1, static_cast<char>(layout - layouts.data()));
      seed.append(reinterpret_cast<const char*>(p.messages.front().data.data()), p.messages.front().data.size());
      std::string name = p.channel.topic;
      for (char& c : name)
        if (c == '/') c = '_';
      write_file(out / "cdr_fuzz" / (name + ".cdr"), seed);
    }
    write_mcap(out / "mcap_fuzz" / (stem + "_zstd.mcap"), all, record::Compression::zstd);
    const std::vector<Picked> two(all.begin(), all.begin() + std::min<std::size_t>(2, all.size()));
    write_mcap(out / "mcap_fuzz" / (stem + "_lz4.mcap"), two, record::Compression::lz4);
    write_mcap(out / "mcap_fuzz" / (stem + "_none.mcap"), two, record::Compression::none);
    // A recording cut short (the recorder killed): the none file without its last third.
    const std::string whole = read_file(out / "mcap_fuzz" / (stem + "_none.mcap"));
    write_file(out / "mcap_fuzz" / (stem + "_truncated.mcap"), whole.substr(0, whole.size() * 2 / 3));
  }
  return 0;
}
