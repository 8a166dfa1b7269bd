#!/usr/bin/env bash
# What an integrator gets from `cmake --install` and from the Debian package, checked from outside the
# build tree. usage: install_test.sh MODE BUILD_DIR SOURCE_DIR
#   prefix        install into BUILD_DIR/install-test (the fixture of the other modes)
#   harness       the installed obscura finds the installed plugin with no environment variable, and renders
#   python        the installed Python package finds the installed plugin the same way
#   find_package  a separate CMake project finds the package and builds the C99 host, which renders
#   pkg_config    the same host built with `pkg-config --cflags --libs obscura`
#   deb           cpack builds the .deb; its layout, dependencies, and its extracted obscura renders
set -euo pipefail
mode=$1; build=$(cd "$2" && pwd); src=$(cd "$3" && pwd)
prefix=$build/install-test
unset OBSCURA_PLUGINPATH
fail() { echo "FAILED: $*" >&2; exit 1; }

# The installed harness with no search path: it must load the plugin of the tree it sits in.
check_harness() {  # check_harness PREFIX
  local out
  out=$("$1/bin/obscura" info) || fail "$1/bin/obscura info exited $?"
  grep -q "loaded: Obscura, ABI" <<<"$out" || fail "no plugin loaded: $out"
  grep -q "$1/lib/obscura/plugin/obscura/plugInfo.json" <<<"$out" || fail "plugin not found in $1: $out"
  "$1/bin/obscura" render "$src/scenes/demo.usda" -o "$build/install-test-$mode.png" --width 32 --height 32 \
    || fail "installed obscura render exited $?"
  [ -s "$build/install-test-$mode.png" ] || fail "no image written"
}

case $mode in
prefix)
  rm -rf "$prefix"
  cmake --install "$build" --prefix "$prefix" >/dev/null
  for f in bin/obscura lib/obscura/plugin/obscura/plugInfo.json lib/obscura/plugin/obscura/libobscuraDelegate.so \
           include/obscura/obscura.h lib/cmake/Obscura/ObscuraConfig.cmake lib/cmake/Obscura/ObscuraConfigVersion.cmake \
           lib/pkgconfig/obscura.pc lib/python3/dist-packages/obscura/__init__.py \
           share/obscura/blender/obscura_render.zip; do
    [ -e "$prefix/$f" ] || fail "$f not installed"
  done
  ;;
harness)
  check_harness "$prefix"
  ;;
python)
  # The installed Python package finds the installed plugin with no environment variable.
  PYTHONPATH=$prefix/lib/python3/dist-packages /usr/bin/python3 -c "
import obscura, os
r = obscura.Renderer()
assert os.path.realpath(str(r.info.library)).startswith(os.path.realpath('$prefix')), r.info.library
print('installed package loaded', r.info.library, r.version)" || fail "the installed Python package"
  ;;
find_package)
  rm -rf "$build/install-test-consumer"
  cmake -S "$src/tests/install/consumer" -B "$build/install-test-consumer" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
    -DOBSCURA_HOST_SOURCE="$src/tests/abi/c_host.c" >/dev/null
  cmake --build "$build/install-test-consumer" >/dev/null
  "$build/install-test-consumer/c_host"
  ;;
pkg_config)
  export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
  cflags=$(pkg-config --cflags obscura); libs=$(pkg-config --libs obscura)
  plugindir=$(pkg-config --variable=plugindir obscura)
  [ "$(cd "$plugindir" && pwd)" = "$prefix/lib/obscura/plugin" ] || fail "plugindir $plugindir is not the installed one"
  # shellcheck disable=SC2086
  cc -std=c99 -o "$build/install-test-pkgconfig-host" $cflags -DOBSCURA_TEST_PLUGIN_DIR="\"$plugindir/obscura\"" \
    "$src/tests/abi/c_host.c" $libs -lm
  "$build/install-test-pkgconfig-host"
  ;;
deb)
  out=$build/install-test-deb
  rm -rf "$out"; mkdir -p "$out"
  (cd "$build" && cpack -G DEB -B "$out" >/dev/null)
  deb=$(ls "$out"/obscura_*.deb)
  listing=$(dpkg-deb -c "$deb")
  for f in ./usr/bin/obscura ./usr/lib/obscura/plugin/obscura/plugInfo.json \
           ./usr/lib/obscura/plugin/obscura/libobscuraDelegate.so ./usr/include/obscura/obscura.h \
           ./usr/lib/cmake/Obscura/ObscuraConfig.cmake ./usr/lib/pkgconfig/obscura.pc; do
    grep -q " $f\$" <<<"$listing" || fail "$f not in $deb"
  done
  depends=$(dpkg-deb -f "$deb" Depends)
  for d in libvulkan1 libopenexr libOpenColorIO mesa-vulkan-drivers; do
    grep -qi "$d" <<<"$depends" || fail "Depends lacks $d: $depends"
  done
  dpkg-deb -x "$deb" "$out/root"
  check_harness "$out/root/usr"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "install_test $mode: passed"
