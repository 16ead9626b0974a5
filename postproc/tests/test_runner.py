"""The runner: namelist text from a mapping (namelist.format_namelist), read back by the
executables and by namelist.parse_namelist; failures raise RunError with the program's words."""

from __future__ import annotations

import math

import pytest

from voussoir_post.namelist import format_namelist, format_value, parse_namelist
from voussoir_post.runner import RunError, Runner, code_hash


def test_namelist_round_trip_through_the_parser():
    groups = {"arch": {"embrace_deg": 156.0, "n_voussoirs": 13, "restrained_springings": "it's"},
              "solver": {"allow_nonconvergence": True, "dt_s": 1.0e-3},
              "sweep": {"frequencies_hz": [1.25, 2.0]}}
    parsed = parse_namelist(format_namelist(groups))
    assert parsed["arch"] == {"embrace_deg": 156.0, "n_voussoirs": 13, "restrained_springings": "it's"}
    assert parsed["solver"] == {"allow_nonconvergence": True, "dt_s": 1.0e-3}
    assert parsed["sweep"] == {"frequencies_hz": [1.25, 2.0]}


@pytest.mark.parametrize("bad", [math.nan, math.inf, [], object()])
def test_values_without_a_namelist_form_are_refused(bad):
    with pytest.raises((ValueError, TypeError)):
        format_value(bad)


def _fake_executable(folder, version: str, body: str, build_id: bytes = b"A" * 20):
    """A stand-in executable that embeds its version string as the drivers do, prints it
    for --version as they do ('<program> (voussoir <version>)'), and holds a GNU build-id
    note as the linker writes it (name size 4, id size 20, type 3, 'GNU', the id)."""
    folder.mkdir(parents=True, exist_ok=True)
    exe = folder / "voussoir-run"
    note = b"\x04\x00\x00\x00\x14\x00\x00\x00\x03\x00\x00\x00GNU\x00" + build_id
    exe.write_bytes(b"#!/bin/sh\n# " + note + f"\n# {body}\nV='voussoir {version}'\n".encode()
                    + b'echo "voussoir-run ($V)"\n')
    exe.chmod(0o755)
    return folder


def test_the_code_hash_ignores_the_version_string_and_the_build_id_and_nothing_else(tmp_path):
    """The caches of the diagnosis are keyed by the executables' hash: a commit that changes
    only the version string they embed (git describe), and with it the linker's build id,
    keeps the key; any other byte changes it."""
    def key(name, version, body, build_id=b"A" * 20):
        return code_hash(_fake_executable(tmp_path / name, version, body, build_id), ["voussoir-run"])
    a = key("a", "0.9.0+1234abc", "the kernel")
    b = key("b", "0.9.0+9876fed", "the kernel", b"B" * 20)
    c = key("c", "0.9.0+9876fed", "the kernel, changed", b"B" * 20)
    assert a == b
    assert c != b
    assert len(a) == 16 and int(a, 16) >= 0


def test_run_single_reads_the_result_and_a_bad_input_raises(voussoir_run_exe, tmp_path):
    runner = Runner(voussoir_run_exe.parent, tmp_path)
    groups = {"arch": {"embrace_deg": 156.0, "n_voussoirs": 13},
              "motion": {"waveform": "afd", "frequency_hz": 1.25, "amplitude_m": 0.0, "rest_s": 0.2,
                         "duration_s": 0.3},
              "solver": {"dt_s": 1.0e-3}}
    result = runner.run_single(groups, "gravity")
    assert not result.collapsed and (tmp_path / "gravity.nml").is_file()
    groups["arch"]["n_voussoirs"] = 1  # below the allowed range: the program refuses it
    with pytest.raises(RunError, match="n_voussoirs"):
        runner.run_single(groups, "bad")
