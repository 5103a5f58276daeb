#!/usr/bin/env python3
"""Writes the game-level scenes of scenarios/levels/ and their glTF files in scenarios/assets/levels/:
walled courtyards seen from the streets, an interior of rooms joined by doors and corridors, and a
street canyon with traffic (docs/scenario-generators.md#game-levels-scriptsmake_levelspy).

    python3 scripts/make_levels.py all                      # the three committed levels
    python3 scripts/make_levels.py courtyards --courtyards 5x5 --door-width 3 --out /tmp/x

Each level is one glTF 2.0 file (JSON beside its .bin buffer) and one scenario: cheap, large
occluders (walls, buildings, the floor; marked "extras": {"occsim_occluder": "always"}, which
makes masked rasterise them whatever their size on screen) hiding heavy props that share their
meshes (hundreds to thousands of triangles each), cars and people as the scenario's path movers,
one large vehicle moved by a glTF animation past the camera, and a camera path that walks, turns
corners and passes gates or doors, its moments named as segments.

Deterministic: the same parameters (and --seed) give byte-identical files (its own random number
generator, nodes and keys in a fixed order, coordinates rounded before they are written). Python 3
standard library only.

Before anything is written the level is checked: no two static objects touch or cut into each
other (their depths would tie), no mover's lane runs into a static object, the camera keeps clear
of everything on every frame, and no box face's plane passes within 1 mm of the eye on any frame
(such a face rasterises as a sliver of wrong depth, docs/scenario-generators.md). Impossible
parameters are refused with one line naming the parameter and what was expected, exit status 2.
"""
import argparse
import json
import math
import os
import struct
import sys
from pathlib import Path

GENERATOR = "occsim scripts/make_levels.py"
EYE = 1.7  # eye height of the walking camera (m); no horizontal face is within 1 cm of it
TARGET_Y = 1.6  # the camera looks slightly down
FLOOR_GAP = 0.01  # everything static floats this far above the floor (no two objects touch)
LANE_Y = 0.02  # path movers' base height above the floor top (y = 0)
CAMERA_CLEARANCE = 0.3  # the eye stays this far from every object's box (near plane 0.1 m)
PLANE_CLEARANCE = 0.001  # no box face's plane passes closer than this to the eye on a frame


class ParameterError(Exception):
    """An impossible parameter: one line naming it and what was expected (exit 2)."""


# ---- Deterministic random numbers (splitmix64; Python's own generator may change) --------------


class Rng:
    def __init__(self, seed):
        self.state = (seed * 0x9E3779B97F4A7C15 + 0x632BE59BD9B4E019) & 0xFFFFFFFFFFFFFFFF

    def next64(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
        return z ^ (z >> 31)

    def random(self):  # [0, 1)
        return (self.next64() >> 11) / float(1 << 53)

    def uniform(self, a, b):
        return a + (b - a) * self.random()

    def below(self, n):  # an integer in [0, n)
        return self.next64() % n

    def sample(self, items, k):  # k distinct items, in their original order
        picked = list(items)
        for i in range(len(picked) - 1, 0, -1):
            j = self.below(i + 1)
            picked[i], picked[j] = picked[j], picked[i]
        return sorted(picked[:k], key=list(items).index)


def rnd(x, digits=4):
    """A coordinate as the files write it: rounded, integers without '.0', never -0."""
    v = round(x, digits)
    if v == int(v):
        return int(v)
    return v


def rvec(v, digits=4):
    return [rnd(c, digits) for c in v]


# ---- Meshes ---------------------------------------------------------------------------------


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return ((c, 0, s), (0, 1, 0), (-s, 0, c))


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return ((1, 0, 0), (0, c, -s), (0, s, c))


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return ((c, -s, 0), (s, c, 0), (0, 0, 1))


def mat_mul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def mat_vec(m, v):
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


def scale_mat(sx, sy, sz):
    return ((sx, 0, 0), (0, sy, 0), (0, 0, sz))


IDENTITY = ((1, 0, 0), (0, 1, 0), (0, 0, 1))


class Mesh:
    """Triangles, counter-clockwise seen from outside; vertices shared where a surface is smooth."""

    def __init__(self):
        self.positions = []
        self.indices = []

    def vertex(self, p):
        self.positions.append(tuple(float(c) for c in p))
        return len(self.positions) - 1

    def tri(self, a, b, c):
        if a != b and b != c and a != c:
            self.indices += [a, b, c]

    def extend(self, other, m=IDENTITY, offset=(0, 0, 0)):
        """Adds `other` under x -> m x + offset (m without mirroring)."""
        base = len(self.positions)
        for p in other.positions:
            q = mat_vec(m, p)
            self.positions.append((q[0] + offset[0], q[1] + offset[1], q[2] + offset[2]))
        self.indices += [base + i for i in other.indices]
        return self

    def triangles(self):
        return len(self.indices) // 3

    def bounds(self):
        lo = [min(p[i] for p in self.positions) for i in range(3)]
        hi = [max(p[i] for p in self.positions) for i in range(3)]
        return lo, hi

    def signed_volume(self):
        v = 0.0
        for t in range(0, len(self.indices), 3):
            a, b, c = (self.positions[self.indices[t + k]] for k in range(3))
            v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]))
        return v / 6.0

    def normals(self):
        """Area-weighted vertex normals (smooth where vertices are shared)."""
        n = [[0.0, 0.0, 0.0] for _ in self.positions]
        for t in range(0, len(self.indices), 3):
            ia, ib, ic = self.indices[t:t + 3]
            a, b, c = self.positions[ia], self.positions[ib], self.positions[ic]
            u = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
            w = (c[0] - a[0], c[1] - a[1], c[2] - a[2])
            f = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
            for i in (ia, ib, ic):
                for k in range(3):
                    n[i][k] += f[k]
        out = []
        for v in n:
            length = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            out.append((0.0, 1.0, 0.0) if length == 0 else (v[0] / length, v[1] / length, v[2] / length))
        return out

    def horizontal_heights(self):
        """The heights of the mesh's horizontal triangles (model space)."""
        heights = set()
        for t in range(0, len(self.indices), 3):
            ys = [self.positions[self.indices[t + k]][1] for k in range(3)]
            if max(ys) - min(ys) < 1e-9:
                heights.add(ys[0])
        return sorted(heights)


BOX_FACES = [  # normal, and two axes spanning the face so that u x v = normal (counter-clockwise)
    ((1, 0, 0), (0, 1, 0), (0, 0, 1)),
    ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
    ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
    ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
    ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
    ((0, 0, -1), (0, 1, 0), (1, 0, 0)),
]


def box(lo=(-0.5, 0.0, -0.5), hi=(0.5, 1.0, 0.5)):
    """A box with flat faces (24 vertices, 12 triangles)."""
    m = Mesh()
    c = [(lo[i] + hi[i]) / 2 for i in range(3)]
    h = [(hi[i] - lo[i]) / 2 for i in range(3)]
    for n, u, v in BOX_FACES:
        base = len(m.positions)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            m.vertex([c[i] + h[i] * (n[i] + su * u[i] + sv * v[i]) for i in range(3)])
        m.tri(base, base + 1, base + 2)
        m.tri(base, base + 2, base + 3)
    return m


def lathe(profile, segments):
    """A surface of revolution about y: `profile` (radius, height) from bottom to top, the solid on
    the profile's left; an end with radius 0 closes on the axis, any other end gets a flat cap."""
    m = Mesh()
    rings = []
    for r, y in profile:
        if r <= 0:
            rings.append([m.vertex((0, y, 0))] * segments)
        else:
            rings.append([m.vertex((r * math.cos(2 * math.pi * k / segments), y,
                                    r * math.sin(2 * math.pi * k / segments)))
                          for k in range(segments)])
    for j in range(len(rings) - 1):
        a, b = rings[j], rings[j + 1]
        for k in range(segments):
            k1 = (k + 1) % segments
            m.tri(a[k], b[k], a[k1])
            m.tri(b[k], b[k1], a[k1])
    if profile[0][0] > 0:
        c = m.vertex((0, profile[0][1], 0))
        for k in range(segments):
            m.tri(c, rings[0][k], rings[0][(k + 1) % segments])
    if profile[-1][0] > 0:
        c = m.vertex((0, profile[-1][1], 0))
        for k in range(segments):
            m.tri(c, rings[-1][(k + 1) % segments], rings[-1][k])
    return m


def sphere_profile(radius, rings, y0=0.0):
    return [(radius * math.sin(math.pi * j / rings), y0 + radius - radius * math.cos(math.pi * j / rings))
            for j in range(rings + 1)]


def cylinder(radius, height, segments):
    return lathe([(radius, 0.0), (radius, height)], segments)


def detail_count(base, detail, least=6):
    return max(least, int(round(base * detail)))


# The props. Each is a mesh in its own space: base centre at the origin, y up, front +x; sizes in
# metres (the level scales some of them).

def fountain_mesh(detail):
    s = detail_count(48, detail, 8)
    profile = [(0, 0.0), (1.0, 0.0), (1.0, 0.36), (0.9, 0.4), (0.86, 0.18), (0.32, 0.18), (0.22, 0.5),
               (0.17, 0.78), (0.5, 0.86), (0.52, 0.93), (0.16, 0.95), (0.11, 1.3), (0.2, 1.36),
               (0.07, 1.42), (0.05, 1.55), (0, 1.62)]
    return lathe(profile, s)  # 2 m across, 1.62 m high; scaled by the level


def figure(detail):
    """A standing figure 1.8 m tall: legs, torso, head, arms (tessellated, about 1,000 triangles)."""
    s = detail_count(20, detail)
    m = Mesh()
    leg = lathe([(0.07, 0.0), (0.09, 0.1), (0.085, 0.45), (0.11, 0.85), (0.12, 0.9), (0, 0.92)], s)
    for z in (-0.1, 0.1):
        m.extend(leg, offset=(0, 0, z))
    torso = lathe([(0, 0.85), (0.2, 0.88), (0.19, 1.1), (0.22, 1.4), (0.16, 1.52), (0.06, 1.55),
                   (0, 1.56)], s)
    m.extend(torso, m=scale_mat(0.8, 1, 1.15))
    m.extend(lathe(sphere_profile(0.12, detail_count(10, detail, 4)), s), offset=(0, 1.52, 0))
    arm = lathe([(0, 0.0), (0.05, 0.02), (0.06, 0.3), (0.05, 0.58), (0, 0.6)], s)
    m.extend(arm, m=rot_x(math.radians(160)), offset=(0, 1.47, -0.26))  # hanging left arm
    m.extend(arm, m=mat_mul(rot_y(math.radians(-20)), rot_x(math.radians(-115))), offset=(0, 1.45, 0.26))
    return m


def statue_mesh(detail, variant):
    """A figure on a stepped plinth (variant 0), or an urn on a fluted column (variant 1): 1.0 m
    across, 2.4 m high."""
    m = box((-0.5, 0.0, -0.5), (0.5, 0.25, 0.5))
    m.extend(box((-0.4, 0.25, -0.4), (0.4, 0.6, 0.4)))
    if variant == 0:
        m.extend(figure(detail), m=scale_mat(1.0, 1.0, 1.0), offset=(0, 0.6, 0))
    else:
        s = detail_count(32, detail, 8)
        column = []
        for j in range(9):
            column.append((0.22 + 0.02 * math.cos(j * math.pi), 0.6 + 0.12 * j))
        m.extend(lathe([(0.3, 0.6)] + column + [(0.3, 1.7), (0.3, 1.78)], s))
        m.extend(lathe([(0.1, 1.78), (0.22, 1.86), (0.34, 2.05), (0.3, 2.22), (0.18, 2.28), (0.2, 2.34),
                        (0.1, 2.38), (0, 2.4)], s))
    return m


def tree_mesh(detail, height=7.0, crown=2.2):
    """A trunk and a crown of three spheres: `crown` m in radius, `height` m high."""
    s = detail_count(20, detail)
    rings = detail_count(12, detail, 4)
    m = lathe([(0.22, 0.0), (0.18, 0.4), (0.15, height * 0.5), (0.1, height * 0.7), (0, height * 0.72)],
              detail_count(10, detail))
    base = height - 2 * crown
    m.extend(lathe(sphere_profile(crown, rings), s), offset=(0, base, 0))
    m.extend(lathe(sphere_profile(crown * 0.7, rings), s), offset=(crown * 0.45, base + crown * 0.9, 0.1))
    m.extend(lathe(sphere_profile(crown * 0.65, rings), s), offset=(-crown * 0.4, base + crown * 0.8, -0.3))
    return m


def bench_mesh(detail):
    """1.8 m long (x), 0.6 m deep, 0.85 m high, with turned legs."""
    m = box((-0.9, 0.42, -0.3), (0.9, 0.48, 0.3))
    m.extend(box((-0.9, 0.55, 0.22), (0.9, 0.85, 0.28)))
    leg = lathe([(0.04, 0.0), (0.05, 0.1), (0.03, 0.25), (0.05, 0.42), (0, 0.43)], detail_count(10, detail))
    for x in (-0.8, 0.8):
        for z in (-0.22, 0.22):
            m.extend(leg, offset=(x, 0, z))
    return m


def lamp_mesh(detail, height=4.6, reach=0.9):
    """A street lamp: base, pole, an arm reaching `reach` m towards +x and a lamp head."""
    s = detail_count(12, detail)
    m = lathe([(0.15, 0.0), (0.15, 0.3), (0.08, 0.4), (0.06, height), (0, height + 0.02)], s)
    arm = lathe([(0, 0.0), (0.035, 0.01), (0.035, reach), (0, reach + 0.01)], detail_count(8, detail, 4))
    m.extend(arm, m=rot_z(math.radians(-90)), offset=(0, height - 0.15, 0))
    m.extend(lathe([(0, 0.0), (0.18, 0.05), (0.22, 0.2), (0.07, 0.3), (0, 0.32)], s),
             offset=(reach, height - 0.45, 0))
    return m


