#!/usr/bin/env python3
"""Measurements of one run of scripts/openfoamTutorials.sh (standard library only).

  analyse.py run RUNDIR CLASSIFY_FIELD      one motion run (moveDynamicMesh + checkMesh logs,
                                            the written time folders); prints key=value lines
  analyse.py baseline RUNDIR                the same loop on the mesh held still: CPU per step
  analyse.py report WORK CASES EXPECTATIONS TABLE COMMIT DATE MACHINE COMMAND SECONDS PLUGIN EMPTY
                                            the checks against the expectations, one line per
                                            case, the Markdown table (TABLE, or - for none);
                                            exit status 1 when a check expected to pass failed

RUNDIR holds the case (constant/polyMesh, the time folders) and the logs log.moveDynamicMesh
and log.checkMesh. CLASSIFY_FIELD is the 0/pointDisplacement whose patch types say which
patches are checked for staying in their planes (the same file for both solvers' runs).

Rules (docs/openfoamTutorials.md):
  steps      time steps moveDynamicMesh completed (an ExecutionTime line after the step);
  inverted   the largest count of negative-volume cells (checkMesh's, at every written time,
             and moveDynamicMesh's own check after every step) or of rbm's "inverted N";
  nonOrth    the worst "Mesh non-orthogonality Max" of checkMesh over the written times;
  planes     every patch of type empty or wedge, and every patch whose pointDisplacement type
             is slip, symmetry, symmetryPlane, fixedNormalSlip, zeroGradient or calculated, is
             split into planes (faces with the same unit normal and offset, 1e-9 of the domain);
             each plane of at least two faces that is flat to 1e-8 of the domain at t = 0 is
             checked: the largest displacement of its points along the plane's normal,
             |n . (x(t) - x(0))|, over the written times;
  axis       with two wedge patches: the points both patches share (the axis), their largest
             displacement off the axis direction (the two planes' normals' cross product),
             |(x(t) - x(0)) x a|, over the written times;
  cost       CPU seconds per step: the mean increment of ExecutionTime over the steps that
             wrote nothing, the first step left out (it includes the set-up).
"""
import gzip
import math
import os
import re
import struct
import sys

SLIDING_OR_FREE = {"slip", "symmetry", "symmetryPlane", "fixedNormalSlip", "zeroGradient",
                   "calculated"}
PLANE_PATCH_TYPES = {"empty", "wedge"}


def read_bytes(path):
    if os.path.exists(path):
        with open(path, "rb") as f:
            return f.read()
    if os.path.exists(path + ".gz"):
        with gzip.open(path + ".gz", "rb") as f:
            return f.read()
    raise FileNotFoundError(path)


def header(data):
    """The FoamFile dictionary's entries and the offset just after it."""
    start = data.find(b"FoamFile")
    if start < 0:
        return {}, 0
    end = data.find(b"}", start)
    entries = {}
    for line in data[start:end].decode("latin-1").splitlines():
        m = re.match(r"\s*(\w+)\s+\"?([^;\"]*)\"?;", line)
        if m:
            entries[m.group(1)] = m.group(2).strip()
    return entries, end + 1


def skip_comments(data, pos):
    while True:
        while pos < len(data) and data[pos:pos + 1].isspace():
            pos += 1
        if data.startswith(b"//", pos):
            pos = data.find(b"\n", pos) + 1
        elif data.startswith(b"/*", pos):
            pos = data.find(b"*/", pos) + 2
        else:
            return pos


def read_count(data, pos):
    pos = skip_comments(data, pos)
    m = re.compile(rb"(\d+)\s*").match(data, pos)
    return int(m.group(1)), m.end()


def label_format(hdr):
    m = re.search(r"label=(\d+)", hdr.get("arch", ""))
    return ("<i", 4) if not m or m.group(1) == "32" else ("<q", 8)


def read_binary_list(data, pos, fmt, size, per_item):
    """N ( raw bytes ) → list of numbers and the offset after ')'."""
    n, pos = read_count(data, pos)
    if data[pos:pos + 1] != b"(":
        raise ValueError("expected '(' at offset %d" % pos)
    pos += 1
    count = n * per_item
    values = struct.unpack_from("<%d%s" % (count, fmt[1:]), data, pos)
    pos += count * size
    if data[pos:pos + 1] != b")":
        raise ValueError("expected ')' at offset %d" % pos)
    return list(values), pos + 1


