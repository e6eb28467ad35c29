"""The GIL is released while rockslide works: another Python thread goes on during a study
and during a case run.

A ticker thread notes the time about every millisecond (it sleeps between ticks, so it
takes no core from the work). While a call holds the GIL the ticker cannot take it back
after its sleep, so the largest gap between its ticks spans the whole call; while the call
has released it, the ticks go on. The measure is shown to tell the two apart on a call
that holds the GIL throughout (a C sort of a large list).
"""

import random
import threading
import time

import rockslide

# the call must last this long for its gaps to say anything, s
MIN_CALL = 0.3
# the largest gap between ticks allowed, as a fraction of the call
MAX_GAP_FRACTION = 0.25
# ticks at least, during the call
MIN_TICKS = 20


class Ticker:
    """A thread that appends `time.perf_counter()` about every millisecond."""

    def __init__(self):
        self.times = []
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        while not self.stop.is_set():
            self.times.append(time.perf_counter())
            time.sleep(0.001)

    def __enter__(self):
        self.thread.start()
        while not self.times:
            time.sleep(0.001)
        return self

    def __exit__(self, *exc):
        self.stop.set()
        self.thread.join()


def ticks_during(call):
    """Run `call` beside a ticker: (its value, its duration, ticks during it, the largest
    gap between ticks over it, the call's start and end counting as ticks)."""
    with Ticker() as ticker:
        start = time.perf_counter()
        value = call()
        end = time.perf_counter()
    inside = [t for t in ticker.times if start < t < end]
    marks = [start] + inside + [end]
    gap = max(b - a for a, b in zip(marks, marks[1:]))
    return value, end - start, len(inside), gap


def assert_other_threads_go_on(call, what):
    value, duration, ticks, gap = ticks_during(call)
    assert duration >= MIN_CALL, f"{what} took {duration:.3f} s: too short to tell"
    assert ticks >= MIN_TICKS and gap <= MAX_GAP_FRACTION * duration, (
        f"{what}: {ticks} ticks in {duration:.3f} s, largest gap {gap:.3f} s"
    )
    print(f"{what}: {ticks} ticks in {duration:.3f} s, largest gap {gap * 1000:.1f} ms")
    return value


def test_the_measure_sees_a_call_that_holds_the_gil():
    numbers = [random.random() for _ in range(2_000_000)]
    _, duration, ticks, gap = ticks_during(lambda: sorted(numbers))
    assert gap > 0.9 * duration, f"{ticks} ticks in {duration:.3f} s, largest gap {gap:.3f} s"


def test_another_thread_goes_on_during_a_study(repo, tmp_path):
    # two points of the shipped record study's base case (every engine it lists)
    (tmp_path / "grid.toml").write_text(
        f"""title = "GIL check"
base = "{repo / 'cases/records/pepo-loma-prieta.toml'}"
records = ["{repo / 'cases/records/Loma_Prieta_1989_HSP-000.AT2'}"]
pga_g = [0.1, 0.2]
polarity = [1]
tail = 2.0
"""
    )
    counts = assert_other_threads_go_on(
        lambda: rockslide.run_study(tmp_path / "grid.toml", tmp_path / "out"), "study"
    )
    assert (counts["points"], counts["executed"]) == (2, 2)


def test_another_thread_goes_on_during_a_case_run(repo):
    # the RPEPO under a record: about 2 s on an idle machine, long enough to tell
    case = rockslide.Case.load(repo / "cases/records/rpepo-loma-prieta.toml")
    result = assert_other_threads_go_on(case.run, "case run")
    assert "fe/single" in result.participants
