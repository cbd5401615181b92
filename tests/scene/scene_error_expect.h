// Checking that a bad scene is rejected where and why it should be: file,
// line, column, key path and a part of the message. Expected positions are
// counted by hand from the inline TOML (line 1 is the string's first line).
#pragma once

#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <string>

namespace spindrift::test {

struct ExpectedError {
    int line;
    int column;
    std::string keyPath;
    std::string messagePart;  ///< must occur in message()
};

/// Parses `text` as the file "bad.toml" with data paths relative to `baseDir`.
inline void expectError(const std::string& text, const ExpectedError& e, const std::string& baseDir = ".") {
    try {
        parseScene(text, "bad.toml", baseDir);
        ADD_FAILURE() << "accepted a bad scene:\n" << text;
    } catch (const SceneError& err) {
        EXPECT_EQ(err.file(), "bad.toml") << err.what();
        EXPECT_EQ(err.line(), e.line) << err.what();
        EXPECT_EQ(err.column(), e.column) << err.what();
        EXPECT_EQ(err.keyPath(), e.keyPath) << err.what();
        EXPECT_NE(err.message().find(e.messagePart), std::string::npos)
            << "message \"" << err.message() << "\" lacks \"" << e.messagePart << "\"";
    }
}

}  // namespace spindrift::test
