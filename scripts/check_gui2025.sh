#!/usr/bin/env bash
# The real MeshLab 2025.07 GUI with the single-precision plugins, checked end to end.
#
#   scripts/check_gui2025.sh [PLUGIN_DIR [CLOUD]]        (as root)
#
# Debian unstable (its meshlab 2025.07, float) is debootstrapped into a folder and kept there for
# the next run; nothing is installed on the host (debootstrap itself is unpacked from its .deb into
# the cache). Xvfb, xdotool, xwininfo and ImageMagick's import run inside that root, and so does
# MeshLab. The two plugins are installed both ways MeshLab finds plugins, one GUI run each:
#   system  copied into Debian's plugin folder /usr/lib/x86_64-linux-gnu/meshlab/plugins/;
#   user    copied into the folder that Help > Plugin Info > Load Plugins copies to,
#           ~/.local/share/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07/.
# In each, for each filter, MeshLab is started on the cloud, the filter is opened and applied through
# the menus (Filters > Remeshing, Simplification and Reconstruction > ..., keyboard navigation with
# xdotool) and the result saved through File > Export Mesh As.... Checked:
#   - MeshLab shows no plugin load error (no "Error while loading plugins." box: among others the
#     "different floating point precision" refusal) and prints none;
#   - the filter's dialog opens from its menu entry and fits the screen: at most
#     GROWTH_GUI2025_MAX_DIALOG_HEIGHT px tall (850) on the 1280x1000 screen, wholly on it;
#   - the filter runs, and the exported mesh has faces, as many vertices and faces as ml_apply (the
#     float build's host of the plugins, the way pymeshlab.load_plugin loads them) gives on the cloud.
# Screenshots (PNG) of the menu, each dialog (also with its help texts shown), each result and the
# Plugin Info list go to the output folder, with the exported meshes and MeshLab's output. Each step's
# time is printed. Exits non-zero, saying what failed, at the first failed check.
#
#   PLUGIN_DIR  the float plugins (default: GROWTH_GUI2025_PLUGINS, else build/meshlab-2025.07/plugins)
#   CLOUD       a PLY point cloud with normals (default: GROWTH_GUI2025_CLOUD, else a torus of
#               30,000 points made by make_cloud --shape torus --points 30000 --seed 1)
# Environment:
#   GROWTH_GUI2025_ROOT        the debootstrapped root, kept between runs (default out/gui2025/root)
#   GROWTH_GUI2025_OUT         screenshots, meshes and logs (default out/gui2025/check; emptied first)
#   GROWTH_GUI2025_MIRROR      Debian mirror (default http://deb.debian.org/debian)
#   GROWTH_GUI2025_ML_APPLY    ml_apply of the float build (default PLUGIN_DIR/../ml_apply)
#   GROWTH_GUI2025_MAKE_CLOUD  make_cloud (default build/make_cloud)
#   GROWTH_GUI2025_MODES       which installs to check (default "system user")
#   GROWTH_GUI2025_MENU_SPHEREPACK, GROWTH_GUI2025_MENU_G2S  the filters' places in the Remeshing
#                              submenu (0 = first; default 31 and 29 with Debian's 2025.07~dfsg-4
#                              plugins); a wrong place is reported, since the dialog's title is checked
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
plugins=${1:-${GROWTH_GUI2025_PLUGINS:-$repo/build/meshlab-2025.07/plugins}}
cloud=${2:-${GROWTH_GUI2025_CLOUD:-}}
root=${GROWTH_GUI2025_ROOT:-$repo/out/gui2025/root}
out=${GROWTH_GUI2025_OUT:-$repo/out/gui2025/check}
mirror=${GROWTH_GUI2025_MIRROR:-http://deb.debian.org/debian}
ml_apply=${GROWTH_GUI2025_ML_APPLY:-$plugins/../ml_apply}
make_cloud=${GROWTH_GUI2025_MAKE_CLOUD:-$repo/build/make_cloud}
modes=${GROWTH_GUI2025_MODES:-system user}
max_dialog_height=${GROWTH_GUI2025_MAX_DIALOG_HEIGHT:-850}
screen_w=1280 screen_h=1000

# What the root gets: MeshLab with its recommended libraries (several of Debian's own plugins need
# them), and the tools that drive and photograph the GUI.
packages_gui="xvfb xdotool x11-utils imagemagick libgl1-mesa-dri fonts-dejavu-core"
sysplugins=/usr/lib/x86_64-linux-gnu/meshlab/plugins
userplugins=.local/share/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07 # under $HOME
work=/growth-check # inside the root
declare -A filter_name=([spherepack]="Surface Reconstruction: Sphere Packing" [g2s]="Surface Reconstruction: Robust G2S")
declare -A filter_menu=([spherepack]=${GROWTH_GUI2025_MENU_SPHEREPACK:-31} [g2s]=${GROWTH_GUI2025_MENU_G2S:-29})
declare -A plugin_name=([spherepack]=FilterSpherePack [g2s]=FilterG2S)

fail() { echo "check_gui2025: FAILED: $*" >&2; exit 1; }
note() { echo "   $*"; }

# --- Steps and their times ----------------------------------------------------------------------
step_names=() step_secs=() step_now="" step_t0=""
seconds_since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }
step() {
  local name=$1; shift
  echo "== $name"
  step_now=$name step_t0=$(date +%s.%N)
  "$@"
  step_names+=("$name"); step_secs+=("$(seconds_since "$step_t0")")
  step_now=""
  note "($name: ${step_secs[-1]} s)"
}
print_times() {
  if [ -n "$step_now" ]; then step_names+=("$step_now (failed)"); step_secs+=("$(seconds_since "$step_t0")"); fi
  [ ${#step_names[@]} -gt 0 ] || return 0
  echo "== times"
  local i total=0
  for i in "${!step_names[@]}"; do
    printf '   %7.1f s  %s\n' "${step_secs[i]}" "${step_names[i]}"
    total=$(awk -v a="$total" -v b="${step_secs[i]}" 'BEGIN { print a + b }')
  done
  printf '   %7.1f s  total\n' "$total"
}

# --- Mounts and processes, undone on any exit -----------------------------------------------------
mounted=() pids=()
mount_in() { # mount_in TARGET mount-args...
  local target=$1; shift
  mount "$@" "$target"
  mounted+=("$target")
}
unmount_under() { # whatever is still mounted below a folder (an interrupted debootstrap's too)
  local dir=$1 m
  awk -v d="$dir/" 'index($2, d) == 1 { print $2 }' /proc/self/mounts | sort -r | while read -r m; do
    umount "$m" 2>/dev/null || umount -l "$m" || echo "check_gui2025: cannot unmount $m" >&2
  done
}
cleanup() {
  local rc=$? i
  for i in "${pids[@]}"; do kill "$i" 2>/dev/null || true; done
  for i in "${pids[@]}"; do wait "$i" 2>/dev/null || true; done
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}" || echo "check_gui2025: cannot unmount ${mounted[i]}" >&2
  done
  unmount_under "$root"
  unmount_under "$root.new"
  print_times
  [ $rc -eq 0 ] || echo "check_gui2025: stopped (exit $rc); output so far in $out" >&2
  exit $rc
}

[ "$(id -u)" -eq 0 ] || fail "needs root (debootstrap, chroot, mount)"
for so in libfilter_spherepack.so libfilter_g2s.so; do
  [ -f "$plugins/$so" ] || fail "no $plugins/$so: build the float plugins (cmake -DGROWTH_MESHLAB_2025F=ON) or give their folder"
done
[ -x "$ml_apply" ] || fail "no ml_apply at $ml_apply (the float build's, next to its plugins/): set GROWTH_GUI2025_ML_APPLY"
if [ -z "$cloud" ]; then
  [ -x "$make_cloud" ] || fail "no make_cloud at $make_cloud: give a cloud or set GROWTH_GUI2025_MAKE_CLOUD"
else
  [ -f "$cloud" ] || fail "no cloud $cloud"
fi
plugins=$(cd "$plugins" && pwd)

mkdir -p "$(dirname "$root")"
exec 9>"$root.lock"
flock -n 9 || fail "another check_gui2025 uses $root"
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
rm -rf "$out"
mkdir -p "$out"

# --- 1. Debian unstable, debootstrapped once ------------------------------------------------------
debootstrap_root() {
  if [ -f "$root/.growth-base" ]; then note "cached: $root"; return; fi
  local dbs
  if command -v debootstrap >/dev/null; then
    dbs=(debootstrap)
  else # the host has none: unpack Debian's package into the cache, install nothing
    local tool="$(dirname "$root")/debootstrap"
    if [ ! -x "$tool/usr/sbin/debootstrap" ]; then
      rm -rf "$tool" && mkdir -p "$tool/deb"
      (cd "$tool/deb" && apt-get download debootstrap >/dev/null 2>&1) \
        || fail "apt-get download debootstrap failed (the host's package lists: apt-get update)"
      dpkg -x "$tool"/deb/debootstrap_*.deb "$tool"
    fi
    dbs=(env DEBOOTSTRAP_DIR="$tool/usr/share/debootstrap" "$tool/usr/sbin/debootstrap")
  fi
  rm -rf "$root" "$root.new"
  # The Release file is checked against the host's debian-archive-keyring (sid is signed with the
  # bookworm and trixie keys); debootstrap does not check its Valid-Until, apt in the root does.
  "${dbs[@]}" --variant=minbase sid "$root.new" "$mirror" > "$out/debootstrap.log" 2>&1 \
    || { tail -20 "$out/debootstrap.log" >&2; fail "debootstrap of sid failed (log: $out/debootstrap.log)"; }
  unmount_under "$root.new"
  mv "$root.new" "$root"
  touch "$root/.growth-base"
  note "debootstrapped $root"
}

mount_root() {
  mount_in "$root/proc" -t proc proc
  mount_in "$root/sys" -t sysfs sysfs
  mount_in "$root/dev" --bind /dev
  mount_in "$root/dev/pts" --bind /dev/pts
  if mountpoint -q /dev/shm; then mount_in "$root/dev/shm" --bind /dev/shm; fi
}

inroot() { # runs a command in the root, with the GUI session's environment
  chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 HOME="$work/home" \
    XDG_RUNTIME_DIR="$work/xdg" DISPLAY="${display:+:$display}" "$@"
}
inroot_bg() { # the same in the background, its pid in $bg_pid (that of the program itself)
  chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 HOME="$work/home" \
    XDG_RUNTIME_DIR="$work/xdg" DISPLAY="${display:+:$display}" "$@" 9>&- &
  bg_pid=$!; pids+=("$bg_pid")
}

# --- 2. MeshLab and the GUI tools in the root -----------------------------------------------------
install_packages() {
  # Debian unstable's Release file can be past its Valid-Until date on the mirror.
  echo 'Acquire::Check-Valid-Until "false";' > "$root/etc/apt/apt.conf.d/99growth-no-valid-until"
  printf '#!/bin/sh\nexit 101\n' > "$root/usr/sbin/policy-rc.d" && chmod +x "$root/usr/sbin/policy-rc.d"
  local want="meshlab(+recommends) $packages_gui"
  if [ "$(cat "$root/.growth-packages" 2>/dev/null)" = "$want" ]; then
    note "cached: $want"
  else
    inroot apt-get update > "$out/apt.log" 2>&1 || { tail "$out/apt.log" >&2; fail "apt-get update in the root failed"; }
    inroot env DEBIAN_FRONTEND=noninteractive apt-get install -y -o APT::Install-Recommends=true meshlab \
      >> "$out/apt.log" 2>&1 || { tail "$out/apt.log" >&2; fail "apt-get install meshlab in the root failed"; }
    # shellcheck disable=SC2086
    inroot env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $packages_gui \
      >> "$out/apt.log" 2>&1 || { tail "$out/apt.log" >&2; fail "apt-get install of the GUI tools failed"; }
    inroot apt-get clean
    echo "$want" > "$root/.growth-packages"
  fi
  local v
  v=$(inroot dpkg-query -W -f='${Version}' meshlab) || fail "meshlab is not installed in the root"
  note "meshlab $v (Debian unstable), $(inroot dpkg-query -W -f='Qt ${Version}' libqt5core5t64 2>/dev/null || true)"
  echo "$v" > "$out/meshlab-version.txt"
  case "$v" in 2025.07*) ;; *) fail "Debian unstable's meshlab is $v, not 2025.07: these plugins load only in 2025.0x";; esac
  [ -d "$root$sysplugins" ] || fail "no $sysplugins in the root"
}

