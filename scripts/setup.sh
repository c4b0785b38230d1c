#!/usr/bin/env bash
# Installs what the project needs on a fresh Debian 12 (bookworm) machine. Each route sets up only
# what it uses:
#   scripts/setup.sh           the MeshLab 2020.09 plugins and the demo: Debian's meshlab
#                              (meshlabserver, libmeshlab-common.so), the compiler, CMake, the Qt5, GL,
#                              GLEW and Eigen headers MeshLab's plugin API includes, Xvfb; and
#                              MeshLab 2020.09's plugin headers (src/common) and vcglib from Debian's
#                              *source* package of the installed version, unpacked into
#                              third_party/meshlab-sdk/ (ignored by git; never committed).
#   scripts/setup.sh --all     also what the tests, the sanitizers, the fuzzers and the benchmark need
#                              (GoogleTest, clang with its sanitizer runtimes and libFuzzer, CGAL for
#                              the benchmark's peer row, numpy and matplotlib for its plots), and:
#     --meshlab-2025           MeshLab 2025.07's sources from Debian's checksum-pinned orig tarball,
#                              unpacked into third_party/meshlab-2025.07/, with its libmeshlab-common
#                              built in single precision there (the SDK of Debian's MeshLab 2025.07 GUI);
#     --pymeshlab              a venv in third_party/venv/ with the PyMeshLab 2025.7 wheel from PyPI
#                              (the host, and the link target, of the double-precision plugins) and pytest.
#   (--all is the three together.) The Python package needs none of this: see pyproject.toml.
# Idempotent: a second run only checks and returns.
# Usage: scripts/setup.sh [--all | --tests | --meshlab-2025 | --pymeshlab ...]   (as root, or with sudo)
set -euo pipefail

with_tests=0; with_ml25=0; with_pymeshlab=0
for a in "$@"; do
  case "$a" in
    --all) with_tests=1; with_ml25=1; with_pymeshlab=1 ;;
    --tests) with_tests=1 ;;
    --meshlab-2025) with_ml25=1 ;;
    --pymeshlab) with_pymeshlab=1 ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$a' (see scripts/setup.sh --help)" >&2; exit 2 ;;
  esac
done

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
third_party="$here/third_party"
sdk="$third_party/meshlab-sdk"
stamp="$sdk/.complete"

if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif command -v sudo >/dev/null; then SUDO="sudo"; else
  echo "setup.sh: needs root or sudo to install Debian packages" >&2; exit 1; fi

packages=(
  meshlab                                     # meshlabserver, libmeshlab-common.so, system plugins
  build-essential cmake pkg-config
  qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev libglew-dev   # what MeshLab's headers include
  libeigen3-dev
  xvfb xauth                                  # meshlabserver needs a display
  xz-utils ca-certificates dpkg-dev           # apt-get source
)
if [ $with_tests -eq 1 ]; then
  packages+=(
    libgtest-dev
    clang-14 libclang-rt-14-dev               # sanitizer build and fuzzers (scripts/sanitize.sh, fuzz.sh)
    time                                      # /usr/bin/time -v: peak memory in the benchmark
    python3 python3-numpy python3-matplotlib  # benchmark tables and plots, README pictures (scripts/render.py)
    libcgal-dev                               # CGAL 5.5 (header-only): tools/cgal/afsr_run and isotropic_remesh_run, the benchmark's
                                              # cgal-afsr and --remesh CGAL rows only (about 16 s of apt, 45 MB of headers)
  )
fi
if [ $with_pymeshlab -eq 1 ]; then
  packages+=(python3-venv)                    # Debian's python3 makes venvs only with it
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# A deb-src entry (sources only) for one suite of Debian main, in the file $1.
add_deb_src() {
  $SUDO tee "$1" >/dev/null <<EOF
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: $2
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
}

# A deb-src entry for bookworm main, beside the binary one, so that `apt-get source` finds meshlab.
src_list=/etc/apt/sources.list.d/growth-meshlab-src.sources
src_list_2025=/etc/apt/sources.list.d/growth-meshlab2025-src.sources
need_update=0
if ! grep -rqsE --exclude="$(basename "$src_list_2025")" '^(Types:.*deb-src|deb-src )' \
       /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "setup.sh: adding a deb-src entry for bookworm main ($src_list)"
  add_deb_src "$src_list" bookworm
  need_update=1
fi