def read_points(path):
    data = read_bytes(path)
    hdr, pos = header(data)
    if hdr.get("format", "ascii") == "binary":
        values, _ = read_binary_list(data, pos, "<d", 8, 3)
        return [tuple(values[i:i + 3]) for i in range(0, len(values), 3)]
    n, pos = read_count(data, pos)
    body = data[pos:].decode("latin-1")
    nums = re.findall(r"\(\s*([^\s()]+)\s+([^\s()]+)\s+([^\s()]+)\s*\)", body)
    if len(nums) < n:
        raise ValueError("%s: %d points, expected %d" % (path, len(nums), n))
    return [(float(a), float(b), float(c)) for a, b, c in nums[:n]]


def read_faces(path):
    data = read_bytes(path)
    hdr, pos = header(data)
    cls = hdr.get("class", "faceList")
    if hdr.get("format", "ascii") == "binary" or cls == "faceCompactList":
        fmt, size = label_format(hdr)
        if hdr.get("format", "ascii") == "binary":
            offsets, pos = read_binary_list(data, pos, fmt, size, 1)
            labels, _ = read_binary_list(data, pos, fmt, size, 1)
        else:
            n, pos = read_count(data, pos)
            end = data.find(b")", pos)
            offsets = [int(x) for x in data[pos + 1:end].split()]
            n2, pos = read_count(data, end + 1)
            end2 = data.find(b")", pos)
            labels = [int(x) for x in data[pos + 1:end2].split()]
        return [labels[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
    n, pos = read_count(data, pos)
    body = data[pos:].decode("latin-1")
    faces = [[int(x) for x in m.split()] for m in re.findall(r"\d+\s*\(([\d\s]+)\)", body)]
    return faces[:n]


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def dictionary_entries(text):
    """Top-level `name { ... }` blocks of a text: name → body."""
    out, pos = {}, 0
    pattern = re.compile(r"\s*(\"[^\"]*\"|[^\s{};]+)\s*\{")
    while True:
        m = pattern.search(text, pos)
        if not m:
            return out
        depth, i = 1, m.end()
        while depth and i < len(text):
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        out[m.group(1).strip('"')] = text[m.end():i - 1]
        pos = i


def read_boundary(path):
    text = strip_comments(read_bytes(path).decode("latin-1"))
    hdr_end = text.find("}", text.find("FoamFile"))
    body = text[hdr_end + 1:]
    body = body[body.find("(") + 1:body.rfind(")")]
    patches = []
    for name, entry in dictionary_entries(body).items():
        get = lambda key: re.search(r"\b%s\s+([^;]+);" % key, entry).group(1).strip()
        patches.append({"name": name, "type": get("type"), "nFaces": int(get("nFaces")),
                        "startFace": int(get("startFace"))})
    return patches


def field_patch_types(path):
    """0/pointDisplacement: patch name or regular expression → type."""
    text = strip_comments(read_bytes(path).decode("latin-1"))
    m = re.search(r"\bboundaryField\s*\{", text)
    if not m:
        return {}
    body = text[m.end():]
    types = {}
    for name, entry in dictionary_entries(body).items():
        t = re.search(r"\btype\s+([^;\s]+)\s*;", entry)
        if t:
            types[name] = t.group(1)
    return types


def type_of(patch, types):
    if patch in types:
        return types[patch]
    for key, value in types.items():
        if re.fullmatch(key, patch):
            return value
    return None


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return (a[0] / n, a[1] / n, a[2] / n) if n > 0 else (0.0, 0.0, 0.0)


def face_normal(points, face):
    """Newell's normal (area-weighted) and the mean of the face's points."""
    n = [0.0, 0.0, 0.0]
    c = [0.0, 0.0, 0.0]
    for i, a in enumerate(face):
        p, q = points[a], points[face[(i + 1) % len(face)]]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
        for k in range(3):
            c[k] += p[k] / len(face)
    return unit(tuple(n)), tuple(c)


def time_dirs(case):
    out = []
    for name in os.listdir(case):
        try:
            value = float(name)
        except ValueError:
            continue
        if value > 0 and (os.path.exists(os.path.join(case, name, "polyMesh", "points"))
                          or os.path.exists(os.path.join(case, name, "polyMesh", "points.gz"))):
            out.append((value, name))
    return [name for _, name in sorted(out)]


def planes_and_axis(case, classify_field):
    points0 = read_points(os.path.join(case, "constant", "polyMesh", "points"))
    faces = read_faces(os.path.join(case, "constant", "polyMesh", "faces"))
    patches = read_boundary(os.path.join(case, "constant", "polyMesh", "boundary"))
    types = field_patch_types(classify_field)
    lo = [min(p[k] for p in points0) for k in range(3)]
    hi = [max(p[k] for p in points0) for k in range(3)]
    size = norm(sub(tuple(hi), tuple(lo)))
    planes = []  # (patch name, normal, offset, point labels)
    wedge_planes = []
    for patch in patches:
        ptype = patch["type"]
        ftype = type_of(patch["name"], types)
        if not (ptype in PLANE_PATCH_TYPES or ftype in SLIDING_OR_FREE) or patch["nFaces"] == 0:
            continue
        clusters = []  # [normal, offset, faces]
        for f in range(patch["startFace"], patch["startFace"] + patch["nFaces"]):
            n, c = face_normal(points0, faces[f])
            for cl in clusters:
                if abs(dot(n, cl[0])) > 1 - 1e-10 and abs(dot(cl[0], c) - cl[1]) < 1e-9 * size:
                    cl[2].append(f)
                    break
            else:
                clusters.append([n, dot(n, c), [f]])
        for n, _, fs in clusters:
            if len(fs) < 2:
                continue
            labels = sorted({p for f in fs for p in faces[f]})
            offset = sum(dot(n, points0[p]) for p in labels) / len(labels)
            flatness = max(abs(dot(n, points0[p]) - offset) for p in labels)
            if flatness > 1e-8 * size:
                continue
            planes.append((patch["name"], n, offset, labels))
            if ptype == "wedge":
                wedge_planes.append((n, labels))
    axis = None
    if len(wedge_planes) >= 2:
        (n1, labels1), (n2, labels2) = wedge_planes[0], wedge_planes[1]
        direction = cross(n1, n2)
        on_axis = sorted(set(labels1) & set(labels2))
        if norm(direction) > 1e-12 and on_axis:
            axis = (unit(direction), on_axis)
    return size, planes, axis, len(points0)


def deviations(case, classify_field):
    size, planes, axis, npoints = planes_and_axis(case, classify_field)
    worst_plane = (0.0, "-", "-")
    worst_axis = (0.0, "-")
    points0 = read_points(os.path.join(case, "constant", "polyMesh", "points"))
    by_patch = {}
    for name in time_dirs(case):
        pts = read_points(os.path.join(case, name, "polyMesh", "points"))
        if len(pts) != npoints:
            continue
        for patch, n, offset, labels in planes:
            d = max(abs(dot(n, sub(pts[p], points0[p]))) for p in labels)
            by_patch[patch] = max(by_patch.get(patch, 0.0), d)
            if d > worst_plane[0]:
                worst_plane = (d, patch, name)
        if axis:
            direction, on_axis = axis
            d = max(norm(cross(sub(pts[p], points0[p]), direction)) for p in on_axis)
            if d > worst_axis[0]:
                worst_axis = (d, name)
    out = {"domainSize": "%.6g" % size, "planesChecked": len(planes),
           "planeDev": "%.3e" % worst_plane[0], "planeDevRel": "%.3e" % (worst_plane[0] / size),
           "planeDevPatch": worst_plane[1], "planeDevTime": worst_plane[2],
           "planeDevByPatch": ",".join("%s:%.1e" % kv for kv in sorted(by_patch.items())) or "-"}
    if axis:
        out.update({"axisPoints": len(axis[1]), "axisDev": "%.3e" % worst_axis[0],
                    "axisDevRel": "%.3e" % (worst_axis[0] / size), "axisDevTime": worst_axis[1]})
    else:
        out.update({"axisPoints": 0, "axisDev": "-", "axisDevRel": "-"})
    return out


def move_log(path):
    """Completed steps (time name, cumulative ExecutionTime), rbm's wall times, inverted counts,
    moveDynamicMesh's own check (negative volumes, non-orthogonality) and the fatal error."""
    steps, walls, inverted, step_nonorth, fatal = [], [], 0, 0.0, ""
    current = None
    lines = read_bytes(path).decode("latin-1").splitlines() if os.path.exists(path) else []
    for i, line in enumerate(lines):
        m = re.match(r"^Time = (\S+)\s*$", line)
        if m:
            current = m.group(1)
            continue
        m = re.search(r"sub-steps.*inverted\s+(\d+)\s+wall\s+([0-9.eE+-]+) s", line)
        if m:
            inverted = max(inverted, int(m.group(1)))
            walls.append(float(m.group(2)))
            continue
        m = re.search(r"Number of negative volume cells: (\d+)", line)
        if m:
            inverted = max(inverted, int(m.group(1)))
        m = re.search(r"has (\d+) inverted cells", line)
        if m:
            inverted = max(inverted, int(m.group(1)))
        m = re.search(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)", line)
        if m:
            step_nonorth = max(step_nonorth, float(m.group(1)))
        m = re.match(r"^ExecutionTime = ([0-9.eE+-]+) s", line)
        if m and current is not None:
            steps.append((current, float(m.group(1))))
            current = None
        if "FOAM FATAL" in line and not fatal:
            words = []
            for l in lines[i + 1:i + 6]:
                if l.strip().startswith(("From function", "From ", "in file")):
                    break
                words.append(l.strip())
            fatal = " ".join(w for w in words if w)
    return steps, walls, inverted, step_nonorth, fatal


def cost_per_step(steps, written):
    incs = [steps[i][1] - steps[i - 1][1] for i in range(1, len(steps))
            if steps[i][0] not in written]
    return (sum(incs) / len(incs), len(incs)) if incs else (float("nan"), 0)


def check_mesh_log(path):
    """checkMesh over the written times (blocks "Time = <t>", t > 0; not constant or 0)."""
    worst, negative, pyramids, times, failed = 0.0, 0, 0, 0, 0
    counting = False
    if os.path.exists(path):
        for line in read_bytes(path).decode("latin-1").splitlines():
            m = re.match(r"^Time = (\S+)", line)
            if m:
                counting = num(m.group(1), 0.0) > 0
                times += counting
                continue
            if not counting:
                continue
            m = re.search(r"Mesh non-orthogonality Max: ([0-9.eE+-]+)", line)
            if m:
                worst = max(worst, float(m.group(1)))
            m = re.search(r"Number of negative volume cells: (\d+)", line)
            if m:
                negative = max(negative, int(m.group(1)))
            m = re.search(r"Error in face pyramids: (\d+) faces", line)
            if m:
                pyramids = max(pyramids, int(m.group(1)))
            if re.search(r"Failed \d+ mesh checks", line):
                failed += 1
    return worst, negative, pyramids, times, failed


def median(values):
    v = sorted(values)
    if not v:
        return float("nan")
    return v[len(v) // 2] if len(v) % 2 else 0.5 * (v[len(v) // 2 - 1] + v[len(v) // 2])


PLANE_TOLERANCE = 1e-8      # of the domain size (bounding-box diagonal): planes and axis
NON_ORTH_MARGIN = 0.5       # degrees rbm's worst max non-orthogonality may exceed OpenFOAM's
TABLE_BEGIN = "<!-- openfoamTutorials table begin -->"
TABLE_END = "<!-- openfoamTutorials table end -->"


def key_values(path):
    out = {}
    if os.path.exists(path):
        for line in open(path, encoding="latin-1"):
            if "=" in line:
                k, v = line.rstrip("\n").split("=", 1)
                out[k] = v
    return out


def read_expectations(path):
    out = {}
    for line in open(path, encoding="utf-8"):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split(None, 3)
        if len(parts) < 3 or parts[2] not in ("pass", "knownMiss"):
            raise SystemExit("%s: bad line '%s' (expected: <case> <check> pass | knownMiss <reason>)"
                             % (path, line))
        out[(parts[0], parts[1])] = (parts[2], parts[3] if len(parts) > 3 else "")
    return out


def num(value, default=float("nan")):
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def coupled_patches(case):
    """The patches rbm refuses: coupled or interface types other than plain cyclic."""
    try:
        return [p["name"] for p in read_boundary(os.path.join(case, "constant", "polyMesh", "boundary"))
                if p["type"] != "cyclic"
                and ("cyclic" in p["type"] or "AMI" in p["type"] or p["type"].startswith("nonConformal"))]
    except (OSError, ValueError, AttributeError):
        return []


def fatal_text(log):
    if not os.path.exists(log):
        return ""
    text = read_bytes(log).decode("latin-1")
    at = text.find("FOAM FATAL")
    return text[at:text.find("FOAM exiting", at) if "FOAM exiting" in text[at:] else len(text)] if at >= 0 else ""


def evaluate(name, work):
    """[(check, passed, value words)] and the row's measurements."""
    d = os.path.join(work, name)
    meta = key_values(os.path.join(d, "meta"))
    rbm = key_values(os.path.join(d, "rbm", "result"))
    ofr = key_values(os.path.join(d, "openfoam", "result"))
    static = key_values(os.path.join(d, "static", "result"))
    planned = int(meta.get("planned", 0))
    checks = []
    if meta.get("meshError"):
        return meta, rbm, ofr, static, [("mesh", False, "mesh generation failed: %s/log.mesh" % d)]
    if meta.get("kind") == "refuse":
        fatal = fatal_text(os.path.join(d, "rbm", "log.moveDynamicMesh"))
        named = [p for p in coupled_patches(os.path.join(d, "rbm")) if ("patch " + p) in fatal]
        ok = rbm.get("rc", "0") != "0" and bool(named)
        first = " ".join(fatal.split())[:160]
        checks.append(("refused", ok, "exit %s, %s" % (rbm.get("rc", "?"),
                       ("FatalError naming " + ", ".join(named)) if ok else
                       ("no FatalError naming a coupled patch" + (": " + first if first else "")))))
        return meta, rbm, ofr, static, checks
    ofSteps, rbmSteps = int(ofr.get("steps", 0)), int(rbm.get("steps", 0))
    checks.append(("reference", ofSteps == planned and ofr.get("rc") == "0",
                   "OpenFOAM's solver %d/%d steps, exit %s" % (ofSteps, planned, ofr.get("rc", "?"))))
    checks.append(("steps", rbmSteps == planned and rbm.get("rc") == "0",
                   "%d/%d steps, exit %s" % (rbmSteps, planned, rbm.get("rc", "?"))))
    # Nothing measured (no step ran, no time written) is a failure, never a pass.
    ran = rbmSteps > 0
    written = int(rbm.get("checkedTimes", 0)) > 0
    none = " (nothing measured: rbm ran no step)" if not ran else \
        (" (nothing measured: rbm wrote no time)" if not written else "")
    inv = int(rbm.get("inverted", 0)) + int(rbm.get("pyramidErrors", 0))
    checks.append(("valid", ran and inv == 0, "%s inverted cells, %s wrongly oriented face pyramids%s"
                   % (rbm.get("inverted", "?"), rbm.get("pyramidErrors", "?"),
                      none if not ran else "")))
    rel = num(rbm.get("planeDevRel"))
    checks.append(("planes", written and rel <= PLANE_TOLERANCE,
                   "%s m off %s (%s of the domain; tolerance %g)%s"
                   % (rbm.get("planeDev"), rbm.get("planeDevPatch"), rbm.get("planeDevRel"),
                      PLANE_TOLERANCE, none)))
    if int(rbm.get("axisPoints", 0)) > 0:
        rel = num(rbm.get("axisDevRel"))
        checks.append(("axis", written and rel <= PLANE_TOLERANCE,
                       "%s m off the axis (%s of the domain)%s"
                       % (rbm.get("axisDev"), rbm.get("axisDevRel"), none)))
    a, b = num(rbm.get("nonOrth")), num(ofr.get("nonOrth"))
    checks.append(("nonOrthogonality", written and a <= b + NON_ORTH_MARGIN,
                   "%.2f° against OpenFOAM's %.2f° (margin %.1f°)%s" % (a, b, NON_ORTH_MARGIN, none)))
    return meta, rbm, ofr, static, checks


def motion_cost(run, static):
    raw = num(run.get("cpuPerStep"))
    if int(run.get("costSteps", 0)) == 0:
        return float("nan")
    base = num(static.get("cpuPerStep"), 0.0)
    return raw - (base if base == base else 0.0)


def deg(value):
    return "–" if value in (None, "", "-") else value + "°"


def fmt_dev(r, key):
    if r.get(key, "-") in ("-", ""):
        return "–"
    return "%.1e m (%.0e)" % (num(r.get(key)), num(r.get(key + "Rel")))


def report(argv):
    work, cases, expectations_path, table_path, commit, date, machine, command, seconds, plugin, empty, coeffs, diffusivity = argv
    expectations = read_expectations(expectations_path)
    status = 0
    rows = []
    loud = []
    for name in cases.split(","):
        meta, rbm, ofr, static, checks = evaluate(name, work)
        words = []
        for check, ok, value in checks:
            expected, reason = expectations.get((name, check), ("pass", ""))
            if ok and expected == "pass":
                verdict = "pass"
            elif ok:
                verdict = "NOW PASSES, update expectations"
                loud.append("%s %s: NOW PASSES, update expectations (%s; was knownMiss: %s)"
                            % (name, check, value, reason))
            elif expected == "knownMiss":
                verdict = "knownMiss"
            else:
                verdict = "FAIL"
                status = 1
            if (name, check) not in expectations:
                verdict += " (no expectation line: pass expected)"
            words.append((check, verdict, value))
        kind = meta.get("kind", "run")
        if kind == "refuse":
            line = "%s: rbm %s" % (name, "; ".join("%s %s: %s" % (c, v, val) for c, v, val in words))
            rows.append("| %s | %s | refused? | – | – | – | – | – | – | – | %s |" % (
                name, meta.get("cells", "?"),
                "; ".join("%s: **%s** (%s)" % (c, v, val) for c, v, val in words)))
            rows[-1] = rows[-1].replace("refused?", "%s / – (of %s)" % (rbm.get("steps", "0"), meta.get("planned")))
            print(line)
            continue
        if int(rbm.get("steps", 0)) == 0 or int(rbm.get("checkedTimes", 0)) == 0:
            rbm = dict(rbm, nonOrth="-", planeDev="-", axisDev="-", planeDevByPatch="-")
        cr, co = motion_cost(rbm, static), motion_cost(ofr, static)
        ratio = cr / co if cr == cr and co == co and co > 0 else float("nan")
        secs = lambda v: "–" if v != v else "%.4f s" % v
        cost = "%s / %s" % (secs(cr), secs(co))
        ratio_text = "–" if ratio != ratio else "%.2f" % ratio
        wall = "–" if rbm.get("rbmWallPerStep", "-") == "-" else "%s s (%s s)" % (
            rbm.get("rbmWallPerStep"), rbm.get("rbmWallMedian"))
        line = ("%s: %s cells; steps rbm %s / OpenFOAM %s of %s; inverted %s / %s; worst non-orth "
                "%s / %s; off planes %s / %s; off axis %s / %s; motion CPU per step %s (ratio %s); "
                "rbm's wall per step, mean (median): %s; %s" % (
                    name, meta.get("cells"), rbm.get("steps"), ofr.get("steps"), meta.get("planned"),
                    rbm.get("inverted"), ofr.get("inverted"), deg(rbm.get("nonOrth")), deg(ofr.get("nonOrth")),
                    fmt_dev(rbm, "planeDev"), fmt_dev(ofr, "planeDev"), fmt_dev(rbm, "axisDev"),
                    fmt_dev(ofr, "axisDev"), cost, ratio_text, wall,
                    "; ".join("%s %s" % (c, v) for c, v, _ in words)))
        line += "; off planes by patch, rbm: %s, OpenFOAM: %s" % (rbm.get("planeDevByPatch"),
                                                                  ofr.get("planeDevByPatch"))
        if rbm.get("fatal", "-") != "-":
            line += "; rbm stopped: " + rbm["fatal"].replace("_", " ")
        print(line)
        failing = ["%s: %s" % (c, v) for c, v, _ in words if v != "pass"]
        rows.append("| %s | %s | %s / %s (of %s) | %s / %s | %s / %s | %s / %s | %s / %s | %s | %s | %s | %s |" % (
            name, meta.get("cells"), rbm.get("steps"), ofr.get("steps"), meta.get("planned"),
            rbm.get("inverted"), ofr.get("inverted"), deg(rbm.get("nonOrth")), deg(ofr.get("nonOrth")),
            fmt_dev(rbm, "planeDev"), fmt_dev(ofr, "planeDev"), fmt_dev(rbm, "axisDev"),
            fmt_dev(ofr, "axisDev"), cost, ratio_text, wall,
            "all pass" if not failing else "; ".join(failing)))
    for message in loud:
        print("*** " + message)
    print("openfoamTutorials: %s (%s s)" % ("FAILED: a check expected to pass failed" if status
                                             else "OK: every check expected to pass passed", seconds))
    if table_path != "-":
        text = "\n".join([
            TABLE_BEGIN,
            "Generated by `scripts/openfoamTutorials.sh` (do not edit by hand): rbm %s, %s, %s; "
            "plugin %s%s. Suite wall time %s s. Regenerate with:" % (
                commit, date, machine, plugin,
                (" (with `--emptyCoeffs`: the plugin did not accept the old solvers' entries)" if empty == "1"
                 else " (rbm with `rigidBodyMotionSolverCoeffs { %s }`, not its defaults)" % coeffs if coeffs
                 else "") + (" (OpenFOAM's runs with `diffusivity %s;`, not the tutorials' own)" % diffusivity
                              if diffusivity else ""), seconds),
            "",
            "```sh",
            command,
            "```",
            "",
            "| case | cells | steps rbm / OpenFOAM | inverted cells rbm / OpenFOAM | worst max "
            "non-orthogonality rbm / OpenFOAM | max off planes rbm / OpenFOAM (m, of the domain) | "
            "max off the wedge axis rbm / OpenFOAM | motion CPU per step rbm / OpenFOAM | ratio | "
            "rbm's own wall per step: mean (median) | checks not passing |",
            "|---|---|---|---|---|---|---|---|---|---|---|",
        ] + rows + [TABLE_END]) + "\n"
        old = open(table_path, encoding="utf-8").read() if os.path.exists(table_path) else ""
        if TABLE_BEGIN in old and TABLE_END in old:
            text = old[:old.find(TABLE_BEGIN)] + text.rstrip("\n") + old[old.find(TABLE_END) + len(TABLE_END):]
        with open(table_path, "w", encoding="utf-8") as f:
            f.write(text)
    return status


def main():
    if sys.argv[1] == "report":
        sys.exit(report(sys.argv[2:]))
    mode, case = sys.argv[1], sys.argv[2]
    steps, walls, inverted, step_nonorth, fatal = move_log(os.path.join(case, "log.moveDynamicMesh"))
    written = set(time_dirs(case))
    cost, ncost = cost_per_step(steps, written)
    out = {"steps": len(steps), "cpuPerStep": "%.4f" % cost, "costSteps": ncost}
    if mode == "run":
        worst, negative, pyramids, times, failed = check_mesh_log(os.path.join(case, "log.checkMesh"))
        out.update({"inverted": max(inverted, negative), "pyramidErrors": pyramids,
                    "nonOrth": "%.2f" % worst, "nonOrthEveryStep": "%.2f" % step_nonorth,
                    "checkedTimes": times, "failedChecks": failed,
                    "rbmWallPerStep": "%.4f" % (sum(walls[1:]) / (len(walls) - 1)) if len(walls) > 1 else "-",
                    "rbmWallMedian": "%.4f" % median(walls[1:]) if len(walls) > 1 else "-",
                    "fatal": fatal.replace(" ", "_")[:300] or "-"})
        out.update(deviations(case, sys.argv[3]))
    for key, value in out.items():
        print("%s=%s" % (key, value))


if __name__ == "__main__":
    main()
