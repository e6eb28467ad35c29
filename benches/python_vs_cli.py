"""Cost of a case run from Python against the same run from the command line.

Both load the case, run every engine and the reference, and write the same report folder
(`rockslide run <case> --out <dir>` against `Case.load(case).run().write_report(dir)`);
the command line's time includes starting its process. Median of N runs each,
interleaved so that both see the same machine load.

    pip install ./python && cargo build --release
    python benches/python_vs_cli.py [case] [N]
"""

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import rockslide

REPO = Path(__file__).resolve().parents[1]
CLI = REPO / "target" / "release" / "rockslide"


def timed(f) -> float:
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def main(case: str, n: int) -> None:
    py_times, cli_times = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(n):
            out = Path(tmp) / str(i)
            py_times.append(timed(lambda: rockslide.Case.load(REPO / case).run().write_report(out / "py")))
            cli_times.append(
                timed(
                    lambda: subprocess.run(
                        [CLI, "run", case, "--quiet", "--out", out / "cli"], cwd=REPO, check=True
                    )
                )
            )
    py, cli = statistics.median(py_times), statistics.median(cli_times)
    print(f"{case}: Python {py:.3f} s, command line {cli:.3f} s (median of {n}); "
          f"Python / CLI = {py / cli:.3f} ({100 * (py / cli - 1):+.1f} %)")
    print("Python:", " ".join(f"{t:.3f}" for t in py_times))
    print("CLI:   ", " ".join(f"{t:.3f}" for t in cli_times))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "cases/pepo-mass-accel.toml",
         int(sys.argv[2]) if len(sys.argv) > 2 else 5)