def lamp_parts(height=4.6, reach=0.9):
    """The lamp as the checks see it: the pole, and the arm with its head above the street."""
    return [((-0.15, 0.0, -0.15), (0.15, height + 0.02, 0.15)),
            ((0.0, height - 0.45, -0.22), (reach + 0.22, height - 0.1, 0.22))]


def wheel_mesh(radius, width, detail):
    """A wheel turning about z, its axle at the origin."""
    s = detail_count(20, detail, 8)
    w = width / 2
    m = lathe([(0, -w), (radius * 0.6, -w), (radius, -w * 0.8), (radius, w * 0.8), (radius * 0.6, w),
               (0, w)], s)
    return Mesh().extend(m, m=rot_x(math.radians(90)))


def car_mesh(detail):
    """A car 4.4 m long (x), 1.8 m wide, 1.45 m high, wheels merged in (one object)."""
    m = box((-2.2, 0.3, -0.9), (2.2, 0.85, 0.9))
    m.extend(box((-1.2, 0.85, -0.8), (1.0, 1.45, 0.8)))
    m.extend(box((2.15, 0.35, -0.85), (2.25, 0.5, 0.85)))  # bumpers
    m.extend(box((-2.25, 0.35, -0.85), (-2.15, 0.5, 0.85)))
    lamp = lathe([(0, 0.0), (0.09, 0.01), (0.09, 0.05), (0, 0.06)], detail_count(10, detail))
    for z in (-0.6, 0.6):
        m.extend(lamp, m=rot_z(math.radians(-90)), offset=(2.2, 0.7, z))
    wheel = wheel_mesh(0.33, 0.24, detail)
    for x in (-1.35, 1.35):
        for z in (-0.8, 0.8):
            m.extend(wheel, offset=(x, 0.33, z))
    return m


def person_mesh(detail):
    """A walker 1.62 m tall (below the 1.7 m eye): a tapered body and a head."""
    s = detail_count(14, detail)
    m = lathe([(0.12, 0.0), (0.2, 0.1), (0.18, 0.85), (0.24, 1.2), (0.2, 1.38), (0.08, 1.42), (0, 1.43)],
              s)
    m.extend(lathe(sphere_profile(0.1, detail_count(8, detail, 4)), s), offset=(0, 1.42, 0))
    return m


def table_mesh(detail):
    """A table 1.6 x 0.9 m, 0.76 m high, turned legs."""
    m = box((-0.8, 0.72, -0.45), (0.8, 0.76, 0.45))
    leg = lathe([(0.035, 0.0), (0.05, 0.05), (0.03, 0.2), (0.045, 0.35), (0.03, 0.55), (0.045, 0.7),
                 (0.045, 0.72)], detail_count(12, detail))
    for x in (-0.72, 0.72):
        for z in (-0.37, 0.37):
            m.extend(leg, offset=(x, 0, z))
    return m


def chair_mesh(detail):
    """A chair 0.45 m square, its back at -x, 0.95 m high."""
    m = box((-0.22, 0.43, -0.22), (0.22, 0.47, 0.22))
    m.extend(box((-0.23, 0.47, -0.2), (-0.2, 0.95, 0.2)))
    leg = lathe([(0.02, 0.0), (0.025, 0.1), (0.018, 0.3), (0.025, 0.43)], detail_count(10, detail))
    for x in (-0.19, 0.19):
        for z in (-0.19, 0.19):
            m.extend(leg, offset=(x, 0, z))
    return m


def bookshelf_mesh(detail, rng):
    """A shelf unit 1.8 m wide (x), 0.4 m deep, 2.05 m high, full of books (about 1,300 triangles)."""
    m = box((-0.9, 0.0, -0.2), (-0.88, 2.05, 0.2))
    m.extend(box((0.88, 0.0, -0.2), (0.9, 2.05, 0.2)))
    m.extend(box((-0.88, 0.0, 0.18), (0.88, 2.05, 0.2)))  # back
    books = max(4, int(round(22 * detail)))
    for level in range(5):
        y = 0.05 + level * 0.4
        m.extend(box((-0.88, y - 0.02, -0.2), (0.88, y, 0.18)))
        x = -0.87
        width = 1.74 / books
        for _ in range(books):
            h = rng.uniform(0.2, 0.34)
            d = rng.uniform(0.22, 0.3)
            m.extend(box((x + 0.002, y, -0.12), (x + width - 0.002, y + h, -0.12 + d)))
            x += width
    m.extend(box((-0.88, 2.03, -0.2), (0.88, 2.05, 0.18)))
    return m


def sofa_mesh(detail):
    """A sofa 2.0 m long (x), 0.9 m deep, 0.85 m high, with rolled arms."""
    m = box((-1.0, 0.05, -0.45), (1.0, 0.42, 0.45))
    m.extend(box((-1.0, 0.42, 0.2), (1.0, 0.85, 0.45)))
    s = detail_count(16, detail)
    roll = lathe([(0, 0.0), (0.13, 0.01), (0.13, 0.89), (0, 0.9)], s)
    for x in (-0.9, 0.9):
        m.extend(roll, m=rot_x(math.radians(90)), offset=(x, 0.5, -0.45))
    for x in (-0.9, 0.9):
        for z in (-0.35, 0.35):
            foot = lathe([(0.03, 0.0), (0.04, 0.05), (0, 0.06)], detail_count(8, detail, 4))
            m.extend(foot, offset=(x, 0, z))
    return m


def vase_mesh(detail):
    """A tall vase on a pedestal, with a plant: 0.7 m across, 1.9 m high (about 1,500 triangles)."""
    s = detail_count(32, detail, 8)
    m = lathe([(0.3, 0.0), (0.3, 0.08), (0.18, 0.12), (0.14, 0.6), (0.25, 0.66), (0.25, 0.7), (0.1, 0.72)], s)
    m.extend(lathe([(0.1, 0.72), (0.22, 0.85), (0.3, 1.05), (0.27, 1.25), (0.14, 1.35), (0.16, 1.42),
                    (0.12, 1.42)], s))
    m.extend(lathe(sphere_profile(0.3, detail_count(10, detail, 4)), s), offset=(0, 1.3, 0))
    return m


def cart_mesh(detail):
    """The big mover of the interior: a service cart 2.4 m long (x), 1.4 m wide, 1.5 m high."""
    m = box((-1.2, 0.25, -0.7), (1.2, 1.1, 0.7))
    m.extend(box((0.6, 1.1, -0.65), (1.15, 1.5, 0.65)))
    m.extend(box((-1.15, 1.1, -0.6), (0.5, 1.3, 0.6)))
    wheel = wheel_mesh(0.2, 0.15, detail)
    for x in (-0.9, 0.9):
        for z in (-0.62, 0.62):
            m.extend(wheel, offset=(x, 0.2, z))
    return m


def beacon_mesh(detail):
    """A turning beacon on the cart's cab: a lathe with two lenses, turning about y."""
    s = detail_count(16, detail)
    m = lathe([(0.12, 0.0), (0.12, 0.05), (0.09, 0.08), (0.09, 0.22), (0.05, 0.25), (0, 0.26)], s)
    lens = box((-0.02, 0.1, -0.06), (0.02, 0.2, 0.06))
    m.extend(lens, offset=(0.1, 0, 0))
    m.extend(lens, offset=(-0.1, 0, 0))
    return m


def kiosk_mesh(detail):
    """A newspaper kiosk 2.4 m across, 3.1 m high: a drum with a domed roof."""
    s = detail_count(32, detail, 8)
    return lathe([(0, 0.0), (1.1, 0.0), (1.1, 0.15), (1.0, 0.2), (1.0, 2.3), (1.2, 2.35), (1.2, 2.5),
                  (0.9, 2.7), (0.5, 2.9), (0.1, 3.05), (0, 3.1)], s)


def bus_stop_mesh(detail):
    """A bus shelter 3.6 m long (x), 1.4 m deep, 2.6 m high: posts, roof, back panel, a bench."""
    m = box((-1.8, 2.45, -0.7), (1.8, 2.6, 0.7))
    m.extend(box((-1.75, 0.3, 0.55), (1.75, 2.4, 0.6)))
    post = cylinder(0.05, 2.45, detail_count(10, detail))
    for x in (-1.7, 1.7):
        for z in (-0.6, 0.6):
            m.extend(post, offset=(x, 0, z))
    m.extend(bench_mesh(detail), offset=(0, 0, 0.15))
    return m


def truck_cab_mesh(detail):
    """The cab of the truck: 2.6 m long (x), 2.4 m wide, 3.2 m high, its back at x = 0."""
    m = box((0.0, 0.5, -1.2), (2.6, 1.6, 1.2))
    m.extend(box((0.1, 1.6, -1.15), (2.2, 3.2, 1.15)))
    m.extend(box((2.55, 0.55, -1.15), (2.7, 0.8, 1.15)))
    lamp = lathe([(0, 0.0), (0.12, 0.01), (0.12, 0.06), (0, 0.07)], detail_count(12, detail))
    for z in (-0.9, 0.9):
        m.extend(lamp, m=rot_z(math.radians(-90)), offset=(2.6, 1.1, z))
    mirror = lathe([(0.03, 0.0), (0.03, 0.3), (0.1, 0.32), (0.1, 0.5), (0, 0.52)], detail_count(10, detail))
    for z in (-1.3, 1.3):
        m.extend(mirror, offset=(2.0, 2.0, z))
    return m


def bus_mesh(detail):
    """A bus 11 m long (x), 2.5 m wide, 3.1 m high, wheels turning with it (one object)."""
    m = box((-5.5, 0.35, -1.25), (5.5, 2.9, 1.25))
    m.extend(box((-5.3, 2.9, -1.1), (4.5, 3.1, 1.1)))
    lamp = lathe([(0, 0.0), (0.12, 0.01), (0.12, 0.06), (0, 0.07)], detail_count(12, detail))
    for z in (-0.9, 0.9):
        m.extend(lamp, m=rot_z(math.radians(-90)), offset=(5.5, 0.8, z))
    wheel = wheel_mesh(0.5, 0.3, detail)
    for x in (-3.6, 3.4):
        for z in (-1.05, 1.05):
            m.extend(wheel, offset=(x, 0.5, z))
    return m


# ---- The glTF document ----------------------------------------------------------------------


class Node:
    """A node: a group (mesh None) or an object; `yaw` turns it about y (radians)."""

    def __init__(self, name, mesh=None, t=(0, 0, 0), yaw=0.0, s=None, extras=None, rotation=None):
        self.name = name
        self.mesh = mesh
        self.t = tuple(t)
        self.yaw = yaw
        self.rotation = rotation  # a quaternion (x, y, z, w) instead of yaw
        self.s = s
        self.extras = extras
        self.children = []
        self.index = None  # in the file, set when written
        self.object = None  # occsim's object index (mesh nodes in visit order), set when written

    def add(self, child):
        self.children.append(child)
        return child


def quat_y(yaw):
    return (0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2))


def quat_z(angle):
    return (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))


