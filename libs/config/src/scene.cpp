#include <algorithm>
#include "mechsim/config/scene.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "mechsim/config/units.h"

namespace mechsim::config {

const std::vector<std::string>& reconstruction_names() {
  static const std::vector<std::string> names{"hold", "linear", "quadratic"};
  return names;
}

const std::vector<std::string>& solver_method_names() {
  static const std::vector<std::string> names{"cvode_bdf", "cvode_adams", "arkode_erk", "arkode_dirk"};
  return names;
}

const char* default_dds_vendor() { return MECHSIM_DEFAULT_DDS_VENDOR; }

long TimeSpec::steps() const { return std::lround((end - start) / step); }

const ParticipantSpec* Scene::find_participant(const std::string& name) const {
  for (const auto& p : participants)
    if (p.name == name) return &p;
  return nullptr;
}

bool Scene::checkpointing() const {
  for (const auto& p : participants)
    if (p.restart) return true;
  return false;
}

const HostSpec* Scene::find_host(const std::string& name) const {
  for (const auto& h : hosts)
    if (h.name == name) return &h;
  return nullptr;
}

FaultTimings fault_timings(double partition_grace) {
  // The lease outlasts the grace by 3 s of discovery traffic; the agent outlasts it by 1 s,
  // so the launcher, not a silent agent, ends a run whose link stays cut.
  return {partition_grace, partition_grace / 2, partition_grace + 3.0, partition_grace + 1.0};
}

bool topic_selected(const std::vector<std::string>& names, const std::string& regex, const std::string& topic) {
  if (names.empty() && regex.empty()) return true;
  if (std::find(names.begin(), names.end(), topic) != names.end()) return true;
  return !regex.empty() && std::regex_match(topic, std::regex(regex, std::regex::ECMAScript));
}

namespace {

// An IPv4 address or a DNS host name (RFC 1123 characters); resolved by the launcher.
bool valid_host_address(const std::string& s) {
  if (s.empty() || s.size() > 63) return false;  // agent.idl carries it as string<64>
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.')) return false;
  return s.front() != '-' && s.front() != '.';
}

bool valid_name(const std::string& s) {
  if (s.empty() || s.size() > 48) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return std::isalpha(static_cast<unsigned char>(s[0]));
}

SignalRef parse_signal_ref(const ConfigNode& node, const std::string& text) {
  auto dot = text.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == text.size())
    node.fail("expected a signal 'participant.output', got '" + text + "'");
  return {text.substr(0, dot), text.substr(dot + 1), node.path()};
}

// `step: adaptive` with tolerance, min, max, initial (defaults: max = a hundredth of the run,
// min = max / 10000, initial = min, tolerance 1e-3; docs/accuracy.md says why).
AdaptiveStepSpec parse_adaptive_step(const ConfigNode& t, double start, double duration) {
  AdaptiveStepSpec a;
  if (t.has("tolerance")) {
    a.tolerance = t.number("tolerance");
    if (!(a.tolerance > 0 && a.tolerance < 1)) t.child("tolerance").fail("expected a tolerance in (0, 1), e.g. 1e-4");
  }
  a.max = t.has("max") ? t.positive_quantity("max", dim::time) : duration / 100;
  a.min = t.has("min") ? t.positive_quantity("min", dim::time) : a.max / 10000;
  if (!(a.min <= a.max)) t.child("min").fail("expected min <= max (" + std::to_string(a.max) + " s)");
  if (a.max > duration) t.child("max").fail("expected max <= end - start (" + std::to_string(duration) + " s)");
  // Each node keeps the instants of the run's steps (a double each): bounded here.
  if (duration / a.min > 1e8) t.child("min").fail("expected at most 1e8 steps of the smallest length (end - start) / min");
  // Every step must move time forward in doubles, at the run's largest |t| too.
  const double largest_t = std::max(std::abs(start), std::abs(start + duration));
  if (!(largest_t + a.min > largest_t))
    t.child("min").fail("expected a smallest step that moves t = " + std::to_string(largest_t) + " s forward in double precision");
  a.initial = t.has("initial") ? t.positive_quantity("initial", dim::time) : a.min;
  if (!(a.initial >= a.min && a.initial <= a.max)) t.child("initial").fail("expected a first step between min and max");
  if (auto scales = t.optional_child("scales")) {
    if (!scales->is_map()) scales->fail("expected a map {participant: {field: value}}, e.g. {follower: {drive_torque: 20 N m}}");
    for (const std::string& participant : scales->keys()) {
      const ConfigNode fields = scales->child(participant);
      if (!fields.is_map()) fields.fail("expected a map {field: value} of what '" + participant + "' publishes");
      for (const std::string& field : fields.keys()) {
        double v = 0.0;
        try {
          v = parse_quantity(fields.child(field).as_string()).value_si;
        } catch (const std::exception& e) {
          fields.child(field).fail(std::string("expected a value (SI, or with its unit): ") + e.what());
        }
        if (!(v > 0) || !std::isfinite(v)) fields.child(field).fail("expected a positive scale");
        a.scales.emplace_back(participant + "." + field, v);
      }
    }
  }
  return a;
}

TimeSpec parse_time(const ConfigNode& t) {
  TimeSpec spec;
  const bool adaptive = t.has("step") && t.child("step").is_scalar() && t.child("step").as_string() == "adaptive";
  if (adaptive) t.allow_only({"start", "end", "step", "tolerance", "min", "max", "initial", "scales"});
  else t.allow_only({"start", "end", "step"});
  spec.start = t.has("start") ? t.quantity("start", dim::time) : 0.0;
  spec.end = t.quantity("end", dim::time);
  if (!(spec.end > spec.start))
    t.child("end").fail("expected an end time after the start time (" + std::to_string(spec.start) + " s)");
  if (adaptive) {
    spec.adaptive = parse_adaptive_step(t, spec.start, spec.end - spec.start);
    spec.step = spec.adaptive->max;
    return spec;
  }
  spec.step = t.positive_quantity("step", dim::time);
  double n = (spec.end - spec.start) / spec.step;
  if (std::abs(n - std::round(n)) > 1e-9 * std::max(1.0, n))
    t.child("end").fail("expected end - start to be a whole number of steps (got " + std::to_string(n) + " steps)");
  if (std::round(n) > 1e9) t.child("step").fail("expected at most 1e9 steps");
  return spec;
}

SolverSpec parse_solver(const ConfigNode& s) {
  s.allow_only({"method", "rtol", "atol"});
  SolverSpec spec;
  if (s.has("method")) spec.method = s.choice("method", solver_method_names());
  if (s.has("rtol")) {
    spec.rtol = s.number("rtol");
    spec.rtol_written = true;
    if (!(spec.rtol > 0 && spec.rtol < 1)) s.child("rtol").fail("expected a relative tolerance in (0, 1)");
  }
  if (s.has("atol")) {
    spec.atol = s.number("atol");
    spec.atol_written = true;
    if (!(spec.atol > 0)) s.child("atol").fail("expected a positive absolute tolerance");
  }
  return spec;
}

std::optional<RecordSpec> parse_record(const ConfigNode& r) {
  if (r.is_scalar()) {
    if (!r.as_boolean()) return std::nullopt;  // `record: false`
    return RecordSpec{};
  }
  if (!r.is_map()) r.fail("expected true/false or a map with file, topics, regex, compression");
  r.allow_only({"file", "topics", "regex", "compression"});
  RecordSpec spec;
  spec.file = r.string_or("file", spec.file);
  if (spec.file.empty()) r.child("file").fail("expected a file name, e.g. recording.mcap");
  if (auto topics = r.optional_child("topics")) {
    if (!topics->is_sequence()) topics->fail("expected a list of topic names");
    for (std::size_t i = 0; i < topics->size(); ++i) spec.topics.push_back(topics->at(i).as_string());
  }
  if (r.has("regex")) {
    if (!spec.topics.empty()) r.child("regex").fail("expected either 'topics' or 'regex', not both");
    spec.regex = r.string("regex");
    try {
      std::regex check(spec.regex, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      r.child("regex").fail(std::string("expected an ECMAScript regular expression (") + e.what() + ")");
    }
  }
  spec.compression = r.has("compression") ? r.choice("compression", {"zstd", "lz4", "none"}) : spec.compression;
  return spec;
}

ProcessLayout parse_process_layout(const ConfigNode& node) {
  ProcessLayout layout;
  layout.key_path = node.path();
  const auto expected = [&] {
    node.fail("expected auto, per_participant, per_core or a number of process groups per DDS vendor (1..64)");
  };
  if (!node.is_scalar()) expected();
  const std::string text = node.as_string();
  if (text == "auto") return layout;
  if (text == "per_participant") {
    layout.kind = ProcessLayout::Kind::per_participant;
    return layout;
  }
  if (text == "per_core") {
    layout.kind = ProcessLayout::Kind::per_core;
    return layout;
  }
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 2) expected();
  layout.count = std::stoi(text);
  if (layout.count < 1 || layout.count > 64) expected();
  layout.kind = ProcessLayout::Kind::count;
  return layout;
}

// The process keys of a `realtime:` map over `base` (the scene's, for a participant).
// Participants sharing a process (`process: <group>`): its threads share what belongs to a
// process, so the members must agree on it.
void check_process_groups(const Scene& scene, const ConfigNode& participants) {
  if (scene.processes.packs() && !scene.security_dir.empty())
    scene.root.child("processes").fail("packs participants into process groups, which are not available with dds.security: "
                                       "each participant's identity is set in its own process's environment "
                                       "(docs/security.md); use processes: per_participant");
  std::map<std::string, const ParticipantSpec*> first;  // group -> its first member
  for (const auto& p : scene.participants) {
    if (p.process.empty()) continue;
    const ConfigNode key = participants.child(p.name).child("process");
    // Each participant's identity reaches it through its process's environment.
    if (!scene.security_dir.empty())
      key.fail("process groups are not available with dds.security: each participant's identity is set in its own "
               "process's environment (docs/security.md)");
    // Scheduling, memory locking and CPUs are a process's settings.
    if (participants.child(p.name).has("realtime"))
      key.fail("a participant in a process group takes the scene's realtime: settings: its own realtime: would apply to the "
               "whole process (remove one of them)");
    auto [at, inserted] = first.emplace(p.process, &p);
    // One process runs on one host.
    if (!inserted && at->second->host != p.host)
      key.fail("the participants of process group '" + p.process + "' run in one process, on one host: '" + at->second->name +
               "' is on " + (at->second->host.empty() ? "the launcher's host" : "host '" + at->second->host + "'") + ", '" + p.name +
               "' on " + (p.host.empty() ? "the launcher's host" : "host '" + p.host + "'"));
    // A crash takes the whole process: it restarts as a whole, or not at all.
    if (!inserted && at->second->restart != p.restart)
      key.fail("the participants of process group '" + p.process + "' restart together: '" + at->second->name + "' has restart: " +
               (at->second->restart ? "on_failure" : "never") + ", '" + p.name + "' " + (p.restart ? "on_failure" : "never"));
  }
}

ProcessRealtimeSpec parse_process_realtime(const ConfigNode& rt, ProcessRealtimeSpec base) {
  if (rt.has("priority")) {
    const long prio = rt.integer("priority");
    if (prio < 0 || prio > 99) rt.child("priority").fail("expected a SCHED_FIFO priority in 1..99 (0: the default scheduler)");
    base.priority = static_cast<int>(prio);
  }
  if (rt.has("lock_memory")) base.lock_memory = rt.boolean("lock_memory");
  if (rt.has("cpus")) {
    const ConfigNode list = rt.child("cpus");
    if (!list.is_sequence() || list.size() == 0) list.fail("expected a non-empty list of CPU numbers, e.g. [1]");
    base.cpus.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const ConfigNode c = list.at(i);
      const long cpu = c.as_integer();
      if (cpu < 0 || cpu > 1023) c.fail("expected a CPU number in 0..1023");
      base.cpus.push_back(static_cast<int>(cpu));
    }
  }
  if (rt.has("priority") || rt.has("lock_memory") || rt.has("cpus")) base.key_path = rt.path();
  return base;
}

}  // namespace

