// Ctrl-C and SIGTERM end a command's loop (`mechsim play`, `record`, `topic`): one flag
// for the process instead of a file-local handler per command.
#pragma once

#include <atomic>

namespace mechsim::tools {

// From now on SIGINT and SIGTERM set stop_requested() instead of ending the process.
void catch_stop_signals();
// True once SIGINT or SIGTERM arrived after catch_stop_signals().
const std::atomic<bool>& stop_requested();

}  // namespace mechsim::tools
