"""Plugin discovery through plugInfo.json (as harness/plugin_loader.cpp) and ABI negotiation."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import obscura
from conftest import environment
from obscura.discovery import discover_plugins


def plug_info(folder: Path, name: str, priority: int, library: str = "lib.so", root: str = ".",
              bases=("HdRendererPlugin",), kind: str = "library", comment: str = "") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    doc = {"Plugins": [{"Type": kind, "Name": name, "Root": root, "LibraryPath": library,
                        "Info": {"Types": {name + "Type": {"bases": list(bases), "priority": priority,
                                                            "abiVersion": "1.0"}}}}]}
    (folder / "plugInfo.json").write_text(comment + json.dumps(doc, indent=1))
    return folder / "plugInfo.json"


def test_search_path_folders_and_their_direct_subfolders(tmp_path: Path) -> None:
    plug_info(tmp_path / "a", "top", 1)
    plug_info(tmp_path / "a" / "child", "child", 5)
    plug_info(tmp_path / "a" / "child" / "grandchild", "too_deep", 9)
    plug_info(tmp_path / "b", "second", 5, library="/abs/lib.so", root="sub")
    plug_info(tmp_path / "c", "not_a_renderer", 7, bases=("HdSceneIndexPlugin",))
    plug_info(tmp_path / "d", "python", 7, kind="python")
    found = discover_plugins(f"{tmp_path / 'a'}::{tmp_path / 'b'}:{tmp_path / 'c'}:{tmp_path / 'd'}:/nonexistent", [])
    # Highest priority first, discovery order breaking the tie between "child" and "second".
    assert [p.name for p in found.plugins] == ["child", "second", "top"]
    assert found.plugins[0].library == tmp_path / "a" / "child" / "." / "lib.so"
    assert found.plugins[1].library == Path("/abs/lib.so")  # absolute: Root does not apply
    assert found.problems == []


def test_entries_may_name_files_and_files_may_hold_comments(tmp_path: Path) -> None:
    file = plug_info(tmp_path / "x", "commented", 3, root="lib", comment='# a comment, as OpenUSD allows\n')
    found = discover_plugins(str(file), [])
    assert [p.library for p in found.plugins] == [tmp_path / "x" / "lib" / "lib.so"]


def test_malformed_files_are_reported_not_fatal(tmp_path: Path) -> None:
    (tmp_path / "bad").mkdir()
    (tmp_path / "bad" / "plugInfo.json").write_text("{ not json")
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "plugInfo.json").write_text("{}")
    found = discover_plugins(f"{tmp_path / 'bad'}:{tmp_path / 'empty'}", [])
    assert found.plugins == []
    assert len(found.problems) == 2 and 'no "Plugins" array' in found.problems[1]


def test_defaults_only_when_the_search_path_finds_nothing(tmp_path: Path) -> None:
    plug_info(tmp_path / "default" / "p", "installed", 1)
    plug_info(tmp_path / "env", "from_env", 0)
    assert [p.name for p in discover_plugins(str(tmp_path / "env"), [tmp_path / "default"]).plugins] == ["from_env"]
    assert [p.name for p in discover_plugins("", [tmp_path / "default"]).plugins] == ["installed"]


def test_the_built_plugin_is_found_and_negotiated(renderer: obscura.Renderer) -> None:
    assert renderer.version == (obscura.ABI_VERSION_MAJOR, obscura.ABI_VERSION_MINOR)
    # plugInfo.json declares the version the header says (one owner: OBSCURA_ABI_VERSION_*).
    declared = f"{obscura.ABI_VERSION_MAJOR}.{obscura.ABI_VERSION_MINOR}"
    assert renderer.info.abi_version == declared and renderer.info.library.exists()
    assert "exposure" in renderer.render_settings() and "taa:frames" in renderer.render_settings()
    assert any(device.name for device in renderer.devices())


def test_a_plugin_without_abi_1_is_refused_and_the_next_one_taken() -> None:
    fake = environment("OBSCURA_TEST_FAKE_PLUGIN_DIR")  # priority 100, speaks ABI 2 only
    wanted = rf"{obscura.ABI_VERSION_MAJOR}\.{obscura.ABI_VERSION_MINOR}"
    with pytest.raises(obscura.UnsupportedVersionError, match=rf"does not provide ABI {wanted} .it declares 2.0") as caught:
        obscura.Renderer(fake)
    assert caught.value.status == obscura.Status.UNSUPPORTED_VERSION
    with obscura.Renderer(f"{fake}:{os.environ['OBSCURA_PLUGINPATH']}") as r:
        assert r.info.name == "obscura"


def test_no_plugin_at_all_is_a_clear_error(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setattr(obscura.discovery, "default_plugin_folders", lambda: [])
    with pytest.raises(obscura.NotFoundError, match="no renderer plugin found"):
        obscura.Renderer(str(tmp_path))


def test_an_installed_package_finds_the_plugin_of_its_prefix(tmp_path: Path, renderer: obscura.Renderer) -> None:
    # The layout CMake installs: PREFIX/lib/python3/dist-packages/obscura and PREFIX/lib/obscura/plugin/obscura.
    packages = tmp_path / "lib" / "python3" / "dist-packages"
    shutil.copytree(Path(obscura.__file__).parent, packages / "obscura", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(renderer.info.plug_info_file.parent, tmp_path / "lib" / "obscura" / "plugin" / "obscura")
    env = {**os.environ, "PYTHONPATH": str(packages), "OBSCURA_PLUGINPATH": ""}
    script = "import obscura; r = obscura.Renderer(); print(r.info.library.resolve())"
    out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == str((tmp_path / "lib" / "obscura" / "plugin" / "obscura" /
                                      renderer.info.library.name).resolve())
