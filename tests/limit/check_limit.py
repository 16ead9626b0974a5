"""Checks of voussoir-limit: check_limit.py EXE CASE [INPUT.nml]."""
import json
import math
import os
import re
import subprocess
import sys

exe, case = sys.argv[1], sys.argv[2]
nml = sys.argv[3] if len(sys.argv) > 3 else None
failures = []


def check(good, what):
    print(("PASS  " if good else "FAIL  ") + what)
    if not good:
        failures.append(what)


def run(*args):
    p = subprocess.run([exe, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def load(path):
    """The JSON of a good input: exit 0 and the whole of stdout is one object."""
    rc, out, err = run(path, "--json")
    check(rc == 0, f"{path}: exit code 0 (stderr: {err.strip()})")
    data = json.loads(out)
    check(isinstance(data, dict), f"{path}: stdout is one JSON object")
    return data


def close(a, b, rtol=0.0, atol=0.0):
    return abs(a - b) <= atol + rtol * abs(b)


def hinge_words(hinges):
    return ", ".join(f"joint {h['joint']} {h['side']}" for h in hinges)


def check_common(d, name):
    check_lp(d, name)
    keys = ["lambda_pos", "lambda_neg", "hinges_pos", "hinges_neg", "min_thickness_ratio_ext",
            "min_thickness_ratio_mean", "arch", "sliding"]
    check(all(k in d for k in keys), f"{name}: keys {keys}")
    a = d["arch"]
    n = a["n_voussoirs"]
    # The arch is symmetric: both directions carry the same load, mechanisms mirror (j <-> n - j).
    check(close(d["lambda_neg"], d["lambda_pos"], rtol=1e-9), f"{name}: lambda_neg = lambda_pos")
    mirror = [{"joint": n - h["joint"], "side": h["side"]} for h in reversed(d["hinges_pos"])]
    check(d["hinges_neg"] == mirror, f"{name}: the -x mechanism mirrors the +x one")
    for key in ("hinges_pos", "hinges_neg"):
        joints = [h["joint"] for h in d[key]]
        check(len(joints) == 4 and joints == sorted(set(joints)) and 0 <= joints[0] and joints[-1] <= n,
              f"{name}: {key} are four joints in 0..n from the left")
        check(all(h["side"] in ("intrados", "extrados") for h in d[key]), f"{name}: {key} sides named")
    # Joint end points from the conventions: joint j at 90 + embrace/2 - j embrace/n degrees.
    r_int = a["r_ext_m"] - a["thickness_m"]
    worst = 0.0
    for j in range(n + 1):
        ang = math.radians(90.0 + 0.5 * a["embrace_deg"] - j * a["embrace_deg"] / n)
        for r, key in ((r_int, "joint_intrados_xy_m"), (a["r_ext_m"], "joint_extrados_xy_m")):
            x, y = a[key][j]
            worst = max(worst, abs(x - r * math.cos(ang)), abs(y - r * math.sin(ang)))
    check(len(a["joint_intrados_xy_m"]) == n + 1 and len(a["joint_extrados_xy_m"]) == n + 1 and worst < 1e-12,
          f"{name}: joint end points follow the geometry conventions (error {worst:.1e} m)")
    check(all(isinstance(j, int) and 0 <= j <= n for j in d["sliding"]), f"{name}: sliding lists joints")
    if d["min_thickness_ratio_ext"] is not None:
        rho = d["min_thickness_ratio_ext"]
        check(close(d["min_thickness_ratio_mean"], rho / (1.0 - 0.5 * rho), rtol=1e-12),
              f"{name}: t/R_mean = t/R_ext / (1 - t/(2 R_ext))")
        hm = d["hinges_min_thickness"]
        check(hm == [{"joint": n - h["joint"], "side": h["side"]} for h in reversed(hm)],
              f"{name}: minimum-thickness hinges symmetric")


def centroid(poly):
    """Centroid of a polygon (shoelace)."""
    a = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        c = x0 * y1 - x1 * y0
        a += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
    return cx / (3 * a), cy / (3 * a)


def check_lp(d, name):
    """The LP keys; the four-hinge lambda where hinging governs, towards +x and -x;
    equilibrium of every voussoir in both directions."""
    for sfx, sign, exact, hinges in (("", 1.0, "lambda_pos", "hinges_pos"), ("_neg", -1.0, "lambda_neg", "hinges_neg")):
        check_lp_direction(d, name, sfx, sign, exact, hinges)


def check_lp_direction(d, name, sfx, sign, exact, hinges):
    """The LP keys ending in `sfx` (the acceleration towards +x for "", -x for "_neg",
    `sign`) against the four-hinge analysis of that direction (`exact`, `hinges`)."""
    keys = [k + sfx for k in ("load_factor", "load_factor_upper", "load_factor_nonassociative", "mechanism",
                              "contact_forces", "mechanism_nonassociative", "contact_forces_nonassociative")]
    check(all(k in d for k in keys + ["assembly"]), f"{name}: LP keys {keys}")
    lam = d["load_factor" + sfx]
    check(close(d["load_factor_upper" + sfx], lam, rtol=1e-6, atol=1e-9), f"{name}: LP{sfx} upper bound = lower bound")
    check(d["load_factor_nonassociative" + sfx] <= lam * (1 + 1e-9) + 1e-12,
          f"{name}: non-associative{sfx} <= associative{sfx}")
    moving = [(m["joint"], m["mode"], m["hinge_side"]) for m in d["mechanism" + sfx] if m["mode"] != "closed"]
    if not d["sliding"]:
        check(close(lam, d[exact], rtol=1e-6, atol=1e-9),
              f"{name}: load_factor{sfx} {lam} = {exact} {d[exact]} (hinging governs)")
        check(moving == [(h["joint"], "hinge", h["side"]) for h in d[hinges]],
              f"{name}: LP{sfx} mechanism {moving} = the four hinges of {hinges}")
    else:
        check(lam <= d[exact] * (1 + 1e-9), f"{name}: load_factor{sfx} <= {exact} where sliding governs")
        check(any(m[1] == "sliding" for m in moving), f"{name}: the LP{sfx} mechanism slides ({moving})")
    # Equilibrium of every voussoir i (body i, joints i-1 and i) under the JSON's contact
    # forces: they carry its weight W (so Fy = W) and lambda W towards sign x (so
    # Fx = -sign lambda Fy), both through its centroid (no moment about it).
    a = d["arch"]
    n = a["n_voussoirs"]
    worst = 0.0
    for i in range(1, n + 1):
        cx, cy = centroid(voussoir_polygon(a, i))
        fx, fy, m = contact_resultant(d, i, cx, cy, "contact_forces" + sfx)
        worst = max(worst, abs(fx + sign * lam * fy) / fy, abs(m) / (fy * a["r_ext_m"]))
    check(worst < 1e-6, f"{name}: every voussoir in equilibrium under the JSON's contact_forces{sfx} ({worst:.1e})")
    check(all(min(f["normal_n"]) >= -1e-9 * max(1.0, max(f["normal_n"])) for f in d["contact_forces" + sfx]),
          f"{name}: no tension at any interface end{sfx}")


def arch_point_load_lambda(a, weight, loads, fixed_joints=()):
    """The least load factor over the arch's four-hinge mechanisms (upper bounds by the
    work equation), independent of the LP: voussoirs i = 1..n between joints i-1 and i
    (rigid, no sliding), weights at their centroids, the live loads `loads` (a list of
    ((x, y), (fx, fy), voussoir)). Hinges at joints j1 < j2 < j3 < j4, each at the intrados or extrados end;
    segment A (j1..j2) turns about H1, C (j3..j4) about H4, B about the intersection of
    lines H1-H2 and H3-H4. A mechanism is admissible when every hinge joint opens at its
    other end; its lambda = -(power of the weights) / (power of the live load > 0).
    No hinge at the joints `fixed_joints` (a springing that cannot hinge)."""
    n = a["n_voussoirs"]
    ends = {"intrados": a["joint_intrados_xy_m"], "extrados": a["joint_extrados_xy_m"]}
    other = {"intrados": "extrados", "extrados": "intrados"}
    cents = []
    for i in range(1, n + 1):
        cents.append(centroid([a["joint_intrados_xy_m"][i - 1], a["joint_intrados_xy_m"][i],
                               a["joint_extrados_xy_m"][i], a["joint_extrados_xy_m"][i - 1]]))

    def cross(u, v):
        return u[0] * v[1] - u[1] * v[0]

    def vel(omega, c, p):   # velocity of p turning at omega about c
        return (-omega * (p[1] - c[1]), omega * (p[0] - c[0]))

    def meet(p1, p2, p3, p4):
        d1 = (p2[0] - p1[0], p2[1] - p1[1])
        d2 = (p4[0] - p3[0], p4[1] - p3[1])
        den = cross(d1, d2)
        if abs(den) < 1e-14:
            return None
        t = cross((p3[0] - p1[0], p3[1] - p1[1]), d2) / den
        return (p1[0] + t * d1[0], p1[1] + t * d1[1])

    best = math.inf
    import itertools
    for js in itertools.combinations([j for j in range(n + 1) if j not in fixed_joints], 4):
        for sides in itertools.product(("intrados", "extrados"), repeat=4):
            h = [ends[s][j] for s, j in zip(sides, js)]
            ib = meet(h[0], h[1], h[2], h[3])
            if ib is None:
                continue
            # omega_A = 1; compatibility at H2 and H3 (collinear points: ratios along the line).
            def ratio(p, c1, c2):   # (p - c1) = k (p - c2): k
                d = (p[0] - c2[0], p[1] - c2[1])
                dd = d[0] ** 2 + d[1] ** 2
                return ((p[0] - c1[0]) * d[0] + (p[1] - c1[1]) * d[1]) / dd if dd > 1e-28 else None
            k2 = ratio(h[1], h[0], ib)
            if k2 is None:
                continue
            om = {"A": 1.0, "B": k2}
            k3 = ratio(h[2], ib, h[3])
            if k3 is None:
                continue
            om["C"] = om["B"] * k3
            centre = {"A": h[0], "B": ib, "C": h[3]}

            def seg(i):   # voussoir i: its segment or None (fixed)
                if js[0] < i <= js[1]:
                    return "A"
                if js[1] < i <= js[2]:
                    return "B"
                if js[2] < i <= js[3]:
                    return "C"
                return None

            def v_at(i, p):
                s_ = seg(i)
                return (0.0, 0.0) if s_ is None else vel(om[s_], centre[s_], p)

            live = sum(f[0] * v_at(i, xy)[0] + f[1] * v_at(i, xy)[1] for xy, f, i in loads)
            dead = sum(-weight[i - 1] * v_at(i, cents[i - 1])[1] for i in range(1, n + 1))
            if abs(live) < 1e-12:
                continue
            sign = 1.0 if live > 0 else -1.0
            # Each hinge joint opens at its other end: relative velocity along the normal
            # from the left voussoir to the right one, n = (sin theta, -cos theta).
            good = True
            for s, j, hp in zip(sides, js, h):
                q = ends[other[s]][j]
                left, right = j, j + 1   # voussoirs on either side (0 and n + 1: the supports)
                vl = v_at(left, q) if 1 <= left <= n else (0.0, 0.0)
                vr = v_at(right, q) if 1 <= right <= n else (0.0, 0.0)
                ang = math.atan2(q[1], q[0])
                nrm = (math.sin(ang), -math.cos(ang))
                opening = sign * ((vr[0] - vl[0]) * nrm[0] + (vr[1] - vl[1]) * nrm[1])
                if opening <= 1e-12:
                    good = False
                    break
            if good:
                best = min(best, -dead / live)
    return best


def top_of_arch(a, x):
    """The extrados at x: the chord between the extrados corners on either side."""
    e = a["joint_extrados_xy_m"]
    for (x0, y0), (x1, y1) in zip(e, e[1:]):
        if min(x0, x1) <= x <= max(x0, x1):
            return y0 + (x - x0) * (y1 - y0) / (x1 - x0)
    return None


def check_loaded_equilibrium(d, name, weight, lam):
    """Every voussoir in equilibrium under the JSON's contact forces, its weight and
    lambda times the live point loads of the JSON (forces recomputed from &load)."""
    a = d["arch"]
    worst = 0.0
    scale = max(weight)
    for i in range(1, a["n_voussoirs"] + 1):
        cx, cy = centroid(voussoir_polygon(a, i))
        fx, fy, m = contact_resultant(d, i, cx, cy)
        fy -= weight[i - 1]
        for pl in d["point_loads"]:
            if pl["block"] != i:
                continue
            gx, gy = lam * pl["force_n"][0], lam * pl["force_n"][1]
            fx, fy = fx + gx, fy + gy
            m += (pl["xy_m"][0] - cx) * gy - (pl["xy_m"][1] - cy) * gx
        worst = max(worst, abs(fx) / scale, abs(fy) / scale, abs(m) / (scale * a["r_ext_m"]))
    check(worst < 1e-7, f"{name}: every voussoir in equilibrium with its weight, lambda x the point load "
                        f"and the JSON's contact forces ({worst:.1e})")


def voussoir_polygon(a, i):
    """Voussoir i of the JSON's arch: the quadrilateral between joints i - 1 and i."""
    return [a["joint_intrados_xy_m"][i - 1], a["joint_intrados_xy_m"][i], a["joint_extrados_xy_m"][i],
            a["joint_extrados_xy_m"][i - 1]]


def contact_resultant(d, i, cx, cy, key="contact_forces"):
    """(Fx, Fy, moment about (cx, cy)) of the JSON's contact forces (`key`) on block i: the
    normal force at each end of every interface it is part of, and the shear at its middle."""
    fx = fy = m = 0.0
    for f in d[key]:
        if i not in f["blocks"]:
            continue
        sign = 1.0 if f["blocks"][1] == i else -1.0
        nx, ny = f["normal"]
        tx, ty = -ny, nx
        (x1, y1), (x2, y2) = f["ends_xy_m"]
        for (px, py), (gx, gy) in (((x1, y1), (nx * f["normal_n"][0], ny * f["normal_n"][0])),
                                   ((x2, y2), (nx * f["normal_n"][1], ny * f["normal_n"][1])),
                                   (((x1 + x2) / 2, (y1 + y2) / 2), (tx * f["shear_n"], ty * f["shear_n"]))):
            fx += sign * gx
            fy += sign * gy
            m += sign * ((px - cx) * gy - (py - cy) * gx)
    return fx, fy, m


def nml_number(text, name):
    """The number given to `name` (a regular expression) in a namelist file's text."""
    return float(re.search(r"\b" + name + r" *= *([-0-9.eE+]+)", text).group(1))


def one_span_bridge(text):
    """A single segmental span's numbers from its &bridge text: span, rise, ring depth,
    voussoirs, the fill's level, the abutments' width and the strip's width."""
    number = lambda name: nml_number(text, name)  # noqa: E731
    return (number(r"span_m\(1\)"), number(r"rise_m\(1\)"), number("ring_thickness_m"), int(number("n_voussoirs")),
            number("fill_level_m"), number("abutment_width_m"), number("width_m"))


def segmental_extrados(span, rise, t, n):
    """The extrados ends of the joints of a segmental ring of n voussoirs (span and rise of
    its intrados, depth t), from the left springing: on the circle of radius R + t about the
    intrados' centre, R = (L^2/4 + r^2)/(2r), at n equal angles."""
    radius = (span ** 2 / 4 + rise ** 2) / (2 * rise)
    half = math.asin(span / 2 / radius)
    phis = [-half + 2 * half * k / n for k in range(n + 1)]
    return [(span / 2 + (radius + t) * math.sin(p), rise - radius + (radius + t) * math.cos(p)) for p in phis]


def top_y(blocks, x):
    """The top surface of the JSON's blocks at x: the highest point of any block's edge there."""
    best = None
    for b in blocks:
        v = b["vertices_xy_m"]
        for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]):
            if min(x0, x1) - 1e-9 <= x <= max(x0, x1) + 1e-9:
                y = max(y0, y1) if abs(x1 - x0) <= 1e-9 else y0 + (min(max((x - x0) / (x1 - x0), 0), 1)) * (y1 - y0)
                best = y if best is None else max(best, y)
    return best


