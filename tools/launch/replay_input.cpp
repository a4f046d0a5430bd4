#include "replay_input.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "cdr_decoder.h"
#include "mechsim/cosim/output_log.h"
#include "mechsim/record/mcap_reader.h"

namespace mechsim::launch {

ReplayRequest parse_replay_request(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw std::invalid_argument("--replay: expected NODE=FILE (a participant and an MCAP recording), got '" + text + "'");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void write_replay_table(const std::string& recording, const cosim::PlannedNode& node, const cosim::StepGrid& grid,
                        const std::string& table_path) {
  const transport::TopicType& type = *node.type->publishes;
  // The node's own topic type: an FMU participant's FmuOutputs with its outputs' names.
  const recorder::MessageLayout own_layout = recorder::layout_of(type);
  const recorder::MessageLayout* layout = &own_layout;
  record::McapReader reader(recording);  // throws naming the file
  std::set<std::uint16_t> channels;
  for (const auto& [id, channel] : reader.channels())
    if (channel.topic == node.topic) channels.insert(id);
  if (channels.empty())
    throw std::runtime_error(recording + ": no topic '" + node.topic + "' (what participant '" + node.name() +
                             "' publishes); `mechsim bag info " + recording + "` lists what it holds");

  std::map<std::uint64_t, std::vector<double>> rows;  // step -> field values
  std::map<std::uint64_t, double> times;              // step -> the sample's t
  std::set<std::uint64_t> runs;
  reader.for_each_message([&](const record::MessageView& m) {
    if (!channels.count(m.channel_id)) return;
    const recorder::DecodedSample s = recorder::decode_sample(m.data, *layout);
    runs.insert(s.header.run_id);
    std::vector<double> values;
    for (const auto& v : s.values) values.push_back(recorder::as_number(v));
    rows.emplace(s.header.step, std::move(values));
    times.emplace(s.header.step, s.header.t);
  });
  if (runs.size() > 1)
    throw std::runtime_error(recording + ": topic '" + node.topic + "' holds samples of " + std::to_string(runs.size()) +
                             " runs; replay needs a recording of one run");
  // An adaptive run's steps are the recording's: up to the sample at the scene's end.
  std::uint64_t steps = grid.steps();
  if (grid.is_adaptive()) {
    const auto end = std::find_if(times.begin(), times.end(), [&](const auto& st) { return st.second >= grid.end(); });
    if (end == times.end())
      throw std::runtime_error(recording + ": topic '" + node.topic + "' has no sample at the scene's end (t = " +
                               std::to_string(grid.end()) + " s)" + (reader.truncated() ? "; the file is truncated: `mechsim record --recover` it" : ""));
    steps = end->first;
  }
  for (std::uint64_t k = 0; k <= steps; ++k)
    if (!rows.count(k))
      throw std::runtime_error(recording + ": topic '" + node.topic + "' has no sample for step " + std::to_string(k) +
                               " (the scene runs steps 0.." + std::to_string(steps) +
                               (reader.truncated() ? "; the file is truncated: `mechsim record --recover` it" : "") + ")");

  std::vector<std::string> columns;  // the writer puts "t" first itself
  for (const auto& f : type.fields) columns.push_back(f.name);
  cosim::OutputLogWriter table(table_path, columns);
  for (std::uint64_t k = 0; k <= steps; ++k) table.append(grid.is_adaptive() ? times[k] : grid.time(k), rows[k]);
  table.close();
}

}  // namespace mechsim::launch
