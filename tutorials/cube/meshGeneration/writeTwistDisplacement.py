#!/usr/bin/env python3
"""Writes 0/pointDisplacement of the cube tutorial: the twist of the thesis' eq. 4.1.

Every plane y = const of the cube turns about the y axis by theta(y) = alpha y + beta
(eq. 4.1d), with beta = 0 (the bottom, y = 0, stays) and alpha such that the top (y = 1)
turns by 30 degrees:
    x_new =  x cos(theta) + z sin(theta)         (4.1a)
    y_new =  y                                   (4.1b)
    z_new = -x sin(theta) + z cos(theta)         (4.1c)
This is the right-handed rotation about +y (counter-clockwise seen from above).

  bottom  fixedValue uniform (0 0 0)
  top     solidBodyMotionDisplacement rotatingMotion about (0 1 0): the top is one plane, so
          its twist is a rigid rotation, 30 degrees during the time step 0 -> 1
  sides   fixedValue nonuniform List<vector>: eq. 4.1 evaluated at every point of the patch,
          listed in OpenFOAM's order of the patch points (localPoints: the order of first
          appearance walking the patch's faces), which is why this script reads the mesh.

Usage: writeTwistDisplacement.py [caseDirectory]   (run after the mesh is written)
"""
import gzip
import math
import os
import re
import sys

TWIST_DEGREES = 30.0   # at the top, y = 1
HEIGHT = 1.0


def read_foam_file(path):
    """Text of an ascii OpenFOAM file (path or path.gz) without comments and FoamFile header."""
    if os.path.exists(path):
        text = open(path, encoding="ascii").read()
    elif os.path.exists(path + ".gz"):
        text = gzip.open(path + ".gz", "rt", encoding="ascii").read()
    else:
        sys.exit(f"writeTwistDisplacement.py: {path} not found")
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    header = re.search(r"FoamFile\s*\{([^}]*)\}", text)
    if header and re.search(r"format\s+binary", header.group(1)):
        sys.exit(f"writeTwistDisplacement.py: {path} is binary; convert it with foamFormatConvert to ascii first")
    return text[header.end():] if header else text


def list_body(text, path):
    """Contents of the first top-level list 'N ( ... )' and its size N."""
    match = re.search(r"(\d+)\s*\(", text)
    if not match:
        sys.exit(f"writeTwistDisplacement.py: no list in {path}")
    return int(match.group(1)), text[match.end():text.rindex(")")]


def read_points(mesh):
    path = os.path.join(mesh, "points")
    size, body = list_body(read_foam_file(path), path)
    points = [tuple(float(c) for c in p) for p in re.findall(r"\(\s*(\S+)\s+(\S+)\s+(\S+)\s*\)", body)]
    if len(points) != size:
        sys.exit(f"writeTwistDisplacement.py: {path} says {size} points but holds {len(points)}")
    return points


def read_faces(mesh):
    path = os.path.join(mesh, "faces")
    size, body = list_body(read_foam_file(path), path)
    faces = [[int(i) for i in f.split()] for f in re.findall(r"\d+\s*\(([^()]*)\)", body)]
    if len(faces) != size:
        sys.exit(f"writeTwistDisplacement.py: {path} says {size} faces but holds {len(faces)}")
    return faces


def read_boundary(mesh):
    text = read_foam_file(os.path.join(mesh, "boundary"))
    patches = {}
    for name, body in re.findall(r"(\w+)\s*\{([^}]*)\}", text):
        entries = dict(re.findall(r"(\w+)\s+([^;]+);", body))
        patches[name] = (int(entries["startFace"]), int(entries["nFaces"]))
    return patches


def patch_mesh_points(faces, start, size):
    """OpenFOAM's PrimitivePatch::meshPoints: point labels in order of first appearance."""
    seen, order = set(), []
    for face in faces[start:start + size]:
        for point in face:
            if point not in seen:
                seen.add(point)
                order.append(point)
    return order


def twist(point):
    """Displacement of `point` by eq. 4.1."""
    x, y, z = point
    theta = math.radians(TWIST_DEGREES) * y / HEIGHT
    c, s = math.cos(theta), math.sin(theta)
    return (x * c + z * s - x, 0.0, -x * s + z * c - z)


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "."
    mesh = os.path.join(case, "constant", "polyMesh")
    points, faces, patches = read_points(mesh), read_faces(mesh), read_boundary(mesh)
    start, size = patches["sides"]
    sides = [twist(points[i]) for i in patch_mesh_points(faces, start, size)]
    values = "\n".join(f"({u[0]:.15g} {u[1]:.15g} {u[2]:.15g})" for u in sides)
    omega = math.radians(TWIST_DEGREES)
    with open(os.path.join(case, "0", "pointDisplacement"), "w", encoding="ascii") as out:
        out.write(f"""/*--------------------------------*- C++ -*----------------------------------*\\
  The twist of the thesis' eq. 4.1: every plane y = const turns about the y
  axis by theta = 30 y degrees (bottom fixed, top 30 degrees), counter-
  clockwise seen from above (+y). Reached at t = 1 (one time step).
  Written by meshGeneration/writeTwistDisplacement.py for this mesh: the
  values of the patch `sides` follow OpenFOAM's order of the patch points.
\\*---------------------------------------------------------------------------*/
FoamFile
{{
    version     2.0;
    format      ascii;
    class       pointVectorField;
    location    "0";
    object      pointDisplacement;
}}

dimensions      [0 1 0 0 0 0 0];

internalField   uniform (0 0 0);

boundaryField
{{
    bottom
    {{
        type            fixedValue;
        value           uniform (0 0 0);
    }}

    top
    {{
        type                    solidBodyMotionDisplacement;
        solidBodyMotionFunction rotatingMotion;
        rotatingMotionCoeffs
        {{
            origin      (0 0 0);
            axis        (0 1 0);
            omega       {omega:.15g};   // {TWIST_DEGREES:g} degrees per second
        }}
        value           uniform (0 0 0);
    }}

    sides
    {{
        type            fixedValue;
        value           nonuniform List<vector>
{len(sides)}
(
{values}
)
;
    }}
}}
""")
    print(f"0/pointDisplacement written: {len(sides)} values on patch sides")


if __name__ == "__main__":
    main()
