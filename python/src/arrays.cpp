#include "arrays.h"

#include <map>
#include <optional>
#include <vector>

#include <pybind11/numpy.h>

#include "cdr_decoder.h"
#include "mechsim/record/mcap_reader.h"

namespace mechsim::python {

namespace py = pybind11;

namespace {

py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

}  // namespace

py::dict comparison_arrays(const assess::ReferenceComparison& c) {
  py::dict out, signals;
  out["t"] = to_array(c.t);
  for (const auto& s : c.signals) {
    std::vector<double> error(s.cosim.size());
    for (std::size_t k = 0; k < error.size(); ++k) error[k] = s.cosim[k] - s.reference[k];
    py::dict d;
    d["unit"] = s.unit;
    d["cosim"] = to_array(s.cosim);
    d["reference"] = to_array(s.reference);
    d["error"] = to_array(error);
    signals[py::str(s.signal.full_name())] = d;
  }
  out["signals"] = signals;
  return out;
}

py::dict read_mcap(const std::string& path) {
  record::ReaderOptions options;
  options.strict = false;  // as `mechsim bag export`: the sound chunks of a damaged file
  const record::McapReader reader(path, options);
  struct Topic {
    std::string name;
    std::optional<recorder::MessageLayout> layout;
    std::vector<double> t, step, run_id;
    std::vector<std::vector<double>> fields;
  };
  std::map<std::uint16_t, Topic> topics;
  for (const auto& [id, ch] : reader.channels()) {
    Topic topic;
    topic.name = ch.topic;
    const auto schema = reader.schemas().find(ch.schema_id);
    if (schema != reader.schemas().end() && ch.message_encoding == "cdr") {
      try {
        topic.layout = recorder::channel_layout(schema->second.name, ch.metadata);
      } catch (const recorder::CdrError&) {
      }
    }
    topics.emplace(id, std::move(topic));
  }
  reader.for_each_message([&](const record::MessageView& m) {
    auto it = topics.find(m.channel_id);
    if (it == topics.end() || !it->second.layout) return;
    Topic& topic = it->second;
    try {
      if (topic.layout->sequences && topic.layout->fields.empty()) topic.layout = recorder::unnamed_fmu_layout(m.data);
      const recorder::DecodedSample s = recorder::decode_sample(m.data, *topic.layout);
      topic.fields.resize(s.values.size());
      topic.t.push_back(s.header.t);
      topic.step.push_back(static_cast<double>(s.header.step));
      topic.run_id.push_back(static_cast<double>(s.header.run_id));
      for (std::size_t k = 0; k < s.values.size(); ++k) topic.fields[k].push_back(recorder::as_number(s.values[k]));
    } catch (const recorder::CdrError&) {
      // a sample that does not decode is left out, as `bag export` skips it
    }
  });
  py::dict out;
  for (const auto& [id, topic] : topics) {
    if (!topic.layout || topic.t.empty()) continue;
    py::dict d;
    d["t"] = to_array(topic.t);
    d["step"] = to_array(topic.step);
    d["run_id"] = to_array(topic.run_id);
    for (std::size_t k = 0; k < topic.fields.size() && k < topic.layout->fields.size(); ++k)
      if (topic.layout->fields[k].kind != recorder::CdrKind::string) d[py::str(topic.layout->fields[k].name)] = to_array(topic.fields[k]);
    out[py::str(topic.name)] = d;
  }
  return out;
}

}  // namespace mechsim::python