class Document:
    """Collects meshes (each converted once, shared by its nodes), nodes and animations, and
    writes the .gltf (JSON) and its .bin."""

    def __init__(self):
        self.meshes = {}  # name -> Mesh
        self.parts = {}  # name -> boxes [(lo, hi)] that cover the mesh more tightly than its bounds
        self.mesh_order = []
        self.roots = []
        self.animations = []  # (name, [(node, path, times, values)])
        self.parameters = {}

    def mesh(self, name, make, parts=None):
        if parts is not None:
            self.parts[name] = parts
        if name not in self.meshes:
            m = make()
            if m.signed_volume() <= 0:
                raise AssertionError(f"mesh {name} is not closed with outward faces")
            self.meshes[name] = m
            self.mesh_order.append(name)
        return name

    def write(self, gltf_path):
        buffer = bytearray()
        views, accessors = [], []

        def add_accessor(data, component, count, kind, target=None, lo=None, hi=None):
            while len(buffer) % 4:
                buffer.append(0)
            view = {"buffer": 0, "byteOffset": len(buffer), "byteLength": len(data)}
            if target is not None:
                view["target"] = target
            buffer.extend(data)
            views.append(view)
            accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count,
                        "type": kind}
            if lo is not None:
                accessor["min"], accessor["max"] = lo, hi
            accessors.append(accessor)
            return len(accessors) - 1

        def f32(x):
            return struct.unpack("<f", struct.pack("<f", x))[0]

        mesh_index, meshes = {}, []
        for name in self.mesh_order:
            m = self.meshes[name]
            pos = b"".join(struct.pack("<3f", *p) for p in m.positions)
            lo, hi = m.bounds()
            p_acc = add_accessor(pos, 5126, len(m.positions), "VEC3", 34962, [f32(v) for v in lo],
                                 [f32(v) for v in hi])
            nor = b"".join(struct.pack("<3f", *n) for n in m.normals())
            n_acc = add_accessor(nor, 5126, len(m.positions), "VEC3", 34962)
            if len(m.positions) < 65536:
                idx = struct.pack(f"<{len(m.indices)}H", *m.indices)
                i_acc = add_accessor(idx, 5123, len(m.indices), "SCALAR", 34963)
            else:
                idx = struct.pack(f"<{len(m.indices)}I", *m.indices)
                i_acc = add_accessor(idx, 5125, len(m.indices), "SCALAR", 34963)
            mesh_index[name] = len(meshes)
            meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": p_acc, "NORMAL": n_acc},
                                                         "indices": i_acc}]})

        nodes = []
        objects = 0

        def visit(node):
            nonlocal objects
            node.index = len(nodes)
            entry = {"name": node.name}
            nodes.append(entry)
            if node.mesh is not None:
                entry["mesh"] = mesh_index[node.mesh]
                node.object = objects
                objects += 1
            if any(node.t):
                entry["translation"] = rvec(node.t)
            if node.rotation is not None:
                entry["rotation"] = rvec(node.rotation, 6)
            elif node.yaw:
                entry["rotation"] = rvec(quat_y(node.yaw), 6)
            if node.s is not None:
                entry["scale"] = rvec(node.s)
            if node.extras:
                entry["extras"] = node.extras
            if node.children:
                entry["children"] = []
                for child in node.children:
                    entry["children"].append(visit(child))
            return node.index

        scene_nodes = [visit(root) for root in self.roots]

        animations = []
        shared = {}  # identical key arrays share one accessor
        for name, channels in self.animations:
            anim = {"name": name, "channels": [], "samplers": []}
            for node, path, times, values in channels:
                key_in = ("in", tuple(times))
                if key_in not in shared:
                    data = struct.pack(f"<{len(times)}f", *times)
                    shared[key_in] = add_accessor(data, 5126, len(times), "SCALAR", None, [f32(times[0])],
                                                  [f32(times[-1])])
                key_out = ("out", tuple(tuple(v) for v in values))
                if key_out not in shared:
                    width = len(values[0])
                    data = b"".join(struct.pack(f"<{width}f", *v) for v in values)
                    shared[key_out] = add_accessor(data, 5126, len(values), "VEC3" if width == 3 else "VEC4")
                anim["samplers"].append({"input": shared[key_in], "output": shared[key_out],
                                         "interpolation": "LINEAR"})
                anim["channels"].append({"sampler": len(anim["samplers"]) - 1,
                                         "target": {"node": node.index, "path": path}})
            animations.append(anim)

        bin_path = gltf_path.with_suffix(".bin")
        doc = {
            "asset": {"version": "2.0", "generator": GENERATOR,
                      "extras": {"parameters": self.parameters,
                                 "note": "made by the occsim project (scripts/make_levels.py); "
                                         "nodes with extras.occsim_occluder \"always\" are the level's large occluders"}},
            "scene": 0,
            "scenes": [{"name": gltf_path.stem, "nodes": scene_nodes}],
            "nodes": nodes,
            "meshes": meshes,
        }
        if animations:
            doc["animations"] = animations
        doc["accessors"] = accessors
        doc["bufferViews"] = views
        doc["buffers"] = [{"byteLength": len(buffer), "uri": bin_path.name}]
        return {gltf_path: (dumps(doc) + "\n").encode(), bin_path: bytes(buffer)}


def dumps(value, indent=0, width=110):
    """JSON as this project's files look: a value on one line when it fits, else one entry a line."""
    flat = json.dumps(value, separators=(", ", ": "), ensure_ascii=True)
    if len(flat) + indent <= width or not isinstance(value, (dict, list)) or not value:
        return flat
    pad = " " * (indent + 2)
    if isinstance(value, dict):
        items = [pad + json.dumps(k) + ": " + dumps(v, indent + 2, width) for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + dumps(v, indent + 2, width) for v in value]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"


# ---- Geometry the checks need ------------------------------------------------------------------


class Box:
    """An axis-aligned box in world space: the checks' view of an object, or of one part of it."""

    def __init__(self, name, lo, hi):
        self.name, self.lo, self.hi = name, tuple(lo), tuple(hi)
        self.owner = name

    def gap(self, other):
        """The largest separation along an axis (negative: they overlap)."""
        return max(max(other.lo[i] - self.hi[i], self.lo[i] - other.hi[i]) for i in range(3))

    def distance(self, p):
        d = [max(self.lo[i] - p[i], 0.0, p[i] - self.hi[i]) for i in range(3)]
        return math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)


def world_box(name, mesh, t, yaw=0.0, s=None, parent=(0, 0, 0), bounds=None):
    """The world box of a mesh (or of `bounds`, a box in its space) under a node's translation,
    yaw and scale below a parent group at `parent`."""
    lo, hi = bounds if bounds is not None else mesh.bounds()
    m = rot_y(yaw)
    if s is not None:
        m = mat_mul(m, scale_mat(*s))
    pts = []
    for x in (lo[0], hi[0]):
        for y in (lo[1], hi[1]):
            for z in (lo[2], hi[2]):
                q = mat_vec(m, (x, y, z))
                pts.append((q[0] + t[0] + parent[0], q[1] + t[1] + parent[1], q[2] + t[2] + parent[2]))
    return Box(name, [min(p[i] for p in pts) for i in range(3)], [max(p[i] for p in pts) for i in range(3)])


class Grid2:
    """Boxes hashed by their xz extent, for nearby-box queries."""

    def __init__(self, boxes, cell=6.0):
        self.cell, self.cells = cell, {}
        for b in boxes:
            for key in self._keys(b.lo, b.hi, 0.0):
                self.cells.setdefault(key, []).append(b)

    def _keys(self, lo, hi, margin):
        c = self.cell
        for i in range(math.floor((lo[0] - margin) / c), math.floor((hi[0] + margin) / c) + 1):
            for k in range(math.floor((lo[2] - margin) / c), math.floor((hi[2] + margin) / c) + 1):
                yield (i, k)

    def near(self, p, margin):
        seen, out = set(), []
        for key in self._keys(p, p, margin):
            for b in self.cells.get(key, ()):
                if id(b) not in seen:
                    seen.add(id(b))
                    out.append(b)
        return out


def check_static_overlaps(boxes):
    """No two static objects touch or cut into each other (their depths would tie on the line
    where they meet, docs/scenario-generators.md); sweep along x."""
    order = sorted(boxes, key=lambda b: b.lo[0])
    active = []
    for b in order:
        active = [a for a in active if a.hi[0] >= b.lo[0] - 0.005]
        for a in active:
            if a.owner != b.owner and b.gap(a) < 0.005:
                raise AssertionError(f"{a.name} and {b.name} touch or overlap")
        active.append(b)


class Shape:
    """A mover's footprint for the checks: a box half_length along its heading (local +x),
    half_width across, `height` high from its base; planes_x and planes_z are the local
    coordinates of its flat faces (across and along its heading)."""

    def __init__(self, half_length, half_width, height, planes_x=(), planes_z=()):
        self.half_length, self.half_width, self.height = half_length, half_width, height
        self.planes_x, self.planes_z = tuple(planes_x), tuple(planes_z)


class Footprint:
    """A mover at one moment: its shape at base point p, heading `direction` (a unit xz vector)."""

    def __init__(self, name, p, direction, shape):
        self.name, self.p, self.shape = name, p, shape
        length = math.hypot(direction[0], direction[2]) or 1.0
        self.d = (direction[0] / length, direction[2] / length)
        self.n = (-self.d[1], self.d[0])  # local +z in plan (x, z), as a yaw turns it

    def local(self, q):
        dx, dz = q[0] - self.p[0], q[2] - self.p[2]
        return dx * self.d[0] + dz * self.d[1], q[1] - self.p[1], dx * self.n[0] + dz * self.n[1]

    def distance(self, q):
        lx, ly, lz = self.local(q)
        s = self.shape
        d = (max(abs(lx) - s.half_length, 0.0), max(-ly, 0.0, ly - s.height),
             max(abs(lz) - s.half_width, 0.0))
        return math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)

    def plane_distance(self, q):
        lx, _, lz = self.local(q)
        gaps = [abs(lx - a) for a in self.shape.planes_x] + [abs(lz - b) for b in self.shape.planes_z]
        return min(gaps) if gaps else math.inf

    def corners(self):
        s = self.shape
        out = []
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):  # around the rectangle
            a, b = a * s.half_length, b * s.half_width
            out.append((self.p[0] + a * self.d[0] + b * self.n[0], self.p[2] + a * self.d[1] + b * self.n[1]))
        return out

    def gap_to_box(self, b):
        """The separation from an axis-aligned box in plan (negative: they overlap), or +inf when
        the box is above or below the mover."""
        if b.lo[1] > self.p[1] + self.shape.height or b.hi[1] < self.p[1]:
            return math.inf
        box_pts = [(b.lo[0], b.lo[2]), (b.hi[0], b.lo[2]), (b.lo[0], b.hi[2]), (b.hi[0], b.hi[2])]
        mine = self.corners()
        best = -math.inf
        for axis in ((1.0, 0.0), (0.0, 1.0), self.d, self.n):
            pa = [x * axis[0] + z * axis[1] for x, z in mine]
            pb = [x * axis[0] + z * axis[1] for x, z in box_pts]
            best = max(best, min(pb) - max(pa), min(pa) - max(pb))
        return best


def polygon_gap(a, b):
    """The separation of two convex polygons in plan (negative: they overlap), by separating axes."""
    best = -math.inf
    for poly in (a, b):
        for i in range(len(poly)):
            p, q = poly[i], poly[(i + 1) % len(poly)]
            ax = (q[1] - p[1], p[0] - q[0])
            length = math.hypot(*ax)
            if length == 0:
                continue
            ax = (ax[0] / length, ax[1] / length)
            pa = [x * ax[0] + z * ax[1] for x, z in a]
            pb = [x * ax[0] + z * ax[1] for x, z in b]
            best = max(best, min(pb) - max(pa), min(pa) - max(pb))
    return best


class Path2:
    """A closed polyline (plan, at one height) with arc lengths, as occsim's path motion walks it."""

    def __init__(self, points):
        self.points = points
        self.lengths = [0.0]
        for i in range(len(points)):
            a, b = points[i], points[(i + 1) % len(points)]
            self.lengths.append(self.lengths[-1] + math.dist(a, b))

    def total(self):
        return self.lengths[-1]

    def at(self, d):
        d %= self.total()
        for i in range(len(self.points)):
            if d <= self.lengths[i + 1]:
                a, b = self.points[i], self.points[(i + 1) % len(self.points)]
                seg = self.lengths[i + 1] - self.lengths[i]
                u = 0.0 if seg == 0 else (d - self.lengths[i]) / seg
                p = tuple(a[k] + (b[k] - a[k]) * u for k in range(3))
                direction = tuple((b[k] - a[k]) / seg for k in range(3))
                return p, direction
        return self.points[0], (1.0, 0.0, 0.0)


def catmull_rom(p0, p1, p2, p3, u):
    u2, u3 = u * u, u * u * u
    return tuple(0.5 * (2 * p1[i] + (-p0[i] + p2[i]) * u + (2 * p0[i] - 5 * p1[i] + 4 * p2[i] - p3[i]) * u2 +
                        (-p0[i] + 3 * p1[i] - 3 * p2[i] + p3[i]) * u3) for i in range(3))


def camera_at(keys, t):
    """occsim's camera path (sim/world/camera_path.cpp): Catmull-Rom through the keyframes, held at
    the ends. keys: [(time, position, target)]."""
    if t <= keys[0][0]:
        return keys[0][1], keys[0][2]
    if t >= keys[-1][0]:
        return keys[-1][1], keys[-1][2]
    i = max(k for k in range(len(keys) - 1) if keys[k][0] <= t)
    u = (t - keys[i][0]) / (keys[i + 1][0] - keys[i][0])
    k0, k1, k2, k3 = keys[max(i - 1, 0)], keys[i], keys[i + 1], keys[min(i + 2, len(keys) - 1)]
    return (catmull_rom(k0[1], k1[1], k2[1], k3[1], u), catmull_rom(k0[2], k1[2], k2[2], k3[2], u))


# ---- A level: its objects, movers, camera and checks -------------------------------------------


