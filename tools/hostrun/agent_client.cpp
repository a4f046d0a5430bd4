#include "agent_client.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "agent_protocol.h"
#include "mechsim/config/hash.h"
#include "elapsed.h"

namespace mechsim::hostrun {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

namespace {


// A name an agent may write into the run folder: no path, no hidden file.
bool plain_file_name(const std::string& name) {
  return !name.empty() && name.find('/') == std::string::npos && name[0] != '.' && name != "scene.yaml" && name != "summary.json";
}

}  // namespace

AgentClient::AgentClient(std::unique_ptr<AgentLink> link, std::uint64_t run_id, std::string run_dir)
    : link_(std::move(link)), run_id_(run_id), run_dir_(std::move(run_dir)) {}

AgentClient::~AgentClient() {
  // Whatever happened, the remote nodes of this run must not outlive the launcher; the
  // agents' heartbeat timeout is the backstop when this message is lost.
  if (!stopped_ && !node_address_.empty()) {
    try {
      stop_all();
    } catch (const std::exception&) {
    }
  }
}

void AgentClient::send(std::int32_t kind, const std::string& host, const std::string& node, const std::string& text) {
  transport::AgentMessage m;
  m.run_id = run_id_;
  m.sequence = ++sequence_;
  m.kind = kind;
  m.host = host;
  m.node = node;
  m.text = text;
  link_->send(m);
}

std::vector<std::string> AgentClient::wait_for_agents(const std::vector<std::string>& addresses, double timeout_s,
                                                      const std::function<bool()>& interrupted) {
  const auto t0 = Clock::now();
  for (;;) {
    pump();
    std::vector<std::string> missing;
    for (const auto& a : addresses)
      if (!hello_.count(a)) missing.push_back(a);
    // An agent's hello arrived: its reader of requests exists; matched is checked too so
    // that the first start is not written into the void.
    if (missing.empty() && link_->reaches(addresses.size())) return {};
    const bool lost = std::any_of(missing.begin(), missing.end(), [&](const std::string& a) { return link_->gone(a); });
    if (lost || seconds_since(t0) > timeout_s || interrupted()) return missing.empty() ? std::vector<std::string>{"(requests not matched)"} : missing;
    link_->wait(std::chrono::milliseconds(20));
  }
}

void AgentClient::start(const std::string& node, const std::string& address, const std::string& request) {
  node_address_[node] = address;
  pending_[node] = {address, request, Clock::now()};
  send(static_cast<std::int32_t>(AgentKind::start), address, node, request);
}

std::map<std::string, std::string> AgentClient::send_files(const std::string& address, const std::vector<std::string>& paths) {
  std::map<std::string, std::string> out;
  for (const std::string& path : paths) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read the file to send to the agent on " + address);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string sha = config::sha256_hex(bytes);
    const std::string name = std::filesystem::path(path).filename().string();
    std::size_t offset = 0;
    do {
      const std::size_t n = std::min(transport::kAgentChunkBytes, bytes.size() - offset);
      transport::AgentMessage m;
      m.run_id = run_id_;
      m.sequence = ++sequence_;
      m.kind = static_cast<std::int32_t>(AgentKind::put_file);
      m.host = address;
      m.node = sha;
      m.text = json{{"name", name}, {"offset", offset}, {"size", bytes.size()}}.dump();
      const auto* p = reinterpret_cast<const std::byte*>(bytes.data() + offset);
      m.data.assign(p, p + n);
      link_->send(m);
      offset += n;
    } while (offset < bytes.size());
    out[path] = sha;
  }
  return out;
}

