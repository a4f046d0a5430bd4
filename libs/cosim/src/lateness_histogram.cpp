#include "mechsim/cosim/lateness_histogram.h"

#include <algorithm>
#include <cmath>

namespace mechsim::cosim {

void LatenessHistogram::add(double lateness_s) {
  const double late = std::max(0.0, lateness_s);
  ++count_;
  max_ = std::max(max_, late);
  const double bin = std::floor(late / kBinWidth);
  if (bin >= static_cast<double>(kBins)) {
    ++overflow_;
    return;
  }
  ++counts_[static_cast<std::size_t>(bin)];
}

double LatenessHistogram::quantile(double q) const {
  if (count_ == 0) return 0.0;
  // The smallest bin whose cumulative count reaches ceil(q n) samples.
  const long wanted = std::max<long>(1, static_cast<long>(std::ceil(q * static_cast<double>(count_))));
  long seen = 0;
  for (std::size_t b = 0; b < kBins; ++b) {
    seen += counts_[b];
    if (seen >= wanted) return std::min(max_, static_cast<double>(b + 1) * kBinWidth);
  }
  return max_;
}

}  // namespace mechsim::cosim
