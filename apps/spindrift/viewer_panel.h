// The viewer's panel (Dear ImGui): statistics, fires, bodies, the fluid's
// look and solver, emitter rates and speeds, keys; and the box that shows a
// scene file's load error. Split from viewer.cpp, which runs the window.
#pragma once

#include "playback.h"
#include "viewer_session.h"

#include <imgui.h>

#include <string>
#include <vector>

namespace spindrift::app {

/// What the panel showed in the last frame, for a test script's report.
struct PanelShown {
    bool shown = false;
    ImVec2 pos{}, size{};
    std::vector<std::string> fires, bodies;  // names listed
};

/// Draws the panel for this frame.
PanelShown panel(Session& s, bool paused, const Playback& playback);

/// A scene file that failed to load again, over the frame until it loads.
void loadErrorBox(const std::string& error);

}  // namespace spindrift::app