# --- 3. The cloud, and what ml_apply makes of it --------------------------------------------------
ply_count() { LC_ALL=C sed -n "/^end_header/q;s/^element $1 \([0-9]*\).*/\1/p" "$2" | head -1; }
declare -A ref_vertices ref_faces
prepare_input() {
  rm -rf "${root:?}$work"
  mkdir -p "$root$work/in" "$root$work/out" "$out/ml_apply"
  if [ -n "$cloud" ]; then
    cp "$cloud" "$root$work/in/cloud.ply"
  else
    "$make_cloud" --shape torus --points 30000 --seed 1 -o "$root$work/in/cloud.ply" > /dev/null
  fi
  grep -aq '^property float nx' "$root$work/in/cloud.ply" || fail "the cloud has no normals (property float nx)"
  note "cloud: $(ply_count vertex "$root$work/in/cloud.ply") points"
  local f
  for f in spherepack g2s; do
    "$ml_apply" "$plugins/libfilter_$f.so" "${filter_name[$f]}" "$root$work/in/cloud.ply" "$out/ml_apply/$f.ply" \
      > "$out/ml_apply/$f.log" 2>&1 || { tail "$out/ml_apply/$f.log" >&2; fail "ml_apply ${filter_name[$f]} failed"; }
    ref_vertices[$f]=$(ply_count vertex "$out/ml_apply/$f.ply")
    ref_faces[$f]=$(ply_count face "$out/ml_apply/$f.ply")
    note "ml_apply ${filter_name[$f]}: ${ref_vertices[$f]} vertices, ${ref_faces[$f]} faces"
  done
}

