// A scene: the YAML file a user launches. This is the typed, validated form of its
// generic part (time, mode, DDS, participants, connections, compared signals); each
// participant's `params:` stays a ConfigNode that its node type parses (libs/cosim/catalog).
// The grammar is documented in docs/scenes.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/config/config_node.h"

namespace mechsim::config {

// The DDS vendor of a participant whose scene names none: "cyclone" when it is compiled in,
// else "fastdds" (a build option, libs/config/CMakeLists.txt).
const char* default_dds_vendor();

// `time: {step: adaptive, tolerance, min, max, initial}`: the macro step follows the coupling
// error (docs/accuracy.md, "Adaptive macro step"; libs/cosim/include/mechsim/cosim/step_control.h).
struct AdaptiveStepSpec {
  double tolerance = 1e-3;  // per-step coupling error, relative to each input field's scale
  double min = 0.0;         // s
  double max = 0.0;         // s
  double initial = 0.0;     // s, the first step's length
  // `scales: {participant: {field: value}}`: the size of a topic field's values the error is
  // measured against from the start (otherwise its range and magnitude so far), SI; kept as
  // ("participant.field", value).
  std::vector<std::pair<std::string, double>> scales;
};

struct TimeSpec {
  double start = 0.0;  // s
  double end = 0.0;    // s
  double step = 0.0;   // macro (base) step H, s; with an adaptive step its largest, `max`
  long steps() const;  // number of macro steps, (end - start) / step, exact (fixed step only)
  std::optional<AdaptiveStepSpec> adaptive = std::nullopt;
};

enum class EdgeOrder { jacobi, gauss_seidel };
enum class Reconstruction { hold, linear, quadratic };
// The names of Reconstruction, in enum order: what a scene's `reconstruction:` accepts and
// what `mechsim bench` sweeps (a new enum value needs only its name here).
const std::vector<std::string>& reconstruction_names();
// The node solvers a scene's `solver: {method}` accepts (libs/solve Method), in its order.
const std::vector<std::string>& solver_method_names();

struct SolverSpec {
  std::string method = "cvode_bdf";  // one of solver_method_names()
  double rtol = 1e-6;
  double atol = 1e-9;
  // Written in the scene (else the defaults above, or under `time.step: adaptive` the ones
  // derived from its tolerance: adaptive_solver_tolerances).
  bool rtol_written = false;
  bool atol_written = false;
};

// Under an adaptive step a node solver's tolerance follows the coupling tolerance, as an FMI
// master hands its tolerance to the slaves' solvers (fmi2SetupExperiment): rtol =
// min(1e-6, tolerance x 1e-4), atol = rtol / 1000, where the scene writes none. Measured on
// the shipped scenes, a node's own integration error reaches 1e3 - 1e4 x rtol of a signal's
// range (the stiff NC cut amplifies it), and an error that the nodes floor does not fall with
// the tolerance (docs/accuracy.md, "The predictor's order and the node solvers' floor").
inline constexpr double kAdaptiveSolverRtolPerTolerance = 1e-4;
void adaptive_solver_tolerances(SolverSpec& solver, double coupling_tolerance);

// Operating-system real-time settings of a node process (`realtime: {priority, lock_memory,
// cpus}` scene-wide, `participants.<p>.realtime:` per participant, key by key over the
// scene's). Applied by the node process at start in real-time mode; refused, never ignored, where
// the process lacks the right (docs/realtime.md).
struct ProcessRealtimeSpec {
  int priority = 0;           // SCHED_FIFO priority 1..99; 0 = the default policy (SCHED_OTHER)
  bool lock_memory = false;   // mlockall + pre-faulted stack and heap
  std::vector<int> cpus;      // CPU affinity; empty = every CPU
  std::string key_path;       // where it was written, for messages ("participants.servo.realtime")
  bool any() const { return priority > 0 || lock_memory || !cpus.empty(); }
};

// A machine of a multi-host run (`hosts: {name: {address: ...}}`, docs/hosts.md).
struct HostSpec {
  std::string name;
  std::string address;   // an IPv4 address or a host name, as written
  std::string key_path;  // "hosts.rt_box"
  // How the launcher reaches the host (docs/hosts.md): "ssh" (default) runs `mechsim agent
  // --stdio` in an SSH session; "dds_agent" talks to a standing `mechsim agent` daemon.
  std::string control = "ssh";
  std::string ssh;         // [user@]host for ssh ("" = address)
  std::string ssh_config;  // absolute: a file for ssh -F ("" = ssh's own, ~/.ssh/config)
  std::string mechsim;     // absolute path of mechsim there ("" = the launcher's own path)
};

struct ParticipantSpec {
  std::string name;    // instance name, unique in the scene; prefixes its topics
  std::string type;    // node type, e.g. "cam_shaft"
  std::string vendor;  // DDS vendor of this node
  std::string host;    // a name of Scene::hosts; "" = where the launcher runs
  // Participants with the same process group run as threads of one process, each still its
  // own DDS participant (docs/scenes.md, `process`); "" = a process of its own.
  std::string process;
  SolverSpec solver;
  ProcessRealtimeSpec process_realtime;  // the scene's realtime settings with this participant's over them
  bool restart = false;  // restarted after a crash (faults.restart, or the participant's own restart:)
  // `testing:` seams for the test suite, never for a real run (tests/integration/restart_test.cpp):
  // lose_writes_after_resume: true, the node leaves out its first writes after a resume, as
  // a partner that had not yet matched its writers would miss them; checkpoint_pause_step: K
  // with checkpoint_pause: 3 s, it stops that long halfway through writing its checkpoint of K;
  // lose_write_of_step: K, it leaves out its write of step K, as a sample lost on the wire
  // and never repaired (tests/integration/lost_sample_test.cpp); lose_failed_status: true, a
  // node that fails writes no failed status, as one lost on the wire (nc_loop_test).
  bool lose_writes_after_resume = false;
  bool lose_failed_status = false;
  std::optional<std::uint64_t> lose_write_of_step;
  std::optional<std::uint64_t> checkpoint_pause_step;
  double checkpoint_pause = 0.0;  // s
  ConfigNode params;   // type-specific, validated by the node type
  // `fmu: {file, interface, step, parameters}`: an FMU plays this participant in place of
  // its node type's native block (libs/cosim fmu_participant.h, docs/fmi.md).
  std::optional<ConfigNode> fmu;
  // `type: fmu`: the participant's own map, which holds `fmu: FILE` and its `interface`,
  // `step` and `parameters` beside it (docs/fmi.md, "FMU participants").
  std::optional<ConfigNode> fmu_participant;
  std::string key_path;  // "participants.cam" for error messages
};

struct ConnectionSpec {
  std::string from;  // publishing participant
  std::string to;    // subscribing participant
  // A port-level connection (`from: slide.spindle_angle, to: ctrl.phi`, the way an FMU
  // participant's ports are joined): the publisher's topic field and the subscriber's block
  // input. Both empty: the node types' own mapping of the whole topic (docs/scenes.md).
  std::string from_field;
  std::string to_input;
  EdgeOrder order = EdgeOrder::jacobi;
  Reconstruction reconstruction = Reconstruction::hold;
  // The element at the cut (e.g. the motor-spindle spring-damper), when the connection
  // crosses one: both participants' node types read it (docs/scenes.md).
  std::optional<ConfigNode> coupling;
  // Jacobi only: values of the partner's topic fields before its first sample arrived,
  // {field: value} (the node's initial outputs use them; default: the inputs' defaults).
  std::optional<ConfigNode> initial;
  // The topic fields this connection carries (`fields: [angle, speed]`); empty: every field
  // the two node types map. Two participants of one type on a line shaft read different
  // fields of each other (docs/line-shaft.md).
  std::vector<std::string> fields;
  std::string key_path;  // "connections[1]"
};

// A signal "participant.output" compared with the reference.
struct SignalRef {
  std::string participant;
  std::string output;
  std::string key_path;
  std::string full_name() const { return participant + "." + output; }
};

// A figure the run summary states for the co-simulation and the reference, e.g. the
// minimum contact force and the cam angle where it occurs, or the rise time of a step.
struct ReportSpec {
  // min | max | max_abs (with the time and optionally `at`), final (the last value),
  // time_true (seconds the signal is > 0.5: a flag), step_response (rise 10-90 %,
  // overshoot, settling into +-band of the target).
  std::string stat;
  SignalRef signal;
  std::optional<SignalRef> at;  // another signal evaluated at the extremum
  std::string at_unit;          // display unit of `at` (e.g. "deg"), "" = SI
  double at_scale = 1.0;        // SI value / at_scale = displayed value
  bool at_wrap_turn = false;    // wrap an angle into [0, 360) deg
  std::string target;           // step_response: the final value as written ("0.1 mm"); "" = the reference's last value
  double band = 0.02;           // step_response: settling band, fraction of the step
  // energy_balance: power signals [W] integrated over the run (supplied, dissipated) and
  // energy signals [J] whose change counts as stored; `signal` is the first supplied one.
  std::vector<SignalRef> supplied, dissipated, stored;
};

// `mode:` lockstep (as fast as the nodes go) | realtime (paced to the wall clock).
enum class RunMode { lockstep, realtime };
// `realtime.on_overrun:` continue (count the misses) | abort (stop the run at the first one).
enum class OverrunPolicy { keep_going, abort };
// The words of the scene file, for summaries and messages.
inline const char* to_string(RunMode m) { return m == RunMode::realtime ? "realtime" : "lockstep"; }
inline const char* to_string(OverrunPolicy p) { return p == OverrunPolicy::abort ? "abort" : "continue"; }

// Real-time mode (`mode: realtime`): pacing and what to do when a node falls behind.
struct RealtimeSpec {
  OverrunPolicy on_overrun = OverrunPolicy::keep_going;
  bool spin_wait = false;               // low-latency wait: spin with sched_yield before blocking
  double spin_limit = 200e-6;           // s of spinning per wait
};

// `faults:` — what a run does about lost packets and cut links (docs/faults.md).
// faults.redundant_samples as written: auto | true | false.
enum class RedundantSamples { automatic, always, never };
inline const char* to_string(RedundantSamples r) {
  return r == RedundantSamples::always ? "true" : r == RedundantSamples::never ? "false" : "auto";
}

struct FaultsSpec {
  // Every data sample also goes out on a best-effort twin topic, and a reader takes
  // whichever copy comes first: a lost packet then costs nothing unless both are lost.
  // "auto": on for multi-host runs (the launcher writes the decision into the run's
  // resolved scene), off on one host, where loopback loses nothing and the copy costs time.
  RedundantSamples redundant_samples = RedundantSamples::automatic;
  bool redundant() const { return redundant_samples == RedundantSamples::always; }
  // A partner silent for longer than this (a cut link, an unreachable host) ends the run,
  // naming it; a shorter cut only stalls the run, which then resumes unchanged.
  double partition_grace = 2.0;  // s
  // Restart with rollback: "on_failure" restarts a participant whose process died, and every
  // node rolls back to the last checkpoint they all hold (a participant's own `restart:`
  // overrides this). Nodes checkpoint every `checkpoint_every` steps while any participant
  // may restart; more than `restart_limit` restarts of one participant end the run.
  std::string restart = "never";  // never | on_failure
  long restart_limit = 3;
  long checkpoint_every = 1000;   // macro steps
  std::string key_path = "faults";
};

// A topic chosen by exact names or an ECMAScript regex over the whole name; neither given:
// every topic. One rule for `record:` and the recorder's selection.
bool topic_selected(const std::vector<std::string>& names, const std::string& regex, const std::string& topic);

// `record:` — the launcher records the run's topics into an MCAP file (docs/recording.md).
// `record: true` takes every default.
struct RecordSpec {
  std::string file = "recording.mcap";  // a relative path is inside the run folder
  std::vector<std::string> topics;       // exact topic names; none and no regex: every topic
  std::string regex;                     // ECMAScript, matches the whole topic name
  std::string compression = "zstd";      // zstd | lz4 | none
  bool records(const std::string& topic) const { return topic_selected(topics, regex, topic); }
};

// `processes:` — how the launcher lays the participants of its own host out on processes
// (docs/scenes.md#processes-per-participant-or-per-core). per_participant (default): a process
// each, unless `process:` groups them; per_core: the launcher packs the participants without
// `process:`, `host:` or a `realtime:` of their own into as many process groups per DDS
// vendor as the host has cores (count: that many groups), neighbours in scene order
// together. `processes_key_path` is "" when the scene does not set it.
// `processes:` (docs/scenes.md#processes-the-default-and-the-choices). automatic, the
// default, lets the launcher choose the fastest layout it can keep safe (process_packing.h).
struct ProcessLayout {
  enum class Kind { automatic, per_participant, per_core, count };
  Kind kind = Kind::automatic;
  int count = 0;  // Kind::count: process groups per vendor
  std::string key_path;
  // The scene asks for process groups itself (per_core or N).
  bool packs() const { return kind == Kind::per_core || kind == Kind::count; }
};

struct Scene {
  std::string file;         // path it was loaded from
  std::string name;
  std::string description;
  TimeSpec time;
  RunMode mode = RunMode::lockstep;
  double rtf = 1.0;
  RealtimeSpec realtime;
  std::string vendor = default_dds_vendor();  // scene-wide default
  std::optional<int> domain_id;    // default: the launcher picks a free one
  // dds.security: the folder of `mechsim security init` (absolute); empty: unsecured
  // (docs/security.md).
  std::string security_dir;
  // dds.protection: encrypt (default: discovery, submessages and payloads encrypted) or sign
  // (signed, readable on the wire); authentication and access control either way.
  std::string security_protection = "encrypt";
  double hang_timeout = 5.0;       // s without a status from a node => hung
  ProcessLayout processes;
  std::vector<HostSpec> hosts;     // empty: a single-host run
  std::vector<ParticipantSpec> participants;
  std::vector<ConnectionSpec> connections;
  std::vector<SignalRef> compare;
  std::vector<ReportSpec> report;
  // Settings of the analyses (`mechsim cam-design`, ...): read by the analysis commands,
  // ignored by a time run.
  std::optional<ConfigNode> design;
  std::optional<RecordSpec> record;
  FaultsSpec faults;
  ConfigNode root;  // the whole document (with overrides applied)

