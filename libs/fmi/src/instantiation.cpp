#include "mechsim/fmi/instantiation.h"

#include <atomic>

namespace mechsim::fmi {

namespace {
std::atomic<Instantiation> g_when{Instantiation::when_made};
}

void set_block_instantiation(Instantiation when) { g_when.store(when); }
Instantiation block_instantiation() { return g_when.load(); }

}  // namespace mechsim::fmi
