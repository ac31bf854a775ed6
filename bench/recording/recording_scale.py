#!/usr/bin/env python3
"""Recording at scale against a reference build, side by side (issue 25).

    bench/recording/recording_scale.py BUILD REFERENCE_BUILD [--runs 50,500,5000]
                                       [--repeats 3] [--stock-repeats 5] [--tmp DIR]

Runs both builds' `rollsense`, interleaved (new, reference, reference, new, ...),
in this one process, each on the stock script scripts/paper_experiment.lua of
its own source tree (from its CMakeCache.txt: an older build may lack a call
today's script makes) with --seed 11, and prints for each:

  record R   the recording alone (--set runs=R --set analyse=false: 27 x R
             trials): wall time, trials/s, bytes the process wrote (write()
             calls, /proc/self/io wchar of the reaped child; write_bytes, what
             reached the block layer, where the kernel counts it) and the final
             dataset's size, and their ratio;
  features   `rollsense features DS` on the 1,350-trial dataset (from disk,
             parallel);
  stock run  the whole stock run (1,350 trials, record + features + the
             bagged-trees cross-validation + final fit + report);
  record+features  the recording plus the features of its trials: the new
             build takes them from memory while recording (so its record run
             pays for them), the reference reads the files back
             (record + `rollsense features`).

Each figure is the median of the repeats; ratios are reference / new (> 1:
the new build is faster). Both builds' datasets are compared byte for byte
(trials/, manifest.csv, dataset-info.csv; and features.csv for the stock run):
a reference from before a deliberate change of the recorded data (e.g. the
simulation's calibration) says DIFFER, and then times similar, not identical,
work. The CPU seconds (user + system of the child) are printed beside the wall
time: on a shared machine they vary less. From them, a "ceiling" line: the
new build's CPU spread perfectly over this machine's cores is the least wall
time it can take, so ref wall / (new CPU / cores) is the largest ratio that
build can reach here without doing less work (like every wall figure here,
meaningful on an idle machine only). Every dataset gets a fresh folder and
all are deleted at the end (ext4 scans past recently deleted inodes when it
allocates new ones, which would charge a run for deleting the one before): the
135k size (--runs 5000) takes minutes and ~1.3 GB of disk per build.
"""
import argparse
import filecmp
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "paper_experiment.lua")