def top_block(blocks, x):
    """The block (1-based) whose edge is the top surface at x, a free one where a free and a
    driven block meet there."""
    best, who = None, None
    for i, b in enumerate(blocks, start=1):
        v = b["vertices_xy_m"]
        for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]):
            if min(x0, x1) - 1e-9 <= x <= max(x0, x1) + 1e-9 and abs(x1 - x0) > 1e-9:
                y = y0 + (x - x0) / (x1 - x0) * (y1 - y0)
                if best is None or y > best + 1e-9 or (y > best - 1e-9 and blocks[who - 1]["driven"] and
                                                       not b["driven"]):
                    best, who = max(y, best or y), i
    return who


def shoelace(poly):
    """The signed area of a polygon [(x, y), ...]: positive counter-clockwise."""
    return 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]))


def convex_ccw(v):
    """Every turn of the polygon to the left: convex and counter-clockwise."""
    return all((x1 - x0) * (y2 - y1) - (y1 - y0) * (x2 - x1) > 0
               for (x0, y0), (x1, y1), (x2, y2) in zip(v, v[1:] + v[:1], v[2:] + v[:2]))


def polyline_y(line, x):
    """The y of an x-ascending polyline [(x, y), ...] at x (None off its ends)."""
    for (x0, y0), (x1, y1) in zip(line, line[1:]):
        if x0 - 1e-12 <= x <= x1 + 1e-12:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    return None


def overlapping(parts):
    """The pairs of convex polygons [(id, vertices), ...] that overlap by more than 1e-9 m
    (separating axes over the edges of both, after their bounding boxes)."""
    def overlap(a, b):
        for poly in (a, b):
            for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
                nx, ny = y1 - y0, x0 - x1
                ln = math.hypot(nx, ny)
                pa = [(x * nx + y * ny) / ln for x, y in a]
                pb = [(x * nx + y * ny) / ln for x, y in b]
                if min(max(pa), max(pb)) - max(min(pa), min(pb)) <= 1e-9:
                    return False
        return True
    boxes = [(min(x for x, _ in v), max(x for x, _ in v), min(y for _, y in v), max(y for _, y in v)) for _, v in parts]
    return [(parts[a][0], parts[b][0]) for a in range(len(parts)) for b in range(a + 1, len(parts))
            if boxes[a][0] < boxes[b][1] and boxes[b][0] < boxes[a][1] and boxes[a][2] < boxes[b][3] and
            boxes[b][2] < boxes[a][3] and overlap(parts[a][1], parts[b][1])]


def arch_weights(a, density, width):
    w = []
    for i in range(1, a["n_voussoirs"] + 1):
        poly = voussoir_polygon(a, i)
        area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]))
        w.append(density * width * 9.81 * area)
    return w


if case == "seed_156":
    d = load(nml)
    check_common(d, nml)
    rc, out, err = run(nml)
    check(rc == 0, f"{nml}: table mode exit code 0")
    for key, label in (("hinges_pos", "+x"), ("hinges_neg", "-x")):
        line = next((l for l in out.splitlines() if l.strip().startswith(label)), "")
        check(f"{d[key.replace('hinges', 'lambda')]:.6f}" in line and line.rstrip().endswith(hinge_words(d[key])),
              f"{nml}: table row {label} shows the JSON's lambda and hinges")
    check("friction check: hinging governs" in out or "friction check: sliding governs" in out,
          f"{nml}: table has the friction check")
    check("hinges: " + hinge_words(d["hinges_min_thickness"]) in out, f"{nml}: table has the minimum-thickness hinges")
elif case in ("seed_180", "seed_118"):
    # An independent static lower-bound program (vertex enumeration, see test_limit_analysis).
    expected = {"seed_180": 0.1513647731436337, "seed_118": 0.9805380116427077}[case]
    d = load(nml)
    check_common(d, nml)
    check(close(d["lambda_pos"], expected, rtol=1e-9), f"{nml}: lambda {d['lambda_pos']} = static LP {expected}")
