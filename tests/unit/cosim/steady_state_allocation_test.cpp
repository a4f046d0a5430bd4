// A node's steady-state step allocates nothing (issue: real time that holds). A heap
// allocation in the step can take the allocator's lock, grow the heap (a page fault, a
// system call) and so turn into lateness; with lock_memory the pre-faulted heap is only
// a reserve, not a guarantee. This test interposes malloc/calloc/realloc for the whole
// process (operator new goes through malloc) and counts the calls made while every node of
// a shipped real-time scene takes 1 000 macro steps after a warm-up: the block, its
// integrator, the coupling scheme, the input channels, the divergence guard, the pacer's
// lateness record and the output log, i.e. everything a node process does in a step except
// the DDS vendor's own write and take and SUNDIALS' difference-quotient Jacobian (counted
// apart, below; docs/realtime.md says what those do).
#include <gtest/gtest.h>

#include <dlfcn.h>
#include <execinfo.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <filesystem>
#include <string>

#include "mechsim/cosim/output_log.h"
#include "mechsim/cosim/pacer.h"
#include "mechsim/cosim/stepped_run.h"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
}

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};  // by mechsim's code (or anything but the one below)
std::atomic<long> g_sundials_dq_jacobian{0};
// MECHSIM_ALLOC_TRACE=N prints the call stacks of the first N counted allocations (to find
// the culprit when a test below fails; backtrace_symbols_fd does not allocate).
long g_trace = std::getenv("MECHSIM_ALLOC_TRACE") ? std::atol(std::getenv("MECHSIM_ALLOC_TRACE")) : 0;
thread_local bool t_in_count = false;

// SUNDIALS 6.4's dense difference-quotient Jacobian (cvLsDenseDQJac, used by every block:
// none provides a Jacobian) wraps each column in an empty N_Vector clone, three small
// mallocs per Jacobian evaluation, freed at once. They are SUNDIALS' own, like the DDS
// vendor's; they are counted apart, by the function on the stack.
bool from_sundials_dq_jacobian(void* const* frames, int depth) {
  for (int i = 0; i < depth; ++i) {
    Dl_info info{};
    if (dladdr(frames[i], &info) && info.dli_sname && std::strcmp(info.dli_sname, "cvLsDenseDQJac") == 0) return true;
  }
  return false;
}

void count() {
  if (!g_counting.load(std::memory_order_relaxed) || t_in_count) return;
  t_in_count = true;
  void* frames[24];
  const int depth = backtrace(frames, 24);
  if (from_sundials_dq_jacobian(frames, depth)) {
    g_sundials_dq_jacobian.fetch_add(1, std::memory_order_relaxed);
  } else if (g_allocations.fetch_add(1, std::memory_order_relaxed) < g_trace) {
    const char line[] = "---- allocation in the counted window:\n";
    (void)!write(2, line, sizeof line - 1);
    backtrace_symbols_fd(frames, depth, 2);
  }
  t_in_count = false;
}
}  // namespace

extern "C" {
void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
}

namespace mechsim::cosim {
namespace {

namespace fs = std::filesystem;

// Allocations while every node takes steps warm .. warm + counted of `scene`.
long allocations_in_steady_state(const std::string& scene, std::uint64_t warm, std::uint64_t counted) {
  SteppedRun run(std::string(MECHSIM_SOURCE_DIR) + "/config/scenes/" + scene, {"time.end=10 s"});
  const fs::path dir = fs::temp_directory_path() / ("mechsim_alloc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // What run_node adds per publication: the pacer's record and the node's output log.
  std::vector<std::unique_ptr<OutputLogWriter>> logs;
  std::vector<std::unique_ptr<Pacer>> pacers;
  for (const auto& node : run.plan().nodes()) {
    std::vector<std::string> columns;
    for (const auto& o : node.block->outputs()) columns.push_back(o.name);
    logs.push_back(std::make_unique<OutputLogWriter>((dir / (node.name() + ".bin")).string(), columns,
                                                    OutputLogWriter::Mode::background));  // as a paced node writes it
    pacers.push_back(std::make_unique<Pacer>(Pacer::now_ns(), run.plan().grid(), 1e6));
  }
  const double h = run.scene().time.step;
  run.on_publish = [&](std::size_t i, std::uint64_t k, const std::vector<double>& outputs) {
    pacers[i]->published(k);
    logs[i]->append(static_cast<double>(k) * h, outputs);
  };
  run.advance(warm);
  void* warm_up[2];
  backtrace(warm_up, 2);  // loads libgcc's unwinder now, not inside the counted window
  g_allocations = 0;
  g_sundials_dq_jacobian = 0;
  g_counting = true;
  run.advance(warm + counted);
  g_counting = false;
  std::cout << scene << ": " << g_allocations.load() << " allocations in " << counted << " steps, besides "
            << g_sundials_dq_jacobian.load() << " by SUNDIALS' difference-quotient Jacobian\n";
  ::testing::Test::RecordProperty("sundials_dq_jacobian_allocations", std::to_string(g_sundials_dq_jacobian.load()));
  EXPECT_FALSE(run.diverged()) << *run.diverged();
  for (auto& log : logs) log->close();
  fs::remove_all(dir);
  return g_allocations.load();
}

TEST(SteadyStateAllocation, TheCountingAllocatorSeesAllocations) {
  // The counter itself works: a vector that grows is counted as ours (else the tests below
  // prove nothing).
  g_allocations = 0;
  g_sundials_dq_jacobian = 0;
  g_counting = true;
  std::vector<double>* v = new std::vector<double>(1000, 1.0);
  v->push_back(2.0);
  g_counting = false;
  delete v;
  EXPECT_GE(g_allocations.load(), 3);
  EXPECT_EQ(g_sundials_dq_jacobian.load(), 0);
}

TEST(SteadyStateAllocation, NcSlideLoopRtStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_steady_state("nc_slide_loop_rt.yaml", 200, 1000), 0);
}

TEST(SteadyStateAllocation, CamPressRtStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_steady_state("cam_press_rt.yaml", 200, 1000), 0);
}

TEST(SteadyStateAllocation, PressLineRtStepsWithoutAllocating) {
  // Over the ratio step at 0.8 s too: steps 200 .. 1200.
  EXPECT_EQ(allocations_in_steady_state("press_line_rt.yaml", 200, 1000), 0);
}

}  // namespace
}  // namespace mechsim::cosim
