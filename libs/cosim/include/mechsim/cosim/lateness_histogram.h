// Publication lateness of a paced node, binned: 1 us bins up to 20 ms and an overflow
// count (with the exact maximum). Fixed memory, allocated once: adding a sample never
// allocates, so a real-time node's steady-state step stays allocation-free, and the
// percentiles (to 1 us) are available at any time, for the live progress line too.
#pragma once

#include <cstdint>
#include <vector>

namespace mechsim::cosim {

class LatenessHistogram {
 public:
  static constexpr double kBinWidth = 1e-6;  // s
  static constexpr std::size_t kBins = 20000;  // up to 20 ms

  LatenessHistogram() : counts_(kBins, 0) {}
  void add(double lateness_s);
  long count() const { return count_; }
  long overflow() const { return overflow_; }  // samples beyond the last bin
  double max() const { return max_; }
  // The q-quantile, as the upper edge of the bin holding it (at most one bin above the
  // exact value); the exact maximum when it lies in the overflow.
  double quantile(double q) const;
  const std::vector<std::uint32_t>& counts() const { return counts_; }

 private:
  std::vector<std::uint32_t> counts_;
  long count_ = 0, overflow_ = 0;
  double max_ = 0;
};

}  // namespace mechsim::cosim
