"""Plugin discovery through ``plugInfo.json``, as OpenUSD and the C++ harness do it.

The folders of ``OBSCURA_PLUGINPATH`` (colon-separated; an entry may also name a
``plugInfo.json`` file) are searched, each folder and its direct sub-folders. A renderer plugin is
a ``"Type": "library"`` entry of ``Plugins`` whose ``Info.Types`` holds a type with
``HdRendererPlugin`` among its ``bases``; ``LibraryPath`` is relative to ``Root``, which is
relative to the file. Plugins of higher ``priority`` come first; discovery order breaks ties.
When the search path names no renderer plugin, the installed locations are searched instead.
"""

from __future__ import annotations

import dataclasses
import json
import os
import re
from pathlib import Path
from typing import Iterable

PLUGIN_PATH_VARIABLE = "OBSCURA_PLUGINPATH"


@dataclasses.dataclass(frozen=True)
class PluginInfo:
    """One renderer plugin declared by a plugInfo.json file."""

    plug_info_file: Path
    name: str  #: ``Plugins[].Name``
    type_name: str  #: the HdRendererPlugin type
    display_name: str
    priority: int
    abi_version: str  #: ``"major.minor"`` as declared; the library is asked, not trusted
    library: Path


@dataclasses.dataclass
class DiscoveryResult:
    plugins: list[PluginInfo]  #: highest priority first
    problems: list[str]  #: unreadable or malformed plugInfo.json files


def default_plugin_folders() -> list[Path]:
    """Where an installed Obscura keeps its plugins.

    CMake installs this package to ``PREFIX/lib/python3/dist-packages/obscura`` and the plugin to
    ``PREFIX/lib/obscura/plugin/obscura``, so the package finds the plugin of its own prefix first.
    """
    package = Path(__file__).resolve().parent
    return [package.parent.parent.parent / "obscura" / "plugin", Path("/usr/local/lib/obscura/plugin"),
            Path("/usr/lib/obscura/plugin")]


# OpenUSD's plugInfo.json may hold # comments (nlohmann's ignore_comments in the harness). Strings
# are matched first so that a '#' inside one is kept.
_COMMENT_OR_STRING = re.compile(r'"(?:\\.|[^"\\])*"|#[^\n]*')


def _strip_comments(text: str) -> str:
    return _COMMENT_OR_STRING.sub(lambda m: m.group(0) if m.group(0).startswith('"') else "", text)


def _read_plug_info(file: Path, out: DiscoveryResult) -> None:
    try:
        doc = json.loads(_strip_comments(file.read_text(encoding="utf-8")))
    except OSError as e:
        out.problems.append(f"{file}: cannot be read ({e.strerror})")
        return
    except (ValueError, UnicodeDecodeError) as e:
        out.problems.append(f"{file}: {e}")
        return
    if not isinstance(doc, dict) or not isinstance(doc.get("Plugins"), list):
        out.problems.append(f'{file}: no "Plugins" array')
        return
    for plugin in doc["Plugins"]:
        if not isinstance(plugin, dict) or plugin.get("Type") != "library":
            continue
        root = file.parent / plugin.get("Root", ".")
        library = plugin.get("LibraryPath", "")
        if not library:
            out.problems.append(f"{file}: plugin without LibraryPath")
            continue
        info = plugin.get("Info")
        types = info.get("Types") if isinstance(info, dict) else None
        if not isinstance(types, dict):
            continue
        for type_name, type_info in types.items():
            if not isinstance(type_info, dict) or not isinstance(type_info.get("bases"), list):
                continue
            if "HdRendererPlugin" not in type_info["bases"]:
                continue
            out.plugins.append(PluginInfo(
                plug_info_file=file,
                name=plugin.get("Name", type_name),
                type_name=type_name,
                display_name=type_info.get("displayName", type_name),
                priority=int(type_info.get("priority", 0)),
                abi_version=type_info.get("abiVersion", ""),
                library=Path(library) if os.path.isabs(library) else root / library,
            ))


def _search(entry: Path, out: DiscoveryResult, seen: set[Path]) -> None:
    def consider(file: Path) -> None:
        canonical = file.resolve()
        if canonical not in seen:
            seen.add(canonical)
            _read_plug_info(file, out)

    if entry.is_file():
        consider(entry)
        return
    if not entry.is_dir():
        return
    if (entry / "plugInfo.json").exists():
        consider(entry / "plugInfo.json")
    # One level down, as USD's "*/" pattern: <dir>/<plugin>/plugInfo.json.
    try:
        children = sorted(entry.iterdir())
    except OSError:
        return
    for child in children:
        if child.is_dir() and (child / "plugInfo.json").exists():
            consider(child / "plugInfo.json")


def discover_plugins(search_path: str | None = None, default_folders: Iterable[Path] | None = None) -> DiscoveryResult:
    """Renderer plugins on ``search_path`` (default: ``$OBSCURA_PLUGINPATH``), else in ``default_folders``
    (default: :func:`default_plugin_folders`)."""
    if search_path is None:
        search_path = os.environ.get(PLUGIN_PATH_VARIABLE, "")
    out = DiscoveryResult(plugins=[], problems=[])
    seen: set[Path] = set()
    for entry in search_path.split(":"):
        if entry:
            _search(Path(entry), out, seen)
    if not out.plugins:
        for folder in default_plugin_folders() if default_folders is None else default_folders:
            _search(Path(folder), out, seen)
    # Highest priority first; sorted() is stable, so discovery order breaks ties.
    out.plugins = sorted(out.plugins, key=lambda p: -p.priority)
    return out