class Level:
    """One level as it is built: its glTF document, what the checks need to know of its objects
    and movers, its camera keyframes and segments."""

    def __init__(self, name, args):
        self.name = name
        self.args = args
        self.doc = Document()
        self.static_boxes = []  # every static object's box, for the checks
        self.plane_boxes = []  # boxes whose faces are real faces (box meshes): their planes
        self.heights = []  # heights of static horizontal faces
        self.lanes = []  # (Path2, [mover nodes], speed in m/s, Shape)
        self.vehicle = None  # t -> Footprint: the vehicle its animation moves
        self.keys = []  # camera keyframes (time, position, target)
        self.segments = []
        self.frames = args.frames
        self.dt = 0.0333333  # the scenario's dt, so that frame f is where occsim renders it

    def run_time(self):
        return self.frames * self.dt

    # Objects ---------------------------------------------------------------------------------

    def add_static(self, parent, name, mesh, t, yaw=0.0, s=None, occluder=False, exact_box=False):
        """A static object below `parent` (a group with translation only, or None)."""
        node = Node(name, mesh, t, yaw, s, {"occsim_occluder": "always"} if occluder else None)
        (parent.add(node) if parent is not None else self.doc.roots.append(node))
        origin = parent.t if parent is not None else (0, 0, 0)
        parts = self.doc.parts.get(mesh) or [None]
        for part in parts:
            b = world_box(name, self.doc.meshes[mesh], t, yaw, s, origin, part)
            self.static_boxes.append(b)
            if exact_box:
                self.plane_boxes.append(b)
        sy = s[1] if s is not None else 1.0
        for h in self.doc.meshes[mesh].horizontal_heights():
            self.heights.append((origin[1] + t[1] + sy * h, name))
        return node

    def box(self):
        return self.doc.mesh("box", box)

    def slab(self, parent, name, lo, hi, occluder=True):
        """A box object spanning lo..hi (world, or relative to the parent group)."""
        t = ((lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2)
        s = (hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2])
        return self.add_static(parent, name, self.box(), t, 0.0, s, occluder, exact_box=True)

    def group(self, name, t=(0, 0, 0)):
        node = Node(name, None, t)
        self.doc.roots.append(node)
        return node

    # Movers ----------------------------------------------------------------------------------

    def lane(self, points, count, spacing, speed, mesh, prefix, group, shape, rng):
        """Up to `count` movers of one shape on a closed lane (plan points), at least `spacing` m
        apart and all at one speed, so that they keep their distances; returns how many."""
        path = Path2([(rnd(x, 3), LANE_Y, rnd(z, 3)) for x, z in points])
        n = min(count, int(path.total() // spacing))
        if n <= 0:
            return 0
        step = path.total() / n
        start = rng.uniform(0, step)
        nodes = []
        for k in range(n):
            d = start + k * step + rng.uniform(0, (step - spacing) * 0.5)
            p, _ = path.at(d)
            nodes.append(group.add(Node(f"{group.name}/{prefix}_{len(group.children)}", mesh, p)))
        self.lanes.append((path, nodes, speed, shape))
        return n

    def mover_entries(self):
        entries = []
        for path, nodes, speed, _ in self.lanes:
            entries.append({"source": 0, "objects": [n.object for n in nodes], "motion": "path",
                            "waypoints": [rvec(p, 3) for p in path.points],
                            "speed": [rnd(speed, 2), rnd(speed, 2)]})
        return entries

    # Checks ----------------------------------------------------------------------------------

    def lane_footprints(self, lane_index, step=0.4):
        """Where the movers of a lane can be: the shape every `step` m along it, and at each corner
        with both headings (a path mover turns at a corner at once)."""
        path, nodes, _, shape = self.lanes[lane_index]
        out = []
        for k in range(int(path.total() / step) + 1):
            p, d = path.at(k * step)
            out.append(Footprint(nodes[0].name, p, d, shape))
        for i, p in enumerate(path.points):
            for j in (i - 1, i):
                a, b = path.points[j % len(path.points)], path.points[(j + 1) % len(path.points)]
                if a != b:
                    out.append(Footprint(nodes[0].name, p, (b[0] - a[0], 0, b[2] - a[2]), shape))
        return out

    def check(self, vehicle_line=()):
        """The level's invariants; an AssertionError names what collides."""
        check_static_overlaps(self.static_boxes)
        for b in self.static_boxes:
            if b.lo[1] < FLOOR_GAP - 1e-6 and b.name != "floor":
                raise AssertionError(f"{b.name} reaches into the floor")
        for h, name in self.heights:
            if abs(h - EYE) < 0.01:
                raise AssertionError(f"a horizontal face of {name} is at eye height ({h:.3f} m)")
        grid = Grid2([b for b in self.static_boxes if b.name != "floor"])
        swept = []  # (lane, footprint)
        for i in range(len(self.lanes)):
            for fp in self.lane_footprints(i):
                swept.append((i, fp))
        swept += [(-1, fp) for fp in vehicle_line]
        for i, fp in swept:
            for b in grid.near(fp.p, 6.0):
                if fp.gap_to_box(b) < 0.02:
                    raise AssertionError(f"the path of {fp.name} runs into {b.name}")
        # Movers of different lanes (and the vehicle) never meet, wherever they are on their lanes.
        cells = {}
        for k, (i, fp) in enumerate(swept):
            cells.setdefault((math.floor(fp.p[0] / 6), math.floor(fp.p[2] / 6)), []).append(k)
        for k, (i, fp) in enumerate(swept):
            cx, cz = math.floor(fp.p[0] / 6), math.floor(fp.p[2] / 6)
            for dx in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for k2 in cells.get((cx + dx, cz + dz), ()):
                        i2, fp2 = swept[k2]
                        if k2 > k and i2 != i and polygon_gap(fp.corners(), fp2.corners()) < 0.02:
                            raise AssertionError(f"the paths of {fp.name} and {fp2.name} meet")

    def frame_problems(self):
        """The frames where the eye comes too close to an object, or a face plane of a box passes
        within PLANE_CLEARANCE of it: [(frame, what)]."""
        grid = Grid2([b for b in self.static_boxes if b.name != "floor"])
        plane_grid = Grid2(self.plane_boxes, cell=10.0)
        starts = [[nearest_distance(path, n.t) for n in nodes] for path, nodes, _, _ in self.lanes]
        problems = []
        for f in range(self.frames):
            t = f * self.dt
            eye, _ = camera_at(self.keys, t)
            for b in grid.near(eye, CAMERA_CLEARANCE + 0.1):
                if b.distance(eye) < CAMERA_CLEARANCE:
                    problems.append((f, f"the eye is {b.distance(eye):.2f} m from {b.name}"))
            for b in plane_grid.near(eye, 40.0):
                for axis in (0, 2):
                    for plane in (b.lo[axis], b.hi[axis]):
                        if abs(eye[axis] - plane) < PLANE_CLEARANCE:
                            problems.append((f, f"a face of {b.name} is in the eye's plane"))
            movers = []
            if self.vehicle is not None:
                movers.append(self.vehicle(t))
            for (path, nodes, speed, shape), d0s in zip(self.lanes, starts):
                for node, d0 in zip(nodes, d0s):
                    p, direction = path.at(d0 + speed * t)
                    if math.hypot(p[0] - eye[0], p[2] - eye[2]) < 40.0:
                        movers.append(Footprint(node.name, p, direction, shape))
            for m in movers:
                gap = m.distance(eye)
                if gap < CAMERA_CLEARANCE:
                    problems.append((f, f"the eye is {gap:.2f} m from {m.name}"))
            # Only the vehicle's faces: cars and walkers cross the eye's planes too, but rarely
            # near enough, and a timing that avoids every one of them rarely exists.
            if self.vehicle is not None and movers[0].plane_distance(eye) < PLANE_CLEARANCE:
                problems.append((f, f"a face of {movers[0].name} is in the eye's plane"))
        return problems

    # Output ----------------------------------------------------------------------------------

    def scenario(self, viewport, extra_sources=()):
        keys = [{"time": rnd(t, 4), "position": rvec(p, 3), "target": rvec(q, 3)} for t, p, q in self.keys]
        return {
            "format_version": 1,
            "name": self.name,
            "seed": self.args.seed,
            "frames": self.frames,
            "dt": 0.0333333,
            "warmup_frames": 10,
            "viewport": {"width": viewport[0], "height": viewport[1]},
            "camera": {"fov_y": 60, "near": 0.1, "far": 600, "keyframes": keys},
            "segments": [seg for seg in self.segments if seg is not None],
            "scene": {"sources": [
                {"type": "gltf", "path": f"../assets/levels/{self.name}.gltf",
                 "animation": {"mode": "clamp"}},
                *extra_sources]},
            "movers": self.mover_entries(),
            "culling": {"algorithm": "statistical+"},
            "bsp": {"split": "sah", "max_depth": 20, "max_objects_per_leaf": 4},
        }


def nearest_distance(path, p):
    """The distance along `path` of its point nearest to p (where occsim puts a joining mover)."""
    best, best_d = None, 0.0
    for i in range(len(path.points)):
        a, b = path.points[i], path.points[(i + 1) % len(path.points)]
        seg = path.lengths[i + 1] - path.lengths[i]
        if seg == 0:
            continue
        u = ((p[0] - a[0]) * (b[0] - a[0]) + (p[2] - a[2]) * (b[2] - a[2])) / (seg * seg)
        u = min(1.0, max(0.0, u))
        q = (a[0] + (b[0] - a[0]) * u, a[2] + (b[2] - a[2]) * u)
        dist = math.hypot(q[0] - p[0], q[1] - p[2])
        if best is None or dist < best - 1e-12:
            best, best_d = dist, path.lengths[i] + u * seg
    return best_d


# ---- Pieces the street levels share ----------------------------------------------------------

CAR = Shape(2.25, 0.9, 1.45, planes_x=(-2.25, -2.2, -2.15, -1.2, 1.0, 2.15, 2.2, 2.25),
            planes_z=(-0.9, -0.85, -0.8, 0.8, 0.85, 0.9))
PERSON = Shape(0.24, 0.24, 1.62)
CAR_LANE = 2.3  # a car's centre from the kerb (the block's wall or facade)
PERSON_LANE = 0.95  # a walker's centre from the wall


def car_reach(lane=CAR_LANE):
    """How far from its block's wall a car rounding the block's corner reaches (its outer corners
    on the arc of radius `lane` about the corner)."""
    return math.hypot(lane + CAR.half_width, CAR.half_length)


def ring(x0, z0, x1, z1, d, arc_segments=6):
    """A closed lane round the block [x0, x1] x [z0, z1] at distance d from it, its corners arcs
    about the block's corners; driven clockwise seen from above (the block on the right)."""
    pts = []
    for cx, cz, a0 in ((x1, z0, -90), (x1, z1, 0), (x0, z1, 90), (x0, z0, 180)):
        for k in range(arc_segments + 1):
            a = math.radians(a0 + 90 * k / arc_segments)
            pts.append((cx + d * math.cos(a), cz + d * math.sin(a)))
    return pts


class Vehicle:
    """A vehicle moved by a glTF animation: a group node whose translation follows keys (LINEAR,
    its heading fixed), wheels that roll with it and parts that spin, each a child node with
    rotation keys."""

    def __init__(self, level, name, shape, heading_yaw):
        self.level, self.name, self.shape, self.yaw = level, name, shape, heading_yaw
        self.node = Node(name, None, (0, 0, 0), heading_yaw)
        level.doc.roots.append(self.node)
        self.wheels = []  # (node, radius)
        self.spinners = []  # (node, radians per second about the node's y)
        self.keys = [(0.0, (0, 0, 0))]  # (time, position of the group node)
        self.direction = (math.cos(heading_yaw), 0.0, -math.sin(heading_yaw))

    def part(self, name, mesh, t, s=None):
        return self.node.add(Node(f"{self.name}/{name}", mesh, t, 0.0, s))

    def wheel(self, name, mesh, t, radius):
        self.wheels.append((self.node.add(Node(f"{self.name}/{name}", mesh, t)), radius))

    def spinner(self, name, mesh, t, rate):
        self.spinners.append((self.node.add(Node(f"{self.name}/{name}", mesh, t)), rate))

    def drive(self, keys):
        """keys: [(time, position)], times increasing from 0."""
        self.keys = keys
        self.node.t = keys[0][1]

    def position(self, t):
        keys = self.keys
        if t <= keys[0][0]:
            return keys[0][1]
        for (t0, p0), (t1, p1) in zip(keys, keys[1:]):
            if t <= t1:
                u = (t - t0) / (t1 - t0)
                return tuple(p0[k] + (p1[k] - p0[k]) * u for k in range(3))
        return keys[-1][1]

    def at(self, t):
        return Footprint(self.name, self.position(t), self.direction, self.shape)

    def line(self, step=0.5):
        """Where it can be: its footprint every `step` m along its way."""
        out = []
        for (_, p0), (_, p1) in zip(self.keys, self.keys[1:]):
            n = int(math.dist(p0, p1) / step) + 1
            for i in range(n + 1):
                out.append(Footprint(self.name, tuple(p0[k] + (p1[k] - p0[k]) * i / n for k in range(3)),
                                     self.direction, self.shape))
        return out

    def animate(self):
        """The animation: the group node's translation keys; each wheel turning as far as the
        vehicle rolled, each spinner at its rate (rotation keys a third of a turn apart, so that
        LINEAR's shorter arc turns the right way)."""
        run = self.level.run_time()
        channels = [(self.node, "translation", [t for t, _ in self.keys], [list(p) for _, p in self.keys])]
        for node, radius in self.wheels:
            # Rolling towards local +x turns a wheel about local -z by distance / radius.
            times, values, angle = [], [], 0.0
            for (t0, p0), (t1, p1) in zip(self.keys, self.keys[1:]):
                forward = sum((p1[k] - p0[k]) * self.direction[k] for k in range(3))
                turn = forward / radius
                steps = max(1, math.ceil(abs(turn) / (2 * math.pi / 3)))
                first = 0 if not times else 1  # a segment after the first starts at its last key
                for i in range(first, steps + 1):
                    u = i / steps
                    times.append(t0 + (t1 - t0) * u)
                    values.append(list(quat_z(-(angle + turn * u))))
                angle += turn
            channels.append((node, "rotation", times, values))
        for node, rate in self.spinners:
            steps = max(1, math.ceil(abs(rate) * run / (2 * math.pi / 3)))
            times = [run * i / steps for i in range(steps + 1)]
            channels.append((node, "rotation", times, [list(quat_y(rate * t)) for t in times]))
        self.level.doc.animations.append((f"{self.name}_drive", channels))


def find_timing(level, route, place_vehicle):
    """Picks the camera path's start delay (a fraction of a frame: the camera holds its first
    keyframe that long) so that no frame has the eye too close to an object or in a face's plane:
    the same path, sampled at another phase. Sets level.keys and places the vehicle."""
    problems = []
    for k in range(48):
        delay = k * level.dt / 48  # before its first keyframe's time the camera holds it
        level.keys = [(t + delay, p, q) for t, p, q in route]
        place_vehicle()
        problems = level.frame_problems()
        if not problems:
            return
    frame, what = problems[0]
    raise AssertionError(f"the camera path has no safe timing: at frame {frame}, {what}")


def time_of(level, predicate, after=0.0):
    """The first frame time from `after` on at which predicate(eye) holds, or None."""
    for f in range(level.frames):
        t = f * level.dt
        if t >= after and predicate(camera_at(level.keys, t)[0]):
            return t
    return None


def segment(name, start, end, run):
    """A named stretch of the run, in seconds (3 decimals, the end rounded down into the run)."""
    start, end = max(0.0, start), min(run, end)
    to = round(end, 3) if round(end, 3) <= run else math.floor(end * 1000) / 1000
    if rnd(to, 3) <= rnd(start, 3):
        return None  # an empty stretch (a moment the walk does not reach): no segment
    return {"name": name, "from": rnd(start, 3), "to": rnd(to, 3)}


def walk(points, speeds, look=20.0):
    """Camera keyframes through plan points at the given speeds (m/s for the stretch into each
    point), each looking from the point before it to the point after it: [(time, position,
    target)]."""
    keys, t = [], 0.0
    for i, (x, z) in enumerate(points):
        if i:
            t += math.dist(points[i - 1], (x, z)) / speeds[i]
        a, b = points[max(i - 1, 0)], points[min(i + 1, len(points) - 1)]
        dx, dz = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dz) or 1.0
        keys.append((t, (x, EYE, z), (x + look * dx / length, TARGET_Y, z + look * dz / length)))
    return keys


def fit_walk(level, keys):
    """The keyframes' times scaled so that the walk ends just before the run does."""
    scale = 0.97 * (level.frames - 1) * level.dt / keys[-1][0]
    return [(t * scale, p, q) for t, p, q in keys]


def place_props(rng, props, half_x, half_z, keep_out, what, partial=False):
    """Positions for props inside the rectangle |x| <= half_x, |z| <= half_z: props are plan boxes
    relative to their origin [(x0, z0, x1, z1)], each placed 0.3 m clear of the others and of the
    keep_out boxes, drawn at random until one fits; ParameterError `what` when one does not
    (`partial`: the props that fit, in order, the rest left out)."""
    placed = list(keep_out)
    out = []
    for x0, z0, x1, z1 in props:
        for _ in range(800):
            x, z = rng.uniform(-half_x - x0, half_x - x1), rng.uniform(-half_z - z0, half_z - z1)
            box2 = (x + x0, z + z0, x + x1, z + z1)
            gaps = (max(b[0] - box2[2], box2[0] - b[2], b[1] - box2[3], box2[1] - b[3]) for b in placed)
            if all(gap >= 0.3 for gap in gaps):
                break
        else:
            if partial:
                return out
            raise ParameterError(what)
        placed.append(box2)
        out.append((x, z))
    return out


def plan_box(mesh, yaw=0.0, s=None):
    """A mesh's plan box under a yaw and scale, relative to its origin: (x0, z0, x1, z1)."""
    b = world_box("", mesh, (0, 0, 0), yaw, s)
    return (b.lo[0], b.lo[2], b.hi[0], b.hi[2])


# ---- Level 1: walled courtyards seen from the streets -------------------------------------------

TRUCK = Shape(5.05, 1.4, 3.87, planes_x=(-5.05, 2.25, 2.35, 2.45, 4.55, 4.9, 4.95, 5.05),
              planes_z=(-1.2, -1.15, 1.15, 1.2))
TRUCK_LANE = 1.0  # the truck's centre line, this far from the street's centre, away from the camera
CAMERA_LANE = 1.3  # the camera walks this far from the street's centre line


def courtyards_min_street(args):
    """The narrowest street that holds a car lane on each side, the truck's lane and the camera's."""
    return 2 * (car_reach() + 0.1 + TRUCK_LANE + TRUCK.half_width)


def courtyards(args):
    level = Level("courtyards", args)
    doc = level.doc
    rng = Rng(args.seed)
    nx, nz = args.courtyards
    size, street, t = args.courtyard_size, args.street_width, args.wall_thickness
    pitch = size + street
    inside = size - 2 * t
    if street < courtyards_min_street(args):
        raise ParameterError(f"--street-width: expected at least {courtyards_min_street(args):.1f} m (a "
                             f"car lane on "
                             f"each side, the truck's lane and the camera's), got {street:g}")
    if inside <= 2.0:  # no gate fits whatever its width: the walls are to blame, not --door-width
        raise ParameterError(f"--courtyard-size {size:g}, --wall-thickness {t:g}: expected a courtyard "
                             f"more than 2 m wider inside than its two walls (a gate is at least 1 m "
                             f"from a wall's ends), got {inside:g} m inside")
    if args.door_width > inside - 2.0:
        raise ParameterError(f"--door-width: expected a gate narrower than its wall (at most "
                             f"{inside - 2.0:g} m "
                             f"inside a {size:g} m courtyard with {t:g} m walls), got {args.door_width:g}")
    if args.prop_size > inside - 1.0:
        raise ParameterError(f"--prop-size: expected a prop smaller than its courtyard (at most "
                             f"{inside - 1.0:g} m "
                             f"inside a {size:g} m courtyard), got {args.prop_size:g}")
    if abs(args.wall_height - EYE) < 0.05:
        raise ParameterError(f"--wall-height: expected a height away from the camera's eye ({EYE} m), "
                             f"got {args.wall_height:g}")
    doc.parameters = parameters_of(args)
    box_mesh = level.box()
    for name, make in (("fountain", lambda: fountain_mesh(args.detail)),
                       ("statue_figure", lambda: statue_mesh(args.detail, 0)),
                       ("statue_urn", lambda: statue_mesh(args.detail, 1)),
                       ("tree", lambda: tree_mesh(args.detail)),
                       ("bench", lambda: bench_mesh(args.detail)),
                       ("lamp", lambda: lamp_mesh(args.detail)),
                       ("car", lambda: car_mesh(args.detail)),
                       ("person", lambda: person_mesh(args.detail)),
                       ("truck_cab", lambda: truck_cab_mesh(args.detail)),
                       ("truck_wheel", lambda: wheel_mesh(0.5, 0.3, args.detail))):
        doc.mesh(name, make)
    doc.parts["lamp"] = lamp_parts()

    def centre(i, count):
        return (i - (count - 1) / 2) * pitch

    def street_line(a, count):  # the street before column (or row) a
        return (a - 0.5 - (count - 1) / 2) * pitch

    half_x, half_z = nx * pitch / 2 + street, nz * pitch / 2 + street
    level.slab(None, "floor", (-half_x, -0.2, -half_z), (half_x, 0.0, half_z))

    # The route: down the street before column a (heading -z), right at the street before row b,
    # then along it (heading +x).
    a, b = nx // 2, nz // 2
    xs, zs = street_line(a, nx), street_line(b, nz)
    cam_x, cam_z = xs + CAMERA_LANE, zs + CAMERA_LANE
    z_start = zs + min(1.2 * pitch, nz * pitch / 2 + street * 0.4 - zs)
    x_end = xs + min(1.1 * pitch, nx * pitch / 2 + street * 0.4 - xs)

    gates = []  # (name, x, z, axis): axis 0 for gates in walls along x
    sides = ("n", "e", "s", "w")
    for j in range(nz):
        for i in range(nx):
            cx, cz = centre(i, nx), centre(j, nz)
            g = level.group(f"courtyard_{i}_{j}", (cx, 0, cz))
            h = size / 2
            gated = rng.sample(range(4), args.gates)
            half_in = h - t - 0.3
            gate_zones = []  # the ground inside each gate stays open: a gate shows the courtyard
            for side in range(4):
                # Walls along x (n, s) span the corners; walls along z (e, w) stop 1 cm short.
                along_x = side in (0, 2)
                length = size if along_x else size - 2 * t - 0.02
                sign = -1 if side in (0, 3) else 1
                gate_at = None
                if side in gated:
                    room = length / 2 - args.door_width / 2 - t - 1.0
                    gate_at = rng.uniform(-room, room)
                pieces = [(-length / 2, length / 2)]
                if gate_at is not None:
                    pieces = [(-length / 2, gate_at - args.door_width / 2),
                              (gate_at + args.door_width / 2, length / 2)]
                    gx, gz = (gate_at, sign * (h - t / 2)) if along_x else (sign * (h - t / 2), gate_at)
                    gates.append((f"gate-{i}-{j}-{sides[side]}", cx + gx, cz + gz, 0 if along_x else 2))
                    inner = sign * (half_in - 1.0)
                    gate_zones.append((gate_at, inner, args.door_width / 2 + 0.5) if along_x else
                                      (inner, gate_at, args.door_width / 2 + 0.5))
                for k, (u0, u1) in enumerate(pieces):
                    if along_x:
                        lo = (u0, FLOOR_GAP, sign * h - (t if sign > 0 else 0))
                        hi = (u1, FLOOR_GAP + args.wall_height, sign * h + (0 if sign > 0 else t))
                    else:
                        lo = (sign * h - (t if sign > 0 else 0), FLOOR_GAP, u0)
                        hi = (sign * h + (0 if sign > 0 else t), FLOOR_GAP + args.wall_height, u1)
                    level.slab(g, f"courtyard_{i}_{j}/wall_{sides[side]}_{k}", lo, hi)
                # Lamps outside the wall, the arm over the street, none in front of a gate.
                count = max(1, int((size - 6) // args.lamp_spacing) + 1)
                for k in range(count):
                    u = 0.0 if count == 1 else -(size - 6) / 2 + k * (size - 6) / (count - 1)
                    if gate_at is not None and abs(u - gate_at) < args.door_width / 2 + 1.2:
                        continue
                    d = h + 0.3
                    p = (u, FLOOR_GAP, sign * d) if along_x else (sign * d, FLOOR_GAP, u)
                    yaw = {0: math.pi / 2, 1: 0.0, 2: -math.pi / 2, 3: math.pi}[side]
                    level.add_static(g, f"courtyard_{i}_{j}/lamp_{sides[side]}_{k}", "lamp", p, yaw)
            # Props: the fountain in the middle, trees, statues and benches around it.
            k = args.prop_size / 2  # the fountain's scale; the statues' too
            fountain_box = plan_box(doc.meshes["fountain"], 0.0, (k, k, k))
            kinds = ["tree"] * args.trees + ["statue"] * args.statues + ["bench"] * args.benches
            chosen = []
            for kind in kinds:
                yaw = rng.uniform(0, 2 * math.pi)
                mesh, s = kind, None
                if kind == "statue":
                    mesh, s = ("statue_figure" if rng.below(2) == 0 else "statue_urn"), (k, k, k)
                chosen.append((kind, mesh, yaw, s, plan_box(doc.meshes[mesh], yaw, s)))
            what = (f"--statues: {args.trees} trees, {args.statues} statues and {args.benches} benches do "
                    f"not fit "
                    f"in a {size:g} m courtyard beside a {args.prop_size:g} m fountain; expected fewer "
                    f"props, "
                    f"a smaller --prop-size or a larger --courtyard-size")
            zones = [fountain_box] + [(x - r, z - r, x + r, z + r) for x, z, r in gate_zones]
            spots = place_props(rng, [c[4] for c in chosen], half_in, half_in, zones, what)
            level.add_static(g, f"courtyard_{i}_{j}/fountain", "fountain", (0, FLOOR_GAP, 0), 0.0, (k, k, k))
            counts = {}
            for (kind, mesh, yaw, s, _), (x, z) in zip(chosen, spots):
                n = counts.get(kind, 0)
                counts[kind] = n + 1
                level.add_static(g, f"courtyard_{i}_{j}/{kind}_{n}", mesh, (x, FLOOR_GAP, z), yaw, s)

    # Traffic: cars on lanes round the blocks, walkers on the pavements, the blocks nearest the
    # corner first (so that they pass the camera).
    traffic = level.group("traffic")
    blocks = sorted(((i, j) for j in range(nz) for i in range(nx)),
                    key=lambda ij: (math.hypot(centre(ij[0], nx) - xs, centre(ij[1], nz) - zs), ij))
    def extent(ij):
        x, z = centre(ij[0], nx), centre(ij[1], nz)
        return x - size / 2, z - size / 2, x + size / 2, z + size / 2

    fill_lanes(level, rng, traffic, blocks, extent, args.cars, args.people)

    # The truck: along the street before row b, heading -x, passing the camera just after the turn.
    truck = Vehicle(level, "truck", TRUCK, math.pi)
    truck.part("trailer", box_mesh, (-5.05 + 7.3 / 2, 1.05, 0), (7.3, 2.8, 2.4))
    truck.part("cab", "truck_cab", (2.35, 0, 0))
    for k, x in enumerate((-4.1, -3.0, 4.2)):
        for side, z in (("l", -1.0), ("r", 1.0)):
            truck.wheel(f"wheel_{k}{side}", "truck_wheel", (x, 0.5, z), 0.5)
    points = [(cam_x, z_start), (cam_x, zs + 9.0), (cam_x + 0.9, zs + 3.7), (cam_x + 3.5, cam_z + 0.4),
              (cam_x + 9.0, cam_z), (x_end, cam_z)]
    route = fit_walk(level, walk(points, [0, 8, 6, 5, 6, 8]))
    truck_z = zs - TRUCK_LANE
    speed = 10.0

    def place_truck():
        t_pass = level.keys[-2][0] + 0.3
        x_pass = camera_at(level.keys, t_pass)[0][0]
        run = level.run_time()
        truck.drive([(0.0, (x_pass + speed * t_pass, LANE_Y, truck_z)),
                     (run, (x_pass - speed * (run - t_pass), LANE_Y, truck_z))])

    level.vehicle = truck.at
    find_timing(level, route, place_truck)
    level.check(truck.line())
    truck.animate()

    run = level.run_time()
    turn_from, turn_to = level.keys[-5][0], level.keys[-2][0]
    t_pass = level.keys[-2][0] + 0.3
    level.segments = [segment("street", 0.0, turn_from, run), segment("corner", turn_from, turn_to, run),
                      segment("truck", t_pass - 1.0, t_pass + 1.0, run),
                      segment("after-corner", turn_to, run, run)]
    for name, gx, gz, axis in gates:
        # A gate in a wall beside the route, passed when the camera is level with it.
        if axis == 2 and abs(abs(gx - xs) - street / 2) < t and zs < gz < z_start:
            when = time_of(level, lambda e: e[2] <= gz)
        elif axis == 0 and abs(abs(gz - zs) - street / 2) < t and xs < gx < x_end:
            when = time_of(level, lambda e: e[0] >= gx and e[2] < zs + street)
        else:
            continue
        if when is not None:
            level.segments.append(segment(name, when - 0.5, when + 0.5, run))
    return level, (1280, 720)


def fill_lanes(level, rng, traffic, blocks, extent, cars, people, car_lane=CAR_LANE, per_block=(3, 6)):
    """Cars (up to per_block[0] a block, 9 m apart) and walkers (up to per_block[1], 3 m apart) on
    the lanes round the blocks, in the order given; ParameterError when they cannot hold them."""
    left_cars, left_people = cars, people
    for ij in blocks:
        x0, z0, x1, z1 = extent(ij)
        if left_cars:
            placed = level.lane(ring(x0, z0, x1, z1, car_lane), min(per_block[0], left_cars), 9.0,
                                round(rng.uniform(6, 10), 1), "car", "car", traffic, CAR, rng)
            left_cars -= placed
        if left_people:
            placed = level.lane(ring(x0, z0, x1, z1, PERSON_LANE), min(per_block[1], left_people), 3.0,
                                round(rng.uniform(1.1, 1.6), 2), "person", "person", traffic, PERSON, rng)
            left_people -= placed
    if left_cars:
        raise ParameterError(f"--cars: expected at most {cars - left_cars} cars for these blocks "
                             f"({per_block[0]} a block), got {cars}")
    if left_people:
        raise ParameterError(f"--people: expected at most {people - left_people} people for these blocks "
                             f"({per_block[1]} a block), got {people}")


# ---- Level 2: an interior of rooms joined by doors and corridors -------------------------------

CART = Shape(1.2, 0.7, 1.76, planes_x=(-1.2, -1.15, 0.5, 0.6, 1.15, 1.2),
             planes_z=(-0.7, -0.65, -0.6, 0.6, 0.65, 0.7))
PEOPLE_SIDE = 0.45  # walkers in a corridor keep this close to one wall (their centres)


def interior_minimums(args):
    """The smallest rooms the camera's walk and the cart fit in: (width, depth)."""
    t, dw = args.wall_thickness, args.door_width
    width = max(t + 2 * (dw / 2 + 0.3) + 2.5, t + 0.7 + 2 * CART.half_length + 2.0)
    depth = t / 2 + 0.35 + 2 * CART.half_width + 0.9 + 1.9 + max(1.9, t / 2 + 0.3 + dw / 2)
    return width, depth


def door_span(rng, lo, hi, width):
    """A door's centre along a wall between lo and hi (the wall's clear span), 0.3 m from its ends."""
    return rng.uniform(lo + width / 2 + 0.3, hi - width / 2 - 0.3)


def wall_with_door(level, parent, name, along_x, line, span, door, args, thickness):
    """A wall on `line` (its centre, in z for a wall along x, else in x) over span (u0, u1),
    with a door centred at `door` (or none): the pieces beside the gap and a lintel over it."""
    h = FLOOR_GAP + args.wall_height
    top = FLOOR_GAP + args.door_height
    pieces = [("", span[0], span[1], FLOOR_GAP, h)]
    if door is not None:
        a, b = door - args.door_width / 2, door + args.door_width / 2
        # The lintel stops 1 cm short of the pieces beside it (no two objects touch).
        pieces = [("_0", span[0], a, FLOOR_GAP, h), ("_1", b, span[1], FLOOR_GAP, h),
                  ("_lintel", a + 0.01, b - 0.01, top, h)]
    for suffix, u0, u1, y0, y1 in pieces:
        if along_x:
            level.slab(parent, name + suffix, (u0, y0, line - thickness / 2), (u1, y1, line + thickness / 2))
        else:
            level.slab(parent, name + suffix, (line - thickness / 2, y0, u0), (line + thickness / 2, y1, u1))


def interior(args):
    level = Level("interior", args)
    doc = level.doc
    rng = Rng(args.seed)
    nx, nz = args.rooms
    W, D = args.room_size
    t, Wc, dw = args.wall_thickness, args.corridor_width, args.door_width
    if nx < 2 or nz < 2:
        raise ParameterError(f"--rooms: expected at least 2x2 (the camera walks from a corridor through "
                             f"two rooms "
                             f"side by side), got {nx}x{nz}")
    min_w, min_d = interior_minimums(args)
    # A room too small for any door is --room-size's to say (below), not --door-width's.
    if 0 < min(W, D) - t - 0.6 < dw:
        raise ParameterError(f"--door-width: expected a door narrower than its wall (at most "
                             f"{min(W, D) - t - 0.6:g} m "
                             f"in {W:g} x {D:g} m rooms with {t:g} m walls), got {dw:g}")
    if W < min_w or D < min_d:
        raise ParameterError(f"--room-size: expected rooms at least {min_w:.1f} x {min_d:.1f} m (the "
                             f"camera's walk "
                             f"through two doors beside the cart's way), got {W:g}x{D:g}")
    if Wc < 2 * (PEOPLE_SIDE + PERSON.half_width) + 2 * 0.45:
        raise ParameterError(f"--corridor-width: expected at least "
                             f"{2 * (PEOPLE_SIDE + PERSON.half_width) + 0.9:.2f} m "
                             f"(walkers along one wall, the camera beside them), got {Wc:g}")
    if not (EYE + 0.3 <= args.door_height <= args.wall_height - 0.1):
        raise ParameterError(f"--door-height: expected a door from {EYE + 0.3:g} m (the camera's eye and "
                             f"0.3 m) up to "
                             f"the walls' height less 0.1 m ({args.wall_height - 0.1:g} m), got "
                             f"{args.door_height:g}")
    doc.parameters = parameters_of(args)
    for name, make in (("table", lambda: table_mesh(args.detail)), ("chair", lambda: chair_mesh(args.detail)),
                       ("bookshelf", lambda: bookshelf_mesh(args.detail, Rng(args.seed + 7))),
                       ("sofa", lambda: sofa_mesh(args.detail)), ("vase", lambda: vase_mesh(args.detail)),
                       ("person", lambda: person_mesh(args.detail)), ("cart", lambda: cart_mesh(args.detail)),
                       ("beacon", lambda: beacon_mesh(args.detail))):
        doc.mesh(name, make)
    level.box()

    # Wall centre lines: room column i between x[i] and x[i + 1]; room row j between z0[j] and
    # z1[j]; corridor j between z1[j] and z0[j + 1] (Wc clear between the walls' faces).
    xs = [(i - nx / 2) * W for i in range(nx + 1)]
    z0 = [j * (D + Wc + t) - (nz * D + (nz - 1) * (Wc + t)) / 2 for j in range(nz)]
    z1 = [z + D for z in z0]
    level.slab(None, "floor", (xs[0] - t / 2 - 1, -0.2, z0[0] - t / 2 - 1),
               (xs[-1] + t / 2 + 1, 0.0, z1[-1] + t / 2 + 1))
    ceiling_y = (FLOOR_GAP + args.wall_height + 0.01, FLOOR_GAP + args.wall_height + 0.21)

    # The route: along corridor 0 (on its row-1 side), into room A = (a, 1) by its north door,
    # east through the door into room B = (a + 1, 1), out of B's south door into corridor 1 (or
    # back into corridor 0 by its north door when there is no corridor 1), then along it.
    a = max(0, nx // 2 - 1)
    A, B = (a, 1), (a + 1, 1)
    doors = {}  # (i, j, side) -> centre along the wall
    for j in range(nz):
        for i in range(nx):
            lo_x, hi_x = xs[i] + t / 2, xs[i + 1] - t / 2
            lo_z, hi_z = z0[j] + t / 2, z1[j] - t / 2
            if j > 0:
                doors[(i, j, "n")] = door_span(rng, lo_x, hi_x, dw)
            if j < nz - 1:
                doors[(i, j, "s")] = door_span(rng, lo_x, hi_x, dw)
            if i < nx - 1:
                doors[(i, j, "e")] = door_span(rng, lo_z, hi_z, dw)
    # The doors on the route are where the walk needs them.
    # The cart runs along B's wall away from the camera's exit: the north wall when the camera
    # leaves by the south door, the south wall when it goes back north (no second corridor).
    exit_side = "s" if nz > 2 else "n"
    zE_lo = max(z0[1] + 1.9, z0[1] + t / 2 + 0.3 + dw / 2)
    zE_hi = min(z1[1] - 1.9, z1[1] - t / 2 - 0.3 - dw / 2)
    if exit_side == "s":
        cart_z = z0[1] + t / 2 + 0.35 + CART.half_width
        zE_lo = max(zE_lo, cart_z + CART.half_width + 0.9)
    else:
        cart_z = z1[1] - t / 2 - 0.35 - CART.half_width
        zE_hi = min(zE_hi, cart_z - CART.half_width - 0.9)
    doors[(a, 1, "e")] = rng.uniform(zE_lo, zE_hi)
    doors[(a, 1, "n")] = rng.uniform(xs[a] + t / 2 + 0.3 + dw / 2, xs[a + 1] - 2.5)
    doors[(a + 1, 1, exit_side)] = rng.uniform(xs[a + 1] + 2.5, xs[a + 2] - t / 2 - 0.3 - dw / 2)

    for j in range(nz):
        for i in range(nx):
            g = level.group(f"room_{i}_{j}")
            # Walls along x span the room, to the outer faces at the building's ends and 1 cm
            # short of the neighbour's elsewhere; walls along z stop 1 cm short of them.
            x_lo = xs[i] - t / 2 if i == 0 else xs[i] + 0.01
            x_hi = xs[i + 1] + t / 2 if i == nx - 1 else xs[i + 1] - 0.01
            room = f"room_{i}_{j}"
            door = {side: doors.get((i, j, side)) for side in "nse"}
            wall_with_door(level, g, f"{room}/wall_n", True, z0[j], (x_lo, x_hi), door["n"], args, t)
            wall_with_door(level, g, f"{room}/wall_s", True, z1[j], (x_lo, x_hi), door["s"], args, t)
            span_z = (z0[j] + t / 2 + 0.01, z1[j] - t / 2 - 0.01)
            if i == 0:
                wall_with_door(level, g, f"room_{i}_{j}/wall_w", False, xs[0], span_z, None, args, t)
            wall_with_door(level, g, f"{room}/wall_e", False, xs[i + 1], span_z, door["e"], args, t)
            level.slab(g, f"{room}/ceiling",
                       (xs[i] + 0.005 if i else xs[i] - t / 2, ceiling_y[0], z0[j] - t / 2),
                       (xs[i + 1] - 0.005 if i < nx - 1 else xs[i + 1] + t / 2, ceiling_y[1], z1[j] + t / 2))
    for j in range(nz - 1):
        g = level.group(f"corridor_{j}")
        span_z = (z1[j] + t / 2 + 0.01, z0[j + 1] - t / 2 - 0.01)
        wall_with_door(level, g, f"corridor_{j}/wall_w", False, xs[0], span_z, None, args, t)
        wall_with_door(level, g, f"corridor_{j}/wall_e", False, xs[-1], span_z, None, args, t)
        level.slab(g, f"corridor_{j}/ceiling", (xs[0] - t / 2, ceiling_y[0], z1[j] + t / 2 + 0.01),
                   (xs[-1] + t / 2, ceiling_y[1], z0[j + 1] - t / 2 - 0.01))

    # The camera's plan points: each door crossed on its axis from 0.9 m before to 0.9 m after
    # the wall, each corner cut 1 m before and after.
    c0 = z0[1] - t / 2 - Wc / 2 + 0.4  # corridor 0, on the side of row 1 (walkers keep to row 0's)
    xa, zE = doors[(a, 1, "n")], doors[(a, 1, "e")]
    xb = doors[(a + 1, 1, exit_side)]
    if exit_side == "s":
        c1, exit_line, sign = z1[1] + t / 2 + Wc / 2 - 0.4, z1[1], 1
    else:
        c1, exit_line, sign = c0, z0[1], -1
    x_end = xs[-1] - t / 2 - 1.0
    points = [(xs[0] + 1.0, c0), (xa - 1.6, c0), (xa, z0[1] - 0.9), (xa, z0[1] + 0.9), (xa, zE - 1.0),
              (xa + 1.0, zE), (xs[a + 1] - 0.9, zE), (xs[a + 1] + 0.9, zE), (xb - 1.0, zE),
              (xb, zE + sign * 1.0), (xb, exit_line - sign * 0.9), (xb, exit_line + sign * 0.9),
              (xb + 1.6, c1), (x_end, c1)]
    speeds = [0, 5, 3, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 3, 5]
    route = fit_walk(level, walk(points, speeds, look=12.0))

    # Furniture, clear of the doors, the camera's walk and the cart's way.
    def keep_outs(i, j):
        boxes = []
        for (di, dj, side), u in doors.items():
            if side in ("n", "s"):
                line = z0[dj] if side == "n" else z1[dj]
                boxes.append((u - dw / 2 - 0.3, line - 1.3, u + dw / 2 + 0.3, line + 1.3))
            else:
                boxes.append((xs[di + 1] - 1.3, u - dw / 2 - 0.3, xs[di + 1] + 1.3, u + dw / 2 + 0.3))
        if (i, j) in (A, B):
            for p, q in zip(points, points[1:]):
                boxes.append((min(p[0], q[0]) - 0.9, min(p[1], q[1]) - 0.9,
                              max(p[0], q[0]) + 0.9, max(p[1], q[1]) + 0.9))
        if (i, j) == B:
            boxes.append((xs[i], cart_z - CART.half_width - 0.3, xs[i + 1], cart_z + CART.half_width + 0.3))
        return boxes

    kinds = ["bookshelf", "table", "sofa", "vase", "chair", "bookshelf", "vase", "table", "chair", "sofa"]
    for j in range(nz):
        for i in range(nx):
            g = next(n for n in doc.roots if n.name == f"room_{i}_{j}")
            cx, cz = (xs[i] + xs[i + 1]) / 2, (z0[j] + z1[j]) / 2
            zones = [(x0 - cx, zz0 - cz, x1 - cx, zz1 - cz) for x0, zz0, x1, zz1 in keep_outs(i, j)]
            chosen = []
            for k in range(args.furniture):
                kind = kinds[(k + i + 2 * j) % len(kinds)]
                yaw = (math.pi / 2) * rng.below(4)
                chosen.append((kind, yaw, plan_box(doc.meshes[kind], yaw)))
            what = (f"--furniture: {args.furniture} pieces do not fit in a {W:g} x {D:g} m room ({i}, {j}) "
                    f"beside its doors "
                    f"and the camera's walk; expected fewer pieces or a larger --room-size")
            # The rooms the camera walks through hold what fits beside its walk (and the cart's way).
            spots = place_props(rng, [c[2] for c in chosen], (W - t) / 2 - 0.05, (D - t) / 2 - 0.05, zones,
                                     what, partial=(i, j) in (A, B))
            counts = {}
            for (kind, yaw, _), (x, z) in zip(chosen, spots):
                n = counts.get(kind, 0)
                counts[kind] = n + 1
                level.add_static(g, f"room_{i}_{j}/{kind}_{n}", kind, (cx + x, FLOOR_GAP, cz + z), yaw)

    # Walkers in the corridors, along one wall (a long thin loop), away from the camera's side.
    people = level.group("people")
    left = args.people
    for j in range(nz - 1):
        if not left:
            break
        near_row = 0 if j == 0 else 1  # corridor 0: along row 0's wall; the others along the far row's
        wall_face = z1[j] + t / 2 if near_row == 0 else z0[j + 1] - t / 2
        inward = 1 if near_row == 0 else -1
        za, zb = wall_face + inward * PEOPLE_SIDE, wall_face + inward * (PEOPLE_SIDE + 0.55)
        xa_, xb_ = xs[0] + t / 2 + 0.5, xs[-1] - t / 2 - 0.5
        loop = [(xa_, za), (xb_, za), (xb_, zb), (xa_, zb)]
        speed = round(rng.uniform(1.1, 1.5), 2)
        left -= level.lane(loop, min(left, 8), 2.5, speed, "person", "person", people, PERSON, rng)
    if left:
        raise ParameterError(f"--people: expected at most {args.people - left} people for these corridors "
                             f"(8 a corridor), got {args.people}")

    # The cart: back and forth across room B, north of the camera's way through it, with a
    # turning beacon.
    cart = Vehicle(level, "cart", CART, 0.0)
    cart.part("body", "cart", (0, 0, 0))
    cart.spinner("beacon", "beacon", (0.85, 1.5 + 0.01, 0), 4.0)
    x_lo = xs[a + 1] + t / 2 + 0.35 + CART.half_length
    x_hi = xs[a + 2] - t / 2 - 0.35 - CART.half_length
    run = level.run_time()

    def place_cart():
        # It crosses the room (1.4 m/s) and back, at the far end when the camera walks in, so
        # that it comes towards the camera.
        t_in = time_of(level, lambda e: e[0] >= xs[a + 1]) or run / 2
        speed = 1.4
        leg = (x_hi - x_lo) / speed
        keys, time, at_hi = [], t_in, True
        while time > 0:
            time -= leg
            at_hi = not at_hi
        while time < run + leg:
            keys.append((time, (x_hi if at_hi else x_lo, LANE_Y, cart_z)))
            time += leg
            at_hi = not at_hi
        # From time 0 to the run's end: the key before 0 and after the end cut at them.
        cut = []
        for (t0, p0), (t1, p1) in zip(keys, keys[1:]):
            if t1 <= 0 or t0 >= run:
                continue
            u0, u1 = max(0.0, -t0) / (t1 - t0), min(1.0, (run - t0) / (t1 - t0))
            q0 = tuple(p0[k] + (p1[k] - p0[k]) * u0 for k in range(3))
            q1 = tuple(p0[k] + (p1[k] - p0[k]) * u1 for k in range(3))
            if not cut:
                cut.append((max(t0, 0.0), q0))
            cut.append((min(t1, run), q1))
        cart.drive(cut)

    level.vehicle = cart.at
    find_timing(level, route, place_cart)
    level.check(cart.line())
    cart.animate()

    # Segments: the corridor, each door crossed or passed, each room, the cart's crossing; each
    # moment looked for after the one before it.
    t_a = time_of(level, lambda e: e[2] >= z0[1]) or 0.0
    t_b = time_of(level, lambda e: e[0] >= xs[a + 1], after=t_a) or t_a
    # The exit: B's wall line crossed (t_out), then its face on the corridor's side (t_left).
    t_out = time_of(level, lambda e: sign * (e[2] - exit_line) >= 0, after=t_b) or t_b
    t_left = time_of(level, lambda e: sign * (e[2] - exit_line) >= t / 2, after=t_b) or t_out
    segs = [segment("corridor", 0.0, time_of(level, lambda e: e[2] >= z0[1] - t / 2) or run, run)]
    exit_door = f"door-{a + 1}-1-{exit_side}"
    for name, when in ((f"door-{a}-1-n", t_a), (f"door-{a}-1-e", t_b), (exit_door, t_out)):
        segs.append(segment(name, when - 0.4, when + 0.4, run))
    segs.append(segment(f"room-{a}-1", t_a, t_b, run))
    segs.append(segment("cart", t_b - 0.5, t_left, run))
    segs.append(segment(f"room-{a + 1}-1", t_b, t_left, run))
    segs.append(segment("corridor-after", t_left, run, run))
    for (i, j, side), u in sorted(doors.items()):
        # The doors passed in the corridors: the camera level with them.
        if side == "s" and j == 0 and xs[0] + 1.0 < u < xa - 1.6:
            when = time_of(level, lambda e, u=u: e[0] >= u)
        elif exit_side == "s" and side == "n" and j == 2 and xb + 1.6 < u < x_end:
            when = time_of(level, lambda e, u=u: e[0] >= u, after=t_left)
        elif exit_side == "n" and side == "s" and j == 0 and xb + 1.6 < u < x_end:
            when = time_of(level, lambda e, u=u: e[0] >= u, after=t_left)
        else:
            continue
        if when is not None:
            segs.append(segment(f"door-{i}-{j}-{side}", when - 0.4, when + 0.4, run))
    level.segments = segs
    return level, (960, 540)


# ---- Level 3: a street canyon with traffic --------------------------------------------------------

BUS = Shape(5.5, 1.25, 3.12, planes_x=(-5.5, -5.3, 4.5, 5.5), planes_z=(-1.25, -1.1, 1.1, 1.25))
BUS_LANE = 1.0  # the bus's centre line, this far from the main street's centre, away from the camera
CANYON_CAR_LANE = 6.9  # cars drive this far from the facades (pavement, props and parked cars between)


def canyon_min_street():
    """The narrowest street for the pavement, props, parked cars, a car lane each side, the bus's
    lane and the camera's."""
    return 2 * (car_reach(CANYON_CAR_LANE) + 0.1 + BUS_LANE + BUS.half_width)


def street_tree_parts(height=6.0, crown=1.5):
    """The tree as the checks see it: the trunk, and the crown above people and cars."""
    return [((-0.22, 0.0, -0.22), (0.22, height * 0.72, 0.22)),
            ((-crown * 1.16, height - 2 * crown, -crown * 1.16), (crown * 1.16, height + 0.01, crown * 1.16))]


def canyon(args):
    level = Level("canyon", args)
    doc = level.doc
    rng = Rng(args.seed)
    nx, nz = args.blocks
    bw, bd = args.block_size
    street = args.street_width
    lo_h, hi_h = args.building_height
    if street < canyon_min_street():
        raise ParameterError(f"--street-width: expected at least {canyon_min_street():.1f} m (pavement, "
                             f"props, parked "
                             f"cars, a car lane each side, the bus's lane and the camera's), got {street:g}")
    if nx < 2 or nz < 2:
        raise ParameterError(f"--blocks: expected at least 2x2 (the camera walks the street between two "
                             f"rows and turns "
                             f"into a side street), got {nx}x{nz}")
    if lo_h > hi_h:
        raise ParameterError(f"--building-height: expected MINxMAX with MIN <= MAX, got {lo_h:g}x{hi_h:g}")
    if args.building_width[0] > args.building_width[1]:
        raise ParameterError(f"--building-width: expected MINxMAX with MIN <= MAX, got "
                             f"{args.building_width[0]:g}x{args.building_width[1]:g}")
    if args.building_width[0] > bw:
        raise ParameterError(f"--building-width: expected buildings narrower than their block ({bw:g} m), "
                             f"got "
                             f"{args.building_width[0]:g}")
    if min(bw, bd) < 2 * 4.0 + 3.6:
        raise ParameterError(f"--block-size: expected blocks at least 11.6 m on a side (props 4 m from the "
                             f"corners), "
                             f"got {bw:g}x{bd:g}")
    doc.parameters = parameters_of(args)
    for name, make in (("tree", lambda: tree_mesh(args.detail, 6.0, 1.5)),
                       ("lamp", lambda: lamp_mesh(args.detail)),
                       ("kiosk", lambda: kiosk_mesh(args.detail)),
                       ("bus_stop", lambda: bus_stop_mesh(args.detail)),
                       ("car", lambda: car_mesh(args.detail)), ("person", lambda: person_mesh(args.detail)),
                       ("bus", lambda: bus_mesh(args.detail))):
        doc.mesh(name, make)
    doc.parts["lamp"] = lamp_parts()
    doc.parts["tree"] = street_tree_parts()
    level.box()
    pitch_x, pitch_z = bw + street, bd + street

    def block_x(i):
        return (i - (nx - 1) / 2) * pitch_x

    def block_z(j):
        return (j - (nz - 1) / 2) * pitch_z

    half_x, half_z = nx * pitch_x / 2 + street, nz * pitch_z / 2 + street
    level.slab(None, "floor", (-half_x, -0.2, -half_z), (half_x, 0.0, half_z))

    # The route: along the main street (the one before row b) heading +x, a right turn into the
    # side street before column c, then along it heading +z.
    b, c = nz // 2, nx // 2 + 1 if nx > 2 else 1
    zs = block_z(b) - pitch_z / 2
    xs = block_x(c) - pitch_x / 2
    cam_z, cam_x = zs + CAMERA_LANE, xs - CAMERA_LANE
    x_start = xs - pitch_x
    z_end = zs + min(0.9 * pitch_z, nz * pitch_z / 2 + street * 0.4 - zs)

    for j in range(nz):
        for i in range(nx):
            cx, cz = block_x(i), block_z(j)
            g = level.group(f"block_{i}_{j}", (cx, 0, cz))
            # Buildings side by side along x, each the block's depth, 2 cm apart.
            x, k = -bw / 2, 0
            while x < bw / 2 - 0.01:
                width = rng.uniform(*args.building_width)
                if bw / 2 - (x + width) < args.building_width[0]:
                    width = bw / 2 - x
                height = rng.uniform(lo_h, hi_h)
                if abs(height - EYE) < 0.05:
                    height = EYE + 0.1
                x1 = min(bw / 2, x + width)
                level.slab(g, f"block_{i}_{j}/building_{k}", (x + (0.01 if k else 0), FLOOR_GAP, -bd / 2),
                           (x1 - (0.01 if x1 < bw / 2 else 0), FLOOR_GAP + height, bd / 2))
                x, k = x1, k + 1
            # The pavement round the block: props in slots along each side, parked cars beside
            # them, none within 4 m of a corner.
            main_side = {(j == b): "n", (j == b - 1): "s"}.get(True)
            for side, (length, sign, along_x) in enumerate(((bw, -1, True), (bd, 1, False), (bw, 1, True),
                                                           (bd, -1, False))):
                name = "nesw"[side]
                slots = max(1, int((length - 8.0) // args.prop_spacing) + 1)
                for s in range(slots):
                    u = 0.0 if slots == 1 else -(length - 8.0) / 2 + s * (length - 8.0) / (slots - 1)
                    roll = rng.random()
                    if s % 2 == 1:
                        kind = "lamp"
                    elif name == main_side and roll < 0.3:
                        kind = "bus_stop"
                    elif roll < 0.7:
                        kind = "tree"
                    else:
                        kind = "kiosk"
                    d = {"lamp": 0.3, "tree": 2.2, "kiosk": 2.5, "bus_stop": 2.3}[kind]
                    # Facing out from the block: +x local towards the street for the lamp's arm,
                    # the shelter's open side (local -z) towards the street.
                    out_yaw = {0: math.pi / 2, 1: 0.0, 2: -math.pi / 2, 3: math.pi}[side]
                    yaw = {"lamp": out_yaw, "bus_stop": out_yaw + math.pi / 2}.get(kind, 0.0)  # round: 0

                    def beside(distance):  # the point `distance` from the facade at slot u
                        if along_x:
                            return (u, FLOOR_GAP, sign * (bd / 2 + distance))
                        return (sign * (bw / 2 + distance), FLOOR_GAP, u)

                    p = beside(d)
                    level.add_static(g, f"block_{i}_{j}/{kind}_{name}_{s}", kind, p, yaw)
                    if rng.random() < args.parked / 100.0 and s % 2 == 0:
                        car_yaw = 0.0 if along_x else math.pi / 2
                        q = beside(4.8)
                        level.add_static(g, f"block_{i}_{j}/parked_car_{name}_{s}", "car", q, car_yaw)

    traffic = level.group("traffic")
    blocks = sorted(((i, j) for j in range(nz) for i in range(nx)),
                    key=lambda ij: (math.hypot(block_x(ij[0]) - xs, block_z(ij[1]) - zs), ij))
    fill_lanes(level, rng, traffic, blocks, lambda ij: (block_x(ij[0]) - bw / 2, block_z(ij[1]) - bd / 2,
                                                       block_x(ij[0]) + bw / 2, block_z(ij[1]) + bd / 2),
               args.cars, args.people, CANYON_CAR_LANE, (5, 6))

    # The bus: along the main street heading -x, on the far side of its centre, passing the camera
    # before the turn.
    bus = Vehicle(level, "bus", BUS, math.pi)
    bus.part("body", "bus", (0, 0, 0))
    points = [(x_start, cam_z), (xs - 12.0, cam_z), (xs - 4.0, cam_z + 0.6), (cam_x - 0.6, zs + 4.0),
              (cam_x, zs + 12.0), (cam_x, z_end)]
    route = fit_walk(level, walk(points, [0, 9, 6, 5, 6, 9], look=25.0))
    bus_z = zs - BUS_LANE
    speed = 11.0

    def place_bus():
        t_pass = level.keys[1][0] - 1.2
        x_pass = camera_at(level.keys, t_pass)[0][0]
        run = level.run_time()
        bus.drive([(0.0, (x_pass + speed * t_pass, LANE_Y, bus_z)),
                   (run, (x_pass - speed * (run - t_pass), LANE_Y, bus_z))])

    level.vehicle = bus.at
    find_timing(level, route, place_bus)
    level.check(bus.line())
    bus.animate()

    run = level.run_time()
    t_pass = level.keys[1][0] - 1.2
    level.segments = [segment("main-street", 0.0, level.keys[1][0], run),
                      segment("bus", t_pass - 1.0, t_pass + 1.0, run),
                      segment("corner", level.keys[1][0], level.keys[4][0], run),
                      segment("side-street", level.keys[4][0], run, run)]
    return level, (960, 540)


# ---- The command line --------------------------------------------------------------------------


class Parser(argparse.ArgumentParser):
    """argparse whose mistakes are one line and exit 2 (ParameterError), without the usage text."""

    def error(self, message):
        raise ParameterError(message)


def number(low=None, high=None, low_open=False):
    def parse(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, got '{text}'")
        if not math.isfinite(v) or (low is not None and (v <= low if low_open else v < low)) or \
                (high is not None and v > high):
            raise argparse.ArgumentTypeError(f"expected a number {expected_range(low, high, low_open)}, "
                                             f"got {text}")
        return v
    return parse


def integer(low, high):
    def parse(text):
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected an integer, got '{text}'")
        if v < low or v > high:
            raise argparse.ArgumentTypeError(f"expected an integer in [{low}, {high}], got {text}")
        return v
    return parse


def expected_range(low, high, low_open):
    if high is None:
        return f"> {low:g}" if low_open else f">= {low:g}"
    return f"in {'(' if low_open else '['}{low:g}, {high:g}]"


def size_pair(low, high):
    def parse(text):
        parts = text.lower().split("x")
        try:
            w, d = (float(p) for p in parts)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected WIDTHxDEPTH in metres (e.g. 8x7), got '{text}'")
        if not (low <= w <= high and low <= d <= high):
            raise argparse.ArgumentTypeError(f"expected WIDTHxDEPTH, each in [{low:g}, {high:g}] m, got "
                                             f"'{text}'")
        return w, d
    return parse


def grid(high):
    def parse(text):
        parts = text.lower().split("x")
        try:
            nx, nz = (int(p) for p in parts)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected COLUMNSxROWS (e.g. 4x4), got '{text}'")
        if not (1 <= nx <= high and 1 <= nz <= high):
            raise argparse.ArgumentTypeError(f"expected COLUMNSxROWS, each in [1, {high}], got '{text}'")
        return nx, nz
    return parse


# (flag, type, default, unit, what it controls) per level; the one table of each level's
# parameters, printed by --markdown for docs/scenario-generators.md.
COMMON = [
    ("--seed", integer(0, 2**32 - 1), 1, "–", "random placement (gates, props, lanes, speeds); also the "
                                              "scenario's seed"),
    ("--frames", integer(60, 100000), 300, "frames", "run length at dt 1/30 s; the camera walks its path "
                                                     "in that time"),
    ("--detail", number(0.25, 4), 1.0, "–", "tessellation of the props (segments round a lathe, books on a "
                                            "shelf)"),
    ("--people", integer(0, 10000), 40, "–", "people walking the pavements (up to 6 a block) or corridors "
                                             "(8 each)"),
]
CARS = ("--cars", integer(0, 10000), 14, "–", "cars driving the lanes round the blocks (up to 3 a block in "
                                              "the courtyards, "
                                               "5 in the canyon)")
LEVELS = {
    "courtyards": {
        "help": "a grid of walled courtyards with gates, seen from the streets between them",
        "build": courtyards,
        "flags": [
            ("--courtyards", grid(40), (4, 4), "–", "courtyards along x and z, COLUMNSxROWS"),
            ("--courtyard-size", number(8, 200), 26.0, "m", "side of a courtyard, walls included"),
            ("--street-width", number(1, 200), 13.0, "m", "streets between the courtyards (at least 12.8: "
                                                          "a car lane each "
                                                          "side, the truck's lane and the camera's)"),
            ("--wall-height", number(0.5, 50), 4.0, "m", "courtyard walls"),
            ("--wall-thickness", number(0.05, 5), 0.4, "m", "courtyard walls"),
            ("--door-width", number(0, 100, True), 3.2, "m", "gate width; a gate is at least 1 m from a "
                                                             "wall's ends"),
            ("--gates", integer(1, 4), 2, "–", "walls with a gate, per courtyard (drawn at random)"),
            ("--statues", integer(0, 100), 4, "–",
             "statues per courtyard (a figure or an urn on a plinth)"),
            ("--benches", integer(0, 100), 4, "–", "benches per courtyard"),
            ("--trees", integer(0, 100), 1, "–", "trees per courtyard (7 m tall: their crowns show over "
                                                 "the walls)"),
            ("--prop-size", number(0, 100, True), 3.0, "m", "the fountain's diameter; statues are half as "
                                                            "wide, 1.2 times "
                                                            "as tall"),
            ("--lamp-spacing", number(1, 100), 13.0, "m", "street lamps along the walls, outside"),
            CARS,
        ],
        "common": {},
    },
    "interior": {
        "help": "rooms joined by doors and corridors, walked through from a corridor",
        "build": interior,
        "flags": [
            ("--rooms", grid(40), (4, 3), "–", "rooms along x and z, COLUMNSxROWS (at least 2x2); a "
                                               "corridor between "
                                               "each two rows"),
            ("--room-size", size_pair(2, 100), (8.0, 7.0), "m", "room WIDTHxDEPTH between the walls' "
                                                                "centre lines"),
            ("--corridor-width", number(0.5, 50), 3.0, "m", "clear width of a corridor"),
            ("--wall-height", number(2.2, 20), 3.0, "m", "walls; ceilings rest 1 cm above them"),
            ("--wall-thickness", number(0.05, 2), 0.2, "m", "walls"),
            ("--door-width", number(0, 20, True), 1.2, "m", "doors (in every wall between two rooms and "
                                                            "between a room "
                                                            "and a corridor)"),
            ("--door-height", number(0.5, 20), 2.2, "m", "doors; a lintel fills the wall above"),
            ("--furniture", integer(0, 100), 6, "–", "pieces per room (shelves of books, tables, chairs, "
                                                     "sofas, vases)"),
        ],
        "common": {"--people": 12},
    },
    "canyon": {
        "help": "a street canyon: tall buildings along streets full of props, traffic and people",
        "build": canyon,
        "flags": [
            ("--blocks", grid(40), (5, 3), "–", "blocks along x and z, COLUMNSxROWS (at least 2x2)"),
            ("--block-size", size_pair(4, 500), (36.0, 28.0), "m", "block WIDTHxDEPTH (facade to facade)"),
            ("--street-width", number(1, 200), 22.0, "m", "every street, facade to facade (at least 20.9)"),
            ("--building-height", size_pair(1, 500), (12.0, 40.0), "m", "MINxMAX of the buildings (one box "
                                                                        "each)"),
            ("--building-width", size_pair(1, 500), (8.0, 14.0), "m", "MINxMAX of a building's frontage"),
            ("--prop-spacing", number(1, 100), 6.0, "m", "slots along a pavement: trees, kiosks, bus "
                                                         "shelters, lamps"),
            ("--parked", number(0, 100), 50.0, "%", "share of the prop slots (not the lamps') with a car "
                                                    "parked beside them"),
            CARS,
        ],
        "common": {"--cars": 30, "--people": 60},
    },
}


def parameters_of(args):
    """The parameters a level was made with, as its files record them."""
    out = {}
    for flag, _, _, _, _ in COMMON + LEVELS[args.level]["flags"]:
        v = getattr(args, flag[2:].replace("-", "_"))
        out[flag[2:]] = show(v) if isinstance(v, tuple) else v
    return out


def make_parser():
    parser = Parser(prog="make_levels.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("--markdown", action="store_true", help="print the parameter tables and exit")
    sub = parser.add_subparsers(dest="level")
    for name, level in LEVELS.items():
        p = sub.add_parser(name, help=level["help"])
        for flag, kind, default, _, what in level["flags"] + COMMON:
            default = level["common"].get(flag, default)
            p.add_argument(flag, type=kind, default=default, help=f"{what} (default {show(default)})")
        p.add_argument("--out", type=Path, default=None, help="scenarios folder to write into (default: "
                                                              "the repository's)")
    p = sub.add_parser("all", help="every level with its defaults (the committed files)")
    p.add_argument("--out", type=Path, default=None, help="scenarios folder to write into (default: the "
                                                          "repository's)")
    return parser


def show(v):
    """A parameter's value as a flag takes it: 4x4, 8x7, 0.4."""
    if isinstance(v, tuple):
        return "x".join(show(c) for c in v)
    return f"{v:g}" if isinstance(v, float) else str(v)


def markdown():
    lines = []
    for name, level in LEVELS.items():
        lines += [f"`{name}`: {level['help']}.", "", "| Flag | Unit | Default | What it controls |",
                  "|---|---|---|---|"]
        for flag, _, default, unit, what in level["flags"] + COMMON:
            default = level["common"].get(flag, default)
            lines.append(f"| `{flag}` | {unit} | `{show(default)}` | {what} |")
        lines.append("")
    return "\n".join(lines).rstrip("\n")


def build(args):
    """Every file of one level: {path: bytes}."""
    level, viewport = LEVELS[args.level]["build"](args)
    out = args.out
    files = level.doc.write(out / "assets" / "levels" / f"{level.name}.gltf")
    files[out / "levels" / f"{level.name}.json"] = (dumps(level.scenario(viewport)) + "\n").encode()
    return level, files


def check_writable(folder):
    """ParameterError unless `folder` is, or can be made, a writable folder (checked before any
    level is made, so that nothing is half written)."""
    existing = folder
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir() or not os.access(existing, os.W_OK | os.X_OK):
        raise ParameterError(f"--out: expected a folder this user can write, but {existing} is not one "
                             f"(for {folder})")


def write_files(files):
    try:
        for path, data in files.items():
            path.parent.mkdir(parents=True, exist_ok=True)
            temp = path.with_name(path.name + ".part")
            temp.write_bytes(data)
            os.replace(temp, path)
    except OSError as e:
        raise ParameterError(f"--out: cannot write {e.filename}: {e.strerror}")


def main(argv):
    parser = make_parser()
    args = parser.parse_args(argv)
    if args.markdown:
        print(markdown())
        return 0
    if args.level is None:
        raise ParameterError("expected a level (" + ", ".join(list(LEVELS) + ["all"]) + ")")
    out = args.out if args.out is not None else Path(__file__).resolve().parent.parent / "scenarios"
    names = list(LEVELS) if args.level == "all" else [args.level]
    for folder in (out / "levels", out / "assets" / "levels"):
        check_writable(folder)
    files, summaries = {}, []
    for name in names:
        level_args = args if args.level != "all" else parser.parse_args([name])
        level_args.level, level_args.out = name, out
        try:
            level, made = build(level_args)
        except AssertionError as e:
            raise ParameterError(f"{name}: these parameters make an impossible level: {e}")
        files.update(made)
        triangles = sum(level.doc.meshes[n.mesh].triangles() for n in iterate(level.doc.roots) if n.mesh)
        objects = sum(1 for n in iterate(level.doc.roots) if n.mesh)
        summaries.append(f"{name}: {objects} objects, {triangles} triangles, {len(level.doc.meshes)} meshes, "
                         f"{sum(len(n) for _, n, _, _ in level.lanes)} path movers, "
                         f"{sum(1 for seg in level.segments if seg)} segments")
    write_files(files)  # only once every level was made and checked
    print("\n".join(summaries))
    for path in files:
        print(f"wrote {path}")
    return 0


def iterate(nodes):
    for n in nodes:
        yield n
        yield from iterate(n.children)


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except ParameterError as e:
        print(f"make_levels.py: {e}", file=sys.stderr)
        sys.exit(2)
