#!/usr/bin/env python3
"""scripts/check-issue7.py's verdicts on made-up figures (--from): a target whose runs are
all within its bound holds in "every run", one whose median run is within but not all runs
"median only", one whose median is over "not met"; exit status 0 only when every run of
every target was within. Usage: check_issue7_verdicts.py REPO_DIR"""
import json
import os
import subprocess
import sys
import tempfile

script = os.path.join(sys.argv[1], "scripts", "check-issue7.py")


def run_of(p50, p99, field):
    return {"sssd_p50_us": p50, "sssd_p99_us": p99, "bidirectional_sssd_p50_us": 40 * p50,
            "bidirectional_sssd_p99_us": 40 * p99, "msad_threads_p50_ms": field, "msad_p50_ms": 2 * field,
            "fixed_work_p99_us": 15.0, "clock": "12:00"}


def figures(runs, x16_p50):
    return {"igea_bake": {"vertices": 134345, "bytes_per_vertex": 143.3, "wall_s": 66.4},
            "igea_error": {"mean_rel_error": 0.000157, "max_rel_error": 0.004656},
            "igea_runs": runs,
            "x16_bake": {"vertices": 2149490, "wall_s": 729.3, "peak_gb": 13.31, "blob_bytes": 518585923,
                         "bytes_per_vertex": 241.3},
            "x16_runs": [run_of(p, 150.0, 65.0) for p in x16_p50]}


def verdicts(data):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "check-issue7.json")
        json.dump(data, open(path, "w"))
        done = subprocess.run([sys.executable, script, "--from", path], capture_output=True, text=True)
    rows = {}
    for line in done.stdout.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if line.startswith("| ") and len(cells) == 6 and cells[0] != "#7 target":
            rows[cells[0]] = (cells[3], cells[5])
    return done.returncode, rows, done.stdout


failures = []


def expect(what, got, wanted):
    if got != wanted:
        failures.append(f"{what}: {got!r}, expected {wanted!r}")


# Every run within every bound: exit 0.
code, rows, out = verdicts(figures([run_of(15.0, 50.0, 2.3) for _ in range(5)], [30.0, 35.0]))
expect("all within: exit status", code, 0)
expect("all within: rows", len(rows), 10)
for target, (within, verdict) in rows.items():
    expect(f"all within: {target}", verdict, "every run")
expect("all within: p50 runs", rows.get("igea p2p p50", ("",))[0], "5 of 5")

# p99 over its bound in one run of five (median within), one-to-all in three (median over),
# x16's p50 exactly at its bound (within).
runs = [run_of(15.0, 50.0, 2.3), run_of(15.0, 130.0, 3.2), run_of(15.0, 50.0, 3.1), run_of(15.0, 50.0, 3.4),
        run_of(15.0, 50.0, 2.5)]
code, rows, out = verdicts(figures(runs, [50.0]))
expect("some over: exit status", code, 1)
expect("p99 one run over", rows.get("igea p2p p99"), ("4 of 5", "median only"))
expect("one-to-all median over", rows.get("igea one-to-all, 2 threads"), ("2 of 5", "not met"))
expect("x16 p50 at the bound", rows.get("x16 p2p p50 (a stream of 20,000)"), ("1 of 1", "every run"))
expect("p50 still holds", rows.get("igea p2p p50"), ("5 of 5", "every run"))
if "not within in every run: igea p2p p99 (4 of 5 runs within)" not in out:
    failures.append("the closing line does not name the p99 target and its count:\n" + out)

# The host's processor and speed, when the figures have them (older saved figures do not).
runs = [dict(run_of(15.0, 50.0, 2.3), host_multiply_add_ns=1.5 + 0.1 * i, host_load_ns=180.0 + i) for i in range(3)]
data = figures(runs, [30.0])
data["host"] = "Some CPU (family 1, model 2), 2 logical CPUs"
code, rows, out = verdicts(data)
if "host: Some CPU (family 1, model 2), 2 logical CPUs; a dependent multiply-add 1.500-1.700 (median 1.600) ns, " \
        "a dependent load over 64 MB 180.0-182.0 (median 181.0) ns" not in out:
    failures.append("the host line does not give the processor and the speed's ranges:\n" + out)
if any(line.startswith("host:") for line in verdicts(figures([run_of(15.0, 50.0, 2.3)], [30.0]))[2].splitlines()):
    failures.append("a host line for figures that recorded no host")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("check-issue7 verdicts: all as expected")
