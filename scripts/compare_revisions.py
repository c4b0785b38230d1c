#!/usr/bin/env python3
"""Before/after speed of the two engines in one run: two revisions, the same clouds, interleaved.

Builds the command-line runners (build/g2s_run, build/spherepack_run) of two git revisions in
out/revisions/<sha>/ (from `git archive`, with third_party/ linked; built once and kept), makes the
clouds once with the newer revision's build/make_cloud (PLY files, so both read the same bytes),
then times both revisions on every cloud in alternating order, round after round, so that the
machine's drift hits both alike. Each run is a fresh process; the time is the engine's own
`seconds:` (reading the PLY excluded). Prints, per filter and cloud, the median and fastest
engine seconds of each revision, the faces, the rates (faces per second, from the medians) and the
ratio of the rates (after / before), the median and quartiles of the ratios of each round's two
back-to-back runs (time after / time before: the least sensitive to the machine's drift), and writes the same table to out/revisions/compare-*.md.

  scripts/compare_revisions.sh BEFORE [AFTER]      (AFTER defaults to HEAD)
      [--rounds N] [--points N] [--shapes sphere,torus] [--filters g2s,spherepack] [--clouds A.ply,B.ply]

The sphere packer runs with --threads 1 (Robust G2S is single-threaded): the machines have two
cores, and one thread each keeps the two revisions' runs from competing with other work.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUNNERS = {"g2s": "g2s_run", "spherepack": "spherepack_run"}


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, **kw)


def resolve(rev):
    return run(["git", "-C", ROOT, "rev-parse", "--verify", rev + "^{commit}"], capture_output=True).stdout.strip()


def build(sha, jobs):
    """The revision's runners, built in out/revisions/<sha>/build (kept for later runs)."""
    top = os.path.join(ROOT, "out", "revisions", sha[:12])
    src, bld = os.path.join(top, "src"), os.path.join(top, "build")
    targets = ["g2s_run", "spherepack_run", "make_cloud"]
    if all(os.path.exists(os.path.join(bld, t)) for t in targets):
        return bld
    if os.path.isdir(src):
        shutil.rmtree(src)
    os.makedirs(src)
    archive = subprocess.Popen(["git", "-C", ROOT, "archive", sha], stdout=subprocess.PIPE)
    run(["tar", "-x", "-C", src], stdin=archive.stdout)
    if archive.wait() != 0:
        sys.exit(f"compare_revisions: git archive {sha} failed")
    os.symlink(os.path.join(ROOT, "third_party"), os.path.join(src, "third_party"))
    print(f"compare_revisions: building {sha[:12]} in {bld}", flush=True)
    run(["cmake", "-S", src, "-B", bld, "-DCMAKE_BUILD_TYPE=Release"], stdout=subprocess.DEVNULL)
    run(["cmake", "--build", bld, "-j", str(jobs), "--target"] + targets, stdout=subprocess.DEVNULL)
    return bld


def engine_seconds(binary, cloud, extra):
    out = run([binary, cloud] + extra, capture_output=True).stdout
    seconds = re.search(r"^seconds: ([0-9.eE+-]+)$", out, re.M)
    faces = re.search(r"^faces: (\d+)$", out, re.M)
    if not seconds or not faces:
        sys.exit(f"compare_revisions: no 'seconds:'/'faces:' in the output of {binary} {cloud}")
    return float(seconds.group(1)), int(faces.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("before")
    ap.add_argument("after", nargs="?", default="HEAD")
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("--points", type=int, default=200000)
    ap.add_argument("--shapes", default="sphere,torus")
    ap.add_argument("--filters", default="g2s,spherepack")
    ap.add_argument("--clouds", default="", help="PLY files timed too, comma-separated (real scans, noisy clouds "
                    "written by make_cloud); --shapes '' leaves only these")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    a = ap.parse_args()

    shas = [resolve(a.before), resolve(a.after)]
    builds = [build(s, a.jobs) for s in shas]
    clouds_dir = os.path.join(ROOT, "out", "revisions", "clouds")
    os.makedirs(clouds_dir, exist_ok=True)
    clouds = []
    for shape in [x for x in a.shapes.split(",") if x]:
        path = os.path.join(clouds_dir, f"{shape}-{a.points}.ply")
        if not os.path.exists(path):
            run([os.path.join(builds[1], "make_cloud"), "--shape", shape, "--points", str(a.points), "--seed", "1",
                 "-o", path], stdout=subprocess.DEVNULL)
        clouds.append((f"{shape}-{a.points}", path))
    for path in [x for x in a.clouds.split(",") if x]:
        if not os.path.isfile(path):
            sys.exit(f"compare_revisions: no cloud {path}")
        clouds.append((os.path.splitext(os.path.basename(path))[0], os.path.abspath(path)))
    if not clouds:
        sys.exit("compare_revisions: no cloud (--shapes and --clouds are both empty)")
    filters = a.filters.split(",")
    extra = {"g2s": [], "spherepack": ["--threads", "1"]}

    times = {}  # (filter, cloud, revision) -> [seconds]
    faces = {}
    started = time.time()
    for r in range(a.rounds):
        for f in filters:
            for name, path in clouds:
                order = (0, 1) if r % 2 == 0 else (1, 0)
                for k in order:
                    s, n = engine_seconds(os.path.join(builds[k], RUNNERS[f]), path, extra[f])
                    times.setdefault((f, name, k), []).append(s)
                    faces[(f, name, k)] = n
        print(f"compare_revisions: round {r + 1}/{a.rounds} ({time.time() - started:.0f} s)", flush=True)

    command = "scripts/compare_revisions.sh " + " ".join(sys.argv[1:])
    lines = [f"Before: {shas[0][:12]} ({a.before}), after: {shas[1][:12]} ({a.after}); {a.rounds} interleaved "
             f"rounds, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; command: `{command}`.", "",
             "| filter | cloud | faces before / after | median s before / after | fastest s before / after "
             "| rate before / after (faces/s, medians) | rate after / before | paired time ratios after / before: "
             "median (quartiles) |",
             "|---|---|---|---|---|---|---|---|"]
    for f in filters:
        for name, _ in clouds:
            t = [times[(f, name, k)] for k in (0, 1)]
            med = [statistics.median(x) for x in t]
            rate = [faces[(f, name, k)] / med[k] for k in (0, 1)]
            # The two runs of a round are back to back: their ratio cancels the machine's slower drift.
            paired = sorted(t1 / t0 for t0, t1 in zip(t[0], t[1]))
            q = statistics.quantiles(paired, n=4) if len(paired) >= 2 else [paired[0]] * 3
            lines.append(f"| {f} | {name} | {faces[(f, name, 0)]:,} / {faces[(f, name, 1)]:,} | {med[0]:.4f} / {med[1]:.4f} "
                         f"| {min(t[0]):.4f} / {min(t[1]):.4f} | {rate[0]:,.0f} / {rate[1]:,.0f} | {rate[1] / rate[0]:.3f} "
                         f"| {statistics.median(paired):.3f} ({q[0]:.3f}–{q[2]:.3f}) |")
    report = "\n".join(lines) + "\n"
    path = os.path.join(ROOT, "out", "revisions", f"compare-{shas[0][:12]}-{shas[1][:12]}.md")
    with open(path, "w") as fh:
        fh.write(report)
    print(report + f"(written to {os.path.relpath(path, ROOT)})")


if __name__ == "__main__":
    main()
