"""The Python package against independent values: the paper's PEPO slip window (exact
solution), the command line's result.json digit for digit, closed forms of the references
on numpy inputs, a record file read against its own text, and located input errors."""

import json
import math
import subprocess

import numpy as np
import pytest

import rockslide

PEPO = "cases/pepo-mass-accel.toml"


@pytest.fixture(scope="module")
def pepo(repo, monkeypatch_module):
    monkeypatch_module.chdir(repo)
    return rockslide.Case.load(PEPO)


@pytest.fixture(scope="module")
def monkeypatch_module():
    mp = pytest.MonkeyPatch()
    yield mp
    mp.undo()


@pytest.fixture(scope="module")
def pepo_result(pepo):
    return pepo.run()


def test_pepo_exact_slip_window_is_the_papers(pepo, pepo_result):
    # the paper's PEPO (Fig. 3): exact slip start 0.06287 s and end 0.30038 s
    exact = rockslide.reference(pepo)["exact"]
    assert exact["slip_start"] == pytest.approx(0.06287, abs=5e-6)
    assert exact["slip_end"] == pytest.approx(0.30038, abs=5e-6)
    reference = pepo_result.responses["reference"]
    assert reference["slip_start"] == exact["slip_start"]
    assert reference["slip_end"] == exact["slip_end"]


def test_every_participant_has_time_and_quantities_as_arrays(pepo_result):
    participants = pepo_result.participants
    assert participants[-1] == "reference"
    assert {"predictor-corrector/paper", "fe/single", "fe/double"} <= set(participants)
    for label in participants:
        trace = pepo_result.trace(label)
        assert isinstance(trace["time"], np.ndarray) and trace["time"].dtype == np.float64
        assert np.all(np.diff(trace["time"]) > 0)
        assert len(trace["rel_disp"]) == len(trace["time"])
    # the paper's spreadsheet step: 0.01 s over 1 s is 101 rows
    assert len(pepo_result.trace("predictor-corrector/paper")["time"]) == 101
    # the friction limit Ru = mu * M * g = 0.5 * 1e6 * 1.0 N caps the resistance
    fe = pepo_result.trace("fe/single")
    assert np.max(np.abs(fe["resistance"])) == pytest.approx(5e5, rel=1e-9)
    with pytest.raises(KeyError, match="participants"):
        pepo_result.trace("no/such")


def test_the_record_equals_the_command_lines_result_json_to_the_last_digit(
    repo, cli, pepo_result, tmp_path
):
    subprocess.run(
        [str(cli), "run", PEPO, "--out", str(tmp_path), "--quiet"],
        cwd=repo,
        check=True,
        capture_output=True,
    )
    from_cli = (tmp_path / "pepo-mass-accel" / "result.json").read_text().splitlines()
    from_python = pepo_result.to_json().splitlines()
    # the wall time is the only value that differs from run to run
    keep = lambda lines: [l for l in lines if '"wall_seconds"' not in l]
    assert len(from_cli) == len(from_python) > 100
    assert keep(from_cli) == keep(from_python)
    assert pepo_result.passed == json.loads("\n".join(from_cli))["gate_passed"]


def test_a_malformed_case_raises_with_its_location():
    text = rockslide_case_text(mu="-0.5")
    line = next(i for i, l in enumerate(text.splitlines(), 1) if l.startswith("mu ="))
    with pytest.raises(rockslide.InputError) as caught:
        rockslide.Case.from_toml(text, path="bad.toml")
    e = caught.value
    assert (e.file, e.line, e.field) == ("bad.toml", line, "model.contact.mu")
    assert e.column == text.splitlines()[line - 1].index("-0.5") + 1  # at the value
    assert "mu" in str(e) and e.reason
    assert str(e).startswith(f"bad.toml:{line}:")
    assert e.errors[0]["line"] == line
    with pytest.raises(rockslide.InputError) as missing:
        rockslide.Case.load("no-such-case.toml")
    assert missing.value.file == "no-such-case.toml"