elif case == "min_thickness_20":
    d = load(nml)
    check_common(d, nml)
    n = d["arch"]["n_voussoirs"]
    check(close(d["min_thickness_ratio_ext"], 0.10188, atol=1e-4),
          f"{nml}: t/R_ext {d['min_thickness_ratio_ext']} = 0.10188 +- 1e-4 (published)")
    # Hinges at the springings (extrados), the crown joint (extrados) and the joints nearest
    # Milankovitch's 54.5 degrees from the crown (intrados).
    haunch = round((90.0 - 54.5) / (180.0 / n))
    expected = [(0, "extrados"), (haunch, "intrados"), (n // 2, "extrados"), (n - haunch, "intrados"),
                (n, "extrados")]
    got = [(h["joint"], h["side"]) for h in d["hinges_min_thickness"]]
    check(got == expected, f"{nml}: minimum-thickness hinges {got} = {expected}")
    # The input arch has the published minimum thickness: it can carry no horizontal load.
    check(abs(d["lambda_pos"]) < 1e-3, f"{nml}: lambda {d['lambda_pos']:.2e} ~ 0 at the minimum thickness")
elif case == "low_friction":
    with open("low_friction_180.nml", "w") as f:
        f.write("&arch embrace_deg = 180, n_voussoirs = 15, r_ext_m = 0.508, thickness_m = 0.071,\n"
                "  friction = 0.1 /\n&limit minimum_thickness = .false. /\n")
    d = load("low_friction_180.nml")
    n = d["arch"]["n_voussoirs"]
    check(d["min_thickness_ratio_ext"] is None, "low friction: minimum thickness not computed (null)")
    # Horizontal springings carry lambda W in shear and W in compression together.
    check(d["lambda_pos"] > 0.1, "low friction: lambda > friction 0.1")
    check(0 in d["sliding"] or n in d["sliding"], f"low friction: sliding at a springing ({d['sliding']})")
    rc, out, err = run("low_friction_180.nml")
    check(rc == 0 and "sliding governs at joints" in out, "low friction: table says sliding governs")
elif case == "friction_0395":
    # The seed 156-degree arch at the friction the diagnosis fits best: sliding governs.
    with open(nml) as f:
        text = f.read().replace("friction = 0.5", "friction = 0.395")
    with open("seed_156_friction_0395.nml", "w") as f:
        f.write(text)
    d = load("seed_156_friction_0395.nml")
    check_common(d, "friction 0.395")
    check(d["load_factor"] < 0.9 * d["lambda_pos"], f"friction 0.395: load_factor {d['load_factor']} well below "
                                                    f"the hinge-only {d['lambda_pos']}")
    moving = [(m["joint"], m["mode"]) for m in d["mechanism_nonassociative"] if m["mode"] != "closed"]
    check(any(mode == "sliding" and j in (0, 13) for j, mode in moving),
          f"friction 0.395: non-associative mechanism slides at a springing ({moving})")
elif case == "polygon_block":
    # input/rocking_block.nml: a 0.2 x 1.0 m block (friction 0.7 > b/h) tips at b/h = 0.2
    # about its +x corner (0.1, 0).
    d = load(nml)
    check(d["assembly"] == "polygon file" and d["arch"] is None and d["lambda_pos"] is None,
          f"{nml}: a polygon file: no arch, no four-hinge lambda (null)")
    check(close(d["load_factor"], 0.2, rtol=1e-9), f"{nml}: load_factor {d['load_factor']} = b/h = 0.2")
    check(close(d["load_factor_nonassociative"], 0.2, rtol=1e-9), f"{nml}: non-associative = b/h")
    m = d["mechanism"]
    check(len(m) == 1 and m[0]["mode"] == "hinge" and close(m[0]["hinge_xy_m"][0], 0.1, atol=1e-12)
          and close(m[0]["hinge_xy_m"][1], 0.0, atol=1e-12), f"{nml}: one hinge at the +x corner ({m})")
    w = 2000 * 0.2 * 1.0 * 0.2 * 9.81
    f = d["contact_forces"][0]
    check(close(sum(f["normal_n"]), w, rtol=1e-9), f"{nml}: the base carries the weight {w} N")
    # Towards -x the block is the same mirrored: b/h about its -x corner.
    check(close(d["load_factor_neg"], 0.2, rtol=1e-9) and close(d["load_factor_nonassociative_neg"], 0.2, rtol=1e-9),
          f"{nml}: load_factor_neg {d['load_factor_neg']} = b/h = 0.2 (symmetric block)")
    m = d["mechanism_neg"]
    check(len(m) == 1 and m[0]["mode"] == "hinge" and close(m[0]["hinge_xy_m"][0], -0.1, atol=1e-12),
          f"{nml}: -x: one hinge at the -x corner ({m})")
    check(d["live_load_neg"].startswith("horizontal acceleration lambda g towards -x"), f"{nml}: live_load_neg says -x")
    rc, out, err = run(nml)
    check(rc == 0 and "do not apply" in out and "lambda 0.2" in out, f"{nml}: the table says what applies")
    check("towards -x" in out, f"{nml}: the table has the -x direction")
    check(d["live_load"].startswith("horizontal acceleration") and d["point_loads"] == [] and
          d["critical_position"] is None and d["load_factor_curve"] == [], f"{nml}: without &load, lambda g towards +x")
    # The same block with a live point load P = 100 N towards +x at its top corner (-0.1, 1)
    # and a dead Q = 200 N down at the top's middle: tips when lambda P h = (W + Q) b/2,
    # lambda = (784.8 + 200) 0.1 / 100 = 0.9848 (sliding needs mu (W + Q) / P = 6.9).
    with open(nml) as f:
        text = f.read().replace("blocks/", os.path.dirname(os.path.abspath(nml)) + "/blocks/")
    with open("block_point_load.nml", "w") as f:
        f.write(text + "&load point_load_n = 100, 200, point_load_dir_deg = 0, -90, point_load_x_m = -0.1, 0.0,\n"
                       "  point_load_y_m = 1.0, 1.0, point_load_live = .true., .false. /\n")
    # A dead Q = 200 N down at the top's +x corner (0.1, 1): towards +x the block tips about
    # (0.1, 0), under Q's line: lambda W h/2 = W b/2, lambda = b/h = 0.2 as without Q;
    # towards -x about (-0.1, 0), Q a lever b away: lambda W h/2 = W b/2 + Q b,
    # lambda = (b/h)(1 + 2Q/W). Sliding needs mu (W + Q)/W = 0.88, more than either.
    with open("block_dead_corner.nml", "w") as f:
        f.write(text + "&load point_load_n = 200, point_load_dir_deg = -90, point_load_x_m = 0.1, point_load_y_m = 1.0,\n"
                       "  point_load_live = .false. /\n")
    d = load("block_dead_corner.nml")
    lam_neg = 0.2 * (1.0 + 2.0 * 200.0 / w)
    check(close(d["load_factor"], 0.2, rtol=1e-9), f"dead load at the +x corner: load_factor {d['load_factor']} = b/h")
    check(close(d["load_factor_neg"], lam_neg, rtol=1e-9) and close(d["load_factor_nonassociative_neg"], lam_neg, rtol=1e-9),
          f"dead load at the +x corner: load_factor_neg {d['load_factor_neg']} = (b/h)(1 + 2Q/W) = {lam_neg}")
    check(d["load_factor_neg"] > d["load_factor"], "dead load at the +x corner: -x is the stronger direction")
    d = load("block_point_load.nml")
    check(d["load_factor_neg"] is None and "horizontal acceleration only" in d["load_factor_note_neg"]
          and d["live_load_neg"] is None, f"live point loads: no -x direction ({d['load_factor_note_neg']})")
    check(close(d["load_factor"], (w + 200.0) * 0.1 / 100.0, rtol=1e-9),
          f"block with a point load: load_factor {d['load_factor']} = (W + Q) b / (2 P h) = {(w + 200.0) * 0.1 / 100.0}")
    check(d["point_loads"] == [{"load": 1, "block": 1, "xy_m": [-0.1, 1.0], "force_n": [100.0, 0.0], "live": True},
                               {"load": 2, "block": 1, "xy_m": [0.0, 1.0], "force_n": [0.0, -200.0], "live": False}],
          f"block with a point load: the loads as placed ({d['point_loads']})")
    rc, out, err = run("block_point_load.nml")
    check(rc == 0 and "live load: lambda x the live point loads of &load (load 1: 100 N at 0 deg); dead: the weights "
          "and 1 dead point load" in out, "block with a point load: the table names the live load")
elif case == "wall_sliding":
    # input/wall_sliding.nml: a 3 x 3 wall, 0.6 m x 0.3 m, friction 0.3 < B/H = 2: it slides
    # at lambda = mu, associative or not.
    d = load(nml)
    check(d["assembly"] == "wall" and d["arch"] is None, f"{nml}: a wall")
    check(close(d["load_factor"], 0.3, rtol=1e-9), f"{nml}: load_factor {d['load_factor']} = mu = 0.3")
    check(close(d["load_factor_nonassociative"], 0.3, rtol=1e-9), f"{nml}: non-associative = mu")
    check(any(m["mode"] == "sliding" for m in d["mechanism"]), f"{nml}: the mechanism slides")
elif case == "arch_point_load":
    # A semicircular arch (16 voussoirs, R_ext 1 m, t 0.15 m, friction 10: no sliding)
    # under a vertical live point load of 1 kN on its extrados at quarter span (x = -0.5 m).
    # Its load factor against the least four-hinge mechanism computed here by the work
    # equation (arch_point_load_lambda); the static field of the JSON in equilibrium; both
    # bounds equal; the point on the extrados chord.
    arch = ("&arch embrace_deg = 180, n_voussoirs = 16, r_ext_m = 1.0, thickness_m = 0.15, width_m = 1.0,\n"
            "  density_kg_m3 = 2000, friction = 10 /\n&limit minimum_thickness = .false. /\n")
    with open("arch_point_load.nml", "w") as f:
        f.write(arch + "&load point_load_n(1) = 1000, point_load_x_m(1) = -0.5, point_load_y_m(1) = 0.86 /\n")
    d = load("arch_point_load.nml")
    check(d["live_load"].startswith("lambda x the live point loads"), f"live_load says so: {d['live_load']}")
    pl = d["point_loads"]
    check(len(pl) == 1 and pl[0]["force_n"] == [0.0, -1000.0] and pl[0]["xy_m"] == [-0.5, 0.86],
          f"one point load of 1 kN downwards at the point given ({pl})")
    a = d["arch"]
    w = arch_weights(a, 2000.0, 1.0)
    lam = d["load_factor"]
    check(close(d["load_factor_upper"], lam, rtol=1e-6), f"upper bound {d['load_factor_upper']} = lower bound {lam}")
    expected = arch_point_load_lambda(a, w, [(pl[0]["xy_m"], (0.0, -1000.0), pl[0]["block"])])
    check(close(lam, expected, rtol=1e-6), f"load factor {lam} = least four-hinge mechanism {expected} (work equation)")
    check_loaded_equilibrium(d, "quarter-span load", w, lam)
    # On the path: the live load on the top surface (the extrados chord), the curve
    # symmetric about the crown, the critical position its least value.
    with open("arch_point_load_path.nml", "w") as f:
        f.write(arch + "&load point_load_n(1) = 1000, path_x0_m = -0.8, path_x1_m = 0.8, path_points = 17 /\n")
    d = load("arch_point_load_path.nml")
    curve = d["load_factor_curve"]
    grid = [c for c in curve if not c["at_joint"]]
    check(len(grid) == 17 and all(c["load_factor"] is not None for c in curve), "17 grid positions, all with a load factor")
    # The refinement: a micrometre either side of every extrados joint end in the path's range.
    ext_x = [x for x, _ in d["arch"]["joint_extrados_xy_m"] if -0.8 <= x <= 0.8]
    at_joint = sorted(c["x_m"] for c in curve if c["at_joint"])
    expected_x = sorted(x + s * 1e-6 for x in ext_x for s in (-1, 1))
    check(len(at_joint) == len(expected_x) and all(close(a, b, atol=1e-12) for a, b in zip(at_joint, expected_x)),
          f"refined at the {len(ext_x)} extrados joint ends within the path, 1e-6 m either side ({at_joint})")
    lf = [c["load_factor"] for c in curve]
    check(all(close(lf[i], lf[-1 - i], rtol=1e-6) for i in range(len(lf))), f"curve symmetric about the crown: {lf}")
    check(d["critical_position"]["load_factor"] < min(c["load_factor"] for c in grid) * (1 - 1e-3),
          f"the refined critical load factor {d['critical_position']['load_factor']} is below the grid's least "
          f"{min(c['load_factor'] for c in grid)}: a grid alone misses it")
    cp = d["critical_position"]
    first = next(c for c in curve if c["load_factor"] <= min(lf) * (1 + 1e-9))
    check(first["x_m"] == cp["x_m"] and first["load_factor"] == cp["load_factor"] and
          close(cp["load_factor"], d["load_factor"], rtol=1e-9),
          f"critical position {cp} = the first least of the curve {first} (to 1e-9), and the load_factor reported")
    x, y = d["point_loads"][0]["xy_m"]
    check(close(x, cp["x_m"], atol=1e-12) and close(y, top_of_arch(d["arch"], x), atol=1e-9),
          f"the live load at the critical x, on the extrados ({x}, {y})")
    expected = arch_point_load_lambda(d["arch"], w, [((x, y), (0.0, -1000.0), d["point_loads"][0]["block"])])
    check(close(d["load_factor"], expected, rtol=1e-6),
          f"critical load factor {d['load_factor']} = least four-hinge mechanism {expected}")
    check_loaded_equilibrium(d, "critical position", w, d["load_factor"])
    # The table: the load case first; the weights-alone acceleration case after it, named
    # as another question (it printed first, as if it were the bridge's answer).
    rc, table, _ = run("arch_point_load_path.nml")
    lp_at, other_at = table.find("Limit analysis by linear programming"), table.find("Not the load case above")
    check(rc == 0 and 0 < lp_at < other_at and "Horizontal collapse" not in table,
          "table: the load case first, then the acceleration case of the weights alone, named as not the load case")
    # An axle group: 500 N at x = -0.6 m and again 0.4 m to its right, both on the extrados.
    with open("arch_axles.nml", "w") as f:
        f.write(arch + "&load point_load_n(1) = 500, point_load_x_m(1) = -0.6, axle_spacing_m(1) = 0.4 /\n")
    d = load("arch_axles.nml")
    pl = d["point_loads"]
    check(len(pl) == 2 and [p["xy_m"][0] for p in pl] == [-0.6, -0.6 + 0.4] and
          all(close(p["xy_m"][1], top_of_arch(d["arch"], p["xy_m"][0]), atol=1e-9) for p in pl),
          f"axle group: two loads at x = -0.6 and -0.2 on the extrados ({pl})")
    expected = arch_point_load_lambda(d["arch"], w, [(p["xy_m"], (0.0, -500.0), p["block"]) for p in pl])
    check(close(d["load_factor"], expected, rtol=1e-6),
          f"axle group: load factor {d['load_factor']} = least four-hinge mechanism {expected}")
    check_loaded_equilibrium(d, "axle group", w, d["load_factor"])
    # The axle group on a path: the path's x is the vehicle's (the resultant of its axles,
    # here 300 N and 100 N 0.4 m apart: 0.1 m from the first), not the first axle's.
    with open("arch_axles_path.nml", "w") as f:
        f.write(arch + "&load point_load_n(1) = 300, point_load_n(2) = 100, point_load_x_m(2) = 0.4,\n"
                "  path_x0_m = -0.6, path_x1_m = 0.6, path_points = 5 /\n")
    d = load("arch_axles_path.nml")
    pl = d["point_loads"]
    xs = [c["x_m"] for c in d["load_factor_curve"]]
    resultant = sum(p["xy_m"][0] * -p["force_n"][1] for p in pl) / sum(-p["force_n"][1] for p in pl)
    check(close(xs[0], -0.6, atol=1e-12) and close(d["critical_position"]["x_m"], resultant, atol=1e-12) and
          close(pl[1]["xy_m"][0] - pl[0]["xy_m"][0], 0.4, atol=1e-12),
          f"path x = the vehicle's resultant ({d['critical_position']['x_m']} = {resultant}), axles 0.4 m apart: {pl}")
elif case == "restrained":
    # The seed 156-degree arch (friction 10: no sliding) with restraint brackets. A bracket
    # stands against the lower half of the springing voussoir's extrados chord, which
    # meets the springing joint at 90 - 6 degrees (half a voussoir's angle less than a
    # right angle): turning about either end of the springing joint drives the voussoir
    # into the bracket or the foundation, so that joint cannot hinge. The load factors
    # are then the least four-hinge mechanisms (work equation, arch_point_load_lambda)
    # with no hinge at a restrained springing, in each direction; a left bracket leaves
    # the +x mechanism only where it does not hinge at joint 0.
    emb, n, r_ext, t = 156.0, 13, 0.508, 0.071
    a = {"n_voussoirs": n, "r_ext_m": r_ext, "joint_intrados_xy_m": [], "joint_extrados_xy_m": []}
    for j in range(n + 1):
        ang = math.radians(90.0 + 0.5 * emb - j * emb / n)
        a["joint_intrados_xy_m"].append([(r_ext - t) * math.cos(ang), (r_ext - t) * math.sin(ang)])
        a["joint_extrados_xy_m"].append([r_ext * math.cos(ang), r_ext * math.sin(ang)])
    w = arch_weights(a, 700.0, 0.145)
    cents = [centroid(voussoir_polygon(a, i)) for i in range(1, n + 1)]

    def expected(fixed, sign):
        return arch_point_load_lambda(a, w, [(cents[i - 1], (sign * w[i - 1], 0.0), i) for i in range(1, n + 1)],
                                      fixed)

    free = expected((), 1.0)
    for side, fixed in (("left", (0,)), ("right", (n,)), ("both", (0, n))):
        path = f"restrained_{side}.nml"
        with open(path, "w") as f:
            f.write(f"&arch embrace_deg = {emb}, n_voussoirs = {n}, r_ext_m = {r_ext}, thickness_m = {t},\n"
                    f"  width_m = 0.145, density_kg_m3 = 700, friction = 10, restrained_springings = '{side}' /\n")
        d = load(path)
        check(d["assembly"] == "restrained arch" and d["lambda_pos"] is None and d["hinges_pos"] == [],
              f"{side}: a restrained arch, the four-hinge keys null")
        da = d["arch"]
        check(da is not None and da["n_voussoirs"] == n and all(
            close(p, q, atol=1e-12) for key in ("joint_intrados_xy_m", "joint_extrados_xy_m")
            for pq in zip(da[key], a[key]) for p, q in zip(*pq)),
              f"{side}: the arch object with the joint ends of the geometry conventions")
        for sfx, sign in (("", 1.0), ("_neg", -1.0)):
            lam, exp = d["load_factor" + sfx], expected(fixed, sign)
            check(close(lam, exp, rtol=1e-6),
                  f"{side}: load_factor{sfx} {lam} = least four-hinge mechanism without hinges at joints {fixed} {exp}")
            check(close(d["load_factor_upper" + sfx], lam, rtol=1e-6), f"{side}: upper{sfx} = lower bound")
            moving = [m["joint"] for m in d["mechanism" + sfx] if m["mode"] != "closed"]
            check(len(moving) == 4 and not set(moving) & set(fixed),
                  f"{side}: the {sfx or '+x'} mechanism hinges at four joints, none restrained ({moving})")
            check(lam >= free * (1 - 1e-9), f"{side}: load_factor{sfx} {lam} >= the free arch's {free}")
        # The brackets (blocks n + 3 and on) hold the springing voussoirs in compression.
        brackets = [f for f in d["contact_forces"] + d["contact_forces_neg"] if f["joint"] is None]
        check(len(brackets) == 2 * len(fixed) and all(max(f["blocks"]) > n + 2 for f in brackets)
              and max(sum(f["normal_n"]) for f in brackets) > 0.0,
              f"{side}: {len(fixed)} bracket interface(s), not arch joints, carrying compression")
    # The free arch's mechanisms both hinge at joint 0 (+x: 0, 5, 10, 13; -x: 0, 3, 8, 13):
    # a left bracket raises both; +x only a little (its hinge moves to joint 1 of a long
    # left segment), -x much (its short left segment of three voussoirs grows).
    d = load("restrained_left.nml")
    check(free < d["load_factor"] < d["load_factor_neg"],
          f"left bracket: free {free} < +x {d['load_factor']} < -x {d['load_factor_neg']}")
    rc, out, err = run("restrained_left.nml")
    check(rc == 0 and "do not model the restraint brackets" in out and "towards -x" in out,
          "left bracket: the table says the LP models the brackets")
    # Brackets with play (bracket_gap_m): in the limit analysis (rigid blocks, small
    # displacements) a bracket that stands off its voussoir touches nothing, so the arch
    # is the free one in both directions, whatever the side; and each bracket's interface
    # is gone. A gap of 0 is the bracket in contact (the cases above).
    for side in ("left", "both"):
        with open(f"gap_{side}.nml", "w") as f:
            f.write(f"&arch embrace_deg = {emb}, n_voussoirs = {n}, r_ext_m = {r_ext}, thickness_m = {t},\n"
                    f"  width_m = 0.145, density_kg_m3 = 700, friction = 10, restrained_springings = '{side}',\n"
                    f"  bracket_gap_m = 0.0004 /\n")
        d = load(f"gap_{side}.nml")
        for sfx, sign in (("", 1.0), ("_neg", -1.0)):
            check(close(d["load_factor" + sfx], expected((), sign), rtol=1e-6),
                  f"{side} brackets 0.4 mm off: load_factor{sfx} {d['load_factor' + sfx]} = the free arch's "
                  f"{expected((), sign)}")
        brackets = [f for f in d["contact_forces"] + d["contact_forces_neg"] if f["joint"] is None]
        check(not brackets, f"{side} brackets 0.4 mm off: no bracket interface ({len(brackets)})")
    with open("gap_none.nml", "w") as f:
        f.write(f"&arch embrace_deg = {emb}, n_voussoirs = {n}, r_ext_m = {r_ext}, thickness_m = {t},\n"
                f"  width_m = 0.145, density_kg_m3 = 700, friction = 10, bracket_gap_m = 0.0004 /\n")
    rc, out, err = run("gap_none.nml")
    check(rc != 0 and "bracket_gap_m" in err + out and "restrained_springings" in err + out,
          f"a bracket gap without brackets is refused, naming both variables: {err.strip()}")
    with open("gap_thick.nml", "w") as f:
        f.write(f"&arch embrace_deg = {emb}, n_voussoirs = {n}, r_ext_m = {r_ext}, thickness_m = {t},\n"
                f"  width_m = 0.145, density_kg_m3 = 700, restrained_springings = 'left', bracket_gap_m = 0.08 /\n")
    rc, out, err = run("gap_thick.nml")
    check(rc != 0 and "bracket_gap_m" in err + out and "thickness_m" in err + out,
          f"a bracket gap wider than the ring is refused: {err.strip()}")
elif case == "joint_friction":
    # &arch joint_friction(j), the friction of joint j alone in the dynamics, in both
    # analyses. Every joint at 0.395 through joint_friction is the arch at friction 0.395.
    with open(nml) as f:
        text = f.read().replace("friction = 0.5", "friction = 10")
    with open("all_joints.nml", "w") as f:
        f.write(text.replace("friction = 10", "friction = 10, " + ", ".join(f"joint_friction({j}) = 0.395"
                                                                           for j in range(14))))
    with open("everywhere.nml", "w") as f:
        f.write(text.replace("friction = 10", "friction = 0.395"))
    d, e = load("all_joints.nml"), load("everywhere.nml")
    for key in ("load_factor", "load_factor_nonassociative", "load_factor_neg", "load_factor_nonassociative_neg"):
        check(close(d[key], e[key], rtol=1e-9), f"joint_friction 0.395 at every joint: {key} {d[key]} = "
                                                f"friction 0.395's {e[key]}")
    check(d["sliding"] == e["sliding"] and d["sliding"], f"the same joints slide in the friction check ({d['sliding']})")
    # Joint 0 alone at 0.2 (the others at 10): every static field keeps |S| <= 0.2 N there;
    # less friction never carries more, and towards -x (the arch leaning onto its left
    # springing, joint 0 at 12 degrees to the horizontal) the capacity drops, the mechanism
    # sliding at joint 0; the four-hinge friction check flags joint 0 alone (its |T|/N at
    # collapse is above 0.2, the others far below 10).
    with open("joint0.nml", "w") as f:
        f.write(text.replace("friction = 10", "friction = 10, joint_friction(0) = 0.2"))
    with open("friction10.nml", "w") as f:
        f.write(text)
    d, e = load("joint0.nml"), load("friction10.nml")
    worst = 0.0
    for key in ("contact_forces", "contact_forces_nonassociative", "contact_forces_neg",
                "contact_forces_nonassociative_neg"):
        for f in d[key]:
            if f["joint"] == 0:
                worst = max(worst, abs(f["shear_n"]) / sum(f["normal_n"]))
    check(worst <= 0.2 * (1 + 1e-9), f"joint 0: |S|/N <= 0.2 in every static field ({worst})")
    check(d["load_factor"] <= e["load_factor"] * (1 + 1e-9) and e["sliding"] == [],
          f"joint 0 at 0.2: load_factor {d['load_factor']} <= friction 10's {e['load_factor']}")
    check(d["load_factor_neg"] < e["load_factor_neg"] * (1 - 1e-6),
          f"joint 0 at 0.2: load_factor_neg {d['load_factor_neg']} below friction 10's {e['load_factor_neg']}")
    moving = {m["joint"]: m["mode"] for m in d["mechanism_neg"] if m["mode"] != "closed"}
    check(moving.get(0) == "sliding", f"joint 0 at 0.2: the -x mechanism slides at joint 0 ({moving})")
    check(d["sliding"] == [0], f"joint 0 at 0.2: the friction check flags joint 0 alone ({d['sliding']})")
    rc, out, err = run("joint0.nml")
    check(rc == 0 and "joint_friction where set" in out, "joint 0 at 0.2: the table says joint_friction is used")
elif case == "crushing":
    # &limit compressive_strength_pa: every interface force kept a = N / (2 sigma_c w) from
    # the ends. input/rocking_block.nml (b = 0.2, h = 1, w = 0.2 m, W = 784.8 N) tips about
    # a point a = W / (2 sigma_c w) in from its corner: lambda W h/2 = W (b/2 - a),
    # lambda = (b - W / (sigma_c w)) / h, both ways (sliding needs mu = 0.7).
    with open(nml) as f:
        text = f.read().replace("blocks/", os.path.dirname(os.path.abspath(nml)) + "/blocks/")
    w = 2000 * 0.2 * 1.0 * 0.2 * 9.81
    for sigma in (1e12, 98100.0, 50000.0):
        path = f"block_sigma_{sigma:g}.nml"
        with open(path, "w") as f:
            f.write(text + f"&limit compressive_strength_pa = {sigma} /\n")
        d = load(path)
        expected = (0.2 - w / (sigma * 0.2)) / 1.0
        for key in ("load_factor", "load_factor_nonassociative", "load_factor_neg", "load_factor_nonassociative_neg"):
            check(close(d[key], expected, rtol=1e-9), f"block, sigma_c {sigma:g} Pa: {key} {d[key]} = "
                                                      f"(b - W/(sigma_c w))/h = {expected}")
        check(d["compressive_strength_pa"] == sigma and d["crushing_converged"] and not d["crushed_through"],
              f"block, sigma_c {sigma:g} Pa: the JSON says so, converged")
        hinge = d["mechanism"][0]["hinge_xy_m"]
        check(close(hinge[0], 0.1 - w / (2 * sigma * 0.2), atol=1e-12),
              f"block, sigma_c {sigma:g} Pa: the hinge {hinge} set in by a = W/(2 sigma_c w) from the +x corner")
    d = load(f"block_sigma_{1e12:g}.nml")
    check(close(d["load_factor"], 0.2, rtol=1e-6), f"block, sigma_c 1e12 Pa: the rigid b/h to 1e-6 ({d['load_factor']})")
    rc, out, err = run("block_sigma_98100.nml")
    check(rc == 0 and "compressive strength 98100 Pa" in out, "block: the table names the strength")
    # The seed arch at 30 kPa: below its rigid lambda; every interface force at the ends of
    # its joint (from the geometry conventions) moved in by N / (2 sigma_c w).
    with open(os.path.join(os.path.dirname(os.path.abspath(nml)), "limit_seed_156.nml")) as f:
        text = f.read().replace("minimum_thickness = .true.", "minimum_thickness = .false.")
    with open("seed_rigid.nml", "w") as f:
        f.write(text)
    with open("seed_crushing.nml", "w") as f:
        f.write(text.replace("&limit\n", "&limit\n  compressive_strength_pa = 3e4,\n"))
    rigid, d = load("seed_rigid.nml"), load("seed_crushing.nml")
    check(d["compressive_strength_pa"] == 3e4, "seed arch: a finite strength read")
    for key in ("load_factor", "load_factor_neg"):
        check(d[key] < rigid[key] * (1 - 1e-3), f"seed arch, 30 kPa: {key} {d[key]} below the rigid {rigid[key]}")
    a = d["arch"]
    worst = 0.0
    for key in ("contact_forces", "contact_forces_neg", "contact_forces_nonassociative"):
        for f in d[key]:
            j = f["joint"]
            ends = [a["joint_intrados_xy_m"][j], a["joint_extrados_xy_m"][j]]
            offset = sum(f["normal_n"]) / (2 * 3e4 * 0.145)
            for p in f["ends_xy_m"]:
                dist = min(math.dist(p, e) for e in ends)
                worst = max(worst, abs(dist - offset) / a["thickness_m"])
    check(worst < 1e-6, f"seed arch, 30 kPa: every force N / (2 sigma_c w) in from its joint's ends ({worst:.1e})")
    for sfx in ("", "_neg"):
        check(close(d["load_factor_upper" + sfx], d["load_factor" + sfx], rtol=1e-6),
              f"seed arch, 30 kPa: upper{sfx} = lower bound")
elif case == "bad_inputs":
    cases = [
        ("unknown_limit_variable", "&limit", "&arch /\n&limit minimum_thicknes = .false. /\n"),
        ("limit_wrong_type", r"&limit.*The variables of &limit are: minimum_thickness \(logical\), inset_m \(real, m\)",
         "&arch /\n&limit inset_m = 'wide' /\n"),
        ("limit_wrong_type_thickness", r"&limit.*The variables of &limit are: minimum_thickness \(logical\)",
         "&arch /\n&limit minimum_thickness = 'x' /\n"),
        # The four-hinge search grows as n^4: 600 voussoirs ran for minutes without a word.
        ("many_voussoirs", r"n_voussoirs = 600 is outside the allowed range 3 <= n_voussoirs <= 200 of voussoir-limit.*n\^4",
         "&arch n_voussoirs = 600 /\n"),
        ("limit_inset_too_big", "inset_m = 0.04.*thickness_m/2", "&arch /\n&limit inset_m = 0.04 /\n"),
        ("limit_inset_negative", "inset_m = -0.001", "&arch /\n&limit inset_m = -0.001 /\n"),
        ("limit_strength_zero", r"compressive_strength_pa = 0.*compressive_strength_pa > 0",
         "&arch /\n&limit compressive_strength_pa = 0 /\n"),
        ("polygon_overhang", "dead load alone brings the assembly down",
         "&arch polygon_file = 'overhang.txt' /\n"),
        ("polygon_against_wall", "unbounded.*block 1 is held against the load", "&arch polygon_file = 'against_wall.txt' /\n"),
        ("polygon_floating", "block 2 touches no other block", "&arch polygon_file = 'floating.txt' /\n"),
        ("polygon_no_support", "no block is driven", "&arch polygon_file = 'no_support.txt' /\n"),
        ("unknown_group", "unknown namelist group &limits", "&arch /\n&limits /\n"),
        ("two_voussoirs", "n_voussoirs = 2", "&arch n_voussoirs = 2 /\n"),
        ("three_voussoirs_min_thickness", "minimum_thickness", "&arch n_voussoirs = 3 /\n"),
        ("thickness", "thickness_m", "&arch thickness_m = 0.6 /\n"),
    ]
    import re
    base = "block driven\n-1.0 -0.2\n1.0 -0.2\n1.0 0.0\n-1.0 0.0\n"
    block = "block free\n-0.1 0.0\n0.1 0.0\n0.1 1.0\n-0.1 1.0\n"
    polygons = {
        # The block's centroid (x = 0) lies beyond the edge of its support (x = -0.05).
        "overhang.txt": block + "block driven\n-1.0 -0.2\n-0.05 -0.2\n-0.05 0.0\n-1.0 0.0\n",
        # A driven wall against the +x face: no mechanism opens towards +x.
        "against_wall.txt": block + base + "block driven\n0.1 0.0\n0.5 0.0\n0.5 1.0\n0.1 1.0\n",
        "floating.txt": base + "block free\n0.0 0.5\n0.2 0.5\n0.2 0.7\n0.0 0.7\n",
        "no_support.txt": block,
    }
    for file, text in polygons.items():
        with open(file, "w") as f:
            f.write(text)
    for name, pattern, text in cases:
        path = f"{name}.nml"
        with open(path, "w") as f:
            f.write(text)
        for mode in (["--json"], []):
            rc, out, err = run(path, *mode)
            good = rc != 0 and path in err and re.search(pattern, err) is not None
            if mode:
                good = good and out == ""
            check(good, f"bad input {name} {' '.join(mode)}: exit {rc}, stderr names the file and "
                        f"matches '{pattern}'" + ("" if good else f" (stdout {out!r}, stderr {err!r})"))
    rc, out, err = run("no_such_file.nml", "--json")
    check(rc != 0 and out == "" and "no_such_file.nml" in err, "missing file: error naming it")
    rc, out, err = run()
    check(rc == 2 and "usage" in err, "no argument: usage, exit code 2")
    rc, out, err = run("a.nml", "b.nml")
    check(rc == 2 and "usage" in err, "two files: usage, exit code 2")
elif case == "bridge":
    # (1) The arch of input/limit_arch_point_load.nml (semicircle, R_ext 1 m, t 0.15 m, 16
    # voussoirs, 2000 kg/m3, 1 m wide, friction 0.6) built by &bridge (span 2 (R_ext - t)):
    # the same blocks, so the same load factors to 1e-10, along the whole path of its 1 kN
    # (x shifted by the bridge's origin, the left springing: 0.85 m) and under horizontal
    # acceleration. (2) input/bridge_two_spans.nml: every block in equilibrium under its
    # weight (each part's density), lambda x the live load and the JSON's contact forces;
    # no tension; each interface within the lesser friction of its two blocks; the bounds meet.
    arch_nml = os.path.join(os.path.dirname(nml), "limit_arch_point_load.nml")
    bridge = ("&bridge shape = 'semicircular', span_m(1) = 1.7, ring_thickness_m = 0.15, n_voussoirs = 16,\n"
              "  width_m = 1.0, ring_density_kg_m3 = 2000, ring_friction = 0.6, abutment_friction = 0.6,\n"
              "  abutment_width_m = 0.5, pier_height_m = 0.5 /\n")
    with open("bridge_semicircle.nml", "w") as f:
        f.write(bridge + "&load point_load_n(1) = 1000, path_x0_m = 0.05, path_x1_m = 1.65, path_points = 17 /\n")
    with open("bridge_semicircle_accel.nml", "w") as f:
        f.write(bridge)
    with open("arch_accel.nml", "w") as f:
        f.write("&arch embrace_deg = 180, n_voussoirs = 16, r_ext_m = 1.0, thickness_m = 0.15, width_m = 1.0,\n"
                "  density_kg_m3 = 2000, friction = 0.6 /\n&limit minimum_thickness = .false. /\n")
    a, b = load(arch_nml), load("bridge_semicircle.nml")
    check(b["assembly"] == "bridge" and b["arch"] is None and len(b["blocks"]) == 18, "the bridge: 16 + 2 blocks")
    ca, cb = [c["load_factor"] for c in a["load_factor_curve"]], [c["load_factor"] for c in b["load_factor_curve"]]
    xa, xb = [c["x_m"] for c in a["load_factor_curve"]], [c["x_m"] for c in b["load_factor_curve"]]
    check(len(ca) == len(cb) > 17 and all(close(y, x + 0.85, atol=1e-12) for x, y in zip(xa, xb)) and
          all(close(y, x, rtol=1e-10) for x, y in zip(ca, cb)),
          f"the bridge's curve = the arch builder's to 1e-10 (largest difference "
          f"{max(abs(y / x - 1) for x, y in zip(ca, cb)):.1e})")
    check(close(b["critical_position"]["x_m"], a["critical_position"]["x_m"] + 0.85, atol=1e-12) and
          close(b["load_factor"], a["load_factor"], rtol=1e-10),
          f"critical position {b['critical_position']} = the arch's {a['critical_position']} shifted by 0.85 m")
    a, b = load("arch_accel.nml"), load("bridge_semicircle_accel.nml")
    check(close(b["load_factor"], a["load_factor"], rtol=1e-10) and close(b["load_factor_neg"], a["load_factor_neg"],
                                                                           rtol=1e-10),
          f"under horizontal acceleration: {b['load_factor']} = the arch builder's {a['load_factor']} (1e-10)")
    # (2) The two-span bridge.
    d = load(os.path.join(os.path.dirname(nml), "bridge_two_spans.nml"))
    lam = d["load_factor"]
    check(d["assembly"] == "bridge" and len(d["blocks"]) == 2 * 20 + 1 + 2 + 1 and lam > 0,
          f"two spans: 40 voussoirs, a pier, two abutments, the ground; lambda {lam}")
    check(close(d["load_factor_upper"], lam, rtol=1e-6), f"upper bound {d['load_factor_upper']} = lower {lam}")
    density = [2200.0] * 40 + [2300.0]
    worst = 0.0
    for i, blk in enumerate(d["blocks"], start=1):
        if blk["driven"]:
            continue
        poly = blk["vertices_xy_m"]
        area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]))
        cx, cy = centroid(poly)
        weight = density[i - 1] * 1.0 * 9.81 * area
        fx, fy, m = contact_resultant(d, i, cx, cy)
        fy -= weight
        for pl in d["point_loads"]:
            if pl["block"] == i:
                gx, gy = lam * pl["force_n"][0], lam * pl["force_n"][1]
                fx, fy, m = fx + gx, fy + gy, m + (pl["xy_m"][0] - cx) * gy - (pl["xy_m"][1] - cy) * gx
        worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(m) / (weight * 10.0))
    check(worst < 1e-7, f"two spans: every free block in equilibrium (weight by its part's density) ({worst:.1e})")
    check(all(min(f["normal_n"]) >= -1e-9 * 1e5 and abs(f["shear_n"]) <= 0.6 * sum(f["normal_n"]) + 1e-6
              for f in d["contact_forces"]), "two spans: no tension, every interface within friction 0.6")
    rc, out, _ = run(os.path.join(os.path.dirname(nml), "bridge_two_spans.nml"))
    check(rc == 0 and "friction: ring 0.6, piers 0.6, skewbacks 0.6" in out and "critical position" in out,
          "two spans: the table gives each part's friction and the critical position")
    names = [b["name"] for b in d["blocks"]]
    check(names[:2] == ["span 1 voussoir 1", "span 1 voussoir 2"] and names[40:] ==
          ["pier 1", "left abutment", "right abutment", "ground"], f"two spans: the blocks named ({names[38:]})")
    hinge_on_pier = [m for m in d["mechanism"] if m["mode"] == "hinge" and 41 in m["blocks"]]
    check(len(hinge_on_pier) == 1 and "(span 1 voussoir 20 / pier 1) hinge" in out,
          "two spans: the table names the hinge of span 1 on the pier by its blocks' names")
    # Each part its own friction: skewbacks at 0.05 hold the ring's springings to that (the
    # lesser of ring 0.6 and skewback 0.05), and the bridge is weaker for it.
    with open(os.path.join(os.path.dirname(nml), "bridge_two_spans.nml")) as f:
        text = f.read().replace("abutment_friction = 0.6", "abutment_friction = 0.05")
    with open("bridge_slippery_skewbacks.nml", "w") as f:
        f.write(text)
    e = load("bridge_slippery_skewbacks.nml")
    skew = [k for k, blk in enumerate(e["blocks"], start=1) if blk["driven"]][:2]
    at_skew = [f for f in e["contact_forces"] if set(f["blocks"]) & set(skew)]
    check(len(at_skew) == 2 and all(abs(f["shear_n"]) <= 0.05 * sum(f["normal_n"]) * (1 + 1e-9) + 1e-6
                                    for f in at_skew) and e["load_factor"] < lam * (1 - 1e-3),
          f"skewback friction 0.05: |S| <= 0.05 N at both springings, load factor {e['load_factor']} < {lam}")
