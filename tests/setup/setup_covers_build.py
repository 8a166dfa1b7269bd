#!/usr/bin/env python3
"""Fails when the build found a file that scripts/setup.sh would not install on a fresh machine.

CMake records everything its find_package / pkg_check_modules / find_library / find_path /
find_program calls found in CMakeCache.txt (a package's <Name>_DIR, a library's path, a
pkg-config module's libraries, a program). Each such system file must belong to a Debian
package that scripts/debian-packages.txt names, or to one of their dependencies: a new
find_package whose package was installed by hand then fails here, on any machine.

usage: setup_covers_build.py CMakeCache.txt scripts/debian-packages.txt
"""
import os
import re
import subprocess
import sys

# Folders whose files a Debian package must own (anything else is the user's own tree: the source,
# the build, a home folder).
SYSTEM_ROOTS = ("/usr/", "/lib", "/bin/", "/sbin/", "/etc/", "/opt/")
# Cache entries that name where things go, not what was found.
NOT_FOUND_THINGS = {"CMAKE_INSTALL_PREFIX", "CMAKE_CACHEFILE_DIR", "CMAKE_HOME_DIRECTORY"}


def listed_packages(path):
    with open(path) as f:
        return {word for line in f for word in line.split("#", 1)[0].split()}


def installed_dependency_closure(roots):
    """Packages installed because `roots` are: Depends and Pre-Depends, every installed alternative,
    virtual packages through Provides."""
    query = subprocess.run(
        ["dpkg-query", "-W", "-f=${Package}\t${Status}\t${Depends}, ${Pre-Depends}\t${Provides}\n"],
        check=True, capture_output=True, text=True).stdout
    depends, providers = {}, {}
    for line in query.splitlines():
        name, status, deps, provides = (line.split("\t") + ["", "", ""])[:4]
        if "install ok installed" not in status:
            continue
        names = [re.split(r"[\s(:]", alt.strip())[0] for group in deps.split(",") for alt in group.split("|")]
        depends[name] = {n for n in names if n}
        for virtual in provides.split(","):
            virtual = re.split(r"[\s(:]", virtual.strip())[0]
            if virtual:
                providers.setdefault(virtual, set()).add(name)
    seen, todo = set(), list(roots)
    while todo:
        name = todo.pop()
        for real in ({name} if name in depends else set()) | providers.get(name, set()):
            if real not in seen:
                seen.add(real)
                todo.extend(depends.get(real, ()))
    return seen


def found_paths(cache):
    """(cache entry, absolute system path) for every path-typed entry of the cache."""
    entry = re.compile(r"^([^#/][^:]*):(FILEPATH|PATH|STRING|INTERNAL)=(.*)$")
    with open(cache) as f:
        for line in f:
            m = entry.match(line.rstrip("\n"))
            if not m or m.group(1) in NOT_FOUND_THINGS:
                continue
            name, kind, value = m.groups()
            # pkg_check_modules keeps its libraries as FILEPATH entries pkgcfg_lib_<prefix>_<lib>.
            if kind in ("STRING", "INTERNAL") and not name.startswith("pkgcfg_lib_"):
                continue
            for item in value.split(";"):
                if item.startswith(SYSTEM_ROOTS) and "NOTFOUND" not in item and os.path.exists(item):
                    yield name, item


def owners(path):
    """Debian packages owning `path` (as given, or through its real path; /usr-merged aliases too)."""
    candidates = [path, os.path.realpath(path)]
    candidates += [c[4:] if c.startswith("/usr/") else "/usr" + c for c in list(candidates)]
    for candidate in dict.fromkeys(candidates):
        result = subprocess.run(["dpkg-query", "-S", candidate], capture_output=True, text=True)
        if result.returncode == 0:
            found = set()
            for line in result.stdout.splitlines():
                pkgs, _, owned = line.rpartition(": ")
                if owned == candidate:
                    found |= {p.strip().split(":")[0] for p in pkgs.split(",")}
            if found:
                return found
    return set()


def main(cache, package_list):
    listed = listed_packages(package_list)
    closure = installed_dependency_closure(listed)
    problems, checked = [], 0
    for name, path in found_paths(cache):
        checked += 1
        owned_by = owners(path)
        if not owned_by:
            problems.append(f"{name}={path}: no Debian package owns it (installed by hand?)")
        elif not owned_by & closure:
            problems.append(f"{name}={path}: from {', '.join(sorted(owned_by))}, "
                            f"which {os.path.basename(package_list)} does not install")
    print(f"{checked} files the build found, from {len(listed)} listed packages ({len(closure)} with dependencies)")
    for p in problems:
        print("MISSING PACKAGE:", p)
    return 1 if problems or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
