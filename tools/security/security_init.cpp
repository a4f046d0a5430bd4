#include "security_init.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "mechsim/cosim/step_topic.h"
#include "mechsim/config/config_node.h"
#include "mechsim/transport/messages.h"
#include "mechsim/transport/topic_types.h"

namespace mechsim::security {

namespace fs = std::filesystem;

namespace {

// Runs openssl with `args` (no shell); throws with its output when it fails.
void openssl(const std::vector<std::string>& args) {
  std::vector<std::string> argv_storage{"openssl"};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  int out[2];
  if (::pipe(out) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(out[1], STDERR_FILENO);
    ::close(out[0]);
    ::close(out[1]);
    ::execvp("openssl", argv.data());
    const char* msg = "cannot execute openssl: is it installed (Debian package openssl)?\n";
    ::write(STDERR_FILENO, msg, std::strlen(msg));
    ::_exit(127);
  }
  ::close(out[1]);
  std::string output;
  char buf[4096];
  for (ssize_t n; (n = ::read(out[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR);)
    if (n > 0) output.append(buf, static_cast<std::size_t>(n));
  ::close(out[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string command = "openssl";
    for (const auto& a : args) command += " " + a;
    throw std::runtime_error("`" + command + "` failed: " + output);
  }
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

// An EC prime256v1 private key (both vendors' PKI-DH accept it), created 0600 before
// openssl writes into it, so it is never readable by others.
void make_private_key(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd < 0) throw std::runtime_error(path.string() + ": cannot create: " + std::strerror(errno));
  ::close(fd);
  ::chmod(path.c_str(), 0600);
  openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out", path.string()});
  ::chmod(path.c_str(), 0600);
}

// S/MIME signature by the CA, the form both vendors read governance and permissions in.
void sign(const fs::path& dir, const fs::path& xml, const fs::path& p7s) {
  openssl({"smime", "-sign", "-text", "-in", xml.string(), "-out", p7s.string(), "-signer", (dir / "ca.pem").string(),
           "-inkey", (dir / "ca_key.pem").string()});
}

std::string utc(std::chrono::system_clock::time_point t) {
  const std::time_t tt = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  ::gmtime_r(&tt, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%S", &tm);
  return b;
}

// Every domain a run may take: the launcher picks one of 1..230; Cyclone DDS refuses a
// governance that names more (0..230 is its domain range).
const char* kDomains = "<domains><id_range><min>0</min><max>230</max></id_range></domains>";

std::string subject(const std::string& name) { return "CN=" + name + ",O=mechsim"; }

void add_unique(std::vector<std::string>& list, const std::string& topic) {
  if (std::find(list.begin(), list.end(), topic) == list.end()) list.push_back(topic);
}

}  // namespace

std::vector<IdentityGrant> grants_for_plan(const cosim::ScenePlan& plan) {
  std::vector<IdentityGrant> grants;
  for (const auto& node : plan.nodes()) {
    if (node.name() == kLauncherIdentity || node.name() == kObserverIdentity)
      throw config::ConfigError(plan.scene().file, node.spec->key_path,
                                "another name: '" + node.name() + "' is the name of the " + node.name() +
                                "'s DDS security identity (docs/security.md)");
    IdentityGrant g{node.name(), {}, {}};
    // Its own topics (with their best-effort twins, multi-host runs) and its status; its
    // inputs and the launcher's control.
    for (const std::string& t : {node.topic, transport::redundant_topic(node.topic)}) add_unique(g.publish, t);
    add_unique(g.publish, transport::kStatusTopic);
    for (const auto& edge : node.inputs)
      for (const std::string& t : {edge.topic, transport::redundant_topic(edge.topic)}) add_unique(g.subscribe, t);
    if (node.cut) {
      for (const std::string& t : {node.cut->topic, transport::redundant_topic(node.cut->topic)}) add_unique(g.publish, t);
      for (const std::string& t : {node.cut->partner_topic, transport::redundant_topic(node.cut->partner_topic)})
        add_unique(g.subscribe, t);
    }
    // An adaptive macro step: its own step proposals out, every other participant's in.
    if (plan.grid()->is_adaptive()) {
      add_unique(g.publish, cosim::step_topic(node.name()));
      for (const auto& other : plan.nodes())
        if (other.name() != node.name()) add_unique(g.subscribe, cosim::step_topic(other.name()));
    }
    add_unique(g.subscribe, transport::kControlTopic);
    grants.push_back(std::move(g));
  }
  grants.push_back({kLauncherIdentity, {transport::kControlTopic}, {"*"}});
  grants.push_back({kObserverIdentity, {}, {"*"}});
  return grants;
}

std::string permissions_xml(const IdentityGrant& grant) {
  const auto now = std::chrono::system_clock::now();
  const auto topics = [](const std::vector<std::string>& list) {
    std::string s;
    for (const auto& t : list) s += "            <topic>" + t + "</topic>\n";
    return s;
  };
  std::string rule = std::string("      <allow_rule>\n        ") + kDomains + "\n";
  if (!grant.publish.empty()) rule += "        <publish>\n          <topics>\n" + topics(grant.publish) + "          </topics>\n        </publish>\n";
  if (!grant.subscribe.empty())
    rule += "        <subscribe>\n          <topics>\n" + topics(grant.subscribe) + "          </topics>\n        </subscribe>\n";
  rule += "      </allow_rule>\n";
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<!-- mechsim security init: what identity '" + grant.name + "' may publish and read (docs/security.md) -->\n"
         "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd\">\n"
         "  <permissions>\n"
         "    <grant name=\"mechsim_" + grant.name + "\">\n"
         "      <subject_name>" + subject(grant.name) + "</subject_name>\n"
         "      <validity>\n"
         "        <not_before>" + utc(now - std::chrono::hours(24)) + "</not_before>\n"
         "        <not_after>" + utc(now + std::chrono::hours(24 * 3650)) + "</not_after>\n"
         "      </validity>\n" +
         rule +
         "      <default>DENY</default>\n"
         "    </grant>\n"
         "  </permissions>\n"
         "</dds>\n";
}

std::string governance_xml(const std::string& protection) {
  if (protection != transport::kProtectionEncrypt && protection != transport::kProtectionSign)
    throw std::invalid_argument("governance_xml: protection '" + protection + "': expected encrypt or sign");
  // Encrypted: discovery, liveliness, every submessage and every payload (per writer).
  // Signed: discovery and liveliness, and every RTPS message as a whole (one MAC per
  // message, with the keys of the sending participant: its submessages and payloads
  // included), not each submessage and payload once more by itself: that costs Fast DDS
  // about 40 % of its signed pace, and Fast DDS 2.9 cannot decode a payload protected SIGN
  // ("Error decoding encoded payload", nodes never ready; docs/security.md, 'Protection').
  const bool sign = protection == transport::kProtectionSign;
  const std::string kind = sign ? "SIGN" : "ENCRYPT", rtps_kind = sign ? "SIGN" : "NONE", topic_kind = sign ? "NONE" : "ENCRYPT";
  return std::string("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n") +
         "<!-- mechsim security init: only authenticated participants join; everything " +
         (sign ? "signed, nothing encrypted" : "encrypted") + " (dds.protection: " + protection + ", docs/security.md) -->\n" +
         "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd\">\n"
         "  <domain_access_rules>\n"
         "    <domain_rule>\n"
         "      " + kDomains + "\n"
         "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
         "      <enable_join_access_control>true</enable_join_access_control>\n"
         "      <discovery_protection_kind>" + kind + "</discovery_protection_kind>\n"
         "      <liveliness_protection_kind>" + kind + "</liveliness_protection_kind>\n"
         "      <rtps_protection_kind>" + rtps_kind + "</rtps_protection_kind>\n"
         "      <topic_access_rules>\n"
         "        <topic_rule>\n"
         "          <topic_expression>*</topic_expression>\n"
         "          <enable_discovery_protection>true</enable_discovery_protection>\n"
         "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
         "          <enable_read_access_control>true</enable_read_access_control>\n"
         "          <enable_write_access_control>true</enable_write_access_control>\n"
         "          <metadata_protection_kind>" + topic_kind + "</metadata_protection_kind>\n"
         "          <data_protection_kind>" + topic_kind + "</data_protection_kind>\n"
         "        </topic_rule>\n"
         "      </topic_access_rules>\n"
         "    </domain_rule>\n"
         "  </domain_access_rules>\n"
         "</dds>\n";
}

void init_security_folder(const std::string& dir_text, const std::vector<IdentityGrant>& grants, std::ostream& log) {
  const fs::path dir = fs::absolute(dir_text);
  fs::create_directories(dir);
  const fs::path ca = dir / "ca.pem", ca_key = dir / "ca_key.pem";
  if (fs::exists(ca) && fs::exists(ca_key)) {
    log << "security: keeping the CA " << ca.string() << "\n";
  } else {
    make_private_key(ca_key);
    openssl({"req", "-new", "-x509", "-key", ca_key.string(), "-out", ca.string(), "-days", "3650", "-subj",
             "/O=mechsim/CN=mechsim CA", "-addext", "basicConstraints=critical,CA:TRUE"});
    log << "security: new CA " << ca.string() << " (its key " << ca_key.string() << " signs identities: keep it off the nodes' machines)\n";
  }
  // One governance per protection: a scene's dds.protection chooses at run time.
  for (const char* protection : {transport::kProtectionEncrypt, transport::kProtectionSign}) {
    const fs::path p7s = transport::SecurityIdentity::governance_file(dir.string(), protection);
    const fs::path xml = fs::path(p7s).replace_extension(".xml");
    write_file(xml, governance_xml(protection));
    sign(dir, xml, p7s);
  }
  for (const auto& g : grants) {
    const fs::path id = dir / g.name;
    fs::create_directories(id);
    make_private_key(id / "key.pem");
    openssl({"req", "-new", "-key", (id / "key.pem").string(), "-out", (id / "cert.csr").string(), "-subj",
             "/O=mechsim/CN=" + g.name});
    // A serial per certificate from the clock: no serial file to keep next to the CA.
    const auto serial = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
    openssl({"x509", "-req", "-in", (id / "cert.csr").string(), "-CA", ca.string(), "-CAkey", ca_key.string(), "-set_serial",
             std::to_string(serial), "-days", "3650", "-out", (id / "cert.pem").string()});
    fs::remove(id / "cert.csr");
    write_file(id / "permissions.xml", permissions_xml(g));
    sign(dir, id / "permissions.xml", id / "permissions.p7s");
    log << "security: identity " << g.name << ": publishes " << (g.publish.empty() ? std::string("nothing") : "");
    for (std::size_t i = 0; i < g.publish.size(); ++i) log << (i ? ", " : "") << g.publish[i];
    log << "; reads ";
    for (std::size_t i = 0; i < g.subscribe.size(); ++i) log << (i ? ", " : "") << g.subscribe[i];
    log << "\n";
  }
}

}  // namespace mechsim::security
