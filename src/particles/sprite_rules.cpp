#include "particles/sprite_rules.h"

#include <fmt/format.h>

namespace spindrift::sprite_rules {

void validateSpriteDef(const FieldCheck& check, const SpriteDef& s) {
    check.number("sprite.stretch", s.stretch, kStretch);
    check.number("sprite.soft_distance", s.softDistance, kSoftDistance);
    const FlipbookDef& f = s.flipbook;
    check.number("sprite.flipbook.rows", f.rows, kSheetSide);
    check.number("sprite.flipbook.columns", f.columns, kSheetSide);
    check.number("sprite.flipbook.frames", f.frames, kFrames);
    check.expect(f.frames <= f.rows * f.columns, "sprite.flipbook.frames",
                 fmt::format("at most rows x columns = {}", f.rows * f.columns), std::to_string(f.frames));
    check.number("sprite.flipbook.fps", f.fps, kFps);
    check.expect(!f.animated() || !s.texture.empty(), "sprite.flipbook", "a sprite `texture` to cut into frames",
                 "none");
}

}  // namespace spindrift::sprite_rules