elif case == "bridge_rings":
    # &bridge n_rings (issue 37): a segmental span (6 m, rise 1.5 m, ring 0.45 m, 10 voussoirs)
    # as one ring and as 2 or 3 rings of the same depth, joints aligned.
    # (1) lambda(rings) <= lambda(one ring), whatever the friction between the rings: every
    # mechanism of the single ring is one of the rings, each stack of voussoirs moving as its
    # voussoir (the ring-to-ring joints closed, each radial joint's segments moving as the
    # whole joint: a hinge through the whole depth is a hinge of one segment and the opening
    # of the others), with the same work of the loads. (2) lambda is non-decreasing in
    # ring_joint_friction: a larger coefficient only widens the statically admissible set.
    # (3) Under the point load (vertical loads: the outer ring is pressed onto the inner one)
    # at friction 10 between the rings the thrust of the single ring can pass from ring to
    # ring within each voussoir, so the load factors are the single ring's (1e-9): measured,
    # not proved (the thrust crosses a collar joint within friction only where it crosses it
    # steeply enough; a failure here would say the LP found a cheaper separation). Under horizontal
    # acceleration this does not hold: the body forces pull the outer ring off the inner one
    # near the springings and the rings separate (docs/bridges.md, "Multi-ring arches"), so
    # there (1) and (2) alone are checked. (4) At friction 0 between the rings, lambda below
    # the single ring's means by (1) that the LP's mechanism is none of the single ring's: a
    # ring-to-ring joint opens or slides in it; the joints carry no shear. (5) The fill (its
    # weight, its pressure) stands on the outer ring alone, the weight the area between the
    # outer extrados and the level; the live load spreads to the outer extrados.
    span = ("&bridge shape = 'segmental', span_m(1) = 6.0, rise_m(1) = 1.5, ring_thickness_m = 0.45, "
            "n_voussoirs = 10,\n  abutment_width_m = 1.0, ring_friction = 0.6{rings} /\n")
    point = "&load point_load_n(1) = 10000, path_x0_m = 1.5, path_x1_m = 1.6, path_points = 2 /\n"

    def bridge_json(name, n_rings, mu, load_text):
        rings = "" if n_rings == 1 else f", n_rings = {n_rings}, ring_joint_friction = {mu}"
        with open(name + ".nml", "w") as f:
            f.write(span.format(rings=rings) + load_text)
        return load(name + ".nml")

    def ring_of(d, i):
        m = re.match(r"span \d+ ring (\d+) voussoir", d["blocks"][i - 1]["name"])
        return int(m.group(1)) if m else 0

    def between_rings(d, f):
        a, b = (ring_of(d, i) for i in f["blocks"])
        return a > 0 and b > 0 and a != b

    one = bridge_json("rings_1", 1, None, point)
    curve1 = [c["load_factor"] for c in one["load_factor_curve"]]
    for n_rings in (2, 3):
        d = bridge_json(f"rings_{n_rings}_mu10", n_rings, 10, point)
        curve = [c["load_factor"] for c in d["load_factor_curve"]]
        check(len(d["blocks"]) == 10 * n_rings + 2 and len(curve) == len(curve1) and
              all(close(a, b, rtol=1e-9) for a, b in zip(curve, curve1)),
              f"{n_rings} rings at friction 10 between them: the point load's curve = the single ring's (1e-9; "
              f"largest difference {max(abs(a / b - 1) for a, b in zip(curve, curve1)):.1e})")
    lams = []
    for mu in (0, 0.3, 0.6, 10):
        d = bridge_json(f"rings_2_mu{mu}", 2, mu, point)
        lams.append(d["load_factor"])
        if mu == 0:
            zero = d
    check(all(lam <= one["load_factor"] * (1 + 1e-9) for lam in lams) and
          all(b >= a * (1 - 1e-9) for a, b in zip(lams, lams[1:])),
          f"2 rings, point load: lambda at ring_joint_friction 0, 0.3, 0.6, 10 = {lams}, non-decreasing, at most "
          f"the single ring's {one['load_factor']}")
    moving = [m for m in zero["mechanism"] if between_rings(zero, m) and m["mode"] != "closed"]
    check(zero["load_factor"] < one["load_factor"] * (1 - 1e-6) and len(moving) > 0,
          f"friction 0 between the rings: lambda {zero['load_factor']:.6g} < {one['load_factor']:.6g}, the rings "
          f"separate: {len(moving)} ring-to-ring joints open or slide in the mechanism "
          f"({sorted(set(m['mode'] for m in moving))})")
    joints = [f for f in zero["contact_forces"] if between_rings(zero, f)]
    largest = max(max(f["normal_n"]) for f in zero["contact_forces"])
    check(len(joints) == 10 and all(abs(f["shear_n"]) <= 1e-9 * largest for f in joints) and
          all(min(f["normal_n"]) >= -1e-9 * largest for f in zero["contact_forces"]),
          "friction 0 between the rings: their 10 joints carry no shear, no interface any tension")
    # Under horizontal acceleration (no &load): (1) and (2) in both directions.
    one = bridge_json("rings_1_accel", 1, None, "")
    both = []
    for mu in (0, 0.6, 10):
        d = bridge_json(f"rings_2_accel_mu{mu}", 2, mu, "")
        both.append((d["load_factor"], d["load_factor_neg"]))
    for k, key in ((0, "load_factor"), (1, "load_factor_neg")):
        seq = [b[k] for b in both]
        check(all(lam <= one[key] * (1 + 1e-9) for lam in seq) and
              all(b >= a * (1 - 1e-9) for a, b in zip(seq, seq[1:])),
              f"2 rings under horizontal acceleration ({key}): {seq} at friction 0, 0.6, 10, non-decreasing, at "
              f"most the single ring's {one[key]}")
    # (5) The fill and its pressure on the outer ring of three.
    with open("rings_fill.nml", "w") as f:
        f.write(span.format(rings=", n_rings = 3, fill_density_kg_m3 = 2000, fill_level_m = 2.25, "
                            "dispersion_angle_deg = 30, fill_friction_deg = 35, passive_mobilisation = 0.33")
                + "&load point_load_n(1) = 100000, point_load_x_m(1) = 1.5 /\n")
    d = load("rings_fill.nml")
    outer = [i for i in range(1, len(d["blocks"]) + 1) if ring_of(d, i) == 3]
    check(sorted(f["block"] for f in d["fill_loads"]) == outer and
          {p["block"] for p in d["fill_pressures"]} <= set(outer) and len(d["fill_pressures"]) >= 8,
          "the fill's weight on each voussoir of the outer ring and on no other, its pressure on the outer ring alone")
    ext = [tuple(d["blocks"][i - 1]["vertices_xy_m"][3]) for i in outer] + [tuple(d["blocks"][outer[-1] - 1]
                                                                                ["vertices_xy_m"][2])]
    poly = ext + [(ext[-1][0], 2.25), (ext[0][0], 2.25)]
    area = abs(0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1])))
    total = -sum(f["force_n"][1] for f in d["fill_loads"])
    check(close(total, 2000 * 9.81 * area, rtol=1e-12),
          f"the fill's weight {total:.6g} N = the area between the outer extrados and the level ({area:.6g} m2) "
          f"x density x g x width")
    (sl,) = d["surface_loads"]
    slope = math.tan(math.radians(30))

    def extrados_y(x):
        for (x0, y0), (x1, y1) in zip(ext, ext[1:]):
            if x0 <= x <= x1:
                return y0 + (x - x0) / (x1 - x0) * (y1 - y0)

    gaps = [2.25 - abs(x - 1.5) / slope - extrados_y(x) for x in sl["spread_x_m"]]
    check(max(abs(g) for g in gaps) < 1e-9,
          f"the live load spreads to where the 30-degree lines meet the outer extrados ({max(map(abs, gaps)):.1e} m)")
