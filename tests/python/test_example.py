"""python/examples/depth_of_field.py runs and writes an OpenEXR file that OpenEXR reads."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from conftest import environment
from obscura.exr import write_exr

EXAMPLE = Path(__file__).resolve().parents[2] / "python" / "examples" / "depth_of_field.py"


def exr_header(path: Path) -> str:
    return subprocess.run(["exrheader", str(path)], capture_output=True, text=True, check=True).stdout


def test_the_example_renders_with_depth_of_field_to_exr(tmp_path: Path) -> None:
    out = tmp_path / "dof.exr"
    run = subprocess.run([sys.executable, str(EXAMPLE), str(out), "--width", "96", "--height", "54",
                          "--taa-frames", "2"], capture_output=True, text=True, env=os.environ)
    assert run.returncode == 0, run.stderr
    assert "error" not in run.stderr.lower(), run.stderr  # the plugin's log (validation on) stays clean
    header = exr_header(out)
    for channel in "RGBA":
        assert f"    {channel}, 32-bit floating-point" in header
    assert "dataWindow (type box2i): (0 0) - (95 53)" in header
    # OpenEXR reads every pixel: the harness compares the file with itself through libOpenEXR.
    compare = subprocess.run([environment("OBSCURA_TEST_HARNESS"), "compare", str(out), str(out)],
                             capture_output=True, text=True)
    assert compare.returncode == 0, compare.stderr + compare.stdout


def test_written_pixels_are_the_arrays_given(tmp_path: Path) -> None:
    # Read back by the harness: a file differing only in one pixel of one channel is not identical.
    rng = np.random.default_rng(7)
    planes = {c: rng.random((5, 7), dtype=np.float32) for c in "RGB"}
    write_exr(tmp_path / "a.exr", planes)
    planes["G"][2, 3] += 0.5
    write_exr(tmp_path / "b.exr", planes)
    harness = environment("OBSCURA_TEST_HARNESS")
    same = subprocess.run([harness, "compare", str(tmp_path / "a.exr"), str(tmp_path / "a.exr"), "--psnr-min", "99"],
                          capture_output=True, text=True)
    different = subprocess.run([harness, "compare", str(tmp_path / "a.exr"), str(tmp_path / "b.exr"),
                                "--psnr-min", "99"], capture_output=True, text=True)
    assert same.returncode == 0, same.stdout + same.stderr
    assert different.returncode == 1, different.stdout + different.stderr