void adaptive_solver_tolerances(SolverSpec& solver, double coupling_tolerance) {
  if (!solver.rtol_written) solver.rtol = std::min(SolverSpec{}.rtol, coupling_tolerance * kAdaptiveSolverRtolPerTolerance);
  if (!solver.atol_written) solver.atol = solver.rtol * 1e-3;
}

namespace {

// The passes of load_scene, one per section, in the order the scene is validated (the first
// error found is the one reported, so the order is part of the behaviour).

// The document, with the overrides applied, and its top-level keys.
void load_document(Scene& scene, const std::string& path, const std::vector<std::string>& overrides) {
  scene.file = path;
  scene.root = ConfigNode::load_file(path);
  for (const auto& o : overrides) scene.root.set_override(o.substr(0, o.find('=')),
                                                          o.find('=') == std::string::npos ? "" : o.substr(o.find('=') + 1));
  const ConfigNode& root = scene.root;
  if (!root.is_map()) root.fail("expected a scene: a map with keys scene, time, participants, ...");
  root.allow_only({"scene", "description", "time", "mode", "rtf", "realtime", "dds", "hosts", "faults", "hang_timeout",
                   "processes", "participants", "connections", "compare", "report", "record", "design"});
}

// `scene:` and `description:`.
void parse_identity(Scene& scene) {
  const ConfigNode& root = scene.root;
  scene.name = root.string("scene");
  if (!valid_name(scene.name)) root.child("scene").fail("expected a name of letters, digits and '_'");
  if (root.has("description")) scene.description = root.string("description");
}

// `mode:` and `rtf:` (after `time:`, which a real-time run constrains).
void parse_run_mode(Scene& scene) {
  const ConfigNode& root = scene.root;
  if (root.has("mode")) scene.mode = root.choice("mode", {"lockstep", "realtime"}) == "realtime" ? RunMode::realtime : RunMode::lockstep;
  // Real-time pacing publishes on a fixed period (an NC loop's sample time).
  if (scene.mode == RunMode::realtime && scene.time.adaptive)
    root.child("mode").fail("lockstep with time.step: adaptive (a real-time run keeps a fixed period: docs/accuracy.md)");
  if (root.has("rtf")) {
    scene.rtf = root.number("rtf");
    if (!(scene.rtf > 0)) root.child("rtf").fail("expected a real-time factor > 0");
  }
}

// `realtime:`: the pacing settings, and the process settings every participant starts from
// (returned: each participant's own realtime: goes over them).
ProcessRealtimeSpec parse_realtime_section(Scene& scene) {
  ProcessRealtimeSpec scene_process_realtime;
  if (auto rt = scene.root.optional_child("realtime")) {
    rt->allow_only({"on_overrun", "wait", "spin_limit", "priority", "lock_memory", "cpus"});
    scene.realtime.on_overrun =
        rt->choice_or("on_overrun", {"continue", "abort"}, "continue") == "abort" ? OverrunPolicy::abort : OverrunPolicy::keep_going;
    scene.realtime.spin_wait = rt->choice_or("wait", {"blocking", "spin"}, "blocking") == "spin";
    scene.realtime.spin_limit = rt->positive_quantity_or("spin_limit", dim::time, scene.realtime.spin_limit);
    scene_process_realtime = parse_process_realtime(*rt, scene_process_realtime);
  }
  return scene_process_realtime;
}

// A path written in the scene at `dotted` is relative to the scene file, one given with --set
// to the working folder: the absolute, normal form of either.
std::string absolute_scene_path(const Scene& scene, const std::string& written, const std::string& dotted,
                                const std::vector<std::string>& overrides) {
  const std::filesystem::path p(written);
  const bool from_file = std::none_of(overrides.begin(), overrides.end(),
                                      [&](const std::string& o) { return o.rfind(dotted + "=", 0) == 0; });
  return std::filesystem::absolute(p.is_absolute() || !from_file ? p : std::filesystem::path(scene.file).parent_path() / p)
      .lexically_normal()
      .string();
}

// `dds: {vendor, domain, security, protection}`.
void parse_dds_section(Scene& scene, const std::vector<std::string>& overrides) {
  auto dds = scene.root.optional_child("dds");
  if (!dds) return;
  dds->allow_only({"vendor", "domain", "security", "protection"});
  if (dds->has("vendor")) scene.vendor = dds->choice("vendor", {"cyclone", "fastdds"});
  if (dds->has("domain") && dds->string("domain") != "auto") {
    long d = dds->integer("domain");
    if (d < 0 || d > 232) dds->child("domain").fail("expected 'auto' or a domain id in 0..232");
    scene.domain_id = static_cast<int>(d);
  }
  if (dds->has("security")) {
    const std::string dir = dds->string("security");
    if (dir.empty()) dds->child("security").fail("expected the folder of `mechsim security init DIR SCENE` (docs/security.md)");
    // Written back absolute, so that the run folder's copy of the scene names the same folder.
    scene.security_dir = absolute_scene_path(scene, dir, "dds.security", overrides);
    if (scene.security_dir.size() > 1 && scene.security_dir.back() == '/') scene.security_dir.pop_back();
    scene.root.set_override("dds.security", scene.security_dir);
  }
  if (dds->has("protection")) {
    scene.security_protection = dds->choice("protection", {"encrypt", "sign"});
    if (scene.security_dir.empty())
      dds->child("protection").fail("expected dds.security with it: protection chooses what DDS Security protects in a secured "
                                    "run (docs/security.md, 'Protection')");
  }
}

// `faults: {redundant_samples, partition_grace, restart, restart_limit, checkpoint_every}`.
void parse_faults_section(Scene& scene) {
  auto faults = scene.root.optional_child("faults");
  if (!faults) return;
  if (!faults->is_map())
    faults->fail("expected a map {redundant_samples: auto|true|false, partition_grace: 2 s, restart: never|on_failure, "
                 "restart_limit: N, checkpoint_every: N}");
  faults->allow_only({"redundant_samples", "partition_grace", "restart", "restart_limit", "checkpoint_every"});
  if (faults->has("restart")) scene.faults.restart = faults->choice("restart", {"never", "on_failure"});
  scene.faults.restart_limit = faults->integer_or("restart_limit", scene.faults.restart_limit);
  if (scene.faults.restart_limit < 1) faults->child("restart_limit").fail("expected a number of restarts >= 1");
  scene.faults.checkpoint_every = faults->integer_or("checkpoint_every", scene.faults.checkpoint_every);
  if (scene.faults.checkpoint_every < 1) faults->child("checkpoint_every").fail("expected a number of macro steps >= 1");
  scene.faults.partition_grace = faults->positive_quantity_or("partition_grace", dim::time, scene.faults.partition_grace);
  if (faults->has("redundant_samples")) {
    const std::string r = faults->choice("redundant_samples", {"auto", "true", "false"});
    scene.faults.redundant_samples = r == "true"    ? RedundantSamples::always
                                     : r == "false" ? RedundantSamples::never
                                                    : RedundantSamples::automatic;
  }
}

// `[user@]host` for ssh: never an option (a leading '-'), no spaces or shell characters.
bool valid_ssh_target(const std::string& s) {
  const auto at = s.find('@');
  const std::string user = at == std::string::npos ? "" : s.substr(0, at);
  const std::string host = at == std::string::npos ? s : s.substr(at + 1);
  if (at != std::string::npos && (user.empty() || user.front() == '-')) return false;
  for (char c : user)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return valid_host_address(host);
}

// `hosts: {name: {address, control, ssh, ssh_config, mechsim}}` (docs/hosts.md).
void parse_hosts(Scene& scene, const std::vector<std::string>& overrides) {
  auto hosts = scene.root.optional_child("hosts");
  if (!hosts) return;
  if (!hosts->is_map() || hosts->size() == 0) hosts->fail("expected a map of machines (name: {address: 10.0.0.2 or a host name})");
  for (const std::string& name : hosts->keys()) {
    ConfigNode h = hosts->child(name);
    if (!valid_name(name)) h.fail("expected a host name of letters, digits and '_'");
    if (!h.is_map()) h.fail("expected {address: an IPv4 address or a host name}");
    h.allow_only({"address", "control", "ssh", "ssh_config", "mechsim"});
    HostSpec spec{name, h.string("address"), h.path()};
    if (!valid_host_address(spec.address))
      h.child("address").fail("expected an IPv4 address (10.0.0.2) or a host name (letters, digits, '-' and '.'), got '" + spec.address + "'");
    for (const auto& other : scene.hosts)
      if (other.address == spec.address) h.child("address").fail("expected each host once: " + other.key_path + " has the same address");
    if (h.has("control")) spec.control = h.choice("control", {"ssh", "dds_agent"});
    if (h.has("ssh")) {
      spec.ssh = h.string("ssh");
      if (!valid_ssh_target(spec.ssh)) h.child("ssh").fail("expected [user@]host for ssh (letters, digits, '-', '.', '_'), got '" + spec.ssh + "'");
    }
    if (h.has("ssh_config")) {
      const std::string dotted = "hosts." + name + ".ssh_config";
      spec.ssh_config = absolute_scene_path(scene, h.string("ssh_config"), dotted, overrides);
      scene.root.set_override(dotted, spec.ssh_config);
    }
    if (h.has("mechsim")) {
      spec.mechsim = h.string("mechsim");
      if (spec.mechsim.empty() || spec.mechsim[0] != '/') h.child("mechsim").fail("expected the absolute path of mechsim on that host, got '" + spec.mechsim + "'");
    }
    if (spec.control == "dds_agent" && (h.has("ssh") || h.has("ssh_config")))
      h.fail("expected ssh keys only with control: ssh (control: dds_agent reaches the host's standing DDS agent)");
    scene.hosts.push_back(spec);
  }
  // The agents and the nodes they start would need identities of their own: not done yet.
  if (!scene.security_dir.empty())
    hosts->fail("expected no hosts with dds.security: DDS security is not available for multi-host runs yet (docs/security.md)");
}

// A participant's `testing:` seams (scene.h, ParticipantSpec).
void parse_testing_seams(const ConfigNode& t, ParticipantSpec& spec) {
  t.allow_only({"lose_writes_after_resume", "lose_write_of_step", "checkpoint_pause_step", "checkpoint_pause", "lose_failed_status"});
  spec.lose_failed_status = t.has("lose_failed_status") && t.boolean("lose_failed_status");
  if (t.has("lose_write_of_step")) spec.lose_write_of_step = static_cast<std::uint64_t>(t.integer("lose_write_of_step"));
  spec.lose_writes_after_resume = t.has("lose_writes_after_resume") && t.boolean("lose_writes_after_resume");
  if (t.has("checkpoint_pause_step")) spec.checkpoint_pause_step = static_cast<std::uint64_t>(t.integer("checkpoint_pause_step"));
  spec.checkpoint_pause = t.non_negative_quantity_or("checkpoint_pause", dim::time, 0.0);
}

// A participant's `host:` and `process:`: where it runs.
void parse_placement(const Scene& scene, const ConfigNode& p, ParticipantSpec& spec) {
  if (p.has("host")) {
    spec.host = p.string("host");
    if (!scene.find_host(spec.host)) {
      std::string names;
      for (const auto& h : scene.hosts) names += (names.empty() ? "" : ", ") + h.name;
      p.child("host").fail("expected a host of the scene's hosts: section (" + (names.empty() ? std::string("there is none") : names) +
                           "), got '" + spec.host + "'");
    }
    // The agents of the other hosts listen on one domain (mechsim agent --domain D).
    if (!scene.domain_id)
      p.child("host").fail("a participant placed on a host needs the agents' DDS domain: set dds.domain to the "
                           "--domain of the hosts' `mechsim agent` (docs/hosts.md)");
  }
  if (p.has("process")) {
    spec.process = p.string("process");
    if (!valid_name(spec.process)) p.child("process").fail("expected a process group name of letters, digits and '_', got '" + spec.process + "'");
  }
}

// A participant's `restart:` (default: faults.restart).
void parse_restart(const Scene& scene, const ConfigNode& p, ParticipantSpec& spec) {
  spec.restart = (p.has("restart") ? p.choice("restart", {"never", "on_failure"}) : scene.faults.restart) == "on_failure";
  const auto restart_key = [&] { return p.has("restart") ? p.child("restart") : scene.root.child("faults").child("restart"); };
  // Real-time pacing counts from the start command's wall time: a rolled-back run would
  // be late by the whole repeated stretch.
  if (spec.restart && scene.mode == RunMode::realtime)
    restart_key().fail("restart: on_failure is built for mode: lockstep only, not for a real-time run (docs/faults.md)");
  // A checkpoint holds a node's state at a step, not the agreed instants before it.
  if (spec.restart && scene.time.adaptive)
    restart_key().fail("restart: on_failure is built for a fixed macro step, not for time.step: adaptive (docs/accuracy.md)");
}

// A participant's `fmu:`: its file written back absolute, so that the run folder's copy of
// the scene (what the nodes read) names the same file; then its role, an FMU with ports of
// its own (`type: fmu`) or one in place of the node type's native block. Returns the
// participant's node as it reads after the rewrite.
ConfigNode parse_fmu(Scene& scene, const std::string& name, ConfigNode p, const std::vector<std::string>& overrides,
                     ParticipantSpec& spec) {
  if (p.has("fmu")) {
    const bool in_map = p.child("fmu").is_map();
    const std::string key = in_map ? "fmu.file" : "fmu";
    const ConfigNode written = scene.root.child("participants").child(name);
    const std::string file = in_map ? written.child("fmu").string("file") : written.string("fmu");
    const std::string dotted = "participants." + name + "." + key;
    scene.root.set_override(dotted, absolute_scene_path(scene, file, dotted, overrides));
    p = scene.root.child("participants").child(name);
  }
  if (spec.type == "fmu") {
    // `fmu: FILE` and its settings beside it, or the map `fmu: {file, interface, step,
    // parameters}` of an FMU in place.
    if (!p.has("fmu")) p.fail("expected `fmu: FILE` for a participant of type fmu");
    if (p.child("fmu").is_map()) {
      for (const char* key : {"interface", "step", "parameters", "unpack_limits"})
        if (p.has(key)) p.child(key).fail("expected it inside the fmu: map (or `fmu: FILE` with it beside)");
      spec.fmu = p.child("fmu");
    } else {
      spec.fmu_participant = p;
    }
    if (p.has("params")) p.child("params").fail("expected no params: for an FMU participant (its parameters: are the FMU's)");
  } else {
    for (const char* key : {"interface", "step", "parameters", "unpack_limits"})
      if (p.has(key)) p.child(key).fail("expected it only beside `fmu: FILE` in a participant of type fmu");
    if (p.has("fmu")) spec.fmu = p.child("fmu");
  }
  return p;
}

// One entry of `participants:`.
ParticipantSpec parse_participant(Scene& scene, const std::string& name, ConfigNode p, const std::vector<std::string>& overrides,
                                  const ProcessRealtimeSpec& scene_process_realtime) {
  if (!valid_name(name)) p.fail("expected an instance name of letters, digits and '_'");
  p.allow_only({"type", "params", "dds", "host", "process", "solver", "realtime", "restart", "fmu", "testing", "interface", "step",
                "parameters", "unpack_limits"});
  ParticipantSpec spec;
  spec.name = name;
  if (auto t = p.optional_child("testing")) parse_testing_seams(*t, spec);
  spec.type = p.string("type");
  spec.vendor = p.has("dds") ? p.choice("dds", {"cyclone", "fastdds"}) : scene.vendor;
  parse_placement(scene, p, spec);
  parse_restart(scene, p, spec);
  spec.process_realtime = scene_process_realtime;
  if (auto rt = p.optional_child("realtime")) {
    rt->allow_only({"priority", "lock_memory", "cpus"});
    spec.process_realtime = parse_process_realtime(*rt, scene_process_realtime);
  }
  if (auto s = p.optional_child("solver")) spec.solver = parse_solver(*s);
  if (scene.time.adaptive) adaptive_solver_tolerances(spec.solver, scene.time.adaptive->tolerance);
  spec.params = p.has("params") ? p.child("params") : ConfigNode::from_string("{}", scene.root.file());
  p = parse_fmu(scene, name, p, overrides, spec);
  spec.key_path = p.path();
  return spec;
}

// `participants:`, then what holds across them (process groups, restart on one host).
void parse_participants(Scene& scene, const std::vector<std::string>& overrides, const ProcessRealtimeSpec& scene_process_realtime) {
  const ConfigNode participants = scene.root.child("participants");
  if (!participants.is_map() || participants.size() == 0)
    participants.fail("expected a map of participant instances (name: {type: ..., params: ...})");
  for (const std::string& name : participants.keys())
    scene.participants.push_back(parse_participant(scene, name, participants.child(name), overrides, scene_process_realtime));

  check_process_groups(scene, participants);

  // Restart with rollback runs on the launcher's host only: an agent cannot restart a node,
  // and the launcher finds the common checkpoint in its own run folder.
  if (scene.checkpointing())
    for (const auto& p : scene.participants)
      if (!p.host.empty())
        participants.child(p.name).child("host").fail(
            "a scene with restart: on_failure runs on the launcher's host only (participant on host '" + p.host +
            "'); restart with rollback across hosts is not built (docs/faults.md)");
}

// One entry of `connections:` (after the participants, whose names it checks).
ConnectionSpec parse_connection(const Scene& scene, const ConfigNode& c) {
  c.allow_only({"from", "to", "order", "reconstruction", "coupling", "initial", "fields"});
  ConnectionSpec spec;
  spec.from = c.string("from");
  spec.to = c.string("to");
  // `participant.port` on both sides, or on neither.
  const auto split = [](std::string& participant, std::string& port) {
    const auto dot = participant.find('.');
    if (dot == std::string::npos) return;
    port = participant.substr(dot + 1);
    participant.resize(dot);
  };
  split(spec.from, spec.from_field);
  split(spec.to, spec.to_input);
  if (spec.from_field.empty() != spec.to_input.empty())
    c.child(spec.from_field.empty() ? "from" : "to")
        .fail("expected participant.port on both sides of a port-level connection (from: slide.spindle_angle, "
              "to: ctrl.phi), or participant names on both");
  spec.key_path = c.path();
  spec.coupling = c.optional_child("coupling");
  spec.initial = c.optional_child("initial");
  if (auto fields = c.optional_child("fields")) {
    if (!fields->is_sequence() || fields->size() == 0) fields->fail("expected a list of topic field names, e.g. [angle, speed]");
    for (std::size_t f = 0; f < fields->size(); ++f) spec.fields.push_back(fields->at(f).as_string());
  }
  if (!scene.find_participant(spec.from)) c.child("from").fail("expected the name of a participant of this scene, got '" + spec.from + "'");
  if (!scene.find_participant(spec.to)) c.child("to").fail("expected the name of a participant of this scene, got '" + spec.to + "'");
  if (spec.from == spec.to) c.child("to").fail("expected another participant than 'from'");
  if (c.has("order"))
    spec.order = c.choice("order", {"jacobi", "gauss_seidel"}) == "jacobi" ? EdgeOrder::jacobi : EdgeOrder::gauss_seidel;
  if (c.has("reconstruction")) {
    const auto& names = reconstruction_names();
    const std::string r = c.choice("reconstruction", names);
    spec.reconstruction = static_cast<Reconstruction>(std::find(names.begin(), names.end(), r) - names.begin());
  }
  for (const auto& other : scene.connections)
    if (other.from == spec.from && other.to == spec.to && other.from_field == spec.from_field && other.to_input == spec.to_input)
      c.fail("expected each from -> to pair once (duplicate of " + other.key_path + ")");
  return spec;
}

// The entries of the optional list section `key` of the scene, each handed to `entry` in order.
template <class Entry>
void for_each_entry(const Scene& scene, const char* key, const std::string& not_a_list, Entry entry) {
  auto list = scene.root.optional_child(key);
  if (!list) return;
  if (!list->is_sequence()) list->fail(not_a_list);
  for (std::size_t i = 0; i < list->size(); ++i) entry(list->at(i));
}

void parse_connections(Scene& scene) {
  for_each_entry(scene, "connections", "expected a list of connections",
                 [&](const ConfigNode& c) { scene.connections.push_back(parse_connection(scene, c)); });
}

// A scalar 'participant.output' naming a participant of the scene.
SignalRef parse_scene_signal(const Scene& scene, const ConfigNode& s) {
  SignalRef ref = parse_signal_ref(s, s.as_string());
  if (!scene.find_participant(ref.participant)) s.fail("expected a participant of this scene in '" + ref.full_name() + "'");
  return ref;
}

// `compare: [participant.output, ...]`.
void parse_compare(Scene& scene) {
  for_each_entry(scene, "compare", "expected a list of signals 'participant.output'",
                 [&](const ConfigNode& s) { scene.compare.push_back(parse_scene_signal(scene, s)); });
}

// A report figure `energy_balance: {supplied: [power signals], dissipated: [power signals],
// stored: [energy signals]}`.
void parse_energy_balance(const Scene& scene, const ConfigNode& r, ReportSpec& spec) {
  ConfigNode b = r.child("energy_balance");
  if (!b.is_map()) b.fail("expected a map {supplied: [signals in W], dissipated: [signals in W], stored: [signals in J]}");
  b.allow_only({"supplied", "dissipated", "stored"});
  for (auto [key, list] : {std::pair{"supplied", &spec.supplied}, std::pair{"dissipated", &spec.dissipated},
                           std::pair{"stored", &spec.stored}}) {
    auto l = b.optional_child(key);
    if (!l) continue;
    if (!l->is_sequence()) l->fail("expected a list of participant.output signals");
    for (std::size_t k = 0; k < l->size(); ++k) list->push_back(parse_scene_signal(scene, l->at(k)));
  }
  if (spec.supplied.empty()) b.fail("expected at least one supplied power signal (supplied: [participant.output])");
  spec.signal = spec.supplied.front();
}

// One entry of `report:`: exactly one statistic of a signal, with its options.
ReportSpec parse_report_figure(const Scene& scene, const ConfigNode& r) {
  static const std::vector<std::string> stats{"min", "max", "max_abs", "final", "time_true", "step_response", "energy_balance"};
  r.allow_only({"min", "max", "max_abs", "final", "time_true", "step_response", "energy_balance", "at", "unit", "target", "band"});
  ReportSpec spec;
  int found = 0;
  for (const auto& s : stats)
    if (r.has(s)) {
      spec.stat = s;
      ++found;
    }
  if (found != 1) r.fail("expected exactly one of min, max, max_abs, final, time_true, step_response, energy_balance");
  if (spec.stat == "energy_balance") {
    parse_energy_balance(scene, r, spec);
    return spec;
  }
  spec.signal = parse_signal_ref(r.child(spec.stat), r.string(spec.stat));
  if (r.has("at")) spec.at = parse_signal_ref(r.child("at"), r.string("at"));
  if (r.has("unit")) {
    spec.at_unit = r.string("unit");
    try {
      spec.at_scale = parse_quantity("1 " + spec.at_unit).value_si;
    } catch (const std::exception& e) {
      r.child("unit").fail(std::string("expected a display unit: ") + e.what());
    }
    spec.at_wrap_turn = spec.at_unit == "deg";
  }
  if (spec.stat == "step_response") {
    if (r.has("target")) spec.target = r.child("target").as_string();
    spec.band = r.has("band") ? r.number("band") : 0.02;
    if (!(spec.band > 0 && spec.band < 0.5)) r.child("band").fail("expected a settling band in (0, 50 %)");
  }
  for (const SignalRef* ref : {&spec.signal, spec.at ? &*spec.at : nullptr})
    if (ref && !scene.find_participant(ref->participant))
      r.fail("expected a participant of this scene in '" + ref->full_name() + "'");
  return spec;
}

void parse_report(Scene& scene) {
  for_each_entry(scene, "report", "expected a list of figures such as {min: signal, at: signal, unit: deg}",
                 [&](const ConfigNode& r) { scene.report.push_back(parse_report_figure(scene, r)); });
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  Scene scene;
  load_document(scene, path, overrides);
  const ConfigNode& root = scene.root;
  parse_identity(scene);
  scene.time = parse_time(root.child("time"));
  parse_run_mode(scene);
  const ProcessRealtimeSpec scene_process_realtime = parse_realtime_section(scene);
  if (root.has("hang_timeout")) scene.hang_timeout = root.positive_quantity("hang_timeout", dim::time);
  if (root.has("processes")) scene.processes = parse_process_layout(root.child("processes"));
  parse_dds_section(scene, overrides);
  parse_faults_section(scene);
  scene.design = root.optional_child("design");
  if (auto rec = root.optional_child("record")) scene.record = parse_record(*rec);
  parse_hosts(scene, overrides);
  parse_participants(scene, overrides, scene_process_realtime);
  parse_connections(scene);
  parse_compare(scene);
  parse_report(scene);
  return scene;
}

std::string scene_to_yaml(const Scene& scene) { return scene.root.to_yaml(); }

}  // namespace mechsim::config