def rockslide_case_text(mu="0.5"):
    return f"""name = "tiny-pepo"
[model]
kind = "oscillator"
mass = 1.0e6
gravity = 1.0
[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = {mu}
[excitation]
kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 1.0
omega = 15.707963267948966
cycles = 0.5
[run]
duration = 1.0
dt = 0.001
[engines.predictor-corrector]
dt = 0.01
"""


def test_a_case_from_a_dict_is_the_case_from_its_toml():
    tables = {
        "name": "tiny-pepo",
        "model": {
            "kind": "oscillator",
            "mass": 1.0e6,
            "gravity": 1.0,
            "contact": {"kx": 9.8696e8, "kz": 3.94784e9, "mu": 0.5},
        },
        "excitation": {
            "kind": "mass-acceleration",
            "shape": "sine-pulse",
            "amplitude": 1.0,
            "omega": 15.707963267948966,
            "cycles": 0.5,
        },
        "run": {"duration": 1.0, "dt": 0.001},
        "engines": {"predictor-corrector": {"dt": 0.01}},
    }
    from_dict = rockslide.Case.from_dict(tables).run()
    from_text = rockslide.Case.from_toml(rockslide_case_text()).run()
    assert from_dict.participants == ["predictor-corrector/paper", "reference"]
    assert from_dict.responses == from_text.responses
    bad = dict(tables, run={"duration": "long", "dt": 0.001})
    with pytest.raises(rockslide.InputError) as caught:
        rockslide.Case.from_dict(bad)
    assert caught.value.field == "run.duration"


def test_engines_can_be_chosen_and_unknown_ones_are_refused(repo):
    case = rockslide.Case.load(repo / PEPO)
    only = rockslide.run(case, engines=["predictor-corrector"])
    assert only.participants == ["predictor-corrector/paper", "reference"]
    with pytest.raises(ValueError, match="no engine"):
        rockslide.run(case, engines=["abaqus"])


def pulse_then_ramp(a, ky, t1, dt):
    """Newmark's block under a drive a for t1 s, then down to zero linearly over dt
    (records are linear between samples): (slid distance, stop time), closed form."""
    v1, d1 = (a - ky) * t1, (a - ky) * t1**2 / 2
    v2 = v1 + (a / 2 - ky) * dt
    d2 = d1 + v1 * dt + (a - ky) * dt**2 / 2 - a * dt**2 / 6
    return d2 + v2**2 / (2 * ky), t1 + dt + v2 / ky


def test_the_rigid_block_under_a_constant_pulse_is_newmarks_closed_form():
    # the block speeds up at a - ky, then slows at ky until it stops
    dt, a, ky = 0.001, 2.0, 0.5
    acc = np.append(np.full(1001, a), 0.0)
    expected, stop = pulse_then_ramp(a, ky, 1.0, dt)
    out = rockslide.rigid_block(dt, acc, ky, tail=5.0)
    assert abs(out["displacement"][-1]) == pytest.approx(expected, rel=1e-12)
    assert out["peak"] == pytest.approx(expected, rel=1e-12)
    [(start, end, _, distance)] = out["slides"]
    assert start == 0.0 and end == pytest.approx(stop, rel=1e-12)
    assert abs(distance) == pytest.approx(expected, rel=1e-12)


def test_the_oscillator_that_never_slips_is_the_elastic_closed_form():
    # a ground acceleration step a0 on an undamped oscillator that never slips:
    # x(t) = -(a0/w^2)(1 - cos w t)
    m, k, a0, dt = 1.0e3, 4.0e5, 0.3, 0.002
    w = math.sqrt(k / m)
    acc = np.full(2001, a0)
    times = np.linspace(0.0, 3.0, 301)
    out = rockslide.epo_record(dt, acc, m, k, mu=100.0, duration=3.0, times=times)
    expected = -(a0 / w**2) * (1 - np.cos(w * times))
    np.testing.assert_allclose(out["rel_disp"], expected, rtol=0, atol=1e-12 * a0 / w**2 * 1e3)
    assert np.all(out["slide"] == 0.0)


