"""Checks of voussoir-limit: check_limit.py EXE CASE [INPUT.nml]."""
import json
import math
import os
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
elif case == "bad_inputs":
    poly = os.path.join(os.path.dirname(os.path.abspath(nml)), "blocks", "rocking_block.txt")
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
        ("restrained", "restrained_springings = 'left'.*restraint", "&arch restrained_springings = 'left' /\n"),
        ("polygon_file", "polygon_file", f"&arch polygon_file = '{poly}' /\n"),
        ("unknown_group", "unknown namelist group &limits", "&arch /\n&limits /\n"),
        ("two_voussoirs", "n_voussoirs = 2", "&arch n_voussoirs = 2 /\n"),
        ("three_voussoirs_min_thickness", "minimum_thickness", "&arch n_voussoirs = 3 /\n"),
        ("thickness", "thickness_m", "&arch thickness_m = 0.6 /\n"),
    ]
    import re
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
else:
    check(False, f"unknown case {case}")

print(f"{case}: {len(failures)} failed")
sys.exit(1 if failures else 0)
