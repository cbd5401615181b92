// A cheap pass over a scene's text before toml++ sees it: toml++ parses
// dotted keys and table headers recursively, one stack frame per part, so a
// one-line file of ~31,000 parts overflows the stack (issue 14). The pass
// bounds what a hostile file could make the parser do, with an error at the
// line and column where a limit is passed:
//   - the text's size (kMaxSceneBytes),
//   - the length of a line (kMaxSceneLineBytes),
//   - the parts of a dotted key or table header (kMaxKeyParts),
//   - the nesting of arrays, inline tables and table headers (kMaxTomlNesting).
// It knows strings (basic, literal, multi-line) and comments, so brackets and
// dots inside them do not count; it does not check TOML syntax, toml++ does.
#pragma once

#include <string>
#include <string_view>

namespace spindrift::scene {

/// Throws SceneError (file `sourceName`) at the first limit passed.
void prescanToml(std::string_view text, const std::string& sourceName);

}  // namespace spindrift::scene
