"""Cost of a case run from Python against the same run from the command line.

Both load the case, run every engine and the reference, and write the same report folder
(`rockslide run <case> --out <dir>` against `Case.load(case).run().write_report(dir)`);
the command line's time includes starting its process, and it also writes the suite's
pages for its one case (summary.md/.html/.csv beside the case folder). Before timing, the
two case folders are compared: the same files, and the same result.json but its wall
times. Median of N runs each, interleaved so that both see the same machine load; wall
time and CPU time (this process's for Python, the child's for the command line: CPU time
moves far less with the load of a shared machine).

    pip install ./python && cargo build --release
    python benches/python_vs_cli.py [case] [N]
"""

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import rockslide

REPO = Path(__file__).resolve().parents[1]
CLI = REPO / "target" / "release" / "rockslide"


def python_run(case: str, out: Path) -> None:
    rockslide.Case.load(case).run().write_report(out)


def cli_run(case: str, out: Path) -> None:
    subprocess.run([CLI, "run", case, "--quiet", "--out", out], cwd=REPO, check=True)


def children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(f, cpu) -> tuple:
    wall, before = time.perf_counter(), cpu()
    f()
    return time.perf_counter() - wall, cpu() - before


def without_wall_times(value):
    """result.json without the fields that are measured times."""
    if isinstance(value, dict):
        return {k: without_wall_times(v) for k, v in value.items() if "wall" not in k}
    if isinstance(value, list):
        return [without_wall_times(v) for v in value]
    return value


def same_outputs(case: str, tmp: Path) -> list:
    """Run both once; the case folder's file names, which must be the same."""
    python_run(case, tmp / "py")
    cli_run(case, tmp / "cli")
    name = Path(case).stem
    files = {side: sorted(p.name for p in (tmp / side / name).iterdir()) for side in ("py", "cli")}
    assert files["py"] == files["cli"], files
    results = [json.loads((tmp / side / name / "result.json").read_text()) for side in ("py", "cli")]
    assert without_wall_times(results[0]) == without_wall_times(results[1]), "result.json differs"
    return files["py"]


def main(case: str, n: int) -> None:
    os.chdir(REPO)  # the case by the same relative path on both sides, as result.json names it
    py, cli = [], []
    with tempfile.TemporaryDirectory() as tmp:
        files = same_outputs(case, Path(tmp) / "check")
        for i in range(n):
            out = Path(tmp) / str(i)
            py.append(timed(lambda: python_run(case, out / "py"), time.process_time))
            cli.append(timed(lambda: cli_run(case, out / "cli"), children_cpu))
    print(f"{case}: both write the same {len(files)} files of the case folder and the same result.json")
    for what, k in (("wall", 0), ("CPU", 1)):
        p = statistics.median(t[k] for t in py)
        c = statistics.median(t[k] for t in cli)
        print(f"  {what}: Python {p:.3f} s, command line {c:.3f} s (median of {n}); "
              f"Python / CLI = {p / c:.3f} ({100 * (p / c - 1):+.1f} %)")
    print("  Python wall:", " ".join(f"{t[0]:.3f}" for t in py))
    print("  CLI wall:   ", " ".join(f"{t[0]:.3f}" for t in cli))
    print("  Python CPU: ", " ".join(f"{t[1]:.3f}" for t in py))
    print("  CLI CPU:    ", " ".join(f"{t[1]:.3f}" for t in cli))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "cases/pepo-mass-accel.toml",
         int(sys.argv[2]) if len(sys.argv) > 2 else 5)