elif case == "bridge_fill":
    # The engineers' fill over input/bridge_fill.nml's span, checked from the JSON's blocks
    # alone: (1) the fill's weight on each voussoir = density x g x width x the area of the
    # polygon between its extrados chord and the fill's level (shoelace), at that polygon's
    # centroid's x; in all, the area between the extrados and the level over the ring;
    # (2) each live load's spread ends where the lines from its point on the surface at the
    # dispersion angle meet the extrados; (3) every free block in equilibrium under its
    # weight, the fill's, lambda x the live load spread uniformly along x between those ends
    # (onto the block on top at each x, as 200 strips) and the JSON's contact forces;
    # (4) a fill of vanishing weight and no dispersion gives the bare bridge's load factor.
    d = load(nml)
    check("on the fill's surface" in d["live_load"] and "spread through it at 30 deg" in d["live_load"],
          f"the live load in words says where it stands and how it spreads: {d['live_load']}")
    text = open(nml).read()
    def number(name):
        return nml_number(text, name)
    rho_f, level, theta = number("fill_density_kg_m3"), number("fill_level_m"), number("dispersion_angle_deg")
    rho_r, width = number("ring_density_kg_m3"), number("width_m")
    blocks = d["blocks"]
    free = [i for i, b in enumerate(blocks, start=1) if not b["driven"]]
    def top_edge(poly):
        """The face of a voussoir that runs right to left on top: its extrados chord."""
        return poly[2], poly[3]
    def column(p_right, p_left):
        poly = [p_left, p_right, (p_right[0], level), (p_left[0], level)]
        area = -0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]))
        return abs(area), centroid(poly)[0]
    fills = {f["block"]: f for f in d["fill_loads"]}
    g_w = 9.81 * width
    worst = 0.0
    total = 0.0
    for i in free:
        area, xc = column(*top_edge(blocks[i - 1]["vertices_xy_m"]))
        f = fills[i]
        worst = max(worst, abs(-f["force_n"][1] - rho_f * g_w * area) / (rho_f * g_w * area), abs(f["xy_m"][0] - xc))
        total += -f["force_n"][1]
    check(len(fills) == len(free) and worst < 1e-12, f"fill on each voussoir = the column above its extrados chord, "
                                                     f"at its centroid's x ({worst:.1e})")
    ext = [tuple(blocks[i - 1]["vertices_xy_m"][3]) for i in free] + [tuple(blocks[free[-1] - 1]["vertices_xy_m"][2])]
    poly = ext + [(ext[-1][0], level), (ext[0][0], level)]
    area = abs(0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1])))
    check(close(total, rho_f * g_w * area, rtol=1e-12), f"fill in all {total:.6g} N = the area over the extrados "
                                                        f"({area:.6g} m2) x density x g x width")
    def top(x):
        return top_y(blocks, x)
    def block_on_top(x):
        return top_block(blocks, x)
    slope = math.tan(math.radians(theta))
    for sl in d["surface_loads"]:
        x0 = sl["xy_m"][0]
        lo, hi = sl["spread_x_m"]
        gaps = [level - abs(x - x0) / slope - top(x) for x in (lo, hi)]
        check(sl["xy_m"][1] == level and lo < x0 < hi and max(abs(g) for g in gaps) < 1e-9,
              f"the load at x = {x0:.4g} m spreads from {lo:.4g} to {hi:.4g} m, where the {theta:g}-degree lines "
              f"meet the extrados ({max(abs(g) for g in gaps):.1e} m)")
    lam = d["load_factor"]
    strips = {}
    for sl in d["surface_loads"]:
        lo, hi = sl["spread_x_m"]
        for k in range(200):
            x = lo + (k + 0.5) * (hi - lo) / 200
            strips.setdefault(block_on_top(x), []).append((x, top(x), -sl["force_n"][1] / 200))
    worst = 0.0
    for i in free:
        v = blocks[i - 1]["vertices_xy_m"]
        area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]))
        cx, cy = centroid(v)
        weight = rho_r * g_w * area
        fx, fy, m = contact_resultant(d, i, cx, cy)
        f = fills[i]
        fy += f["force_n"][1] - weight
        m += (f["xy_m"][0] - cx) * f["force_n"][1]
        for x, y, p in strips.get(i, []):
            fy -= lam * p
            m -= (x - cx) * lam * p
        worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(m) / (weight * 10.0))
    check(worst < 1e-7, f"every voussoir in equilibrium: weight, fill, lambda x the spread load, contact forces "
                        f"({worst:.1e})")
    bare = text.replace(f"fill_density_kg_m3 = {rho_f:g}", "fill_density_kg_m3 = 1e-9").replace(
        f"dispersion_angle_deg = {theta:g}", "dispersion_angle_deg = 0")
    with open("bridge_fill_vanishing.nml", "w") as f:
        f.write(bare)
    with open("bridge_fill_none.nml", "w") as f:
        f.write(re.sub(r"fill_density_kg_m3 *= *[^,/]*,? *|fill_level_m *= *[^,/]*,? *|dispersion_angle_deg *= *[^,/]*,? *",
                       "", text))
    a, b = load("bridge_fill_vanishing.nml"), load("bridge_fill_none.nml")
    check(close(a["load_factor"], b["load_factor"], rtol=1e-6) and a["load_factor"] < lam,
          f"a fill of vanishing weight, no spread: the bare bridge's {b['load_factor']:.7g} "
          f"({a['load_factor']:.7g}); the fill raises it to {lam:.7g}")
    # The fill's horizontal pressure (Rankine, phi = 35 deg): on each voussoir's extrados,
    # between K_a and m K_p times the integral of the vertical stress over the face's height,
    # (F - y_a)^2/2 - (F - y_b)^2/2, at that pressure's centroid, horizontal into the ring;
    # the LP's value at collapse within those bounds; upper = lower bound (the work equation
    # with each pressure at its passive bound where the ring moves into the fill, else
    # active); the load factor grows with the mobilisation; statics with the pressures.
    factors = {}
    for m in (0.0, 0.33, 1.0):
        with open(f"bridge_fill_pressure_{m}.nml", "w") as f:
            f.write(text.replace("dispersion_angle_deg = 30", f"dispersion_angle_deg = 30, fill_friction_deg = 35, "
                                                              f"passive_mobilisation = {m}"))
        e = load(f"bridge_fill_pressure_{m}.nml")
        factors[m] = e["load_factor"]
        check(close(e["load_factor_upper"], e["load_factor"], rtol=1e-6),
              f"pressure, mobilisation {m}: upper bound {e['load_factor_upper']} = lower {e['load_factor']}")
        ka = math.tan(math.radians(45 - 35 / 2)) ** 2
        kp = max(ka, m * math.tan(math.radians(45 + 35 / 2)) ** 2)
        worst = 0.0
        for p in e["fill_pressures"]:
            v = blocks[p["block"] - 1]["vertices_xy_m"]
            (x0, y0), (x1, y1) = v[2], v[3]     # the extrados chord, right to left
            ya, yb = min(y0, y1), max(y0, y1)
            s_n = rho_f * g_w * ((level - ya) ** 2 - (level - yb) ** 2) / 2
            yc = (level * (yb ** 2 - ya ** 2) / 2 - (yb ** 3 - ya ** 3) / 3) / s_n * rho_f * g_w
            into = 1.0 if y0 > y1 else -1.0      # the left haunch's face looks left: pushed to +x
            worst = max(worst, abs(p["active_n"] - ka * s_n) / s_n, abs(p["passive_n"] - kp * s_n) / s_n,
                        abs(p["xy_m"][1] - yc), abs(p["direction"][0] - into))
            inside = ka * s_n * (1 - 1e-9) - 1e-9 <= p["at_collapse_n"] <= kp * s_n * (1 + 1e-9) + 1e-9
            worst = max(worst, 0.0 if inside else 1.0)
        check(len(e["fill_pressures"]) == len(free) and worst < 1e-9,
              f"pressure, mobilisation {m}: Rankine's bounds on every extrados face, at the pressure's centroid, into "
              f"the ring, the LP's value between them ({worst:.1e})")
        if m == 0.33:
            worst = 0.0
            press = {p["block"]: p for p in e["fill_pressures"]}
            strips = {}
            for sl in e["surface_loads"]:
                lo, hi = sl["spread_x_m"]
                for k in range(200):
                    x = lo + (k + 0.5) * (hi - lo) / 200
                    strips.setdefault(block_on_top(x), []).append((x, top(x), -sl["force_n"][1] / 200))
            fills_e = {f["block"]: f for f in e["fill_loads"]}
            for i in free:
                v = blocks[i - 1]["vertices_xy_m"]
                area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]))
                cx, cy = centroid(v)
                weight = rho_r * g_w * area
                fx, fy, mo = contact_resultant(e, i, cx, cy)
                f = fills_e[i]
                fy += f["force_n"][1] - weight
                mo += (f["xy_m"][0] - cx) * f["force_n"][1]
                p = press[i]
                h = p["at_collapse_n"] * p["direction"][0]
                fx += h
                mo -= (p["xy_m"][1] - cy) * h
                for x, y, q in strips.get(i, []):
                    fy -= e["load_factor"] * q
                    mo -= (x - cx) * e["load_factor"] * q
                worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(mo) / (weight * 10.0))
            check(worst < 1e-7, f"pressure: every voussoir in equilibrium with the pressures at collapse ({worst:.1e})")
    check(factors[0.0] < factors[0.33] < factors[1.0],
          f"the load factor grows with the passive pressure mobilised: {factors}")