def stock_script(build):
    """The stock script of the source tree `build` was configured from (this tree's if unknown)."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as cache:
            for line in cache:
                if line.startswith("CMAKE_HOME_DIRECTORY:INTERNAL="):
                    script = os.path.join(line.split("=", 1)[1].strip(), "scripts", "paper_experiment.lua")
                    return script if os.path.exists(script) else SCRIPT
    except OSError:
        pass
    return SCRIPT
TRIALS_PER_RUN = 27  # 9 objects x 3 speeds


def proc_io():
    """This process's I/O counters, its reaped children's included."""
    out = {}
    with open("/proc/self/io") as f:
        for line in f:
            key, value = line.split(":")
            out[key.strip()] = int(value)
    return out


CPU = {}  # command → CPU seconds (user + system) of its last run


def run(cmd):
    """Runs cmd; returns (wall seconds, bytes written via write(), bytes to the block layer)."""
    before = proc_io()
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = proc_io()
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU[cmd[0]] = used.ru_utime - usage.ru_utime + used.ru_stime - usage.ru_stime
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr}")
    return wall, after["wchar"] - before["wchar"], after["write_bytes"] - before["write_bytes"]


def folder_bytes(path):
    total = 0
    for base, _, files in os.walk(path):
        for name in files:
            total += os.path.getsize(os.path.join(base, name))
    return total


def ceiling(label, new_cpu, ref_wall):
    cores = os.cpu_count() or 1
    best = new_cpu / cores
    print(f"ceiling {label}: new {new_cpu:.2f} s CPU over {cores} cores = at least {best:.2f} s wall, "
          f"so ref/new at most {ref_wall / best:.2f}x")


def same_dataset(a, b, files):
    for name in files:
        if not filecmp.cmp(os.path.join(a, name), os.path.join(b, name), shallow=False):
            return f"{name} differs"
    cmp = filecmp.dircmp(os.path.join(a, "trials"), os.path.join(b, "trials"))
    if cmp.left_only or cmp.right_only:
        return "trials/ lists differ"
    _, mismatch, errors = filecmp.cmpfiles(os.path.join(a, "trials"), os.path.join(b, "trials"), cmp.common,
                                           shallow=False)
    return f"trials/{(mismatch + errors)[0]} differs" if mismatch or errors else None


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build")
    p.add_argument("reference")
    p.add_argument("--runs", default="50,500,5000", help="repetitions per object and speed (27 trials each)")
    p.add_argument("--repeats", type=int, default=3, help="repeats of each recording size (135k: once)")
    p.add_argument("--stock-repeats", type=int, default=5, help="0: no stock run")
    p.add_argument("--tmp", default=None, help="folder for the datasets (default: the system's temporary folder)")
    a = p.parse_args()
    builds = {"new": os.path.join(a.build, "bin", "rollsense"), "ref": os.path.join(a.reference, "bin", "rollsense")}
    for b in builds.values():
        if not os.access(b, os.X_OK):
            sys.exit(f"{b}: no rollsense program there; build it first (cmake --build BUILD --target rollsense)")
    work = tempfile.mkdtemp(prefix="rollsense-recording-", dir=a.tmp)
    base = {b: [stock_script(d), "--seed", "11", "-q", "--no-progress"] for b, d in (("new", a.build), ("ref", a.reference))}

    def order(i):  # interleaved, alternating which build goes first
        return ["new", "ref"] if i % 2 == 0 else ["ref", "new"]

    try:
        record_1k, record_cpu = {}, {}
        for runs in [int(r) for r in a.runs.split(",")]:
            trials = TRIALS_PER_RUN * runs
            repeats = 1 if trials > 20000 else a.repeats
            t = {"new": [], "ref": []}
            cpu = {"new": [], "ref": []}
            written = {}
            for i in range(repeats):
                for b in order(i):
                    # A fresh folder each time, deleted only at the end: ext4 scans past
                    # recently deleted inodes when it allocates, which would charge
                    # one run for the deletion of the one before it.
                    out = os.path.join(work, f"{b}-{runs}-{i}")
                    wall, wchar, wbytes = run([builds[b], "run", *base[b], "--set", f"runs={runs}", "--set",
                                               "analyse=false", "--out", out])
                    t[b].append(wall)
                    cpu[b].append(CPU[builds[b]])
                    written[b] = (wchar, wbytes, folder_bytes(out))
            why = same_dataset(os.path.join(work, f"new-{runs}-0"), os.path.join(work, f"ref-{runs}-0"),
                               ["manifest.csv", "dataset-info.csv"])
            for b in ("new", "ref"):
                wall = statistics.median(t[b])
                wchar, wbytes, size = written[b]
                block = f", {wbytes / size:.2f}x to the block layer" if wbytes else ""
                print(f"record {trials:>6} trials  {b}: {wall:7.2f} s ({statistics.median(cpu[b]):6.2f} s CPU)  "
                      f"{trials / wall:7.0f} trials/s  wrote "
                      f"{wchar / 1e6:8.1f} MB for a {size / 1e6:7.1f} MB dataset = {wchar / size:5.2f}x{block}")
            print(f"record {trials:>6} trials  ref/new time {statistics.median(t['ref']) / statistics.median(t['new']):.2f}x; "
                  f"datasets {'byte-identical' if why is None else 'DIFFER: ' + why}")
            record_1k.setdefault(runs, {b: statistics.median(t[b]) for b in t})
            record_cpu.setdefault(runs, statistics.median(cpu["new"]))
        sizes = sorted(record_1k)
        for small, big in zip(sizes, sizes[1:]):
            for b in ("new", "ref"):
                print(f"scaling {b}: {TRIALS_PER_RUN * big} trials take {record_1k[big][b] / record_1k[small][b]:.1f}x "
                      f"the time of {TRIALS_PER_RUN * small} ({big / small:.0f}x the trials)")

        if 50 in record_1k:  # the features stage, on the 1,350-trial dataset
            t = {"new": [], "ref": []}
            for i in range(a.repeats):
                for b in order(i):
                    ds = os.path.join(work, f"{b}-50-0")
                    t[b].append(run([builds[b], "features", ds, "-o", os.path.join(work, f"{b}-features.csv")])[0])
            f = {b: statistics.median(t[b]) for b in t}
            print(f"features 1350 trials (from disk): new {f['new']:.3f} s, ref {f['ref']:.3f} s, ref/new {f['ref'] / f['new']:.2f}x")
            rf_new, rf_ref = record_1k[50]["new"], record_1k[50]["ref"] + f["ref"]
            print(f"record+features 1350 trials: new {rf_new:.2f} s (features from memory), ref {rf_ref:.2f} s "
                  f"(record + features from disk), ref/new {rf_ref / rf_new:.2f}x")
            ceiling("record+features", record_cpu[50], rf_ref)

        if a.stock_repeats == 0:
            return
        t = {"new": [], "ref": []}
        cpu = {"new": [], "ref": []}
        for i in range(a.stock_repeats):
            for b in order(i):
                out = os.path.join(work, f"{b}-stock-{i}")
                t[b].append(run([builds[b], "run", *base[b], "--out", out])[0])
                cpu[b].append(CPU[builds[b]])
        why = same_dataset(os.path.join(work, "new-stock-0"), os.path.join(work, "ref-stock-0"),
                           ["manifest.csv", "dataset-info.csv", "features.csv", "model.rsm"])
        s = {b: statistics.median(t[b]) for b in t}
        print(f"stock run (1350 trials, record + features + 10x5-fold CV + final fit + report): new {s['new']:.2f} s, "
              f"ref {s['ref']:.2f} s, ref/new {s['ref'] / s['new']:.2f}x; outputs "
              f"{'byte-identical' if why is None else 'DIFFER: ' + why}")
        print(f"stock run CPU: new {statistics.median(cpu['new']):.2f} s, ref {statistics.median(cpu['ref']):.2f} s")
        ceiling("stock run", statistics.median(cpu["new"]), s["ref"])
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