def test_housner_free_rocking_reaches_the_first_impact_when_energy_says():
    # free rocking from tilt t0 < alpha conserves energy until the first impact:
    # thetadot^2 = 2 p^2 (cos(alpha - t0) - cos(alpha - theta)), p^2 = 3 g / (4 R), so the
    # impact comes at T = int_0^t0 dtheta / thetadot (theta = t0 - s^2 removes the
    # singularity at the start)
    b, h, g, tilt = 0.5, 1.5, 9.80665, 0.1
    alpha, radius = math.atan(b / h), math.hypot(b, h)
    p2 = 3 * g / (4 * radius)
    s = np.linspace(0.0, math.sqrt(tilt), 400001)
    theta = tilt - s**2
    speed2 = 2 * p2 * (math.cos(alpha - tilt) - np.cos(alpha - theta))
    integrand = np.empty_like(s)
    integrand[1:] = 2 * s[1:] / np.sqrt(speed2[1:])
    integrand[0] = 2 / math.sqrt(2 * p2 * math.sin(alpha - tilt))  # the limit s -> 0
    impact = float(np.sum((integrand[1:] + integrand[:-1]) / 2 * np.diff(s)))
    times = np.array([0.0, impact])
    out = rockslide.housner(b, h, amplitude=0.0, omega=1.0, duration=2 * impact, initial_tilt=tilt, times=times)
    rotation = np.abs(out["rotation"])
    assert rotation[0] == pytest.approx(tilt, rel=1e-12)
    # |thetadot| at impact is about 0.6 rad/s: 1e-6 rad is 2 microseconds
    assert rotation[1] == pytest.approx(0.0, abs=1e-6)


def test_the_plan_block_driven_along_x_alone_is_the_one_way_block():
    dt, a, mu, g = 0.001, 3.0, 0.1, 9.80665
    acc = np.append(np.full(501, a), 0.0)
    zeros = np.zeros_like(acc)
    expected, _ = pulse_then_ramp(a, mu * g, 0.5, dt)
    plan = rockslide.plan_block(dt, acc, zeros, mu, g, duration=3.0, times=np.array([3.0]))
    assert abs(plan["rel_disp"][0]) == pytest.approx(expected, rel=1e-9)
    assert abs(plan["rel_disp_y"][0]) <= 1e-15  # round-off of the rotation: 9.5e-17 measured


def test_a_record_reads_into_dt_and_samples_as_its_text_says(repo):
    path = repo / "cases/records/Imperial_Valley_1979_BCR-230.csv"
    rows = np.loadtxt(path, delimiter=",", comments="#")
    dt, samples = rockslide.read_record(path, unit="g")
    assert dt == pytest.approx(rows[1, 0] - rows[0, 0], rel=1e-12)
    assert len(samples) == len(rows)
    np.testing.assert_allclose(samples, rows[:, 1] * 9.80665, rtol=1e-15)
    with pytest.raises(rockslide.InputError) as caught:
        rockslide.read_record(path, unit="furlongs")
    assert caught.value.field == "unit"


def test_to_pandas_indexes_by_time(pepo_result):
    pd = pytest.importorskip("pandas")
    frame = pepo_result.to_pandas("fe/single")
    assert isinstance(frame, pd.DataFrame)
    trace = pepo_result.trace("fe/single")
    np.testing.assert_array_equal(frame.index.to_numpy(), trace["time"])
    np.testing.assert_array_equal(frame["rel_disp"].to_numpy(), trace["rel_disp"])


def test_the_report_is_written_with_its_record_and_layout(pepo_result, tmp_path):
    folder = pepo_result.write_report(tmp_path)
    assert (folder / "result.json").read_text() .count('"case"') == 1
    for name in ["report.html", "pepo-mass-accel.mcap", "pepo-mass-accel.layout.json"]:
        assert (folder / name).is_file(), name


