#pragma once
// Test helper: EXPECT_TRUE(contains(message, "part")) prints the whole message when it fails.
#include <gtest/gtest.h>

#include <string>

namespace gran::testing {

inline ::testing::AssertionResult contains(const std::string& text, const std::string& part) {
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "\"" << part << "\" not found in:\n" << text;
}

}  // namespace gran::testing
