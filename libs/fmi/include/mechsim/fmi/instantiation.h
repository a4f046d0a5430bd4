// When this process's FMU blocks (co_simulation_block.h, model_exchange_block.h) load and
// instantiate their FMU: when they are made (the nodes, which run them), or at their first
// use (the launcher and `mechsim check`, which only plan a run: an FMU's code must not run
// in them; they have it instantiated in a child process, docs/fmi.md "Where FMU code runs").
#pragma once

namespace mechsim::fmi {

enum class Instantiation { when_made, at_first_use };

void set_block_instantiation(Instantiation when);
Instantiation block_instantiation();

}  // namespace mechsim::fmi
