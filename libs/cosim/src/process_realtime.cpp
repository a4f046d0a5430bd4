#include "mechsim/cosim/process_realtime.h"

#include <malloc.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mechsim::cosim {

namespace {

// Effective capability bit from /proc/self/status (CapEff is a hex mask).
bool has_capability(int bit) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("CapEff:", 0) == 0) {
      const unsigned long long mask = std::strtoull(line.c_str() + 7, nullptr, 16);
      return (mask >> bit) & 1ULL;
    }
  return false;
}

std::string cpu_list(const std::vector<int>& cpus) {
  std::string s = "[";
  for (std::size_t i = 0; i < cpus.size(); ++i) s += (i ? ", " : "") + std::to_string(cpus[i]);
  return s + "]";
}

std::string errno_text(const char* call) { return std::string(call) + " failed: " + std::strerror(errno); }

// Touch a stack region and a heap region now, so that the steady state never page-faults
// (with mlockall(MCL_FUTURE) the pages stay resident). The heap is kept: no trimming, no
// mmap for large blocks, so freed memory is reused instead of returned and faulted again.
constexpr std::size_t kStackPrefault = 512 * 1024;
constexpr std::size_t kHeapPrefault = 32 * 1024 * 1024;

__attribute__((noinline)) void prefault_stack() {
  char buffer[kStackPrefault];
  for (std::size_t i = 0; i < kStackPrefault; i += 4096) reinterpret_cast<volatile char*>(buffer)[i] = 0;
}

void prefault_heap() {
  mallopt(M_TRIM_THRESHOLD, -1);
  mallopt(M_MMAP_MAX, 0);
  char* block = static_cast<char*>(std::malloc(kHeapPrefault));
  if (!block) throw std::runtime_error("lock_memory: could not pre-fault " + std::to_string(kHeapPrefault >> 20) + " MiB of heap");
  for (std::size_t i = 0; i < kHeapPrefault; i += 4096) block[i] = 0;
  std::free(block);
}

}  // namespace

ProcessRights current_process_rights() {
  ProcessRights r;
  r.root = geteuid() == 0;
  r.cap_sys_nice = has_capability(23);  // CAP_SYS_NICE
  r.cap_ipc_lock = has_capability(14);  // CAP_IPC_LOCK
  rlimit lim{};
  if (getrlimit(RLIMIT_RTPRIO, &lim) == 0) r.rtprio_limit = lim.rlim_cur == RLIM_INFINITY ? 99 : static_cast<long>(lim.rlim_cur);
  if (getrlimit(RLIMIT_MEMLOCK, &lim) == 0) r.memlock_unlimited = lim.rlim_cur == RLIM_INFINITY;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0)
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &set)) r.allowed_cpus.push_back(c);
  return r;
}

std::string realtime_refusal(const config::ProcessRealtimeSpec& spec, const ProcessRights& rights) {
  std::ostringstream why;
  const std::string key = spec.key_path.empty() ? "realtime" : spec.key_path;
  if (spec.priority > 0 && !rights.cap_sys_nice && rights.rtprio_limit < spec.priority) {
    why << key << ".priority: SCHED_FIFO priority " << spec.priority
        << " needs CAP_SYS_NICE (root has it) or RLIMIT_RTPRIO >= " << spec.priority << " (`ulimit -r`, limits.conf rtprio); this process has "
        << (rights.root ? "uid 0 without CAP_SYS_NICE" : "no CAP_SYS_NICE") << " and RLIMIT_RTPRIO " << rights.rtprio_limit;
    return why.str();
  }
  if (spec.lock_memory && !rights.cap_ipc_lock && !rights.memlock_unlimited) {
    why << key << ".lock_memory: mlockall needs CAP_IPC_LOCK (root has it) or an unlimited RLIMIT_MEMLOCK (`ulimit -l unlimited`, "
        << "limits.conf memlock); this process has neither";
    return why.str();
  }
  for (int cpu : spec.cpus) {
    bool allowed = false;
    for (int c : rights.allowed_cpus) allowed = allowed || c == cpu;
    if (!allowed) {
      why << key << ".cpus: CPU " << cpu << " is not available to this process (it may run on " << cpu_list(rights.allowed_cpus) << ")";
      return why.str();
    }
  }
  return {};
}

std::string AppliedRealtime::describe() const {
  std::string s = priority > 0 ? policy + " " + std::to_string(priority) : policy;
  s += memory_locked ? ", memory locked" : ", memory not locked";
  s += cpus.empty() ? ", any cpu" : ", cpus " + cpu_list(cpus);
  return s;
}

std::string AppliedRealtime::to_json() const {
  return "{\"policy\": \"" + policy + "\", \"priority\": " + std::to_string(priority) +
         ", \"memory_locked\": " + (memory_locked ? "true" : "false") + ", \"cpus\": " + cpu_list(cpus) + "}";
}

void AppliedRealtime::write_json(const std::string& path) const { std::ofstream(path) << to_json() << "\n"; }

AppliedRealtime apply_process_realtime(const config::ProcessRealtimeSpec& spec) {
  AppliedRealtime applied;
  if (!spec.any()) return applied;
  if (std::string why = realtime_refusal(spec, current_process_rights()); !why.empty()) throw std::runtime_error(why);
  const std::string key = spec.key_path.empty() ? "realtime" : spec.key_path;
  if (!spec.cpus.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (int c : spec.cpus) CPU_SET(c, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) throw std::runtime_error(key + ".cpus: " + errno_text("sched_setaffinity"));
    applied.cpus = spec.cpus;
  }
  if (spec.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) throw std::runtime_error(key + ".lock_memory: " + errno_text("mlockall"));
    prefault_heap();
    prefault_stack();
    applied.memory_locked = true;
  }
  if (spec.priority > 0) {
    sched_param param{};
    param.sched_priority = spec.priority;
    // sched_setscheduler(0) sets the calling thread; threads created afterwards (the DDS
    // vendor's receive and event threads) inherit it.
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0)
      throw std::runtime_error(key + ".priority: " + errno_text("sched_setscheduler(SCHED_FIFO)") +
                               " (in a container, the runtime may withhold real-time scheduling)");
    applied.policy = "SCHED_FIFO";
    applied.priority = spec.priority;
  }
  return applied;
}

}  // namespace mechsim::cosim
