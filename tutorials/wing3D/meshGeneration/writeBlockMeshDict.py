#!/usr/bin/env python3
"""Writes system/blockMeshDict of tutorials/wing3D: a straight NACA0012 wing (chord 1, semi-span
2, flat tip) in the box [-5, 6] x [-5, 5] x [0, 5], its root on the symmetry plane z = 0.

    writeBlockMeshDict.py [--resolution R] [--output FILE]

R scales every cell count: R = 1 (the default) gives 984 000 hexahedra, R = 0.3 (the test's
coarse setting) 27 900. The first cell on the wing is about 6e-4 chord thick at R = 1 (the
radial expansion ratio is fixed, so it grows as the count shrinks).

Topology (why blockMesh: every cell a hexahedron, the boundary layer a structured O-grid whose
lines leave the wing normally, and the count set exactly by one number):
  * an O-grid of four blocks around the section (leading-edge arc, upper surface, trailing-edge
    arc, lower surface), from the wing to the four sides of the box; its radial block edges
    are quadratic Bezier curves that leave the wing along its normal and end at a box corner;
  * the same four blocks repeated from the tip to the top of the box, plus one "cap" block
    filling the section above the tip (its bottom face is the flat tip);
  * cells cluster towards the wing radially (expansion 1000) and towards the tip in z.
The section's block corners are at x = 0.02 on both surfaces (near the leading edge, where the
surface normal points at the box's upstream corners) and at the two corners of the blunt
trailing edge.
"""
import argparse
import math

CHORD = 1.0
SEMI_SPAN = 2.0
BOX_X = (-5.0, 6.0)
BOX_Y = (-5.0, 5.0)
BOX_TOP = 5.0
SPLIT_LEADING = 0.02   # x of the block corners near the leading edge
SPLIT_TRAILING = 1.0   # the block corners at the trailing edge: the two corners of its blunt base
RADIAL_EXPANSION = 1000.0   # last / first radial cell
SPAN_EXPANSION = 0.15       # tip cell / root cell along the wing
ABOVE_TIP_EXPANSION = 10.0  # top cell / tip cell above the wing


def thickness(x):
    """NACA0012 half-thickness, the standard blunt trailing edge (-0.1015 x^4: 0.25 % chord thick)."""
    x = min(max(x, 0.0), 1.0)
    return 0.6 * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1015 * x**4)


def surface(x, side):
    """A point of the section: side +1 upper, -1 lower."""
    return (x * CHORD, side * thickness(x) * CHORD)


def normal(x, side):
    """Outward unit normal of the section at x on a side (finite difference of the surface)."""
    h = 1e-6
    x0, x1 = max(x - h, 0.0), min(x + h, 1.0)
    dx = (x1 - x0) * CHORD
    dy = side * (thickness(x1) - thickness(x0)) * CHORD
    length = math.hypot(dx, dy)
    # the tangent (dx, dy) runs towards the trailing edge; outward is its left turn on the upper
    # surface and its right turn on the lower one
    return (-side * dy / length, side * dx / length)


def cosine_samples(x0, x1, count):
    """count points from x0 to x1 (both included), clustered at both ends."""
    return [x0 + (x1 - x0) * 0.5 * (1 - math.cos(math.pi * k / (count - 1))) for k in range(count)]


def section_curve(name):
    """Interior points of one wall edge of the section, in the direction the blocks use."""
    a, b = SPLIT_LEADING, SPLIT_TRAILING
    if name == "upper":          # A -> B
        return [surface(x, 1) for x in cosine_samples(a, b, 60)[1:-1]]
    if name == "lower":          # C -> D
        return [surface(x, -1) for x in cosine_samples(b, a, 60)[1:-1]]
    if name == "trailing":       # B -> C: the blunt base, straight
        return []
    if name == "leading":        # D -> leading edge -> A
        lower = [surface(x, -1) for x in cosine_samples(a, 0.0, 30)[1:]]
        upper = [surface(x, 1) for x in cosine_samples(0.0, a, 30)[1:-1]]
        return lower + upper
    raise ValueError(name)


def radial_curve(x, side, corner):
    """Interior points of the quadratic Bezier from the section point to a box corner, leaving
    the wing along its normal (so that the boundary-layer cells are nearly orthogonal)."""
    p0 = surface(x, side)
    n = normal(x, side)
    if x >= 1.0:   # a corner of the blunt base: leave along the bisector of the surface and the base
        n = (n[0] + 1.0, n[1])
        length = math.hypot(*n)
        n = (n[0] / length, n[1] / length)
    reach = 0.4 * math.hypot(corner[0] - p0[0], corner[1] - p0[1])
    c = (p0[0] + reach * n[0], p0[1] + reach * n[1])
    points = []
    for k in range(1, 20):
        t = k / 20
        points.append(tuple((1 - t) ** 2 * p0[d] + 2 * t * (1 - t) * c[d] + t * t * corner[d] for d in range(2)))
    return points


