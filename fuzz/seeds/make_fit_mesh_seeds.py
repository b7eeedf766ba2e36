"""Writes the fit_mesh seeds (fuzz_fit_mesh.c's byte layout): a few plain
grids of each size class, a bumpy and a holed one, a soup, and TSurf
text. Run with /usr/bin/python3 from this folder; output is fixed."""
import os
import random

rng = random.Random(7)
out = "fit_mesh"
tail = bytes([0, 5, 0, 0, 0, 6, 0, 0])  # repair flags, fit refinements, size, top, extend, sea level, passes


def grid(nx, ny, length, width, strike, dip, top, jitter, bump, far, drop, cells_rng):
    b = bytes([0, nx - 2, ny - 2, length, width, strike, dip, top, jitter, bump, far])
    for _ in range(nx * ny):
        b += bytes(rng.randrange(256) if cells_rng else 128 for _ in range(3))
    b += bytes([drop])
    b += bytes(rng.randrange(256) for _ in range((nx - 1) * (ny - 1)))
    return b


seeds = {
    "grid_flat": grid(2, 2, 9, 4, 0, 40, 30, 0, 0, 0, 0, False),
    "grid_mid": grid(4, 3, 14, 9, 70, 60, 25, 40, 30, 1, 0, True),
    "grid_big": grid(7, 7, 19, 14, 200, 80, 18, 90, 120, 1, 0, True),
    "grid_vertical": grid(5, 4, 10, 8, 90, 85, 15, 30, 10, 0, 0, True),
    "grid_holes": grid(7, 6, 12, 10, 130, 30, 22, 60, 60, 0, 3, True),
    "grid_above_sea": grid(5, 5, 8, 6, 10, 20, 0, 20, 20, 1, 0, True),
}
soup = bytes([1, 30, 50, 10, 10])
soup += bytes(rng.randrange(256) for _ in range(33 * 3 + 51 * 4))
seeds["soup"] = soup
tsurf = (b"GOCAD TSurf 1\nHEADER {\nname:s\n}\nTFACE\n"
         b"VRTX 1 0 0 0\nVRTX 2 4000 0 -100\nVRTX 3 0 3000 -2500\nVRTX 4 4000 3000 -2600\n"
         b"VRTX 5 2000 1500 -1200\nTRGL 1 2 5\nTRGL 2 4 5\nTRGL 4 3 5\nTRGL 3 1 5\nEND\n")
seeds["tsurf"] = bytes([2]) + tsurf
for v in range(3):
    seeds["grid_top%d" % v] = grid(6, 5, 15, 12, 33 * v, 50, 21, 50, 40, v & 1, 0, True) \
        + bytes([0, 4 + v, v, 100, 200, 6, 0, 0])

os.makedirs(out, exist_ok=True)
for name, data in sorted(seeds.items()):
    if not name.startswith("grid_top"):
        data = data + tail
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)
