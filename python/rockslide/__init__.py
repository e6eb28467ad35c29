"""rockslide from Python: cross-code verification of seismic sliding and rocking.

A case (a TOML file, TOML text or a dict) runs on every engine that applies to it — the
paper's predictor-corrector, the penalty FE model, the rapier rigid-body model — and its
exact reference; the result gives each participant's time history as numpy arrays (SI),
the response quantities, the tolerance checks and the verdict, and writes the report::

    import rockslide
    case = rockslide.Case.load("cases/pepo-mass-accel.toml")
    result = case.run()                      # or rockslide.run(case, engines=["fe"])
    fe = result.trace("fe/single")           # {"time": array, "rel_disp": array, ...}
    result.responses["reference"]["slip_start"]   # 0.06287... s, exact
    result.passed, result.failures
    result.write_report("reports")

The exact references take numpy inputs (:func:`epo_record`, :func:`rigid_block`,
:func:`housner`, :func:`plan_block`, :func:`plan_oscillator`, or a case's own with
:func:`reference`); :func:`read_record` reads a PEER AT2 or CSV record into
``(dt, samples)``; :func:`run_study` runs a study grid across cores. A case, record or
argument that cannot be used raises :class:`InputError`, which carries the file, line,
column, field and reason of the problem.
"""

from ._rockslide import (
    ENGINES,
    Case,
    InputError,
    Result,
    __version__,
    case_from_dict,
    case_from_toml,
    epo_record,
    housner,
    load_case,
    plan_block,
    plan_oscillator,
    quantities,
    read_record,
    reference,
    rigid_block,
    run,
    run_study,
)

__all__ = [
    "ENGINES",
    "Case",
    "InputError",
    "Result",
    "__version__",
    "case_from_dict",
    "case_from_toml",
    "epo_record",
    "housner",
    "load_case",
    "plan_block",
    "plan_oscillator",
    "quantities",
    "read_record",
    "reference",
    "rigid_block",
    "run",
    "run_study",
]