# --- 4. The GUI -----------------------------------------------------------------------------------
display="" xvfb_pid="" meshlab_pid="" log="" shots=()
xdo() { inroot xdotool "$@"; }
shot() { # shot NAME: the whole screen
  inroot import -window root png:- > "$out/$mode/$1.png" || { echo "check_gui2025: screenshot $1 failed" >&2; return 1; }
  shots+=("$out/$mode/$1.png")
}
windows() { xdo search --onlyvisible --name . getwindowname %@ 2>/dev/null || true; }
wait_window() { # wait_window REGEX [SECONDS]: prints the id of the first visible window so named
  local i id
  for ((i = 0; i < ${2:-30} * 4; i++)); do
    id=$(xdo search --onlyvisible --name "$1" 2>/dev/null | head -1) || true
    [ -n "$id" ] && { echo "$id"; return 0; }
    sleep 0.25
  done
  return 1
}
wait_gone() { local i; for ((i = 0; i < ${2:-20} * 4; i++)); do [ -z "$(xdo search --onlyvisible --name "$1" 2>/dev/null)" ] && return 0; sleep 0.25; done; return 1; }
wait_log() { # wait_log FIXED-STRING [SECONDS]
  local i
  for ((i = 0; i < ${2:-60} * 4; i++)); do grep -qF -- "$1" "$log" && return 0; meshlab_alive || return 1; sleep 0.25; done
  return 1
}
meshlab_alive() { kill -0 "$meshlab_pid" 2>/dev/null; }
gui_fail() { # screenshot what is on screen, then fail
  shot "failure-$1" 2>/dev/null || true
  echo "   windows on screen: $(windows | tr '\n' '|')" >&2
  echo "   MeshLab's output: $log" >&2
  fail "$2 (screenshot $out/$mode/failure-$1.png)"
}
expect_no_other_windows() { # a message box (load error, failed filter, missing normals) fails the check
  local w
  while read -r w; do
    [ -z "$w" ] && continue
    case "$w" in "MeshLab 2025.07"*|"$1") ;; *) gui_fail "$2" "MeshLab shows the window '$w' ($2)";; esac
  done < <(windows)
}
load_errors() {
  grep -E "different floating point precision|different version|Unable to load|does not seem to be a Qt Plugin|is not a MeshLab plugin|has been already loaded|Cannot load library" "$log" || true
}

