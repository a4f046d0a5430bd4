// Checkpoints of a node for restart with rollback (docs/faults.md): every
// `faults.checkpoint_every` steps a node writes its complete state at that step boundary
// into the run folder, `checkpoints/<node>.<step>.ckpt`. A checkpoint is written to a
// temporary file and renamed into place, and the older ones are removed only
// afterwards, so a process killed while writing leaves its previous checkpoint usable; a
// file with the .ckpt name is always complete. The launcher picks the newest step every
// node holds (common_checkpoint) and each node, restarted or live, restores it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mechsim/cosim/node_stepper.h"

namespace mechsim::cosim {

struct NodeCheckpoint {
  StepperSnapshot stepper;       // stepper.step is the checkpoint's step
  std::vector<double> guard;     // DivergenceGuard::save()
  std::uint64_t output_rows = 0; // rows of <node>.outputs.bin at the step (steps 0..step)
  std::int64_t events_bytes = 0; // length of <node>.events.jsonl at the step
};

std::string checkpoint_path(const std::string& run_dir, const std::string& node, std::uint64_t step);

// Writes atomically (temporary file, rename), then removes all but the newest
// `keep` checkpoints of the node. Throws std::runtime_error naming the file.
// pause_halfway_s: a test seam (restart_test kills the node there): stop this long halfway
// through the temporary file, unless a killed writer's temporary file was left.
void write_checkpoint(const std::string& run_dir, const std::string& node, const NodeCheckpoint& checkpoint, int keep = 3,
                      double pause_halfway_s = 0.0);

// Throws std::runtime_error naming the file when it is missing, of another node, or damaged.
NodeCheckpoint read_checkpoint(const std::string& run_dir, const std::string& node, std::uint64_t step);

// The steps of the node's complete checkpoints, ascending.
std::vector<std::uint64_t> checkpoint_steps(const std::string& run_dir, const std::string& node);

// The newest step of which every one of `nodes` holds a complete checkpoint.
std::optional<std::uint64_t> common_checkpoint(const std::string& run_dir, const std::vector<std::string>& nodes);

// How many checkpoints a node keeps: enough that the slowest node's newest one is still
// held by the fastest (lock-step nodes differ by a few steps per node of the scene).
int checkpoints_to_keep(long checkpoint_every, std::size_t nodes);

// The words of the status message, for people, of a node that holds the checkpoint of
// `step` and waits for resume; the launcher reads the typed fields
// (StatusMessage::rollback_step, generation), never this text.
std::string rolled_back_message(std::uint64_t step, std::int32_t generation);

}  // namespace mechsim::cosim