elif case == "bridge_particles":
    # The fill as particles (input/bridge_fill_particles.nml: the span of input/bridge_fill.nml,
    # fill_model = 'particles'), checked from the input and the JSON's blocks alone:
    # (1) every particle convex, counter-clockwise, of positive area, inside the region
    # between the abutments' level tops, the extrados chords (the segmental geometry computed
    # here: R = (L^2/4 + r^2)/(2r), n equal angles) and the level, no two overlapping (a
    # separating axis), their areas summing to the region's shoelace area (1e-9): so they
    # tile it; (2) the live load on a particle at the surface at the critical position;
    # (3) every free block (voussoirs at the ring's density, particles at the fill's) in
    # equilibrium under its weight, lambda x the load and the JSON's contact forces (1e-7),
    # no tension, every interface within friction; (4) the lower bound: with friction
    # mu >= tan of the steepest extrados chord on every interface, the particles carry the
    # fill's weight and the load straight down (sigma_y = rho g (F - y), no shear on level
    # faces, none on vertical ones, a vertical traction on a chord within friction): the
    # ring then carries exactly the engineers' columns with the load on the extrados beneath
    # it (dispersion 0, no horizontal pressure), so the associative lambda with particles is
    # at least the columns' at the same load position.
    d = load(nml)
    text = open(nml).read()
    def number(name):
        return nml_number(text, name)
    span, rise, t, n, level, w, width = one_span_bridge(text)
    rho_f, rho_r, size = number("fill_density_kg_m3"), number("ring_density_kg_m3"), number("fill_particle_size_m")
    ext = segmental_extrados(span, rise, t, n)
    bottom = [(-w, ext[0][1])] + ext + [(span + w, ext[-1][1])]
    region = shoelace(bottom + [(span + w, level), (-w, level)])
    def bottom_y(x):
        return polyline_y(bottom, x)
    blocks = d["blocks"]
    parts = [(i, b["vertices_xy_m"]) for i, b in enumerate(blocks, start=1) if b["name"].startswith("fill particle")]
    check(len(blocks) == n + 2 + len(parts) and all(not b["driven"] for _, b in
                                                   ((i, blocks[i - 1]) for i, _ in parts)),
          f"{n} voussoirs, 2 abutments and {len(parts)} free particles")
    voussoir_ext = [tuple(blocks[k]["vertices_xy_m"][3]) for k in range(n)] + [tuple(blocks[n - 1]["vertices_xy_m"][2])]
    check(max(math.dist(a, b) for a, b in zip(voussoir_ext, ext)) < 1e-9,
          "the voussoirs' extrados ends where the segmental geometry puts them (1e-9 m)")
    areas = [shoelace(v) for _, v in parts]
    check(all(convex_ccw(v) for _, v in parts) and min(areas) > 0,
          f"every particle convex, counter-clockwise, of positive area (least {min(areas):.4g} m2 for size {size} m)")
    inside = all(-w - 1e-9 <= x <= span + w + 1e-9 and bottom_y(x) - 1e-9 <= y <= level + 1e-9
                 for _, v in parts for x, y in v)
    check(inside, "every particle between the abutments' tops and the extrados below and the level above")
    clash = overlapping(parts)
    check(not clash, f"no two particles overlap ({clash[:3]})")
    check(close(sum(areas), region, rtol=1e-9), f"the particles' areas sum to the fill's region {region:.9g} m2 "
                                                f"(shoelace; {abs(sum(areas) / region - 1):.1e})")
    lam = d["load_factor"]
    live = [pl for pl in d["point_loads"] if pl["live"]]
    check(len(live) == 1 and live[0]["xy_m"][1] == level and blocks[live[0]["block"] - 1]["name"].startswith(
        "fill particle") and close(live[0]["xy_m"][0], d["critical_position"]["x_m"], atol=1e-12),
          f"the live load stands on a particle at the surface at the critical position x = "
          f"{d['critical_position']['x_m']:.4g} m (lambda {lam:.6g})")
    worst = 0.0
    g_w = 9.81 * width
    for i, b in enumerate(blocks, start=1):
        if b["driven"]:
            continue
        v = b["vertices_xy_m"]
        weight = (rho_f if b["name"].startswith("fill particle") else rho_r) * g_w * shoelace(v)
        cx, cy = centroid(v)
        fx, fy, m = contact_resultant(d, i, cx, cy)
        fy -= weight
        for pl in live:
            if pl["block"] == i:
                gy = lam * pl["force_n"][1]
                fy, m = fy + gy, m + (pl["xy_m"][0] - cx) * gy
        worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(m) / (weight * size))
    check(worst < 1e-7, f"every voussoir and particle in equilibrium: weight, lambda x the load, contacts ({worst:.1e})")
    mu = number("fill_particle_friction")
    check(all(min(f["normal_n"]) >= -1e-6 and abs(f["shear_n"]) <= mu * sum(f["normal_n"]) * (1 + 1e-9) + 1e-6
              for f in d["contact_forces"]), f"no tension, every interface within friction {mu}")
    steepest = max(abs((y1 - y0) / (x1 - x0)) for (x0, y0), (x1, y1) in zip(ext, ext[1:]))
    rough = 1.5
    check(rough > steepest, f"premise: friction {rough} > tan of the steepest extrados chord ({steepest:.4f})")
    base = re.sub(r"path_x0_m *= *[^,/]*, *path_x1_m *= *[^,/]*, *path_points *= *[^,/\n]*", "POINT", text)
    for key in ("ring_friction", "abutment_friction", "fill_particle_friction"):
        base = re.sub(key + r" *= *[0-9.]+", f"{key} = {rough}", base)
    x0 = 2.5
    with open("particles_rough.nml", "w") as f:
        f.write(base.replace("POINT", f"point_load_x_m(1) = {x0}, point_load_y_m(1) = {level}"))
    columns = re.sub(r",\s*fill_model *= *'particles', *fill_particle_size_m *= *[0-9.]+, *fill_particle_friction *= *"
                     r"[0-9.]+", "", base)
    with open("columns_rough.nml", "w") as f:
        f.write(columns.replace("POINT", f"point_load_x_m(1) = {x0}, point_load_y_m(1) = {level}"))
    b, a = load("particles_rough.nml"), load("columns_rough.nml")
    check("fill_model" not in columns and a["load_factor"] > 0 and
          b["load_factor"] >= a["load_factor"] * (1 - 1e-9),
          f"friction {rough} everywhere, the load at x = {x0} m: lambda with particles {b['load_factor']:.6g} >= "
          f"the columns' without spread or pressure {a['load_factor']:.6g}")
elif case == "bridge_backing":
    # Masonry backing over the haunches (input/bridge_backing.nml: input/bridge_fill.nml's
    # span with backing to 1.5 m in 0.3 m courses), checked from the input and the JSON:
    # (1) the backing's blocks convex, counter-clockwise, between the bottom (the abutments'
    # level tops and the extrados chords of the segmental geometry computed here) and the
    # level, no two overlapping, their areas summing to the trapezoids between the level and
    # every piece of the bottom wholly below it (1e-9): they tile the backed region; (2) the
    # fill's weight on the backing's top courses and on the bare voussoirs, in all the area
    # between the bottom (the backing's top where it is) and the fill's level; (3) every free
    # block (voussoirs at the ring's density, backing at its own) in equilibrium under its
    # weight, the fill's, lambda x the spread load (200 strips onto the block on top) and the
    # JSON's contact forces (1e-7); (4) the lower bound: without fill, a point load on the
    # ring at x = 2.5 m, the backing of vanishing weight adds blocks and interfaces whose
    # forces may be zero, so every static field of the bare bridge stays admissible: lambda
    # with it is at least the bare bridge's.
    d = load(nml)
    text = open(nml).read()
    def number(name):
        return nml_number(text, name)
    span, rise, t, n, level, w, width = one_span_bridge(text)
    theta = number("dispersion_angle_deg")
    back, course = number("backing_level_m"), number("backing_course_m")
    rho_f, rho_r, rho_b = number("fill_density_kg_m3"), number("ring_density_kg_m3"), number("backing_density_kg_m3")
    ext = segmental_extrados(span, rise, t, n)
    bottom = [(-w, ext[0][1])] + ext + [(span + w, ext[-1][1])]
    region = sum((x1 - x0) * (back - (y0 + y1) / 2) for (x0, y0), (x1, y1) in zip(bottom, bottom[1:])
                 if max(y0, y1) <= back)
    blocks = d["blocks"]
    parts = [(i, b["vertices_xy_m"]) for i, b in enumerate(blocks, start=1) if b["name"].startswith("backing ")]
    areas = [shoelace(v) for _, v in parts]
    check(parts and all(convex_ccw(v) for _, v in parts) and min(areas) > 0 and
          all(not blocks[i - 1]["driven"] for i, _ in parts),
          f"{len(parts)} free backing blocks, every one convex, counter-clockwise, of positive area")
    inside = all(-w - 1e-9 <= x <= span + w + 1e-9 and polyline_y(bottom, x) - 1e-9 <= y <= back + 1e-9
                 for _, v in parts for x, y in v)
    check(inside, f"every backing block between the bottom and the level y = {back} m")
    clash = overlapping(parts)
    check(not clash, f"no two backing blocks overlap ({clash[:3]})")
    check(close(sum(areas), region, rtol=1e-9), f"the backing's areas sum to the backed region {region:.9g} m2 "
                                                f"({abs(sum(areas) / region - 1):.1e})")
    beds = sorted({round(y0, 9) for _, v in parts for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1])
                   if y0 == y1 and abs(polyline_y(bottom, (x0 + x1) / 2) - y0) > 1e-9})
    check(beds and all(close((back - y) / course, round((back - y) / course), atol=1e-9) for y in beds),
          f"every bed (a level edge off the bottom) a whole number of {course} m courses below the level: {beds}")
    g_w = 9.81 * width
    # The fill's region: between the bottom and its level, less the backing's.
    fill_area = sum((x1 - x0) * (level - (y0 + y1) / 2) for (x0, y0), (x1, y1) in zip(bottom, bottom[1:])) - region
    fill_total = sum(-f["force_n"][1] for f in d["fill_loads"])
    check(close(fill_total, rho_f * g_w * fill_area, rtol=1e-9) and
          any(blocks[f["block"] - 1]["name"].startswith("backing ") for f in d["fill_loads"]),
          f"the fill's weight {fill_total:.6g} N = its area over the ring and the backing ({fill_area:.6g} m2) x "
          f"density x g x width, the backing's top courses carrying their part")
    lam = d["load_factor"]
    strips = {}
    for sl in d["surface_loads"]:
        lo, hi = sl["spread_x_m"]
        for k in range(200):
            x = lo + (k + 0.5) * (hi - lo) / 200
            strips.setdefault(top_block(blocks, x), []).append((x, -sl["force_n"][1] / 200))
    fills = {}
    for f in d["fill_loads"]:
        fills.setdefault(f["block"], []).append(f)
    worst = 0.0
    for i, b in enumerate(blocks, start=1):
        if b["driven"]:
            continue
        v = b["vertices_xy_m"]
        weight = (rho_b if b["name"].startswith("backing ") else rho_r) * g_w * shoelace(v)
        cx, cy = centroid(v)
        fx, fy, m = contact_resultant(d, i, cx, cy)
        fy -= weight
        for f in fills.get(i, []):
            fy += f["force_n"][1]
            m += (f["xy_m"][0] - cx) * f["force_n"][1]
        for x, p in strips.get(i, []):
            fy -= lam * p
            m -= (x - cx) * lam * p
        worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(m) / (weight * 10.0))
    check(worst < 1e-7, f"every voussoir and backing block in equilibrium: weight, fill, lambda x the spread load, "
                        f"contact forces ({worst:.1e})")
    bare = re.sub(r"fill_density_kg_m3 *= *[^,/]*, *fill_level_m *= *[^,/]*, *dispersion_angle_deg *= *[^,/\n]*,",
                  "", text)
    bare = re.sub(r"path_x0_m *= *[^,/]*, *path_x1_m *= *[^,/]*, *path_points *= *[^,/\n]*",
                  f"point_load_x_m(1) = 2.5, point_load_y_m(1) = {polyline_y(bottom, 2.5)!r}", bare)
    light = re.sub(r"backing_density_kg_m3 *= *[^,/\n]*", "backing_density_kg_m3 = 1e-6", bare)
    none = re.sub(r",?\s*backing_level_m *= *[^,/]*, *backing_course_m *= *[^,/]*, *backing_density_kg_m3 *= *[^,/]*,"
                  r" *backing_friction *= *[^,/\n]*", "", bare)
    for name, body in (("bridge_backing_light.nml", light), ("bridge_backing_none.nml", none)):
        with open(name, "w") as f:
            f.write(body)
    a, b = load("bridge_backing_light.nml"), load("bridge_backing_none.nml")
    check("fill_density" not in light and "backing_level_m" in light and "backing_level_m" not in none and
          a["load_factor"] >= b["load_factor"] * (1 - 1e-9),
          f"no fill, the load on the ring at x = 2.5 m: lambda with weightless backing {a['load_factor']:.7g} >= "
          f"the bare bridge's {b['load_factor']:.7g}")