start_gui() { # start_gui NAME: Xvfb and MeshLab on the cloud, the main window filling the screen
  rm -rf "${root:?}$work/home" "$root$work/xdg" "$root$work/out"
  mkdir -p "$root$work/home" "$root$work/out" && install -d -m 700 "$root$work/xdg"
  if [ "$mode" = user ]; then
    mkdir -p "$root$work/home/$userplugins"
    cp "$plugins/libfilter_spherepack.so" "$plugins/libfilter_g2s.so" "$root$work/home/$userplugins/"
  fi
  # The display's socket is the file in the root's /tmp/.X11-unix only (-nolisten local: no abstract
  # socket), so the number cannot clash with an X server of the host.
  rm -f "$root/tmp/.X"*-lock "$root/tmp/.X11-unix/X"*
  display=""
  rm -f "$out/$mode/xvfb.display"
  inroot_bg Xvfb -displayfd 3 -screen 0 "${screen_w}x${screen_h}x24" -nolisten tcp -nolisten local \
    3> "$out/$mode/xvfb.display" > "$out/$mode/xvfb-$1.log" 2>&1
  xvfb_pid=$bg_pid
  local i
  for ((i = 0; i < 80; i++)); do [ -s "$out/$mode/xvfb.display" ] && break; sleep 0.25; done
  display=$(tr -d '\n' < "$out/$mode/xvfb.display")
  [ -n "$display" ] || fail "Xvfb did not start (log: $out/$mode/xvfb-$1.log)"
  log="$out/$mode/meshlab-$1.log"
  inroot_bg meshlab "$work/in/cloud.ply" > "$log" 2>&1
  meshlab_pid=$bg_pid
  local w
  w=$(wait_window '^(MeshLab 2025|Error while loading plugins)' 60) || gui_fail "$1-start" "MeshLab's window did not appear in 60 s"
  sleep 2 # the load error box comes before the main window
  if [ -n "$(xdo search --onlyvisible --name 'Error while loading plugins' 2>/dev/null)" ]; then
    gui_fail "$1-load-error" "MeshLab could not load plugins ('Error while loading plugins.' box; the reasons are in the screenshot)"
  fi
  local errs; errs=$(load_errors)
  [ -z "$errs" ] || fail "MeshLab printed plugin load errors: $errs"
  wait_log "Opened mesh $work/in/cloud.ply" 30 || gui_fail "$1-open" "MeshLab did not open the cloud"
  main=$(wait_window '^MeshLab 2025' 10) || gui_fail "$1-start" "no main window"
  xdo windowsize "$main" "$screen_w" "$screen_h" windowmove "$main" 0 0
  sleep 1
  expect_no_other_windows "" "$1-start"
}
stop_gui() {
  kill "$meshlab_pid" 2>/dev/null || true; wait "$meshlab_pid" 2>/dev/null || true
  kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true
  local errs; errs=$(load_errors)
  [ -z "$errs" ] || fail "MeshLab printed plugin load errors: $errs"
}
keys() { xdo key --delay 80 "$@"; sleep 0.5; }
downs() { local a=() i; for ((i = 0; i < $1; i++)); do a+=(Down); done; [ $1 -eq 0 ] || keys "${a[@]}"; }
focus() { xdo windowfocus --sync "$1"; sleep 0.2; }

