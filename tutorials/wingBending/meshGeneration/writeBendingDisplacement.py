#!/usr/bin/env python3
"""Writes 0/pointDisplacement of the wingBending tutorial: the bending of the thesis' eq. 4.2.

The wing bends in y in proportion to the square of the spanwise coordinate z:
    x_new = x,   y_new = y + alpha z^2,   z_new = z        (4.2a-c), alpha = 0.1
so the root (z = 0, on the symmetry plane) stays and the tip (z = 1.5) rises by 0.225 chord.

  wing            fixedValue nonuniform List<vector>: eq. 4.2 evaluated at every point of
                  the patch, listed in OpenFOAM's order of the patch points (localPoints:
                  the order of first appearance walking the patch's faces), which is why
                  this script reads the mesh
  symmetryPlane   symmetryPlane: points slide in the plane z = 0
  farfield        fixedValue uniform (0 0 0)

Usage: writeBendingDisplacement.py [caseDirectory]   (run after the mesh is written)
"""
import gzip
import os
import re
import sys

ALPHA = 0.1   # eq. 4.2b


def read_foam_file(path):
    """Text of an ascii OpenFOAM file (path or path.gz) without comments and FoamFile header."""
    if os.path.exists(path):
        text = open(path, encoding="ascii").read()
    elif os.path.exists(path + ".gz"):
        text = gzip.open(path + ".gz", "rt", encoding="ascii").read()
    else:
        sys.exit(f"writeBendingDisplacement.py: {path} not found")
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    header = re.search(r"FoamFile\s*\{([^}]*)\}", text)
    if header and re.search(r"format\s+binary", header.group(1)):
        sys.exit(f"writeBendingDisplacement.py: {path} is binary; convert it with foamFormatConvert to ascii first")
    return text[header.end():] if header else text


def list_body(text, path):
    """Contents of the first top-level list 'N ( ... )' and its size N."""
    match = re.search(r"(\d+)\s*\(", text)
    if not match:
        sys.exit(f"writeBendingDisplacement.py: no list in {path}")
    return int(match.group(1)), text[match.end():text.rindex(")")]


def read_points(mesh):
    path = os.path.join(mesh, "points")
    size, body = list_body(read_foam_file(path), path)
    points = [tuple(float(c) for c in p) for p in re.findall(r"\(\s*(\S+)\s+(\S+)\s+(\S+)\s*\)", body)]
    if len(points) != size:
        sys.exit(f"writeBendingDisplacement.py: {path} says {size} points but holds {len(points)}")
    return points


def read_faces(mesh):
    path = os.path.join(mesh, "faces")
    size, body = list_body(read_foam_file(path), path)
    faces = [[int(i) for i in f.split()] for f in re.findall(r"\d+\s*\(([^()]*)\)", body)]
    if len(faces) != size:
        sys.exit(f"writeBendingDisplacement.py: {path} says {size} faces but holds {len(faces)}")
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


def bending(point):
    """Displacement of `point` by eq. 4.2."""
    z = point[2]
    return (0.0, ALPHA * z * z, 0.0)


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "."
    mesh = os.path.join(case, "constant", "polyMesh")
    points, faces, patches = read_points(mesh), read_faces(mesh), read_boundary(mesh)
    start, size = patches["wing"]
    wing_points = patch_mesh_points(faces, start, size)
    wing = [bending(points[i]) for i in wing_points]
    tip = max(points[i][2] for i in wing_points)
    values = "\n".join(f"({u[0]:.15g} {u[1]:.15g} {u[2]:.15g})" for u in wing)
    with open(os.path.join(case, "0", "pointDisplacement"), "w", encoding="ascii") as out:
        out.write(f"""/*--------------------------------*- C++ -*----------------------------------*\\
  The bending of the thesis' eq. 4.2: the wing's points move by
  (0, {ALPHA:g} z^2, 0), the tip (z = {tip:g}) by {ALPHA * tip * tip:g} chord, at t = 1
  (one time step).
  Written by meshGeneration/writeBendingDisplacement.py for this mesh: the
  values of the patch `wing` follow OpenFOAM's order of the patch points.
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
    wing
    {{
        type            fixedValue;
        value           nonuniform List<vector>
{len(wing)}
(
{values}
)
;
    }}

    symmetryPlane
    {{
        type            symmetryPlane;
    }}

    farfield
    {{
        type            fixedValue;
        value           uniform (0 0 0);
    }}
}}
""")
    print(f"0/pointDisplacement written: {len(wing)} values on patch wing")


if __name__ == "__main__":
    main()
