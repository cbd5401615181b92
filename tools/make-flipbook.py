#!/usr/bin/env python3
"""Writes scenes/data/flame_sheet.png: a 4 x 4 sprite sheet (flipbook) of a
flame tongue, 32 x 32 texels a frame, read left to right, top row first.

Procedural (no downloaded art): frame k of 16 is a teardrop of coverage whose
tip sways and whose body breaks into two tongues as the flame dies, coloured
from white-yellow at the root to orange-red at the tip. The colour is
premultiplied-friendly: rgb is the flame's own colour, alpha its coverage.
Standard library only (tools/png_writer.py): run `tools/make-flipbook.py`.
"""
import math
import sys

from png_writer import png

FRAME = 32
SIDE = 4
FRAMES = SIDE * SIDE


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def texel(k, x, y):
    """RGBA bytes of texel (x, y) of frame k (y = 0 the top row)."""
    life = k / (FRAMES - 1)                 # 0 at birth, 1 at death
    u = (x + 0.5) / FRAME * 2.0 - 1.0       # -1..1 across
    v = 1.0 - (y + 0.5) / FRAME * 2.0       # -1 bottom .. 1 top
    height = 0.9 - 0.5 * life               # the flame shrinks as it dies
    sway = 0.25 * math.sin(2.0 * math.pi * life * 1.5) * (v + 1.0) / 2.0
    w = (u - sway)
    # Teardrop: wide at the root (v = -0.6), narrowing to the tip.
    along = (v + 0.6) / (height + 0.6)
    if along < 0.0:
        half = 0.45 * math.sqrt(max(0.0, 1.0 - (along * 2.5) ** 2))
    else:
        half = 0.45 * (1.0 - along) ** 0.8 if along < 1.0 else 0.0
    # Two tongues late in life: a notch down the middle of the upper body.
    notch = life * 0.35 * smoothstep(0.2, 0.8, along) * math.exp(-(w / 0.08) ** 2)
    edge = half - abs(w) - notch
    alpha = smoothstep(0.0, 0.12, edge) * (1.0 - 0.6 * life)
    heat = 1.0 - smoothstep(-0.2, 1.0, along)
    r = 1.0
    g = 0.35 + 0.6 * heat
    b = 0.08 + 0.7 * heat * heat
    return [round(255 * c) for c in (r, g, b, alpha)]


def main():
    side = FRAME * SIDE
    rows = []
    for y in range(side):
        row = []
        for x in range(side):
            k = (y // FRAME) * SIDE + x // FRAME
            row += texel(k, x % FRAME, y % FRAME)
        rows.append(row)
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/data/flame_sheet.png"
    with open(out, "wb") as f:
        f.write(png(side, side, rows))


if __name__ == "__main__":
    main()
