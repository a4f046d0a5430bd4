#include <unistd.h>

#include <cmath>
#include <stdexcept>

#include "step_observers.h"

namespace mechsim::cosim {

namespace {

// One JSON line per event.
std::string event_line(const models::BlockEvent& ev) {
  std::string line = "{\"kind\": \"" + ev.kind + "\", \"t_s\": " + std::to_string(ev.t);
  char buf[64];
  for (const auto& [name, value] : ev.values) {
    std::snprintf(buf, sizeof buf, "%.17g", value);
    line += ", \"" + name + "\": " + (std::isfinite(value) ? std::string(buf) : std::string("null"));
  }
  return line + "}";
}

}  // namespace

EventsObserver::EventsObserver(PlannedNode& node, std::string path, bool resumed) : node_(node), path_(std::move(path)) {
  if (!path_.empty()) file_ = std::fopen(path_.c_str(), resumed ? "r+" : "w");
}

EventsObserver::~EventsObserver() {
  if (file_) std::fclose(file_);
}

void EventsObserver::step_completed(const CompletedStep& s) {
  if (s.initial) return;
  s.stepper.take_events();  // the block's own event log below says what they meant
  for (const auto& ev : node_.block->take_event_log()) {
    const std::string line = event_line(ev);
    std::printf("event: %s\n", line.c_str());
    if (file_) {
      std::fprintf(file_, "%s\n", line.c_str());
      std::fflush(file_);
    }
  }
}

void EventsObserver::add_to(NodeCheckpoint& c) {
  c.events_bytes = 0;
  if (!file_) return;
  std::fflush(file_);
  c.events_bytes = std::ftell(file_);
}

// Cuts the file to the checkpoint's length and goes on writing at its end.
void EventsObserver::restore(const NodeCheckpoint& c) {
  if (!file_) return;
  std::fflush(file_);
  if (::ftruncate(::fileno(file_), c.events_bytes) != 0 || std::fseek(file_, c.events_bytes, SEEK_SET) != 0)
    throw std::runtime_error(path_ + ": cannot truncate to the checkpoint");
}

}  // namespace mechsim::cosim
