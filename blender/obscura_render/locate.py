"""Finding the ``obscura`` Python package and the renderer plugin.

The package is taken from wherever Blender's Python imports it (an installed Obscura under
/usr), else from an installed Obscura under /usr/local, else from the copy the add-on's zip
carries (``vendor/``). The plugin is then found as every Obscura host finds it: plugInfo.json on
``OBSCURA_PLUGINPATH``, else the installed plugin folders (obscura.discovery).
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

_VENDOR = Path(__file__).resolve().parent / "vendor"
_INSTALLED_PACKAGE_FOLDERS = [Path("/usr/local/lib/python3/dist-packages"), _VENDOR]

HOW_TO_FIX = ("install Obscura (its .deb, or cmake --install) or set OBSCURA_PLUGINPATH to the folder "
              "holding the plugin's plugInfo.json before starting Blender")


class PluginMissing(Exception):
    """The package or the plugin cannot be found: the message says what was searched and what to do."""


def import_package():
    """The ``obscura`` module; raises PluginMissing."""
    try:
        return importlib.import_module("obscura")
    except ImportError:
        pass
    for folder in _INSTALLED_PACKAGE_FOLDERS:
        if (folder / "obscura" / "__init__.py").is_file():
            sys.path.append(str(folder))
            return importlib.import_module("obscura")
    searched = ", ".join(str(f) for f in _INSTALLED_PACKAGE_FOLDERS)
    raise PluginMissing(f"Obscura's Python package was not found (Blender's Python path, {searched}): {HOW_TO_FIX}")


def load_renderer():
    """An ``obscura.Renderer`` (the plugin loaded); raises PluginMissing with the reason."""
    obscura = import_package()
    try:
        return obscura.Renderer()
    except obscura.ObscuraError as e:
        raise PluginMissing(f"the Obscura plugin could not be loaded: {e.message}. To fix: {HOW_TO_FIX}") from None