if [ ${#missing[@]} -gt 0 ] || { [ $need_update -eq 1 ] && [ ! -f "$stamp" ]; }; then
  echo "setup.sh: apt-get update"
  $SUDO apt-get update -qq
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup.sh: installing ${missing[*]}"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# MeshLab SDK: headers of the same version as the installed binary.
version=$(dpkg-query -W -f='${Version}' meshlab)
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$version" ]; then
  echo "setup.sh: MeshLab $version SDK already in $sdk"
else
  echo "setup.sh: fetching the Debian source package of meshlab $version"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  ( cd "$work" && apt-get source --download-only "meshlab=$version" >/dev/null 2>&1 ) || {
    [ $need_update -eq 1 ] || { $SUDO apt-get update -qq; }
    ( cd "$work" && apt-get source --download-only "meshlab=$version" >/dev/null )
  }
  orig=$(ls "$work"/meshlab_*.orig.tar.* | head -1)
  rm -rf "$sdk" && mkdir -p "$sdk"
  # Only what a plugin build needs: the plugin API (src/common) and vcglib's headers.
  tar -xf "$orig" -C "$sdk" --strip-components=1 --wildcards \
      '*/src/common/*' '*/vcglib/vcg/*' '*/vcglib/wrap/*' '*/ML_VERSION'
  # vcglib includes Eigen as "../../eigenlib/Eigen/..."; Debian removed the bundled copy, so point
  # that path at the system Eigen (what Debian's own build of MeshLab uses).
  ln -sfn /usr/include/eigen3 "$sdk/vcglib/eigenlib"
  echo "$version" > "$stamp"
  echo "setup.sh: MeshLab SDK unpacked into $sdk"
fi

# MeshLab 2025.07 (--meshlab-2025): the sources of Debian unstable's source package, whose orig
# tarball is fetched by itself (apt's own transport, checksum pinned here; the mirror serves it while
# the .dsc may be missing), with the pinned copy in ../shared/third_party as the fallback; and their
# libmeshlab-common in single precision, the SDK of Debian's MeshLab 2025.07 GUI. The stamp
# $ml25/.complete-float holds the version, the checksum and the precision, so a finished build is
# skipped. (The double-precision plugins link the PyMeshLab wheel's own library: --pymeshlab.)
ml25_version="2025.07~dfsg-4"
ml25_orig="meshlab_2025.07~dfsg.orig.tar.xz"
ml25_sha256="d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4" # also cmake/MeshLab2025Sources.cmake
ml25="$third_party/meshlab-2025.07"
ml25_stamp="$ml25/.complete-float"
pinned="$here/../shared/third_party"

if [ $with_ml25 -eq 1 ]; then
  if [ -f "$ml25_stamp" ] && [ "$(cat "$ml25_stamp")" = "$ml25_version $ml25_sha256 float" ] && \
     [ -f "$ml25/build-float/src/distrib/libmeshlab-common.so" ]; then
    echo "setup.sh: MeshLab 2025.07 (float) SDK already in $ml25"
  else
    if [ ! -f "$src_list_2025" ]; then
      echo "setup.sh: adding a deb-src entry for unstable main ($src_list_2025; sources only)"
      add_deb_src "$src_list_2025" unstable
    fi
    work25=$(mktemp -d)
    got=""
    uri_of() { apt-get source --print-uris "meshlab=$ml25_version" 2>/dev/null |
               awk -v f="$ml25_orig" '$2 == f { gsub("\047", "", $1); print $1 }'; }
    uri=$(uri_of || true)
    if [ -z "$uri" ]; then
      # Refresh only the unstable source index; keep every other list as it is.
      $SUDO apt-get update -qq -o Dir::Etc::SourceList="$src_list_2025" -o Dir::Etc::SourceParts=- \
          -o APT::Get::List-Cleanup=0 || true
      uri=$(uri_of || true)
    fi
    if [ -n "$uri" ] && /usr/lib/apt/apt-helper download-file "$uri" "$work25/$ml25_orig" \
         "SHA256:$ml25_sha256" >/dev/null 2>&1; then
      got="$work25/$ml25_orig"; echo "setup.sh: downloaded $ml25_orig from the package mirror"
    elif [ -f "$pinned/$ml25_orig" ]; then
      got="$pinned/$ml25_orig"; echo "setup.sh: the mirror did not serve $ml25_orig; using $got"
    else
      echo "setup.sh: cannot get $ml25_orig (mirror failed, no copy in $pinned)" >&2; exit 1
    fi
    echo "$ml25_sha256  $got" | sha256sum -c --quiet - || {
      echo "setup.sh: checksum mismatch for $got" >&2; exit 1; }
    # What building libmeshlab-common with MeshLab's own CMake needs: the top CMakeLists, src/common,
    # vcglib, and the small src/{cmake,external,common_gui} it configures (nothing else is built).
    rm -rf "$ml25" && mkdir -p "$ml25"
    tar -xf "$got" -C "$ml25" --strip-components=1 --wildcards \
        '*/CMakeLists.txt' '*/ML_VERSION' '*/LICENSE.txt' '*/src/common/*' '*/src/vcglib/*' \
        '*/src/cmake/*' '*/src/external/*' '*/src/common_gui/*' \
        --exclude='*/src/meshlabplugins/*' --exclude='*/src/meshlab/*' --exclude='*/docs/*' \
        --exclude='*/scripts/*' --exclude='*/.devcontainer/*'
    rm -rf "$work25"
    ln -sfn /usr/include/eigen3 "$ml25/src/vcglib/eigenlib"   # Debian removed the bundled Eigen
    t0=$(date +%s)
    echo "setup.sh: building libmeshlab-common 2025.07 in single precision (a few minutes)"
    nice cmake -S "$ml25" -B "$ml25/build-float" -DCMAKE_BUILD_TYPE=Release \
        -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR=OFF -DMESHLAB_BUILD_ONLY_LIBRARIES=ON -DMESHLAB_BUILD_MINI=ON \
        -DMESHLAB_PLUGINS="" -DEIGEN3_INCLUDE_DIR=/usr/include/eigen3 >"$ml25/configure-float.log" 2>&1 || {
      tail -20 "$ml25/configure-float.log" >&2; exit 1; }
    nice cmake --build "$ml25/build-float" --target meshlab-common -j"$(nproc)" >"$ml25/build-float.log" 2>&1 || {
      tail -30 "$ml25/build-float.log" >&2; exit 1; }
    echo "$ml25_version $ml25_sha256 float" > "$ml25_stamp"
    echo "setup.sh: MeshLab 2025.07 (float) SDK built in $ml25/build-float ($(( $(date +%s) - t0 )) s)"
  fi
fi

# PyMeshLab 2025.7 (--pymeshlab): the real wheel from PyPI in a venv of the project's own.
venv="$third_party/venv"
pymeshlab_pin="pymeshlab==2025.7.post1"
if [ $with_pymeshlab -eq 1 ]; then
  if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c \
       'import importlib.metadata as m, sys; sys.exit(m.version("pymeshlab") != "2025.7.post1")' 2>/dev/null &&
     "$venv/bin/python" -c 'import pytest' 2>/dev/null; then
    echo "setup.sh: $pymeshlab_pin already in $venv"
  else
    echo "setup.sh: making $venv with $pymeshlab_pin and pytest from PyPI"
    rm -rf "$venv"
    "${PYTHON:-python3}" -m venv "$venv"
    "$venv/bin/python" -m pip install -q --disable-pip-version-check "$pymeshlab_pin" pytest
  fi
fi

checks=(/usr/bin/meshlabserver /usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so
        "$sdk/src/common/interfaces.h" "$sdk/vcglib/vcg/complex/complex.h" /usr/include/eigen3/Eigen/Core)
[ $with_ml25 -eq 0 ] || checks+=("$ml25/src/common/plugins/interfaces/filter_plugin.h"
                                 "$ml25/build-float/src/distrib/libmeshlab-common.so")
[ $with_pymeshlab -eq 0 ] || checks+=("$venv/bin/python")
for f in "${checks[@]}"; do
  [ -e "$f" ] || { echo "setup.sh: $f is missing after set-up" >&2; exit 1; }
done
echo "setup.sh: ready. Build with: cmake -S . -B build && cmake --build build"
[ $with_ml25 -eq 0 ] || echo "setup.sh:   the MeshLab 2025.07 GUI plugins: add -DGROWTH_MESHLAB_2025F=ON"
[ $with_pymeshlab -eq 0 ] || echo "setup.sh:   the PyMeshLab plugins: add -DGROWTH_MESHLAB_2025D=ON -DGROWTH_PYMESHLAB_DIR=\$($venv/bin/python -c 'import pymeshlab, os; print(os.path.dirname(pymeshlab.__file__))' 2>/dev/null)"
