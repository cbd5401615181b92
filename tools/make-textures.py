#!/usr/bin/env python3
"""Writes the showcase's procedural textures into scenes/data:

- night_sky.png (512 x 288, RGB, a 16:9 background stretched over the frame):
  a dark blue sky that lightens toward a warm haze at the horizon, a moon
  high on the right (where the scene's `sun`, the moonlight, comes from) and
  about 400 stars, fewer and dimmer toward the horizon;
- wisp.png (64 x 64, RGBA): a steam wisp, white with a ragged, stretched
  coverage (fractal value noise in streaks, under an elliptical falloff), so rotated and
  scaled sprites read as wisps rather than round blobs;
- bricks.png (64 x 64, RGB): four courses of bricks in running bond, each
  brick its own shade of red-brown, in grey mortar, for a body's or
  collider's `texture` (it tiles);
- planks.png (64 x 64, RGB): four vertical wooden planks with grain and dark
  seams, for the crates (it tiles).

Procedural and deterministic (a fixed linear congruential generator; no
downloaded art). Colours are computed in linear light and written sRGB
encoded, as the renderer decodes them. Run `tools/make-textures.py`.
"""
import math
import os
import sys

from png_writer import png


class Lcg:
    """Numerical Recipes' 32-bit LCG: the same numbers on every machine."""
    def __init__(self, seed):
        self.state = seed

    def next(self):
        self.state = (1664525 * self.state + 1013904223) & 0xFFFFFFFF
        return self.state / 4294967296.0


def encode(linear):
    """IEC 61966-2-1 sRGB encoding of a linear value, as a byte."""
    x = min(max(linear, 0.0), 1.0)
    e = 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1.0 / 2.4) - 0.055
    return round(255.0 * e)


def mix(a, b, t):
    return [a[i] + (b[i] - a[i]) * t for i in range(3)]


def night_sky(width=512, height=288):
    top = (0.002, 0.004, 0.018)
    horizon = (0.035, 0.022, 0.03)
    sky = [[mix(top, horizon, (y / (height - 1)) ** 2.2) for x in range(width)] for y in range(height)]
    # The moon: a disc with a soft halo, at 80 % across and 16 % down.
    mx, my, radius = 0.8 * width, 0.16 * height, 7.0
    for y in range(height):
        for x in range(width):
            d = math.hypot(x + 0.5 - mx, y + 0.5 - my)
            disc = min(max(radius + 0.5 - d, 0.0), 1.0)
            halo = 0.05 * math.exp(-((d / (5.0 * radius)) ** 2))
            sky[y][x] = mix(sky[y][x], (0.95, 0.93, 0.82), disc)
            sky[y][x] = [c + halo * w for c, w in zip(sky[y][x], (0.55, 0.6, 0.8))]
    rng = Lcg(2026)
    for _ in range(400):
        x, y = rng.next() * width, rng.next() * height
        haze = 1.0 - (y / height) ** 1.5              # fewer, dimmer stars low down
        if rng.next() > haze:
            continue
        brightness = 0.08 + 0.6 * rng.next() ** 6    # most faint, a few bright
        tint = mix((1.0, 0.85, 0.7), (0.75, 0.85, 1.0), rng.next())
        for sy in range(int(y) - 2, int(y) + 3):
            for sx in range(int(x) - 2, int(x) + 3):
                if 0 <= sx < width and 0 <= sy < height:
                    g = math.exp(-((sx + 0.5 - x) ** 2 + (sy + 0.5 - y) ** 2) / (2 * 0.55 ** 2))
                    sky[sy][sx] = [c + brightness * haze * g * t for c, t in zip(sky[sy][sx], tint)]
    return [[encode(c) for texel in row for c in texel] for row in sky]


def value_noise(size, cells_x, cells_y, rng):
    """Smoothed bilinear value noise over a cells_x x cells_y grid of random
    values, tiled; fewer cells across than down stretches it into streaks."""
    grid = [[rng.next() for _ in range(cells_x)] for _ in range(cells_y)]

    def at(i, j):
        return grid[j % cells_y][i % cells_x]
    out = []
    for y in range(size):
        fy = y / size * cells_y
        y0, ty = int(fy), fy - int(fy)
        ty = ty * ty * (3 - 2 * ty)
        row = []
        for x in range(size):
            fx = x / size * cells_x
            x0, tx = int(fx), fx - int(fx)
            tx = tx * tx * (3 - 2 * tx)
            a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * tx
            b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * tx
            row.append(a + (b - a) * ty)
        out.append(row)
    return out


def wisp(size=64):
    rng = Lcg(7)
    octaves = [(value_noise(size, cells, 2 * cells, rng), weight) for cells, weight in ((2, 0.6), (4, 0.4))]
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            u = (x + 0.5) / size * 2.0 - 1.0
            v = (y + 0.5) / size * 2.0 - 1.0
            n = sum(o[y][x] * w for o, w in octaves)              # 0..1, mean 0.5
            falloff = max(0.0, 1.0 - (u / 0.95) ** 2 - (v / 0.45) ** 2)  # wider than tall
            a = max(0.0, min(1.0, (n - 0.3) * 2.2)) * falloff ** 1.5
            row += [255, 255, 255, round(255 * a)]
        rows.append(row)
    return rows


def bricks(size=64):
    rng = Lcg(11)
    courses, per_course = 4, 2
    shades = [[0.75 + 0.5 * rng.next() for _ in range(per_course + 1)] for _ in range(courses)]
    height = size // courses
    width = size // per_course
    rows = []
    for y in range(size):
        course = y // height
        offset = (width // 2) * (course % 2)          # running bond
        row = []
        for x in range(size):
            xs = (x + offset) % size
            brick = xs // width
            mortar = y % height in (0, height - 1) or xs % width in (0, width - 1)
            if mortar:
                colour = (0.20, 0.19, 0.17)
            else:
                k = shades[course][brick] * (0.9 + 0.2 * rng.next())
                colour = (0.36 * k, 0.12 * k, 0.07 * k)
            row += [encode(c) for c in colour]
        rows.append(row)
    return rows


def planks(size=64):
    rng = Lcg(23)
    count = 4
    width = size // count
    shades = [0.8 + 0.4 * rng.next() for _ in range(count)]
    phases = [6.28 * rng.next() for _ in range(count)]
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            plank = x // width
            u = x % width
            if u in (0, width - 1):
                colour = (0.06, 0.035, 0.02)          # the seam
            else:
                # Grain: stripes along the plank that wander with height.
                grain = 0.5 + 0.5 * math.sin(1.9 * u + 0.8 * math.sin(0.2 * y + phases[plank]))
                k = shades[plank] * (0.85 + 0.15 * grain)
                colour = (0.42 * k, 0.26 * k, 0.12 * k)
            row += [encode(c) for c in colour]
        rows.append(row)
    return rows


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join("scenes", "data")
    with open(os.path.join(folder, "night_sky.png"), "wb") as f:
        f.write(png(512, 288, night_sky(), channels=3))
    with open(os.path.join(folder, "wisp.png"), "wb") as f:
        f.write(png(64, 64, wisp()))
    with open(os.path.join(folder, "bricks.png"), "wb") as f:
        f.write(png(64, 64, bricks(), channels=3))
    with open(os.path.join(folder, "planks.png"), "wb") as f:
        f.write(png(64, 64, planks(), channels=3))


if __name__ == "__main__":
    main()
