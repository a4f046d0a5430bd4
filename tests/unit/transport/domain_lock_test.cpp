// The domains the launcher picks from keep their ports out of the kernel's ephemeral range.
#include "mechsim/transport/domain_lock.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace mechsim::transport {
namespace {

TEST(DomainLock, PortsOfADomainFollowTheRtpsMapping) {
  // RTPS 2.2 9.6.1.1 with the default PB 7400, DG 250: domain 186 starts at 53900, the port
  // CI could not bind.
  EXPECT_EQ(domain_ports(186).first, 53900);
  EXPECT_EQ(domain_ports(186).last, 54149);
  EXPECT_EQ(domain_ports(0).first, 7400);
}

TEST(DomainLock, PicksOnlyDomainsWhosePortsMissTheEphemeralRange) {
  // Linux's default 32768..60999: domain 100 ends at 32649, 101 starts at 32650 and ends in
  // the range; 214 ends at 61149 (inside from 60900), 215 starts at 61150.
  const std::vector<int> picked = pickable_domains({32768, 60999});
  ASSERT_FALSE(picked.empty());
  EXPECT_EQ(picked.front(), 1);
  EXPECT_EQ(picked.size(), 100u + 16u);  // 1..100 and 215..230
  const auto has = [&](int d) { return std::find(picked.begin(), picked.end(), d) != picked.end(); };
  EXPECT_TRUE(has(100));
  EXPECT_FALSE(has(101));
  EXPECT_FALSE(has(186));
  EXPECT_FALSE(has(214));
  EXPECT_TRUE(has(215));
  EXPECT_TRUE(has(230));
  for (int d : picked) {
    const PortRange p = domain_ports(d);
    EXPECT_TRUE(p.last < 32768 || p.first > 60999) << d;
  }
}

TEST(DomainLock, AcquiredDomainsAreDistinctAndPickable) {
  const DomainLock a = DomainLock::acquire();
  const DomainLock b = DomainLock::acquire();
  EXPECT_NE(a.domain_id(), b.domain_id());
  const std::vector<int> picked = pickable_domains();
  EXPECT_NE(std::find(picked.begin(), picked.end(), a.domain_id()), picked.end());
  EXPECT_NE(std::find(picked.begin(), picked.end(), b.domain_id()), picked.end());
}

}  // namespace
}  // namespace mechsim::transport
