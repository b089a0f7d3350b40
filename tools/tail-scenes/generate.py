#!/usr/bin/env python3
"""tools/tail-scenes/generate.py — dense scenes the bench does not generate, and strokes over them.

Why: `contactlab bench` times its own sinusoids. A user's scene is an imported outline: a gear,
a bowl, a rough or wavy terrain. This writes four such scenes (seeded, so every run is the same)
and, for each, a stroke 1 mm deep along the surface and the same stroke 1 cm above it, as the
t,x,y,phi CSV `contactlab bench --scene S --input P` replays. tools/tail-scenes/run times them.

  gear      closed outline, solid inside, radius 40 mm with 24 teeth 3 mm high, 100,000 lines
  bowl27    a valley of radius 27 mm (the pad's is 26 mm: its offset pieces crowd within 1 mm of
            one point), 50,000 lines, with 60 mm flats either side
  terrain   a smooth random terrain (8 seeded sinusoids, 4-40 mm wavelengths), 20,000 quadratic
            curves over 0.4 m
  rough     a 0.4 m floor with 20 um of seeded jitter at every vertex, 100,000 lines

Usage: generate.py OUTDIR
"""
import json
import math
import os
import random
import sys

R = 0.026      # m, seed 000's pad radius
L = 0.020      # m, pad length
DEPTH = 0.001  # m, how far the finger presses in (contact strokes)
HOVER = 0.010  # m, the pad's height above the surface (hover strokes)
TICKS = 4000   # samples a stroke, 1 ms apart (a contact stroke has one more first: 5 cm out)


def scene(contours):
    return {
        "version": 1,
        "finger": {"radius": R, "length": L},
        "force": {"model": "spring", "stiffness": 1000.0, "max_force": 1.5},
        "contact_location": {"rule": "centroid"},
        "curves": {"mode": "exact", "tolerance": 0.0001},
        "contours": contours,
    }


def polyline(points, closed=False):
    segs = [{"type": "line", "from": list(a), "to": list(b)} for a, b in zip(points, points[1:])]
    return {"closed": closed, "segments": segs}


def write_stroke(path, samples, lead=None):
    """`lead`: where the first sample is, 5 cm out from the surface: the replay places the proxy at
    the first sample, so a stroke that started pressed in would start inside the solid."""
    if lead is not None:
        samples = [lead] + samples
    with open(path, "w") as f:
        f.write("t,x,y,phi\n")
        for k, (x, y, phi) in enumerate(samples):
            f.write(f"{k * 1e-3:.6f},{x:.12f},{y:.12f},{phi:.9f}\n")


def profile_strokes(height, x0, x1):
    """Finger samples at a steady speed from x0 to x1 (m), the pad (facing down) resting on the
    profile y = height(x) and pressed DEPTH into it, or HOVER above it: the centre's height is
    where the pad's arc first touches the profile sampled every 0.1 mm under it. (Offsetting the
    surface point along its normal instead folds back where the profile curves tighter than the
    pad, and the finger jumped a millimetre in a tick there.)"""
    step = 1e-4
    half = R * math.sin(0.5 * L / R)  # m, the pad's half-width seen from above
    contact, hover = [], []
    for k in range(TICKS):
        x = x0 + (x1 - x0) * k / (TICKS - 1)
        rest = -math.inf  # m, the centre's height with the pad just touching
        for j in range(-int(half / step), int(half / step) + 1):
            u = x + j * step
            rest = max(rest, height(u) + math.sqrt(R * R - (u - x) ** 2))
        contact.append((x, rest - DEPTH, 0.0))
        hover.append((x, rest + HOVER, 0.0))
    return contact, hover


def gear(out):
    n, teeth, r0, h = 100000, 24, 0.040, 0.003

    def radius(t):
        return r0 + 0.5 * h * (1.0 + math.tanh(4.0 * math.sin(teeth * t)))  # flat-topped teeth

    # Clockwise: solid inside.
    pts = [(radius(-2 * math.pi * i / n) * math.cos(-2 * math.pi * i / n),
            radius(-2 * math.pi * i / n) * math.sin(-2 * math.pi * i / n)) for i in range(n + 1)]
    pts[-1] = pts[0]
    json.dump(scene([polyline(pts, closed=True)]), open(os.path.join(out, "gear.json"), "w"))
    contact, hover = [], []
    for k in range(TICKS):  # a quarter turn around the outside, the pad facing the centre
        t = 0.5 * math.pi * k / (TICKS - 1)
        u = (math.cos(t), math.sin(t))
        phi = t - 0.5 * math.pi
        r = radius(t)
        contact.append(((r + R - DEPTH) * u[0], (r + R - DEPTH) * u[1], phi))
        hover.append(((r + R + HOVER) * u[0], (r + R + HOVER) * u[1], phi))
    write_stroke(os.path.join(out, "gear_contact.csv"), contact, (radius(0.0) + R + 0.05, 0.0, -0.5 * math.pi))
    write_stroke(os.path.join(out, "gear_hover.csv"), hover)


