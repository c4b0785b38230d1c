#!/usr/bin/env bash
# Installs everything the project needs on a fresh Debian 12 (bookworm) machine:
#   - Debian packages: MeshLab 2020.09 (meshlabserver, libmeshlab-common.so, plugins), the Qt5 and GL
#     development headers MeshLab's plugin API includes, Eigen, GoogleTest, CMake, Xvfb, clang with
#     its sanitizer runtimes and libFuzzer, and the Python packages the benchmark plots use;
#   - MeshLab's plugin API headers (src/common) and vcglib, from the Debian *source* package of the
#     installed meshlab version, unpacked into third_party/ (ignored by git; never committed).
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
  python3 python3-numpy python3-matplotlib    # benchmark tables and plots (/usr/bin/python3)
  xz-utils ca-certificates dpkg-dev            # apt-get source
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# A deb-src entry for bookworm main, beside the binary one, so that `apt-get source` finds meshlab.
src_list=/etc/apt/sources.list.d/growth-meshlab-src.sources
need_update=0
if ! grep -rqsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "setup.sh: adding a deb-src entry for bookworm main ($src_list)"
  $SUDO tee "$src_list" >/dev/null <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
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

for f in /usr/bin/meshlabserver /usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so \
         "$sdk/src/common/interfaces.h" "$sdk/vcglib/vcg/complex/complex.h" \
         /usr/include/eigen3/Eigen/Core; do
  [ -e "$f" ] || { echo "setup.sh: $f is missing after set-up" >&2; exit 1; }
done
echo "setup.sh: ready. Build with: cmake -S . -B build && cmake --build build"