  const ParticipantSpec* find_participant(const std::string& name) const;
  // True when some participant restarts after a crash: then every node checkpoints.
  bool checkpointing() const;
  const HostSpec* find_host(const std::string& name) const;
};

// The timings one setting, faults.partition_grace, decides; the launcher, the agents and
// the nodes all take them from here (docs/faults.md, 'Cut links').
struct FaultTimings {
  double partition_grace = 0;  // s: a node waiting longer for a partner's sample ends the run
  double silence_warning = 0;  // s: the launcher names a remote node silent this long (grace / 2)
  double dds_lease = 0;        // s: a multi-host run's DDS lease; a cut up to the grace loses no endpoint (grace + 3 s)
  double agent_timeout = 0;    // s: an agent stops its nodes when the launcher is silent this long (grace + 1 s)
};
FaultTimings fault_timings(double partition_grace);
inline FaultTimings fault_timings(const Scene& scene) { return fault_timings(scene.faults.partition_grace); }

// Loads and validates the generic part of a scene. `overrides` are "dotted.key=value"
// strings (from --set and the shortcut options) applied before validation.
// Throws ConfigError naming the file and key path.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Writes the scene document (with overrides applied) as YAML, for the run folder.
std::string scene_to_yaml(const Scene& scene);

}  // namespace mechsim::config
