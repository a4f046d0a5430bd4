#include "bench_text.h"

#include <cmath>
#include <cstdio>

namespace mechsim::bench {

std::string time_text(double s) {
  char buf[64];
  if (s < 1e-3)
    std::snprintf(buf, sizeof buf, "%.9g us", s * 1e6);
  else if (s < 1.0)
    std::snprintf(buf, sizeof buf, "%.9g ms", s * 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.9g s", s);
  return buf;
}

std::string num(double v, const char* fmt) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string tol_text(double v) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  std::string m(buf), e;
  const auto pos = m.find('e');
  if (pos != std::string::npos) {
    e = m.substr(pos + 1);
    m.resize(pos);
  }
  while (m.find('.') != std::string::npos && (m.back() == '0' || m.back() == '.')) m.pop_back();
  std::string sign;
  if (!e.empty() && (e[0] == '-' || e[0] == '+')) {
    if (e[0] == '-') sign = "-";
    e = e.substr(1);
  }
  while (e.size() > 1 && e[0] == '0') e = e.substr(1);
  return e == "0" ? m : m + "e" + sign + e;
}

}  // namespace mechsim::bench