void AgentClient::handle(const transport::AgentMessage& m) {
  const auto kind = static_cast<AgentKind>(m.kind);
  last_heard_[m.host] = Clock::now();
  if (kind == AgentKind::hello) {
    hello_[m.host] = m.text;
    return;
  }
  if (m.run_id != run_id_) return;
  switch (kind) {
    case AgentKind::started:
      pending_.erase(m.node);
      break;
    case AgentKind::refused:
      pending_.erase(m.node);
      exits_.push_back({m.node, 126, false, 0, "refused by the agent on " + m.host + ": " + m.text});
      break;
    case AgentKind::exited: {
      const json j = json::parse(m.text, nullptr, false);
      RemoteExit e{m.node, 1, false, 0, "exit (unreadable report) on " + m.host};
      if (!j.is_discarded()) {
        e.exit_code = j.value("exit_code", 1);
        e.signalled = j.value("signalled", false);
        e.signal = j.value("signal", 0);
        e.describe = j.value("describe", std::string("exit")) + " on " + m.host;
        e.reached_end = j.value("reached_end", false);
      }
      exits_.push_back(e);
      break;
    }
    case AgentKind::log:
      if (plain_file_name(m.node + ".log")) {
        std::ofstream out(run_dir_ + "/" + m.node + ".log", std::ios::binary | std::ios::app);
        out.write(reinterpret_cast<const char*>(m.data.data()), static_cast<std::streamsize>(m.data.size()));
      }
      break;
    case AgentKind::file: {
      if (!plain_file_name(m.node)) break;
      const json j = json::parse(m.text, nullptr, false);
      const std::uint64_t offset = j.is_discarded() ? 0 : j.value("offset", std::uint64_t{0});
      const std::string path = run_dir_ + "/" + m.node;
      // The first chunk replaces what was there (the log streamed so far): the file is the record.
      std::fstream out(path, offset == 0 ? (std::ios::out | std::ios::binary | std::ios::trunc)
                                         : (std::ios::in | std::ios::out | std::ios::binary));
      out.seekp(static_cast<std::streamoff>(offset));
      out.write(reinterpret_cast<const char*>(m.data.data()), static_cast<std::streamsize>(m.data.size()));
      break;
    }
    case AgentKind::collected:
      collected_.insert(m.host);
      break;
    default:
      break;
  }
}

void AgentClient::pump() {
  while (auto m = link_->take()) handle(*m);
  if (seconds_since(last_heartbeat_) > kHeartbeatPeriodS && !node_address_.empty()) {
    send(static_cast<std::int32_t>(AgentKind::heartbeat), kAllAgents, "", "");
    last_heartbeat_ = Clock::now();
  }
  for (auto& [node, p] : pending_)
    if (seconds_since(p.sent) > 1.0) {
      send(static_cast<std::int32_t>(AgentKind::start), p.address, node, p.request);
      p.sent = Clock::now();
    }
}

std::vector<RemoteExit> AgentClient::take_exits() {
  pump();
  std::vector<RemoteExit> out;
  out.swap(exits_);
  return out;
}

void AgentClient::stop_all() {
  stopped_ = true;
  pending_.clear();
  send(static_cast<std::int32_t>(AgentKind::stop), kAllAgents, "", "");
}

std::vector<std::string> AgentClient::collect(double timeout_s) {
  std::set<std::string> addresses;
  for (const auto& [node, address] : node_address_) addresses.insert(address);
  const auto t0 = Clock::now();
  auto last_ask = Clock::now() - std::chrono::hours(1);
  auto silent_for = [&](const std::string& a) {
    const auto it = last_heard_.find(a);
    return it == last_heard_.end() ? seconds_since(t0) : std::min(seconds_since(it->second), seconds_since(t0));
  };
  for (;;) {
    pump();
    bool all = true;
    for (const auto& a : addresses) all = all && (collected_.count(a) || silent_for(a) > kSilentAgentS);
    if (all) break;
    if (seconds_since(t0) > timeout_s) break;
    if (seconds_since(last_ask) > 2.0) {  // repeated: a request right after a stop may be lost
      for (const auto& a : addresses)
        if (!collected_.count(a)) send(static_cast<std::int32_t>(AgentKind::collect), a, "", "");
      last_ask = Clock::now();
    }
    link_->wait(std::chrono::milliseconds(20));
  }
  std::vector<std::string> missing;
  for (const auto& a : addresses) {
    if (collected_.count(a)) continue;
    char silent[160];
    std::snprintf(silent, sizeof silent, "the agent on %s has been silent for %.1f s (unreachable?): its nodes' files stay on that host",
                  a.c_str(), silent_for(a));
    missing.push_back(silent_for(a) > kSilentAgentS ? std::string(silent)
                                                    : "the agent on " + a + " did not hand back its nodes' files within " +
                                                          std::to_string(static_cast<int>(timeout_s)) + " s");
  }
  stopped_ = true;  // collected: the agents forgot the run
  return missing;
}

}  // namespace mechsim::hostrun
