#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <regex>

TEST(Version, IsSemanticVersion) {
    EXPECT_TRUE(std::regex_match(spindrift::versionString(), std::regex(R"(\d+\.\d+\.\d+)")));
}
