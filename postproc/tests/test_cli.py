"""The command-line programs, in process and through their installed entry points."""

from __future__ import annotations

import csv
import subprocess
import sys

import numpy as np
import pytest

from voussoir_post.cli import diagnose, post
from voussoir_post.readers.results import read_run


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_history_cli_writes_png_table_and_csv(run_copy, capsys):
    assert post.main(["history", str(run_copy), "--csv"]) == 0
    out = capsys.readouterr().out
    png = run_copy.parent / f"{run_copy.stem}_history.png"
    assert png.is_file() and f"wrote {png}" in out
    assert "nlgs_iterations" in out and "table_x_mm" in out
    rows = read_csv(run_copy.parent / f"{run_copy.stem}_history.csv")
    run = read_run(run_copy)
    assert len(rows) == run.n_samples
    assert np.allclose([float(r["crown_dy_mm"]) for r in rows], 1e3 * run.crown_dy_m)
    steps = read_csv(run_copy.parent / f"{run_copy.stem}_history_steps.csv")
    assert [int(r["iterations"]) for r in steps] == run.step_iterations.tolist()


def test_sequence_cli_times_out_and_gif(run_copy, tmp_path, capsys):
    out_dir = tmp_path / "figs"
    assert post.main(["sequence", str(run_copy), "--times", "0,0.2,0.3", "--amplify", "2", "--gif",
                      "--gif-frames", "8", "--out", str(out_dir), "--csv"]) == 0
    out = capsys.readouterr().out
    assert "(8 frames)" in out
    assert (out_dir / f"{run_copy.stem}_sequence.png").is_file()
    assert (out_dir / f"{run_copy.stem}_sequence.gif").is_file()
    rows = read_csv(out_dir / f"{run_copy.stem}_sequence.csv")
    assert [float(r["time_s"]) for r in rows] == pytest.approx([0.0, 0.2, 0.3], abs=0.006)
    assert "open_joints" in out


def test_gif_frames_below_one_is_refused(run_copy, tmp_path, capsys):
    for bad, got in (("0", "got 0"), ("-3", "got -3"), ("x", "got 'x'")):
        with pytest.raises(SystemExit) as exit_info:
            post.main(["sequence", str(run_copy), "--gif", "--gif-frames", bad, "--out", str(tmp_path)])
        assert exit_info.value.code == 2
        err = capsys.readouterr().err
        assert "argument --gif-frames: expects a whole number >= 1, " + got in err


def test_xdmf_cli(run_copy, capsys):
    assert post.main(["xdmf", str(run_copy), "--every", "2"]) == 0
    out = capsys.readouterr().out
    assert (run_copy.parent / f"{run_copy.stem}.xmf").is_file()
    assert (run_copy.parent / f"{run_copy.stem}.vtk.h5").is_file()
    run = read_run(run_copy)
    assert f"{(run.n_samples + 1) // 2}" in out.split("\n")[3]


def test_wrong_inputs_exit_2(run_file, tmp_path, capsys):
    assert post.main(["envelope", str(run_file)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("voussoir-post: error: ") and "written by 'voussoir-run'" in err
    assert post.main(["history", str(tmp_path / "missing.h5")]) == 2
    assert "no such file" in capsys.readouterr().err
    assert post.main(["mechanism", str(run_file)]) == 2
    assert "not a JSON file" in capsys.readouterr().err


def test_output_path_rules(tmp_path):
    assert post.output_path("/a/b/run.h5", "history", None) == "/a/b/run_history.png"
    assert post.output_path("/a/b/run.h5", "history", "/c/x.png") == "/c/x.png"
    assert post.output_path("/a/b/run.h5", "history", "/c") == "/c/run_history.png"


def test_diagnose_check_seed(seed_campaign, capsys):
    assert diagnose.main(["check", str(seed_campaign)]) == 0
    out = capsys.readouterr().out
    assert "'seed_2013'" in out and "valid" in out
    line = next(l for l in out.splitlines() if l.strip().startswith("A156") and "1.25" in l)
    assert "46c" in line and " 46 " in line + " " and "(-, 46]" in line
    assert "Records: none" in out and "Hinges: none" in out
    # The check says the prior a diagnosis weighs and how its probabilities were checked.
    assert "Prior: none 1/4" in out and "calibration study" in out


def test_diagnose_check_invalid(tmp_path, capsys):
    folder = tmp_path / "bad"
    folder.mkdir()
    (folder / "specimens.csv").write_text(
        "specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,density_kg_m3\n"
        "S1,190,13,0.5,0.07,0.1,700\n")
    (folder / "tests.csv").write_text("test_id,specimen_id,waveform,outcome\n")
    assert diagnose.main(["check", str(folder)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"{folder / 'specimens.csv'}:2:2: column 'embrace_deg': 190 is out of range: "
                   "0 < embrace_deg <= 180")


def test_diagnose_check_lists_records_hinges_and_warnings(tmp_path, capsys):
    folder = tmp_path / "c"
    (folder / "records").mkdir(parents=True)
    (folder / "hinges").mkdir()
    (folder / "specimens.csv").write_text(
        "specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,density_kg_m3,builder\n"
        "S1,156,13,0.508,0.071,0.145,700,me\n")
    (folder / "tests.csv").write_text(
        "test_id,specimen_id,waveform,frequency_hz,amplitude_m,outcome\n"
        "T1,S1,afd,1.25,0.04,stand\nT2,S1,afd,1.25,0.05,collapse\n")
    (folder / "records" / "T2.csv").write_text("t_s,table_x_m,crown_dx_m\n0,0,0\n0.01,0.002,0\n0.02,0.004,0\n")
    (folder / "hinges" / "T2.csv").write_text("t_s,joint,side\n0.5,4,extrados\n")
    assert diagnose.main(["check", str(folder)]) == 0
    out = capsys.readouterr().out
    assert "(40, 50]" in out and " 45 " in out  # bracket and midpoint threshold
    assert "0.5 4e" in out
    assert "unknown column, ignored" in out and "builder" in out
    t2 = next(l for l in out.splitlines() if l.strip().startswith("T2") and "afd" in l)
    assert " 3 " in t2 and "dx" in t2


def test_diagnose_run_refuses_missing_executables(seed_campaign, tmp_path, capsys):
    assert diagnose.main(["run", str(seed_campaign), "--bin-dir", str(tmp_path)]) == 2
    assert "voussoir-run not found" in capsys.readouterr().err


def test_diagnose_run_refuses_invalid_campaign(tmp_path, capsys):
    folder = tmp_path / "bad"
    folder.mkdir()
    (folder / "specimens.csv").write_text("specimen_id,embrace_deg,n_voussoirs,r_ext_m,thickness_m,width_m,"
                                          "density_kg_m3\nA,190,10,0.5,0.07,0.1,700\n")
    (folder / "tests.csv").write_text("test_id,specimen_id,waveform,outcome\n")
    assert diagnose.main(["run", str(folder), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "specimens.csv:2:" in err and "embrace_deg" in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("module, args, code", [
    ("voussoir_post.cli.diagnose", ["check"], 0),
    ("voussoir_post.cli.diagnose", ["run", "--bin-dir", "/nonexistent"], 2),
])
def test_entry_points_as_processes(module, args, code, seed_campaign):
    proc = subprocess.run([sys.executable, "-m", module, *args, str(seed_campaign)], capture_output=True,
                          text=True)
    assert proc.returncode == code, proc.stderr
