// Frames as PNG files.
#pragma once

#include <spindrift/render.h>

#include <filesystem>

namespace spindrift::io {

/// Writes an RGBA8 frame (top row first) as a PNG, atomically (AtomicFile):
/// a reader never sees a half-written image. Throws spindrift::Error if the
/// frame's size and pixel count disagree or the file cannot be written.
void writePng(const std::filesystem::path& path, const Frame& frame);

}  // namespace spindrift::io
