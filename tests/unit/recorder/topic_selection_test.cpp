// Which topics a recording takes: every mechsim topic by default, exact names, or a regex
// that must match the whole name.
#include <gtest/gtest.h>

#include "recorder.h"

namespace mechsim::recorder {
namespace {

TEST(TopicSelection, DefaultTakesEveryTopic) {
  const TopicSelection all;
  EXPECT_TRUE(all.all());
  EXPECT_TRUE(all.selects("cam/state"));
  EXPECT_TRUE(all.selects("mechsim/status"));
}

TEST(TopicSelection, NamesMatchExactly) {
  const TopicSelection s{{"cam/state", "mechsim/control"}, ""};
  EXPECT_TRUE(s.selects("cam/state"));
  EXPECT_TRUE(s.selects("mechsim/control"));
  EXPECT_FALSE(s.selects("cam/state2"));
  EXPECT_FALSE(s.selects("follower/state"));
}

TEST(TopicSelection, RegexMustMatchTheWholeName) {
  const TopicSelection s{{}, ".*/state"};
  EXPECT_TRUE(s.selects("cam/state"));
  EXPECT_TRUE(s.selects("x_axis/state"));
  EXPECT_FALSE(s.selects("cam/state/extra"));
  EXPECT_FALSE(s.selects("mechsim/status"));
}

TEST(TopicSelection, RefusesABadRegexAndNamesWithARegex) {
  EXPECT_THROW((TopicSelection{{}, "(unclosed"}.validate()), std::invalid_argument);
  EXPECT_THROW((TopicSelection{{"cam/state"}, ".*"}.validate()), std::invalid_argument);
  EXPECT_NO_THROW((TopicSelection{{}, "cam/.*"}.validate()));
}

TEST(RecordOptions, CompressionNames) {
  EXPECT_EQ(parse_compression("zstd"), record::Compression::zstd);
  EXPECT_EQ(parse_compression("lz4"), record::Compression::lz4);
  EXPECT_EQ(parse_compression("none"), record::Compression::none);
  EXPECT_THROW(parse_compression("gzip"), std::invalid_argument);
}

}  // namespace
}  // namespace mechsim::recorder