elif case == "bridge_strength":
    # The parts' compressive strengths (&bridge ring_/pier_compressive_strength_pa), on
    # input/bridge_fill.nml and input/bridge_two_spans.nml, against the rule they state (an
    # interface takes the lesser of its two blocks' sigma_c, a rigid block's neighbour's
    # own): (1) a single span, whose every interface touches a voussoir, with the ring at S
    # is the span with &limit compressive_strength_pa = S on every interface (the same load
    # factors to 1e-9) and the crushing lowers it; (2) two spans with the ring at 5 MPa and
    # the pier at 2 MPa: each interface's strength in the JSON is the one its blocks' names
    # call for (ring-ring 5, ring-abutment 5, ring-pier 2, pier-ground 2 MPa); (3) a ring of
    # 1e10 Pa moves each interface's force in by at most delta = N_max / (2 sigma_c w)
    # (tens of micrometres): the load factor falls below the rigid one by a fraction of the
    # order of delta / t (the hinges move in by delta), here at most 10 delta / t.
    fill_text = open(nml).read()
    # (two spans: the load at span 1's crown, on its extrados at rise + ring, not the path)
    spans_text = re.sub(r"path_x0_m *= *[^,/]*, *path_x1_m *= *[^,/]*, *path_points *= *[^,/\n]*",
                        "point_load_x_m(1) = 5.0, point_load_y_m(1) = 2.95",
                        open(os.path.join(os.path.dirname(nml), "bridge_two_spans.nml")).read())
    check("point_load_x_m(1) = 5.0" in spans_text, "the two spans' path replaced by a load at the crown")
    S = 5.0e6
    def variant(text, name, extra_bridge="", extra_groups=""):
        body = text.replace("ring_density_kg_m3 = 2200", "ring_density_kg_m3 = 2200" + extra_bridge, 1)
        check(body != text or not extra_bridge, f"{name}: the input names ring_density_kg_m3 = 2200 to extend")
        with open(name, "w") as f:
            f.write(body + extra_groups)
        return load(name)
    rigid = variant(fill_text, "strength_none.nml")
    by_part = variant(fill_text, "strength_ring.nml", f", ring_compressive_strength_pa = {S:g}")
    everywhere = variant(fill_text, "strength_limit.nml", "", f"\n&limit compressive_strength_pa = {S:g} /\n")
    check(close(by_part["load_factor"], everywhere["load_factor"], rtol=1e-9) and
          by_part["load_factor"] < rigid["load_factor"] * (1 - 1e-3),
          f"one span, ring at {S:g} Pa: lambda {by_part['load_factor']:.9g} = &limit's on every interface "
          f"{everywhere['load_factor']:.9g}, below the rigid {rigid['load_factor']:.9g}")
    check(by_part["compressive_strength_pa"] is None and
          all(x == S for x in by_part["interface_compressive_strength_pa"]) and
          len(by_part["interface_compressive_strength_pa"]) == len(by_part["contact_forces"]),
          "one span: every interface at the ring's strength in the JSON")
    two = variant(spans_text, "strength_two_spans.nml",
                  ", ring_compressive_strength_pa = 5e6, pier_compressive_strength_pa = 2e6")
    names = [b["name"] for b in two["blocks"]]
    def expected(a, b):
        def own(n):
            return 5e6 if n.startswith("span ") else 2e6 if n.startswith("pier ") else 0.0
        x, y = own(a), own(b)
        return min(x, y) if x > 0 and y > 0 else max(x, y)
    got = [(names[c["blocks"][0] - 1], names[c["blocks"][1] - 1], st)
           for c, st in zip(two["contact_forces"], two["interface_compressive_strength_pa"])]
    kinds = {(a.split()[0], b.split()[0]) for a, b, _ in got}
    check(all(st == expected(a, b) for a, b, st in got) and ("pier", "ground") in kinds and
          any("pier" in (a.split()[0], b.split()[0]) and "span" in (a.split()[0], b.split()[0]) for a, b, _ in got),
          f"two spans: each of {len(got)} interfaces at the lesser of its blocks' strengths (ring 5 MPa, pier 2 MPa)")
    strong = variant(fill_text, "strength_strong.nml", ", ring_compressive_strength_pa = 1e10")
    n_max = max(sum(c["normal_n"]) for c in strong["contact_forces"])
    width, t = nml_number(fill_text, "width_m"), nml_number(fill_text, "ring_thickness_m")
    delta = n_max / (2 * 1e10 * width)
    deficit = 1 - strong["load_factor"] / rigid["load_factor"]
    check(by_part["load_factor"] < strong["load_factor"] <= rigid["load_factor"] and deficit <= 10 * delta / t,
          f"a ring of 1e10 Pa: {strong['load_factor']:.9g} against the rigid {rigid['load_factor']:.9g} "
          f"(deficit {deficit:.2e} <= 10 delta / t = {10 * delta / t:.2e})")
elif case == "bridge_vehicle":
    # &vehicle on input/bridge_fill.nml's span (fill, live loads spread at 30 deg), checked
    # against what follows from the input alone: (1) a one-axle vehicle of 100 kN is the
    # point load of 100000 N (the same curve, 1e-12); (2) two axles of 50 kN 0 m apart are
    # one of 100 kN (1e-9); (3) at the critical position the axles stand on the fill's
    # surface spacing apart, each axle_load_kn x 1e3 x width_m/effective_width_m, their
    # resultant at the position; (4) the harmonic bound: the set of live loads the bridge
    # carries (associative friction) is convex, so a vehicle whose axles alone carry
    # lambda_1 and lambda_2 where they stand carries at least 1/(1/lambda_1 + 1/lambda_2)
    # (a convex combination of the two collapse loads is carried); (5) EN 1991-2's tandem
    # on lane 1 (2 x 300 kN, 1.2 m) on an effective width of 3 m is the user-defined 2 x
    # 100 kN, 1.2 m apart, on the whole strip.
    text = open(nml).read()
    bridge = text[text.index("&bridge"):text.index("/", text.index("&bridge")) + 1]
    def write(name, groups):
        with open(name, "w") as f:
            f.write(bridge + "\n" + groups)
        return load(name)
    def curve(d):
        return [(p["x_m"], p["load_factor"]) for p in d["load_factor_curve"]]
    path = "path_x0_m = 1.0, path_x1_m = 9.0, path_points = 17"
    point = write("vehicle_point.nml", f"&load point_load_n(1) = 100000, {path} /\n")
    one = write("vehicle_one_axle.nml", f"&load {path} /\n&vehicle axle_load_kn = 100 /\n")
    a, b = curve(point), curve(one)
    worst = max(abs(la - lb) / la for (_, la), (_, lb) in zip(a, b))
    check(len(a) == len(b) and all(xa == xb for (xa, _), (xb, _) in zip(a, b)) and worst < 1e-12,
          f"a one-axle vehicle of 100 kN = the point load of 100000 N along the path ({len(a)} positions, {worst:.1e})")
    check("&vehicle" in one["live_load"] and "1 axles of 100 kN" in one["live_load"],
          f"the live load in words names the vehicle: {one['live_load'][:90]}")
    pair = write("vehicle_zero_spacing.nml", f"&load {path} /\n&vehicle axle_load_kn = 50, 50, axle_spacing_m = 0 /\n")
    c = curve(pair)
    worst = max(abs(la - lc) / la for (_, la), (_, lc) in zip(a, c))
    check(len(a) == len(c) and worst < 1e-9, f"two axles of 50 kN 0 m apart = one of 100 kN ({worst:.1e})")
    spacing = 2.0
    veh = write("vehicle_two_axles.nml", "&load path_x0_m = 2.0, path_x1_m = 8.0, path_points = 13 /\n"
                f"&vehicle name = 'two axles', axle_load_kn = 100, 100, axle_spacing_m = {spacing}, "
                "effective_width_m = 2.5 /\n")
    width = float(re.search(r"\bwidth_m *= *([-0-9.eE+]+)", bridge).group(1))
    share = width / 2.5
    xc = veh["critical_position"]["x_m"]
    loads = sorted(veh["surface_loads"], key=lambda q: q["xy_m"][0])
    level = float(re.search(r"fill_level_m *= *([-0-9.eE+]+)", bridge).group(1))
    check(len(loads) == 2 and close(loads[1]["xy_m"][0] - loads[0]["xy_m"][0], spacing, atol=1e-12)
          and all(close(-q["force_n"][1], 100e3 * share, rtol=1e-15) and q["xy_m"][1] == level for q in loads)
          and close(0.5 * (loads[0]["xy_m"][0] + loads[1]["xy_m"][0]), xc, atol=1e-12),
          f"at the critical x = {xc:.4f} m two axles of 100 kN x {share:g} on the surface {spacing:g} m apart, "
          f"their resultant there: {[(q['xy_m'][0], q['force_n'][1]) for q in loads]}")
    # The axles alone, on the grid 1.0 .. 9.0 m by 0.5 m: at vehicle position X they stand at X -/+ 1 m.
    # (a's 100 kN at x carries lambda; an axle of 100 kN x share alone carries lambda/share.)
    on_grid = dict((round(x, 9), lam) for x, lam in a)
    alone = {round(1.0 + 0.5 * i, 9): on_grid[round(1.0 + 0.5 * i, 9)] for i in range(17)}
    worst, n = math.inf, 0
    for x, lam in curve(veh):
        xr = round(x, 9)
        if xr not in {round(2.0 + 0.5 * i, 9) for i in range(13)}:
            continue
        l1, l2 = alone[round(xr - 1.0, 9)] / share, alone[round(xr + 1.0, 9)] / share
        bound = 1.0 / (1.0 / l1 + 1.0 / l2)
        worst = min(worst, lam / bound - 1.0)
        n += 1
    check(n == 13 and worst >= -1e-9, f"at each of {n} grid positions the vehicle's lambda >= the harmonic bound of "
                                      f"its axles alone (least margin {worst:.3g})")
    tandem = write("vehicle_lm1.nml", f"&load {path} /\n&vehicle name = 'lm1_tandem_lane1', effective_width_m = 3 /\n")
    user = write("vehicle_lm1_user.nml", f"&load {path} /\n&vehicle axle_load_kn = 100, 100, axle_spacing_m = 1.2 /\n")
    check(close(tandem["load_factor"], user["load_factor"], rtol=1e-12),
          f"LM1's tandem (2 x 300 kN, 1.2 m) over 3 m = 2 x 100 kN 1.2 m apart on the 1 m strip: "
          f"{tandem['load_factor']:.10g} and {user['load_factor']:.10g}")
elif case == "load_cases":
    # Patches, load cases and partial factors (issue 37, item 3) on input/bridge_load_cases.nml
    # (its span is input/bridge_fill.nml's), each expectation from the inputs alone:
    # (1) a patch of vanishing length is the point load (the whole curve, 1e-9), with the
    # fill and without; (2) gamma_q multiplies the live loads alone, so the load factor on
    # the factored live load is the unfactored one / gamma_q (every position, 1e-9); (3) with
    # rigid blocks (no compressive strength) the LP is homogeneous in the loads (equilibrium,
    # no tension and Coulomb are cones), so gamma_g on every permanent load multiplies the
    # load factor by gamma_g (the permanent loads stabilise the arch: it rises, 1e-9); the
    # statics of that solution: every voussoir in equilibrium under gamma_g x its weight,
    # lambda x the factored patch as 200 uniform strips and the JSON's forces (1e-7); (4)
    # each case of the two-case file equals that case alone in its own file (1e-12), the
    # governing one the least, the JSON's top-level keys its; the table's summary.
    text = open(nml).read()
    bridge = text[text.index("&bridge"):text.index("/", text.index("&bridge")) + 1]
    bare = re.sub(r",\s*fill_density_kg_m3 *= *[^,/]*, *fill_level_m *= *[^,/]*, *dispersion_angle_deg *= *[^,/\n]*",
                  "", bridge)
    check("fill" not in bare, "the bridge without its fill")
    path = "path_x0_m = 1.0, path_x1_m = 9.0, path_points = 17"
    def write(name, groups, b=bridge):
        with open(name, "w") as f:
            f.write(b + "\n" + groups)
        return load(name)
    def curve(d):
        return [(p["x_m"], p["load_factor"]) for p in d["load_factor_curve"]]
    def worst_ratio(a, b, factor=1.0):
        return max(abs(lb * factor / la - 1) for (_, la), (_, lb) in zip(a, b))
    for label, b in (("fill", bridge), ("no fill", bare)):
        point = write(f"cases_point_{label[:2]}.nml", f"&load point_load_n(1) = 100000, {path} /\n", b)
        # Without the fill 2e-9 m is still strips (beyond the 1e-9 m below which a patch is
        # one load); with it the spread's feet move by half the patch, 1e-10 m.
        tiny_m = 1e-10 if label == "fill" else 2e-9
        tiny = write(f"cases_tiny_patch_{label[:2]}.nml",
                     f"&load point_load_n(1) = 100000, point_load_patch_m(1) = {tiny_m}, {path} /\n", b)
        a, c = curve(point), curve(tiny)
        check(len(a) == len(c) > 17 and all(xa == xc for (xa, _), (xc, _) in zip(a, c)) and
              worst_ratio(a, c) < 1e-9,
              f"{label}: a patch of {tiny_m:g} m = the point load along the path ({len(a)} positions, "
              f"{worst_ratio(a, c):.1e})")
        patched = write(f"cases_patch_{label[:2]}.nml",
                        f"&load point_load_n(1) = 100000, point_load_patch_m(1) = 0.3, {path} /\n", b)
        key = "surface_loads" if label == "fill" else "patch_loads"
        pl = patched[key]
        check(len(pl) == 1 and pl[0]["patch_m"] == 0.3 and (label == "fill" or
              close(pl[0]["spread_x_m"][1] - pl[0]["spread_x_m"][0], 0.3, atol=1e-12) and
              close(sum(pl[0]["spread_x_m"]) / 2, patched["critical_position"]["x_m"], atol=1e-12)),
              f"{label}: the patch of 0.3 m in {key}, centred on the critical position: {pl}")
        check(patched["load_factor"] >= point["load_factor"] * (1 - 1e-9),
              f"{label}: spreading the load over 0.3 m does not lower the least load factor "
              f"({patched['load_factor']:.6g} against the point's {point['load_factor']:.6g})")
        if label == "no fill":
            plain, plain_curve = patched, curve(patched)
        else:
            filled = patched
            axle = write("cases_vehicle_patch.nml", f"&load {path} /\n&vehicle axle_load_kn = 100, "
                                                    "patch_length_m = 0.3 /\n")
            check(worst_ratio(curve(patched), curve(axle)) < 1e-12,
                  f"&vehicle patch_length_m = 0.3: a one-axle vehicle of 100 kN = the patch of &load along the path "
                  f"({worst_ratio(curve(patched), curve(axle)):.1e})")
    # (2) gamma_q on the bare bridge (a patch of 0.3 m).
    one = "&load point_load_n(1) = 100000, point_load_patch_m(1) = 0.3, " + path + " /\n"
    q = write("cases_gamma_q.nml", one + "&load_cases name(1) = 'q', gamma_q(1) = 1.5 /\n", bare)
    check(worst_ratio(plain_curve, curve(q), 1.5) < 1e-9 and close(q["load_factor"] * 1.5, plain["load_factor"],
                                                                    rtol=1e-9),
          f"gamma_q = 1.5: lambda = the unfactored {plain['load_factor']:.7g} / 1.5 = {q['load_factor']:.7g} "
          f"at every position ({worst_ratio(plain_curve, curve(q), 1.5):.1e})")
    lc = q["load_cases"]
    check(len(lc) == 1 and lc[0]["adequacy_factor"] == q["load_factor"] and
          close(lc[0]["characteristic_load_factor"], plain["load_factor"], rtol=1e-9) and
          close(lc[0]["collapse_live_load_n"], q["load_factor"] * 150000, rtol=1e-12) and
          lc[0]["factored_live_load_n"] == 150000,
          f"gamma_q: adequacy factor = lambda, lambda x gamma_q = the unfactored one, the collapse load lambda x 150 kN: "
          f"{lc[0]['adequacy_factor']:.7g}, {lc[0]['characteristic_load_factor']:.7g}, "
          f"{lc[0]['collapse_live_load_n']:.7g} N")
    # (3) gamma_g, without the fill and with it.
    for label, b, ref in (("no fill", bare, plain), ("fill", bridge, None)):
        if ref is None:
            ref = write("cases_gamma_g_ref.nml", one)
        g = write(f"cases_gamma_g_{label[:2]}.nml", one + "&load_cases name(1) = 'g', gamma_q(1) = 1.5, "
                                                          "gamma_g(1) = 1.3 /\n", b)
        check(g["load_factor"] > ref["load_factor"] / 1.5 and
              close(g["load_factor"], ref["load_factor"] * 1.3 / 1.5, rtol=1e-9),
              f"{label}: gamma_g = 1.3, gamma_q = 1.5: lambda {g['load_factor']:.7g} = the unfactored "
              f"{ref['load_factor']:.7g} x 1.3 / 1.5 (homogeneous LP; the permanent loads stabilise)")
        if label != "no fill":
            continue
        rho = float(re.search(r"ring_density_kg_m3 *= *([-0-9.eE+]+)", bare).group(1))
        blocks = g["blocks"]
        patch = g["patch_loads"][0]
        lo, hi = patch["spread_x_m"]
        lam, p_n = g["load_factor"], -patch["force_n"][1]
        check(p_n == 150000, f"the patch in the JSON is the factored load 1.5 x 100 kN: {p_n}")
        def top_block(x):
            best, who = None, None
            for i, blk in enumerate(blocks, start=1):
                v = blk["vertices_xy_m"]
                for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]):
                    if min(x0, x1) - 1e-9 <= x <= max(x0, x1) + 1e-9 and abs(x1 - x0) > 1e-9:
                        y = y0 + (x - x0) / (x1 - x0) * (y1 - y0)
                        if best is None or y > best + 1e-9:
                            best, who = y, i
            return who
        strips = {}
        for k in range(200):
            x = lo + (k + 0.5) * (hi - lo) / 200
            strips.setdefault(top_block(x), []).append((x, p_n / 200))
        worst = 0.0
        for i, blk in enumerate(blocks, start=1):
            if blk["driven"]:
                continue
            v = blk["vertices_xy_m"]
            area = 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(v, v[1:] + v[:1]))
            cx, cy = centroid(v)
            weight = 1.3 * rho * 9.81 * 1.0 * area
            fx, fy, m = contact_resultant(g, i, cx, cy)
            fy -= weight
            for x, pk in strips.get(i, []):
                fy -= lam * pk
                m -= (x - cx) * lam * pk
            worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(m) / (weight * 10.0))
        check(worst < 1e-7 and len(strips) >= 1,
              f"gamma_g = 1.3: every voussoir in equilibrium under 1.3 x its weight, lambda x the factored patch "
              f"as 200 strips and the JSON's forces ({worst:.1e})")
    # (4) The two cases of the file, each alone.
    both = load(nml)
    lc = both["load_cases"]
    # Each case alone: its own loads (those of input/bridge_load_cases.nml) and factors.
    alone = [write("cases_alone_1.nml", "&load_cases name(1) = 'single axle', gamma_q(1) = 1.5 /\n"
                   "&load point_load_n(1) = 100000, point_load_patch_m(1) = 0.3, " + path + " /\n"),
             write("cases_alone_2.nml", "&load_cases name(1) = 'tandem', gamma_q(1) = 1.35 /\n"
                   "&load point_load_n(1) = 100000, point_load_x_m(1) = 0.0, point_load_patch_m(1) = 0.4,\n"
                   "  point_load_n(2) = 100000, point_load_x_m(2) = 1.2, point_load_patch_m(2) = 0.4, " + path + " /\n")]
    for k, a in enumerate(alone):
        c = lc[k]
        same = (close(c["load_factor"], a["load_factor"], rtol=1e-12) and
                close(c["critical_position"]["x_m"], a["critical_position"]["x_m"], atol=1e-12) and
                len(c["load_factor_curve"]) == len(a["load_factor_curve"]) and
                all(close(p["load_factor"], r["load_factor"], rtol=1e-12)
                    for p, r in zip(c["load_factor_curve"], a["load_factor_curve"])))
        check(same and a["load_cases"][0]["factored_live_load_n"] == c["factored_live_load_n"],
              f"case {k + 1} '{c['name']}' in the two-case file = alone in its own file: lambda "
              f"{c['load_factor']:.7g} at x = {c['critical_position']['x_m']:.6g} m, "
              f"{c['factored_live_load_n']:.6g} N of factored live load")
    gov = min(range(2), key=lambda k: lc[k]["load_factor"])
    check(both["governing_load_case"] == gov + 1 and both["load_factor"] == lc[gov]["load_factor"] and
          both["critical_position"]["x_m"] == lc[gov]["critical_position"]["x_m"],
          f"the governing case {both['governing_load_case']} is the least, and the top-level keys are its own")
    check(lc[0]["factored_live_load_n"] == 150000 and lc[1]["factored_live_load_n"] == 270000 and
          close(lc[0]["load_factor"] * 1.5, filled["load_factor"], rtol=1e-9),
          f"case 1: 1.5 x 100 kN, its lambda x 1.5 = the unfactored patch's on the filled span "
          f"{filled['load_factor']:.7g}; case 2: 1.35 x 2 x 100 kN")
    rc, out, _ = run(nml)
    rows = [line for line in out.splitlines() if line.startswith("  1 ") or line.startswith("  2 ")]
    check(rc == 0 and "Load case 1 'single axle'" in out and "Load case 2 'tandem'" in out and len(rows) == 2 and
          "(governs)" in rows[gov] and all(("NOT adequate" in r) == (c["load_factor"] < 1) for r, c in zip(rows, lc)),
          f"the table: each case's LP, and a summary row each, the governing case marked: {rows}")