plugin_info() { # Help > Plugin Info, our plugins' rows (vendor, file)
  focus "$main"
  keys alt+h
  keys Down Return
  local w; w=$(wait_window '^Plugin Information$' 10) || gui_fail plugininfo "Help > Plugin Info did not open"
  eval "$(xdo getwindowgeometry --shell "$w")"
  xdo mousemove $((X + 150)) $((Y + 64)) click 1 # the first row: the list takes the keyboard
  sleep 0.5
  local f
  for f in g2s spherepack; do
    xdo type --delay 40 "${plugin_name[$f]}"; sleep 1.2 # the list's keyboard search
    shot "plugininfo-$f"
  done
  keys Escape
  wait_gone '^Plugin Information$' 10 || gui_fail plugininfo "Plugin Info did not close"
}

dialog_geometry() { # prints "height top bottom width right" of a window
  inroot xwininfo -id "$1" | awk '/Absolute upper-left X/ { x = $NF } /Absolute upper-left Y/ { y = $NF }
    /^ *Width:/ { w = $NF } /^ *Height:/ { h = $NF } END { print h, y, y + h, w, x + w }'
}
declare -A dialog_height dialog_help_height gui_vertices gui_faces
run_filter() { # run_filter spherepack|g2s
  local f=$1 name=${filter_name[$1]}
  mkdir -p "$out/$mode"
  start_gui "$f"
  [ "$f" = spherepack ] && plugin_info
  # Filters > Remeshing, Simplification and Reconstruction > the filter. The Filters menu opens on
  # its first enabled entry (Show current filter script); the Remeshing submenu is four below.
  focus "$main"
  keys alt+l
  downs 4
  keys Right
  downs "${filter_menu[$f]}"
  sleep 0.5
  shot "$f-1-menu"
  keys Return
  local d
  d=$(wait_window "^$name\$" 20) \
    || gui_fail "$f-menu" "Filters > Remeshing, Simplification and Reconstruction > entry ${filter_menu[$f]} did not open '$name' (is the plugin loaded? has Debian's list of filters changed? GROWTH_GUI2025_MENU_${f^^})"
  sleep 1
  shot "$f-2-dialog"
  local h top bottom w right
  read -r h top bottom w right < <(dialog_geometry "$d")
  dialog_height[$mode.$f]=$h
  note "$name: dialog ${w}x$h px, y = $top to $bottom on the ${screen_w}x$screen_h screen (right edge $right)"
  # The help texts: Help is two before Apply, which has the focus, in the dialog's tab order.
  focus "$d"
  keys shift+Tab shift+Tab space
  sleep 1
  shot "$f-3-dialog-help"
  local hh htop hbottom hw hright
  read -r hh htop hbottom hw hright < <(dialog_geometry "$d")
  dialog_help_height[$mode.$f]="${hw}x$hh"
  note "with the help texts shown: ${hw}x$hh px, y = $htop to $hbottom (right edge $hright)"
  keys space Tab Tab # help off; Close, Apply
  sleep 0.5
  read -r h top bottom w right < <(dialog_geometry "$d")
  [ "$h" -le "$max_dialog_height" ] || gui_fail "$f-dialog" "the dialog of '$name' is $h px tall, more than $max_dialog_height"
  [ "$top" -ge 0 ] && [ "$bottom" -le "$screen_h" ] || gui_fail "$f-dialog" "the dialog of '$name' is not wholly on the screen (y = $top to $bottom)"
  # Apply, then close the dialog (Close is before Apply).
  keys space
  wait_log "Applied filter: $name" 300 || gui_fail "$f-apply" "'$name' did not finish (no 'Applied filter' in MeshLab's log)"
  sleep 1
  expect_no_other_windows "$name" "$f-apply"
  focus "$d"
  keys shift+Tab space
  wait_gone "^$name\$" 10 || gui_fail "$f-close" "the dialog of '$name' did not close"
  # File > Export Mesh As... (the eighth entry): the result is the current layer.
  focus "$main"
  keys alt+f
  downs 7
  shot "$f-4-export-menu"
  keys Return
  local s
  s=$(wait_window '^Save "' 20) || gui_fail "$f-export" "File > Export Mesh As... did not open its file dialog"
  focus "$s"
  xdo type --delay 20 "$work/out/$f.ply"; sleep 0.3
  keys Return
  s=$(wait_window '^Choose Saving Options' 20) || gui_fail "$f-export" "no saving options after the file dialog"
  focus "$s"
  keys Return
  wait_log "Saved Mesh $work/out/$f.ply" 60 || gui_fail "$f-export" "MeshLab did not save $work/out/$f.ply"
  # The result alone: the cloud's layer (row 0 of the layer list) hidden by its eye.
  focus "$main"
  xdo mousemove 876 111 click 1
  sleep 2
  shot "$f-5-result"
  expect_no_other_windows "" "$f-result"
  stop_gui
  cp "$root$work/out/$f.ply" "$out/$mode/$f.ply"
  local v fc
  v=$(ply_count vertex "$out/$mode/$f.ply"); fc=$(ply_count face "$out/$mode/$f.ply")
  gui_vertices[$mode.$f]=$v gui_faces[$mode.$f]=$fc
  note "exported $out/$mode/$f.ply: $v vertices, $fc faces (ml_apply: ${ref_vertices[$f]}, ${ref_faces[$f]})"
  [ "${fc:-0}" -gt 0 ] || fail "the mesh '$name' exported from the GUI has no faces"
  [ "$v" = "${ref_vertices[$f]}" ] && [ "$fc" = "${ref_faces[$f]}" ] \
    || fail "'$name' in the GUI gave $v vertices, $fc faces; ml_apply ${ref_vertices[$f]}, ${ref_faces[$f]}"
}

