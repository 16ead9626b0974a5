"""The drivers' --help lists the namelist groups they read, every variable with its
unit: checked against what a run really records (the effective settings in /config of a
file written by the real voussoir-run), not against a list kept here."""

from __future__ import annotations

import re
import subprocess

import h5py
import pytest

from conftest import run_executable

#: A run of a few steps that sets one joint_friction entry, so that /config/arch holds
#: the sparse list too (an unset entry is not a setting and is not recorded).
SHORT_NML = """\
&arch
  joint_friction(0) = 0.4
/
&motion
  amplitude_m = 0.0, rest_s = 0.0, duration_s = 0.01
/
&output
  file = '{file}'
/
"""

#: The unit a variable's name ends with (the project's naming rule: units in the name).
UNIT_OF_SUFFIX = (("_kg_m3", "kg/m3"), ("_m_s3", "m/s3"), ("_n_per_m", "N/m"), ("_deg", "deg"), ("_hz", "Hz"),
                  ("_rad", "rad"), ("_pa", "Pa"), ("_m", "m"), ("_s", "s"), ("_n", "N"), ("_g", "g"))


def help_groups(exe) -> dict[str, dict[str, str]]:
    """{group: {variable: its line}} of ``exe --help``."""
    proc = subprocess.run([str(exe), "--help"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    groups, current = {}, None
    for line in proc.stdout.splitlines():
        if line.startswith("&"):
            current = groups.setdefault(line[1:].strip(), {})
        elif current is not None and line.startswith("  "):
            name = re.match(r"\s+([a-z0-9_]+)", line).group(1)
            current[name] = line
        elif not line.strip():
            current = None
    return groups


def unit_of(name: str) -> str | None:
    for suffix, unit in UNIT_OF_SUFFIX:
        if name.endswith(suffix):
            return unit
    return None


@pytest.fixture(scope="module")
def recorded_config(voussoir_run_exe, tmp_path_factory):
    """{group: [variable, ...]} of the effective settings of a real run file."""
    folder = tmp_path_factory.mktemp("help")
    h5 = folder / "short.h5"
    (folder / "short.nml").write_text(SHORT_NML.format(file=h5))
    run_executable([voussoir_run_exe, folder / "short.nml"], folder)
    with h5py.File(h5, "r") as f:
        return {g: sorted({re.sub(r"\(\d+\)$", "", k) for k in f["config"][g].attrs}) for g in f["config"]}


def test_run_help_lists_every_arch_variable_with_its_unit(voussoir_run_exe, recorded_config):
    listed = help_groups(voussoir_run_exe)
    arch = recorded_config["arch"]
    assert "joint_friction" in arch and "embrace_deg" in arch and len(arch) >= 13
    for name in arch:
        assert name in listed["arch"], f"--help of voussoir-run does not list &arch {name}"
        line = listed["arch"][name]
        unit = unit_of(name)
        if unit is not None:
            # "  name = default   type, unit; range": the unit as a word of the description
            description = line.split("=", 1)[1].split(None, 1)[1]
            assert re.search(rf"(^|[ ,]){re.escape(unit)}([;, ]|$)", description), \
                f"&arch {name}: unit {unit} missing from '{line.strip()}'"
    assert re.search(r"joint_friction\(j\) = unset .*j = 0\.\.", listed["arch"]["joint_friction"])
    assert "0 < embrace_deg <= 180" in listed["arch"]["embrace_deg"]


def test_every_driver_lists_the_groups_it_reads(voussoir_run_exe, voussoir_limit_exe, voussoir_sweep_exe,
                                                recorded_config):
    """Each group of the run file's /config, every variable of it, in each driver's --help;
    and each driver's own group (&limit, &sweep)."""
    for exe, own in ((voussoir_run_exe, "wall"), (voussoir_limit_exe, "limit"), (voussoir_sweep_exe, "sweep")):
        listed = help_groups(exe)
        assert own in listed and listed[own]
        for group, names in recorded_config.items():
            assert set(names) <= set(listed[group]), f"{exe.name} --help: &{group} misses " \
                                                    f"{sorted(set(names) - set(listed[group]))}"
    sweep = help_groups(voussoir_sweep_exe)["sweep"]
    assert "mode = 'threshold'" in sweep["mode"] and "Hz" in sweep["frequencies_hz"]
    assert "real, Pa" in help_groups(voussoir_limit_exe)["limit"]["compressive_strength_pa"]