def fmt(p, z):
    return "(%.10g %.10g %.10g)" % (p[0], p[1], z)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--resolution", type=float, default=1.0,
                        help="scales every cell count (1: about 10^6 cells; 0.3: about 3*10^4)")
    parser.add_argument("--output", default="system/blockMeshDict")
    args = parser.parse_args()
    r = args.resolution
    along = max(4, round(80 * r))        # cells along each surface block (upper, lower)
    around = max(3, round(30 * r))       # cells around each edge arc (leading, trailing)
    radial = max(4, round(60 * r))       # cells from the wing to the box
    span = max(3, round(45 * r))         # cells from root to tip
    above = max(3, round(25 * r))        # cells from the tip to the top

    a, b = SPLIT_LEADING, SPLIT_TRAILING
    section = {"A": surface(a, 1), "B": surface(b, 1), "C": surface(b, -1), "D": surface(a, -1)}
    corners = {"A": (BOX_X[0], BOX_Y[1]), "B": (BOX_X[1], BOX_Y[1]),
               "C": (BOX_X[1], BOX_Y[0]), "D": (BOX_X[0], BOX_Y[0])}
    levels = [0.0, SEMI_SPAN, BOX_TOP]
    # vertex numbers: 8 per level: A B C D on the section, then their box corners
    names = ["A", "B", "C", "D"]
    vertices = []
    index = {}
    for level, z in enumerate(levels):
        for name in names:
            index[(name, level)] = len(vertices)
            vertices.append(fmt(section[name], z))
        for name in names:
            index[("O" + name, level)] = len(vertices)
            vertices.append(fmt(corners[name], z))
    surface_grading = "((0.5 0.5 3) (0.5 0.5 0.3333333333))"   # finer at both ends, symmetric
    z_grading = [SPAN_EXPANSION, ABOVE_TIP_EXPANSION]
    z_cells = [span, above]
    # ring blocks: (wall start, wall end, cells along the wall, grading along the wall)
    ring = [("A", "B", along, surface_grading), ("B", "C", around, "1"),
            ("C", "D", along, surface_grading), ("D", "A", around, "1")]
    blocks = []
    for layer in range(2):
        for w0, w1, count, grading in ring:
            v = [index[(w0, layer)], index[(w1, layer)], index[("O" + w1, layer)], index[("O" + w0, layer)]]
            v += [index[(w0, layer + 1)], index[(w1, layer + 1)], index[("O" + w1, layer + 1)], index[("O" + w0, layer + 1)]]
            blocks.append("    hex (%s) (%d %d %d) edgeGrading (%s %s %s %s  %g %g %g %g  %g %g %g %g)"
                          % (" ".join(map(str, v)), count, radial, z_cells[layer],
                             grading, grading, grading, grading,
                             RADIAL_EXPANSION, RADIAL_EXPANSION, RADIAL_EXPANSION, RADIAL_EXPANSION,
                             *([z_grading[layer]] * 4)))
    # the cap above the tip: one block over the section, D -> C along the lower surface, C -> B
    # across the blunt trailing edge, whose two corners are block corners (a sharp trailing edge
    # inside a block side makes the cells there degenerate)
    v = [index[(n, 1)] for n in "DCBA"] + [index[(n, 2)] for n in "DCBA"]
    blocks.append("    hex (%s) (%d %d %d) edgeGrading (%s %s %s %s  1 1 1 1  %g %g %g %g)"
                  % (" ".join(map(str, v)), along, around, above,
                     surface_grading, surface_grading, surface_grading, surface_grading,
                     *([ABOVE_TIP_EXPANSION] * 4)))

    edges = []
    wall_edges = [("A", "B", "upper"), ("B", "C", "trailing"), ("C", "D", "lower"), ("D", "A", "leading")]
    side_of = {"A": (a, 1), "B": (b, 1), "C": (b, -1), "D": (a, -1)}
    for level, z in enumerate(levels):
        for w0, w1, curve in wall_edges:
            points = " ".join(fmt(p, z) for p in section_curve(curve))
            if points:
                edges.append("    polyLine %d %d (%s)" % (index[(w0, level)], index[(w1, level)], points))
        for name in names:
            x, side = side_of[name]
            points = " ".join(fmt(p, z) for p in radial_curve(x, side, corners[name]))
            edges.append("    polyLine %d %d (%s)" % (index[(name, level)], index[("O" + name, level)], points))

    def quad(v):
        return "(%s)" % " ".join(map(str, v))

    wing, symmetry, farfield = [], [], []
    for w0, w1, _, _ in ring:
        wing.append(quad([index[(w0, 0)], index[(w0, 1)], index[(w1, 1)], index[(w1, 0)]]))
        symmetry.append(quad([index[(w0, 0)], index[("O" + w0, 0)], index[("O" + w1, 0)], index[(w1, 0)]]))
        for layer in range(2):
            farfield.append(quad([index[("O" + w0, layer)], index[("O" + w1, layer)],
                                  index[("O" + w1, layer + 1)], index[("O" + w0, layer + 1)]]))
        farfield.append(quad([index[(w0, 2)], index[(w1, 2)], index[("O" + w1, 2)], index[("O" + w0, 2)]]))
    wing.append(quad([index[(n, 1)] for n in "ABCD"]))
    farfield.append(quad([index[(n, 2)] for n in "DCBA"]))

    cells = 2 * (along + around) * radial * (span + above) + along * around * above
    text = f"""/*--------------------------------*- C++ -*----------------------------------*\\
  tutorials/wing3D: written by meshGeneration/writeBlockMeshDict.py --resolution {r:g}
  ({cells} hexahedra). Do not edit: change the script.
\\*---------------------------------------------------------------------------*/
FoamFile
{{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      blockMeshDict;
}}

scale 1;

vertices
(
{chr(10).join("    " + v for v in vertices)}
);

blocks
(
{chr(10).join(blocks)}
);

edges
(
{chr(10).join(edges)}
);

boundary
(
    wing
    {{
        type wall;
        faces
        (
{chr(10).join("            " + f for f in wing)}
        );
    }}
    symmetryPlane
    {{
        type symmetryPlane;
        faces
        (
{chr(10).join("            " + f for f in symmetry)}
        );
    }}
    farfield
    {{
        type patch;
        faces
        (
{chr(10).join("            " + f for f in farfield)}
        );
    }}
);
"""
    with open(args.output, "w") as f:
        f.write(text)
    print(f"{args.output}: {cells} hexahedra (resolution {r:g})")


if __name__ == "__main__":
    main()
