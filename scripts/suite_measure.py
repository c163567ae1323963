"""Runs vbsim commands for the workload suite under /usr/bin/time -v and reads
their figures: every run's wall time and peak resident set, `vbsim score`'s
rows (every method's errors with 95% intervals; cycles, energy and area of the
preset) and `vbsim bench`'s speeds against Embree (docs/suite.md)."""
import json
import os
import re
import subprocess
import time

TIME = "/usr/bin/time"


class RunError(Exception):
    pass


def run(cmd, log_path):
    """Runs cmd; returns {"wall_s", "peak_rss_mb", "peak_rss_kb"} (the peak as /usr/bin/time
    gives it; None without that program). Raises RunError with the
    log's tail on failure. stdout and stderr go to log_path."""
    timed = [TIME, "-v"] + cmd if os.path.exists(TIME) else cmd
    start = time.monotonic()
    with open(log_path, "w") as log:
        log.write(" ".join(cmd) + "\n")
        log.flush()
        proc = subprocess.run(timed, stdout=log, stderr=subprocess.STDOUT)
    wall = time.monotonic() - start
    with open(log_path) as f:
        text = f.read()
    if proc.returncode != 0:
        raise RunError(f"exit {proc.returncode}: {' '.join(cmd)}\n{text[-2000:]}")
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
    peak_kb = int(m.group(1)) if m else None
    return {"wall_s": round(wall, 3), "peak_rss_mb": round(peak_kb / 1024, 1) if m else None, "peak_rss_kb": peak_kb}


def score(vbsim, trace, preset, methods, testers, out_json, log_path):
    cmd = [vbsim, "score", trace, "--testers", testers, "--cycle-testers", "three-half-plane",
           "--mode", "cycle", "--preset", preset, "--out", out_json, "-q"]
    if methods:
        cmd += ["--methods", methods]
    info = run(cmd, log_path)
    with open(out_json) as f:
        table = json.load(f)
    return info, table


def score_rows(table, kind):
    """One dict per (method, tester): the rays of `kind` (secondary, or primary
    for camera rays) and their error rate per million with its interval, and
    the cycle-level figures of the whole trace where the run has them."""
    cycles = {}
    for r in table["rows"]:
        if r["kind"] == "all" and r.get("cycle"):
            cycles[(r["method"], r["tester"])] = r["cycle"]
    out = []
    for r in table["rows"]:
        if r["kind"] != kind:
            continue
        key = (r["method"], r["tester"])
        per = r["errors"]["per_million"]
        c = r["counts"]
        row = {"method": r["method"], "tester": r["tester"], "kind": kind,
               "rays": sum(c[v] for v in ("correct", "self_hit", "false_hit", "missed")),
               "errors": r["errors"]["count"], "self_hit": c["self_hit"], "false_hit": c["false_hit"],
               "missed": c["missed"], "rate": per["rate"] / 1e6, "lower": per["lower"] / 1e6,
               "upper": per["upper"] / 1e6}
        cyc = cycles.get(key)
        if cyc:
            row.update({"cycles_per_ray": cyc["cycles_per_ray"], "energy_per_ray_pj": cyc["energy_per_ray_pj"],
                        "chip_mm2": cyc["chip_mm2"], "rays_in_cycle_run": cyc["rays"]})
        out.append(row)
    return out


def bench_json(vbsim, rays_args, mode, method, repeats, out_json, log_path, preset="small"):
    """One `vbsim bench` run of the rays `rays_args` names (["--trace", FILE], or ["--scene",
    FILE, "--rays", N] for random rays): one thread; the cycle level on `preset`. Returns
    run()'s figures and the bench's JSON."""
    cmd = [vbsim, "bench"] + rays_args + ["--mode", mode, "-m", method, "--repeats", str(repeats),
                                          "--json", out_json, "-q"]
    if mode == "functional":
        cmd += ["--threads", "1"]
    else:
        cmd += ["--preset", preset]
    info = run(cmd, log_path)
    with open(out_json) as f:
        return info, json.load(f)


def bench(vbsim, trace, mode, method, repeats, out_json, log_path, preset="small"):
    info, b = bench_json(vbsim, ["--trace", trace], mode, method, repeats, out_json, log_path, preset)
    info.update({"mode": mode, "method": method, "rays": b.get("rays"),
                 "vbsim_rays_per_s": b.get("vbsim_rays_per_s"), "embree_rays_per_s": b.get("embree_rays_per_s"),
                 "ratio": b.get("ratio")})
    return info
