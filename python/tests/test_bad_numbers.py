"""Numbers no analysis can use, passed from a script, raise an exception with the reason:
never a crash of the interpreter (an aborted allocation, a Rust panic, a stack overflow).
Each input here crashed the interpreter before the package checked its numbers."""

import numpy as np
import pytest

import rockslide


@pytest.mark.parametrize(
    "call, reason",
    [
        # 10^15 sample instants asked for: 8 PB of times
        (lambda: rockslide.housner(0.2, 1.0, 5.0, 10.0, 1.0, samples=10**15), "1.000e15 sample instants"),
        # 1e15 s of rocking kept every 2e-5 s: memory grew until the system killed Python
        (lambda: rockslide.housner(0.2, 1.0, 5.0, 10.0, 1e15, samples=10), "5.000e19 samples, more than the limit"),
        # a sample interval of 1e-300 s over 1 s: 1e300 instants
        (lambda: rockslide.epo_record(1e-300, np.zeros(3), 1.0, 1e6, 0.2, duration=1.0), "below the smallest a record may have"),
        (lambda: rockslide.epo_record(0.01, np.zeros(0), 1.0, 1e6, 0.2), "the record has no samples"),
        (lambda: rockslide.epo_record(0.01, np.zeros(3), 1.0, 1e6, 0.2, times=np.array([0.0, np.nan])), r"time 1 \(NaN\) is not finite"),
        (lambda: rockslide.plan_block(1e-300, np.zeros(3), np.zeros(3), 0.2, duration=1.0), "integration steps|sample instants"),
        (lambda: rockslide.plan_block(0.01, np.zeros(3), np.zeros(3), 0.2, duration=1e12), "integration steps"),
        (lambda: rockslide.plan_oscillator(0.01, np.ones(3), np.ones(3), 1.0, 1e6, 0.2, step=1e-300), "integration steps"),
        (lambda: rockslide.plan_oscillator(0.01, np.zeros(3), np.zeros(3), 1.0, np.nan, 0.2), "the stiffness NaN"),
    ],
)
def test_numbers_beyond_what_memory_holds_raise_with_the_reason(call, reason):
    with pytest.raises(ValueError, match=reason):
        call()


def test_a_case_dict_nested_beyond_any_case_file_raises_instead_of_overflowing_the_stack():
    deep = {}
    inner = deep
    for _ in range(200_000):
        inner["a"] = {}
        inner = inner["a"]
    with pytest.raises(ValueError, match="nested more than 32 levels deep"):
        rockslide.case_from_dict(deep)
    nested_list = []
    inner = nested_list
    for _ in range(200_000):
        inner.append([])
        inner = inner[0]
    with pytest.raises(ValueError, match="nested more than 32 levels deep"):
        rockslide.case_from_dict({"a": nested_list})


def test_an_integer_beyond_64_bits_in_a_case_dict_names_its_place():
    with pytest.raises(ValueError, match=r"`run.dt`: the integer 10{30} does not fit"):
        rockslide.case_from_dict({"run": {"dt": 10**30}})
