#!/usr/bin/env python3
"""Checks that the wing's points of a moved wing3D case are where the motion law puts them.

    checkWingMotion.py CASE_OR_PROCESSOR_DIR [TOLERANCE]

For every time folder with polyMesh/points, each point of the patch `wing` must be at
    c + R(-a(t)) (p0 - c),   a(t) = 6 degrees * sin(2 pi t),   c = (0.25, 0, 0),
R(-a) the rotation about +z by -a (the pitch-up about the spanwise axis -z that
0/pointDisplacement prescribes), p0 its position in constant/polyMesh/points. The law is written
here again on purpose, not read from 0/pointDisplacement: this is an independent check of what
OpenFOAM evaluated and the motion solver kept. Prints the largest distance over the wing's points
(relative to the chord, 1) and exits 1 when it exceeds TOLERANCE (default 1e-9), 2 when the case
cannot be read. Works on a processor folder of a decomposed case too (its own patch and points).
Needs the mesh files in ascii (the tutorial's writeFormat).
"""
import math
import os
import re
import sys

AMPLITUDE = math.radians(6.0)
OMEGA = 2.0 * math.pi
CENTRE = (0.25, 0.0, 0.0)
CHORD = 1.0


def body(path):
    """The text of an OpenFOAM ascii file after its FoamFile header."""
    with open(path) as f:
        text = f.read()
    header = text.find("FoamFile")
    return text[text.index("}", header) + 1:] if header >= 0 else text


def read_points(path):
    number = r"([-+0-9.eE]+)"
    return [tuple(map(float, m)) for m in re.findall(r"\(%s %s %s\)" % (number, number, number), body(path))]


def read_faces(path):
    return [list(map(int, m.split())) for m in re.findall(r"\d+\(([\d ]+)\)", body(path))]


def wing_points(polymesh):
    boundary = body(os.path.join(polymesh, "boundary"))
    match = re.search(r"\bwing\s*\{([^}]*)\}", boundary)
    if not match:
        return []
    start = int(re.search(r"startFace\s+(\d+)", match.group(1)).group(1))
    count = int(re.search(r"nFaces\s+(\d+)", match.group(1)).group(1))
    faces = read_faces(os.path.join(polymesh, "faces"))
    return sorted({p for face in faces[start:start + count] for p in face})


def expected(p0, t):
    angle = -AMPLITUDE * math.sin(OMEGA * t)
    c, s = math.cos(angle), math.sin(angle)
    x, y = p0[0] - CENTRE[0], p0[1] - CENTRE[1]
    return (CENTRE[0] + c * x - s * y, CENTRE[1] + s * x + c * y, p0[2])


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    case = sys.argv[1]
    tolerance = float(sys.argv[2]) if len(sys.argv) == 3 else 1e-9
    try:
        polymesh = os.path.join(case, "constant", "polyMesh")
        wing = wing_points(polymesh)
        initial = read_points(os.path.join(polymesh, "points"))
        times = []
        for name in os.listdir(case):
            try:
                t = float(name)
            except ValueError:
                continue
            if t > 0 and os.path.isfile(os.path.join(case, name, "polyMesh", "points")):
                times.append((t, name))
        worst = 0.0
        for t, name in sorted(times):
            moved = read_points(os.path.join(case, name, "polyMesh", "points"))
            if len(moved) != len(initial):
                print(f"checkWingMotion: {case}/{name}: {len(moved)} points, the mesh has {len(initial)}", file=sys.stderr)
                return 2
            for p in wing:
                e = expected(initial[p], t)
                worst = max(worst, math.dist(moved[p], e) / CHORD)
    except (OSError, ValueError, AttributeError, IndexError) as error:
        print(f"checkWingMotion: cannot read {case}: {error}", file=sys.stderr)
        return 2
    if not times:
        print(f"checkWingMotion: {case}: no time folder with polyMesh/points", file=sys.stderr)
        return 2
    verdict = "within" if worst <= tolerance else "NOT within"
    print(f"wing points of {case}: max |x - x(law)| / chord {worst:.3e} over {len(wing)} points "
          f"and {len(times)} times, {verdict} {tolerance:g}")
    return 0 if worst <= tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
