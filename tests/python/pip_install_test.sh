#!/usr/bin/env bash
# `pip install` of python/ offline into a fresh virtual environment that sees Debian's numpy
# (--system-site-packages), then the installed package, not the source tree, imports and finds
# the plugin through OBSCURA_PLUGINPATH. Usage: pip_install_test.sh PYTHON SOURCE_DIR
set -euo pipefail
python=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# pip builds in the tree it is given (build/, *.egg-info): give it a copy, not the sources.
cp -r "$source_dir/python" "$work/package"
"$python" -m venv --system-site-packages "$work/venv"
"$work/venv/bin/python" -m pip install --quiet --no-index --no-build-isolation --disable-pip-version-check \
  "$work/package"
cd "$work"
env -u PYTHONPATH "$work/venv/bin/python" - "$work/venv" <<'PY'
import sys
from pathlib import Path

import obscura

venv = Path(sys.argv[1]).resolve()
where = Path(obscura.__file__).resolve()
assert venv in where.parents, f"imported {where}, not the installed package"
assert (where.parent / "py.typed").exists(), "py.typed was not installed"
with obscura.Renderer() as renderer, renderer.delegate() as d:
    assert renderer.version == (obscura.ABI_VERSION_MAJOR, obscura.ABI_VERSION_MINOR)
    d.insert_prim("camera", "/Camera")
print(f"installed {where.parent}, plugin {renderer.info.library}")
PY
