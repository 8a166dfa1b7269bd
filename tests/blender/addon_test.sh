#!/usr/bin/env bash
# Runs tests/blender/addon_test.py in Blender, headless with factory settings, with user folders
# of its own (the add-on is installed into them from its zip, as Blender's preferences install it).
# With `viewport`: tests/blender/viewport_test.py in Blender's own UI under Xvfb (Mesa's GL), as
# the viewport draws through Blender's gpu module only with a GL context, which -b does not make.
#   addon_test.sh BLENDER ADDON_ZIP TESTS_DIR WORK_DIR [viewport]
set -euo pipefail
blender=$1 zip=$2 tests=$3 work=$4 mode=${5:-}
if [[ ! -x $blender ]]; then
    echo "blender not found ($blender): install Debian's blender package (scripts/debian-packages.txt)" >&2
    exit 1
fi
rm -rf "$work"
mkdir -p "$work"
# As an artist starts Blender: the Python package comes through the add-on, not a PYTHONPATH.
unset PYTHONPATH
export BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config BLENDER_USER_DATAFILES=$work/datafiles
export TMPDIR=$work  # Blender's temporary files (the session saved at quit)
if [[ $mode == viewport ]]; then
    if ! command -v xvfb-run >/dev/null; then echo "xvfb-run not found: install xvfb and xauth" >&2; exit 1; fi
    exec xvfb-run -a -s "-screen 0 640x480x24" "$blender" --factory-startup --python-exit-code 1 \
        --python "$tests/blender/viewport_test.py" -- "$zip" "$tests/python" "$work"
fi
exec "$blender" -b --factory-startup --python-exit-code 1 --python "$tests/blender/addon_test.py" -- \
    "$zip" "$tests/python"