def bowl27(out):
    n, rho, flat = 50000, 0.027, 0.060
    half = math.radians(70.0)  # the bowl's wall up to 70 degrees from the bottom
    pts = [(-rho * math.sin(half) - flat, rho - rho * math.cos(half))]
    for i in range(n + 1):  # centre (0, rho), counter-clockwise along the bottom: solid below
        a = -half + 2 * half * i / n
        pts.append((rho * math.sin(a), rho - rho * math.cos(a)))
    pts.append((rho * math.sin(half) + flat, rho - rho * math.cos(half)))
    json.dump(scene([polyline(pts)]), open(os.path.join(out, "bowl27.json"), "w"))
    contact, hover = [], []
    for k in range(TICKS):  # side to side across the bottom, twice, pressed toward the centre
        a = math.radians(25.0) * math.sin(2 * math.pi * 2 * k / TICKS)
        q = (rho * math.sin(a), rho - rho * math.cos(a))
        inward = (-math.sin(a), math.cos(a))
        contact.append((q[0] + (R - DEPTH) * inward[0], q[1] + (R - DEPTH) * inward[1], 0.0))
        hover.append((q[0] + (R + HOVER) * inward[0], q[1] + (R + HOVER) * inward[1], 0.0))
    write_stroke(os.path.join(out, "bowl27_contact.csv"), contact, (0.0, R + 0.05, 0.0))
    write_stroke(os.path.join(out, "bowl27_hover.csv"), hover)


def terrain(out):
    rng = random.Random(27)
    waves = [(rng.uniform(0.0005, 0.003), 2 * math.pi / rng.uniform(0.004, 0.040), rng.uniform(0, 2 * math.pi))
             for _ in range(8)]

    def height(x):
        return sum(a * math.sin(k * x + p) for a, k, p in waves)

    def slope(x):
        return sum(a * k * math.cos(k * x + p) for a, k, p in waves)

    n, length = 20000, 0.4
    segs = []
    for i in range(n):  # G1 quadratics: control point where the end tangents meet
        x0, x1 = length * i / n, length * (i + 1) / n
        y0, y1, s0, s1 = height(x0), height(x1), slope(x0), slope(x1)
        xm = (y1 - y0 + s0 * x0 - s1 * x1) / (s0 - s1) if abs(s0 - s1) > 1e-12 else 0.5 * (x0 + x1)
        if not (x0 < xm < x1):
            xm = 0.5 * (x0 + x1)
        segs.append({"type": "quad", "p0": [x0, y0], "p1": [xm, y0 + s0 * (xm - x0)], "p2": [x1, y1]})
    json.dump(scene([{"closed": False, "segments": segs}]), open(os.path.join(out, "terrain.json"), "w"))
    contact, hover = profile_strokes(height, 0.05, 0.35)
    write_stroke(os.path.join(out, "terrain_contact.csv"), contact, (contact[0][0], contact[0][1] + 0.05, 0.0))
    write_stroke(os.path.join(out, "terrain_hover.csv"), hover)


def rough(out):
    rng = random.Random(20)
    n, length, jitter = 100000, 0.4, 20e-6
    pts = [(length * i / n, rng.uniform(-jitter, jitter)) for i in range(n + 1)]
    json.dump(scene([polyline(pts)]), open(os.path.join(out, "rough.json"), "w"))
    contact, hover = profile_strokes(lambda x: 0.0, 0.05, 0.35)
    write_stroke(os.path.join(out, "rough_contact.csv"), contact, (contact[0][0], contact[0][1] + 0.05, 0.0))
    write_stroke(os.path.join(out, "rough_hover.csv"), hover)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for make in (gear, bowl27, terrain, rough):
        make(out)
        print(f"generate.py: {make.__name__} written to {out}")
