"""rockslide from Python: run the paper's PEPO case on every engine, compare each with the
exact solution, solve a reference on a recorded ground motion, and write the report.

    pip install ./python          # once, from the repository's root
    python examples/python/quickstart.py [output folder]

CI runs this script (.ci/run) after installing the package in a fresh environment.
"""

import sys
import tempfile
from pathlib import Path

import numpy as np

import rockslide

REPO = Path(__file__).resolve().parents[2]


def main(out: Path) -> None:
    case = rockslide.Case.load(REPO / "cases" / "pepo-mass-accel.toml")
    result = case.run()  # every engine that applies, in parallel, GIL released

    exact = result.responses["reference"]
    print(f"{case.title}")
    print(f"exact slip window: {exact['slip_start']:.5f} s to {exact['slip_end']:.5f} s")
    print(f"{'participant':<28} {'peak x (mm)':>12} {'slip start (s)':>15} {'residual (mm)':>14}")
    for label in result.participants:
        r = result.responses[label]
        print(
            f"{label:<28} {1e3 * r['peak_relative_displacement']:>12.4f}"
            f" {r.get('slip_start', float('nan')):>15.5f} {1e3 * r['residual_sliding']:>14.4f}"
        )
    fe = result.trace("fe/double")  # {"time": array, "rel_disp": array, ...}, SI
    print(f"fe/double: {len(fe['time'])} rows, max |x| = {1e3 * np.max(np.abs(fe['rel_disp'])):.4f} mm")
    print("gate:", "PASS" if result.passed else "FAIL", *result.failures, sep="\n  ")

    # an exact reference on numpy inputs: the same oscillator under a recorded motion
    dt, acc = rockslide.read_record(REPO / "cases/records/Loma_Prieta_1989_HSP-000.AT2")
    acc = acc * (0.3 * 9.80665 / np.max(np.abs(acc)))  # scaled to PGA = 0.3 g
    epo = rockslide.epo_record(dt, acc, mass=1.0e6, stiffness=9.8696e8, mu=0.1)
    print(f"Loma Prieta at 0.3 g, mu = 0.1: residual sliding {1e3 * epo['slide'][-1]:.2f} mm (exact)")

    try:
        frame = result.to_pandas("predictor-corrector/paper")
        print(frame[["rel_disp", "slide"]].describe().loc[["min", "max"]])
    except ImportError:
        print("(pandas not installed: to_pandas skipped)")

    folder = result.write_report(out)
    print(f"report: {Path(folder) / 'report.html'}")


if __name__ == "__main__":
    if len(sys.argv) > 1:
        main(Path(sys.argv[1]))
    else:
        with tempfile.TemporaryDirectory() as tmp:
            main(Path(tmp))