elif case == "bridge_boussinesq":
    # &bridge dispersion = 'boussinesq' on input/bridge_fill.nml's span, each expectation
    # from the input and the JSON's blocks alone. Flamant's vertical stress under a line load
    # P at depth z and offset u, sigma = 2 P z^3 / (pi (u^2 + z^2)^2), integrates over u from
    # a to b to (P/pi) [G(b/z) - G(a/z)], G(t) = atan(t) + t/(1 + t^2) (differentiate: G' =
    # 2/(1 + t^2)^2); a patch of length p is that integrand averaged over the patch, here by
    # Simpson's rule (not the code's closed form). (1) The strips sum to P (1e-12) and each
    # carries that integral over its length at its depth (the fill's level less the top at
    # its middle) times P / the sum of them all (1e-9); the JSON's `retained` is that sum / P;
    # the strips tile the spread and each lies on one straight face of the blocks' top.
    # (2) Each end of the spread is the deck's end or where the stress there falls to the
    # cutoff x the stress beneath the load (1e-6), and no sample of the deck outside the
    # spread reaches the cutoff. (3) A load over the crown of the symmetric span: the spread
    # and the strips mirror, the applied load's centroid is under the load (1e-9 m).
    # (4) Every voussoir in equilibrium under its weight, the fill's, lambda x the strips and
    # the JSON's forces (1e-7). (5) The ordering: the strips are a convex combination of
    # point loads on the blocks' top, and with associative friction the loads carried form a
    # convex set (equilibrium and yield are linear), so the spread load is carried at least
    # at the least load factor of the load placed undispersed (angle 0) anywhere on the deck.
    # Against the 30-degree spread no ordering follows (neither distribution is a mixture of
    # the other's translates): the two are only reported.
    text = open(nml).read()
    bous = text.replace("dispersion_angle_deg = 30", "dispersion = 'boussinesq'")
    check(bous != text, "the input gives dispersion_angle_deg = 30 to replace")
    path = "path_x0_m = 1.0, path_x1_m = 9.0, path_points = 17"
    check(path in text, "the input's path to replace")
    def number(name):
        return nml_number(text, name)
    level, rho_f, rho_r, width = (number(k) for k in ("fill_level_m", "fill_density_kg_m3", "ring_density_kg_m3",
                                                      "width_m"))
    g_w = 9.81 * width
    def flamant_g(t):
        return math.atan(t) + t / (1.0 + t * t)
    def stress(P, patch, u, z):
        if patch == 0.0:
            return 2.0 * P * z ** 3 / (math.pi * (u * u + z * z) ** 2)
        h = patch / 2      # the patch: Flamant's stress averaged over it (Simpson, 400 pieces)
        return simpson(lambda s: 2.0 * P * z ** 3 / (math.pi * ((u - s) ** 2 + z * z) ** 2), -h, h) / patch
    def strip_integral(P, patch, a, b, z):
        if patch == 0.0:
            return P / math.pi * (flamant_g(b / z) - flamant_g(a / z))
        h = patch / 2
        return simpson(lambda s: P / math.pi * (flamant_g((b - s) / z) - flamant_g((a - s) / z)), -h, h) / patch
    def simpson(f, a, b, n=400):
        hh = (b - a) / n
        return hh / 3 * (f(a) + f(b) + sum((4 if k % 2 else 2) * f(a + k * hh) for k in range(1, n)))
    def check_strips(d, name):
        blocks = d["blocks"]
        xs = [x for b in blocks for x, _ in b["vertices_xy_m"]]
        deck = (min(xs), max(xs))
        out = []
        for sl in d["surface_loads"]:
            P, x0, patch = -sl["force_n"][1], sl["xy_m"][0], sl["patch_m"]
            lo, hi = sl["spread_x_m"]
            loads, edges = sl["strip_load_n"], sl["strip_edges_x_m"]
            n = len(loads)
            # The strips tile the spread, none longer than 1/200 of it, and each lies on one
            # straight face of the top: every block vertex inside the spread is a strip's end.
            inside = [x for x in xs if lo + 1e-9 < x < hi - 1e-9]
            check(len(edges) == n + 1 and edges[0] == lo and edges[-1] == hi and
                  all(0 < b - a <= (hi - lo) / 200 * (1 + 1e-12) for a, b in zip(edges, edges[1:])) and
                  all(min(abs(e - x) for e in edges) <= 1e-9 for x in inside),
                  f"{name}: {n} strips tile the spread, each at most 1/200 of it, cut at the {len(set(inside))} "
                  f"vertices inside it")
            mids = [(a + b) / 2 for a, b in zip(edges, edges[1:])]
            raw = [strip_integral(P, patch, a - x0, b - x0, level - top_y(blocks, m))
                   for a, b, m in zip(edges, edges[1:], mids)]
            scale = P / sum(raw)
            worst = max(abs(q - r * scale) / (r * scale) for q, r in zip(loads, raw))
            check(sl["dispersion"] == "boussinesq" and n >= 200 and close(sum(loads), P, rtol=1e-12),
                  f"{name}: {n} strips summing to the load {P:g} N ({abs(sum(loads) - P) / P:.1e})")
            check(worst < 1e-9, f"{name}: each strip carries Flamant's stress integrated over it at its depth, "
                                f"times P / their sum ({worst:.1e})")
            check(close(sl["retained"], sum(raw) / P, rtol=1e-12),
                  f"{name}: retained {sl['retained']:.6g} = the strips' integrals / P")
            ref = stress(P, patch, 0.0, level - top_y(blocks, x0))
            cutoff = sl["cutoff"]
            for end, bound in ((lo, deck[0]), (hi, deck[1])):
                ratio = stress(P, patch, end - x0, level - top_y(blocks, end)) / ref
                check(abs(end - bound) < 1e-12 or abs(ratio / cutoff - 1) < 1e-6,
                      f"{name}: the spread ends at x = {end:.6g} m, the deck's end or where the stress is "
                      f"{cutoff:g} x that beneath the load ({ratio:.6g})")
            outside = [deck[0] + (deck[1] - deck[0]) * (k + 0.5) / 997 for k in range(997)]
            outside = [x for x in outside if x < lo or x > hi]
            check(all(stress(P, patch, x - x0, level - top_y(blocks, x)) / ref < cutoff for x in outside),
                  f"{name}: no point of the deck outside the spread ({len(outside)} sampled) reaches the cutoff")
            out.append((mids, loads, lo, hi, x0))
        return out
    with open("bridge_boussinesq.nml", "w") as f:
        f.write(bous)
    d = load("bridge_boussinesq.nml")
    check("Boussinesq" in d["live_load"], f"the live load in words says how it spreads: {d['live_load']}")
    ((mids, loads, lo, hi, x0),) = check_strips(d, "critical position")
    blocks = d["blocks"]
    lam = d["load_factor"]
    fills = {f["block"]: f for f in d["fill_loads"]}
    worst = 0.0
    for i in [i for i, b in enumerate(blocks, start=1) if not b["driven"]]:
        v = blocks[i - 1]["vertices_xy_m"]
        area = 0.5 * sum(xa * yb - xb * ya for (xa, ya), (xb, yb) in zip(v, v[1:] + v[:1]))
        cx, cy = centroid(v)
        weight = rho_r * g_w * area
        fx, fy, m = contact_resultant(d, i, cx, cy)
        fy += fills[i]["force_n"][1] - weight
        m += (fills[i]["xy_m"][0] - cx) * fills[i]["force_n"][1]
        for x, q in zip(mids, loads):
            if top_block(blocks, x) == i:
                fy -= lam * q
                m -= (x - cx) * lam * q
        worst = max(worst, abs(fx) / weight, abs(fy) / weight, abs(m) / (weight * 10.0))
    check(worst < 1e-7,
          f"every voussoir in equilibrium: weight, fill, lambda x the strips, contact forces ({worst:.1e})")
    # Over the crown of the symmetric span, the abutments 6 m long so that the cutoff ends
    # the spread; and a patch of 0.3 m at the critical position.
    crown = bous.replace(path, "point_load_x_m(1) = 5.0").replace("abutment_width_m = 2.0", "abutment_width_m = 6.0")
    check("abutment_width_m = 6.0" in crown, "the input's abutments to lengthen")
    with open("bridge_boussinesq_crown.nml", "w") as f:
        f.write(crown)
    e = load("bridge_boussinesq_crown.nml")
    ((mids, loads, lo, hi, x0),) = check_strips(e, "crown")
    xc = sum(x * q for x, q in zip(mids, loads)) / sum(loads)
    mirror = max(abs(a - b) / a for a, b in zip(loads, reversed(loads)))
    check(abs(xc - 5.0) < 1e-9 and abs(lo + hi - 10.0) < 1e-9 and mirror < 1e-9 and -6.0 < lo and hi < 16.0,
          f"crown: the spread from {lo:.6g} to {hi:.6g} m, within the deck, mirrors about x = 5 m "
          f"(strips {mirror:.1e}); the load's centroid at {xc:.12g} m")
    with open("bridge_boussinesq_patch.nml", "w") as f:
        x_critical = d["critical_position"]["x_m"]
        f.write(bous.replace(path, f"point_load_x_m(1) = {x_critical!r}, point_load_patch_m(1) = 0.3"))
    check_strips(load("bridge_boussinesq_patch.nml"), "patch of 0.3 m")
    # The ordering (5): the undispersed load moved over the whole deck, refined at the joints.
    with open("bridge_boussinesq_none.nml", "w") as f:
        f.write(text.replace(", dispersion_angle_deg = 30", "").replace(
            path, "path_x0_m = -1.99, path_x1_m = 11.99, path_points = 29"))
    none = load("bridge_boussinesq_none.nml")["load_factor"]
    angle = load(nml)["load_factor"]
    check(lam >= none * (1 - 1e-9), f"Boussinesq's load factor {lam:.7g} >= the least undispersed one on the deck "
                                    f"{none:.7g} (the 30-degree spread: {angle:.7g}, not ordered)")
else:
    check(False, f"unknown case {case}")

print(f"{case}: {len(failures)} failed")
sys.exit(1 if failures else 0)