def test_a_study_runs_its_grid_once_and_resumes(repo, tmp_path):
    record = repo / "cases/records/Loma_Prieta_1989_HSP-000.AT2"
    (tmp_path / "base.toml").write_text(
        f"""name = "pepo-study-base"
[model]
kind = "oscillator"
mass = 1.0e6
gravity = 1.0
[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = 0.5
[excitation]
kind = "ground-acceleration"
record = "{record}"
scale_to_pga_g = 0.1
[run]
duration = 40.0
dt = 0.005
[engines.predictor-corrector]
variants = ["ground-accel"]
"""
    )
    grid = tmp_path / "grid.toml"
    grid.write_text(
        f"""title = "two PGAs, both polarities"
base = "base.toml"
records = ["{record}"]
pga_g = [0.1, 0.2]
polarity = [1, -1]
tail = 2.0
"""
    )
    first = rockslide.run_study(grid, tmp_path / "out")
    # 1 record x 2 PGAs x 2 polarities
    assert (first["points"], first["executed"], first["skipped"]) == (4, 4, 0)
    assert (tmp_path / "out" / "study.json").is_file()
    again = rockslide.run_study(grid, tmp_path / "out")
    assert (again["executed"], again["skipped"]) == (0, 4)
    assert again["study"] == first["study"]


def azimuth_case_text(azimuth_line):
    """CI.CCC's 90° channel and vertical on a PEPO along one azimuth, 6 s at Δt = 1 ms."""
    return f"""
name = "ccc-azimuths"
[model]
kind = "oscillator"
mass = 1.0e6
gravity = 9.81
[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = 0.3
[excitation]
kind = "ground-acceleration"
[excitation.station]
file = "../records/Ridgecrest_2019_CI.CCC.RAW"
{azimuth_line}
start = 30.0
components = "xz"
[run]
duration = 6.0
dt = 0.001
[engines.predictor-corrector]
[[tolerance]]
quantity = "peak_abs_sliding"
percent = 100
"""


def test_a_set_of_azimuths_comes_back_per_azimuth(repo, pepo_result):
    path = repo / "cases" / "three-component" / "azimuth-test.toml"
    sweep_case = rockslide.Case.from_toml(azimuth_case_text("x_azimuths_deg = [0, 90, 270]"), path=path)
    result = sweep_case.run()
    single = rockslide.Case.from_toml(azimuth_case_text("x_azimuth_deg = 90.0"), path=path).run()
    sweep = result.azimuths
    assert pepo_result.azimuths is None
    assert [p["azimuth_deg"] for p in sweep["points"]] == [0.0, 90.0, 270.0]
    assert sweep["participants"] == ["reference", "predictor-corrector/ground-accel"]
    # at 90° the set's figures are the single case's, to the last digit
    at_90 = {f["participant"]: f for f in sweep["points"][1]["figures"]}
    for participant, responses in single.responses.items():
        assert at_90[participant]["peak_sliding"] == responses["peak_abs_sliding"]
        assert at_90[participant]["residual_sliding"] == responses["residual_sliding"]
    # 270° is 90° in the other polarity: the same peak, the residual negated
    at_270 = {f["participant"]: f for f in sweep["points"][2]["figures"]}
    assert at_270["reference"]["peak_sliding"] == pytest.approx(at_90["reference"]["peak_sliding"], rel=1e-9)
    assert at_270["reference"]["residual_sliding"] == pytest.approx(
        -at_90["reference"]["residual_sliding"], rel=1e-9
    )
    # the maximum is the table's largest, at its azimuth; the reference's governs
    for i, m in enumerate(sweep["maxima"]):
        column = [p["figures"][i]["peak_sliding"] for p in sweep["points"]]
        assert m["peak_sliding"]["value"] == max(column)
        assert m["peak_sliding"]["azimuth_deg"] == sweep["points"][column.index(max(column))]["azimuth_deg"]
    governing = sweep["points"][sweep["governing"]]["azimuth_deg"]
    assert governing == sweep["maxima"][0]["peak_sliding"]["azimuth_deg"]
    assert result.record_dict()["azimuths"] == sweep