install_plugins() { # the plugins in exactly one of the two places
  rm -f "$root$sysplugins/libfilter_spherepack.so" "$root$sysplugins/libfilter_g2s.so"
  if [ "$mode" = system ]; then
    cp "$plugins/libfilter_spherepack.so" "$plugins/libfilter_g2s.so" "$root$sysplugins/"
    note "copied into $sysplugins"
  else
    note "copied into ~/$userplugins at each start"
  fi
}

gui_mode() {
  mkdir -p "$out/$mode"
  install_plugins
  run_filter spherepack
  run_filter g2s
  [ "$mode" = user ] && ls "$root$work/home/$userplugins" > "$out/$mode/user-plugin-folder.txt"
  rm -f "$root$sysplugins/libfilter_spherepack.so" "$root$sysplugins/libfilter_g2s.so"
}

step "debootstrap Debian unstable" debootstrap_root
mount_root
step "install meshlab and the GUI tools" install_packages
step "cloud and ml_apply reference" prepare_input
for mode in $modes; do
  case "$mode" in system|user) ;; *) fail "unknown mode $mode (system, user)";; esac
  step "GUI, plugins in the $mode folder" gui_mode
done

echo "== result"
for mode in $modes; do
  for f in spherepack g2s; do
    note "$mode: ${filter_name[$f]}: ${gui_vertices[$mode.$f]} vertices, ${gui_faces[$mode.$f]} faces (ml_apply the same)"
  done
done
for mode in $modes; do
  for f in spherepack g2s; do
    note "$mode: ${filter_name[$f]}: dialog ${dialog_height[$mode.$f]} px tall (at most $max_dialog_height); ${dialog_help_height[$mode.$f]} px with the help texts shown"
  done
done
note "no plugin load error; screenshots:"
for s in "${shots[@]}"; do note "  $s"; done
echo "check_gui2025: OK"
