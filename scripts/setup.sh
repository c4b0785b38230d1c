#!/usr/bin/env bash
# Installs everything the project needs on a fresh Debian 12 (bookworm) machine:
#   - Debian packages: MeshLab 2020.09 (meshlabserver, libmeshlab-common.so, plugins), the Qt5 and GL
#     development headers MeshLab's plugin API includes, Eigen, GoogleTest, CMake, Xvfb, clang with
#     its sanitizer runtimes and libFuzzer, the Python packages the benchmark plots use, and CGAL
#     (header-only; only for the benchmark's peer row, CGAL's advancing front, tools/cgal/afsr_run);
#   - MeshLab's plugin API headers (src/common) and vcglib, from the Debian *source* package of the
#     installed meshlab version, unpacked into third_party/ (ignored by git; never committed);
#   - MeshLab 2025.07's src/common and vcglib, from Debian unstable's source package (a deb-src entry
#     only: no binary package changes), unpacked into third_party/meshlab-2025.07/, where its
#     libmeshlab-common is built in double precision (the SDK of PyMeshLab 2025.7 and MeshLab 2025.07d)
#     and in single precision (the SDK of the plain MeshLab 2025.07 GUI).
# Idempotent: a second run only checks and returns.
# Usage: scripts/setup.sh            (as root, or as a user with sudo)
set -euo pipefail

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
  libeigen3-dev libgtest-dev
  clang-14 libclang-rt-14-dev                 # sanitizer build and fuzzers (scripts/sanitize.sh, fuzz.sh)
  xvfb xauth                                  # meshlabserver needs a display
  time                                        # /usr/bin/time -v: peak memory in the benchmark
  python3 python3-numpy python3-matplotlib    # benchmark tables and plots, README pictures (scripts/render.py)
  libcgal-dev                                 # CGAL 5.5 (header-only): tools/cgal/afsr_run, the benchmark's
                                              # cgal-afsr row only (about 16 s of apt, 45 MB of headers)
  xz-utils ca-certificates dpkg-dev            # apt-get source
)

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

# MeshLab 2025.07 SDK (the plugins for MeshLab 2025.07 and PyMeshLab 2025.7): Debian unstable's
# source package. Only the orig tarball is needed; the mirror serves it while the .dsc may be
# missing, so it is fetched by itself (apt's own transport, checksum from the source index), with
# the pinned copy in ../shared/third_party as the fallback. The checksum is verified either way.
ml25_version="2025.07~dfsg-4"
ml25_orig="meshlab_2025.07~dfsg.orig.tar.xz"
ml25_sha256="d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4"
ml25="$third_party/meshlab-2025.07"
pinned="$here/../shared/third_party"

# libmeshlab-common 2025.07 in one precision ("double": the SDK of PyMeshLab 2025.7 and MeshLab
# 2025.07d; "float": that of the plain MeshLab 2025.07 GUI), built from the sources in $ml25 into
# $ml25/build-<precision>/. Its stamp ($ml25/.complete for double, .complete-float for float) holds
# the version, the checksum and the precision, so that a finished build is skipped.
ml25_build_dir() { echo "$ml25/build-$1"; }
ml25_suffix() { [ "$1" = double ] && echo "" || echo "-$1"; }
ml25_stamp_of() { echo "$ml25/.complete$(ml25_suffix "$1")"; }
ml25_built() {
  local stamp; stamp=$(ml25_stamp_of "$1")
  [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$ml25_version $ml25_sha256 $1" ] && \
    [ -f "$(ml25_build_dir "$1")/src/distrib/libmeshlab-common.so" ]
}
build_ml25() {
  local precision=$1 scalar=OFF t0 dir suffix
  [ "$precision" = double ] && scalar=ON
  t0=$(date +%s); dir=$(ml25_build_dir "$precision"); suffix=$(ml25_suffix "$precision")
  echo "setup.sh: building libmeshlab-common 2025.07 in $precision precision (a few minutes)"
  nice cmake -S "$ml25" -B "$dir" -DCMAKE_BUILD_TYPE=Release \
      -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR=$scalar -DMESHLAB_BUILD_ONLY_LIBRARIES=ON -DMESHLAB_BUILD_MINI=ON \
      -DMESHLAB_PLUGINS="" -DEIGEN3_INCLUDE_DIR=/usr/include/eigen3 >"$ml25/configure$suffix.log" 2>&1 || {
    tail -20 "$ml25/configure$suffix.log" >&2; exit 1; }
  nice cmake --build "$dir" --target meshlab-common -j"$(nproc)" >"$ml25/build$suffix.log" 2>&1 || {
    tail -30 "$ml25/build$suffix.log" >&2; exit 1; }
  echo "$ml25_version $ml25_sha256 $precision" > "$(ml25_stamp_of "$precision")"
  echo "setup.sh: MeshLab 2025.07 ($precision) SDK built in $dir ($(( $(date +%s) - t0 )) s)"
}

# The sources are fetched and unpacked only when the double build is missing (unpacking starts
# $ml25 afresh, so the float build is then made again too).
if ml25_built double; then
  echo "setup.sh: MeshLab 2025.07 (double) SDK already in $ml25"
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
  build_ml25 double
fi
if ml25_built float; then
  echo "setup.sh: MeshLab 2025.07 (float) SDK already in $ml25"
else
  build_ml25 float
fi

for f in /usr/bin/meshlabserver /usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so \
         "$sdk/src/common/interfaces.h" "$sdk/vcglib/vcg/complex/complex.h" \
         /usr/include/eigen3/Eigen/Core "$ml25/src/common/plugins/interfaces/filter_plugin.h" \
         "$(ml25_build_dir double)/src/distrib/libmeshlab-common.so" "$(ml25_build_dir float)/src/distrib/libmeshlab-common.so"; do
  [ -e "$f" ] || { echo "setup.sh: $f is missing after set-up" >&2; exit 1; }
done
echo "setup.sh: ready. Build with: cmake -S . -B build && cmake --build build" \
     "(add -DGROWTH_MESHLAB_2025D=ON -DGROWTH_MESHLAB_2025F=ON for the MeshLab 2025.07d and 2025.07 plugins)"
