// The viewer's session (viewer.cpp): the world, its renderer and the window's
// presenter, with what the panel (viewer_panel.cpp) shows and edits.
#pragma once

#include "presenter.h"

#include <spindrift/effects.h>
#include <spindrift/render.h>
#include <spindrift/world.h>

#include <cstdint>
#include <string>
#include <vector>

namespace spindrift::app {

struct Session {
    WorldId world{};
    RendererId renderer{};
    bool hasWorld = false, hasRenderer = false;
    Presenter presenter;
    std::vector<EmitterDef> emitters;     // as last applied (the panel edits copies)
    std::vector<std::uint64_t> alive;     // per emitter, refreshed now and then
    std::vector<std::string> fireNames;   // per fire, as the scene names them
    StepStats last;                       // of the last step
    double simMs = 0.0, frameMs = 0.0;
};

}  // namespace spindrift::app
