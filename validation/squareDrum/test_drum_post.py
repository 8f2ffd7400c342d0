"""Unit tier of the square drum's post-processing (granularfoam.post.drum):
where the grains are below zero pressure and how the pattern repeats over a
quarter turn, on a synthetic 6 x 6 drum, and
the steps' grain pressure by the phase of the quarter turn.
"""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from granularfoam.post import drum as post

pytestmark = pytest.mark.unit

N = 6
OMEGA = -math.pi / 5


def _synthetic(p_low):
    """A 6 x 6 drum at rest in the lab: air in the top two rows, p = 100
    Pa in the grains but for p_low {(row, column): p}."""
    edges = np.linspace(-0.1, 0.1, N + 1)
    X, Y = np.meshgrid(edges, edges)
    air = np.zeros((N, N))
    air[4:, :] = 1
    p = np.full((N, N), 100.0)
    for cell, value in p_low.items():
        p[cell] = value
    eta = np.full((N, N), 3000.0)
    eta[2, 0], eta[1, 2] = 7.0, 9.0
    inertial = np.full((N, N), 1e-4)
    inertial[1, 2] = 50.0
    return X, Y, {"p": p, "alpha.air": air, "Ux": np.zeros((N, N)),
                  "Uy": np.zeros((N, N)), "etaGranular": eta,
                  "I": inertial}


def test_tension_where(monkeypatch):
    """The lowest grain cell below zero, its distances in cells to the
    wall, the corner and the air, the cells below zero and their largest
    viscosity and inertial number; times without tension left out."""
    fields = {"71.875": _synthetic({(2, 0): -5.0, (1, 2): -1.0}),
              "72.5": _synthetic({})}
    monkeypatch.setattr(post, "grid", lambda case, name, names:
                        fields[name])
    out = post.tension_where("case", ["71.875", "72.5"])
    assert len(out) == 1
    r = out[0]
    assert r["t"] == 71.875
    assert r["quarter_turn_phase_s"] == pytest.approx(1.875)
    assert r["lowest_p"] == -5.0
    assert r["grain_cells_below_zero"] == 2
    assert r["cells_to_wall"] == 0
    assert r["cells_to_corner"] == 2
    assert r["cells_to_air"] == 2.0
    assert r["eta_granular_below_zero_max"] == 9.0
    assert r["I_below_zero_max"] == 50.0
    xc, yc = -0.1 + 0.5 * 0.2 / N, -0.1 + 2.5 * 0.2 / N
    assert r["position_m"] == pytest.approx([xc, yc])
    # At rest in the lab, the drum turns past the cell at |Omega| r
    assert r["speed_relative_to_drum"] == pytest.approx(
        abs(OMEGA) * math.hypot(xc, yc))


def test_tension_by_phase():
    """Steps binned by t mod T/4: counts, those below zero, lowest and
    median per bin; bins without steps left out."""
    t = np.array([0.1, 2.6, 1.3, 1.4, 2.4])
    low = np.array([1.0, -1.0, -3.0, 4.0, -2.0])
    out = post.tension_by_phase(t, low)
    assert [b["phase_s"] for b in out] == [
        pytest.approx([0.0, 0.25]), pytest.approx([1.25, 1.5]),
        pytest.approx([2.25, 2.5])]
    assert [b["steps"] for b in out] == [2, 2, 1]
    assert [b["below_zero"] for b in out] == [1, 1, 1]
    assert [b["lowest_p"] for b in out] == [-1.0, -3.0, -2.0]
    assert [b["median_p"] for b in out] == [0.0, 0.5, -2.0]


def _turned_grid(t):
    """Corners (N+1, N+1) of a 6 x 6 drum turned by Omega t about its axis,
    in blockMesh's order (x first)."""
    edges = np.linspace(-0.1, 0.1, N + 1)
    X0, Y0 = np.meshgrid(edges, edges)
    c, s = math.cos(OMEGA * t), math.sin(OMEGA * t)
    return c * X0 - s * Y0, s * X0 + c * Y0


def test_quarter_turn_map():
    """The map brings the cells a quarter turn later back to the lab
    positions the cells held before."""
    xc0, yc0 = post.centres(*_turned_grid(1.0))
    xc1, yc1 = post.centres(*_turned_grid(1.0 + post.PERIOD / 4))
    assert np.allclose(post.quarter_turn_map(xc1), xc0, atol=1e-12)
    assert np.allclose(post.quarter_turn_map(yc1), yc0, atol=1e-12)


@pytest.mark.parametrize("frame", ["lab", "drum"])
def test_quarter_turn_changes(monkeypatch, frame):
    """A pattern fixed in the lab (phi^s a function of the lab position)
    does not change over a quarter turn in the lab but does in the drum;
    one frozen in the drum the other way round.  The pattern has no
    four-fold symmetry, so that neither change vanishes by symmetry."""
    times = {"1": 1.0, "3.5": 1.0 + post.PERIOD / 4}

    def grid(case, name, names):
        X, Y = _turned_grid(times[name])
        if frame == "lab":
            x, y = post.centres(X, Y)
        else:
            x, y = post.centres(*_turned_grid(0.0))
        small = 0.5 + 2 * x + 3 * y ** 2        # within (0, 1) on the drum
        air = np.zeros((N, N))
        return X, Y, {"alpha.small": small, "alpha.large": 1 - small,
                      "alpha.air": air}

    monkeypatch.setattr(post, "grid", grid)
    monkeypatch.setattr(post, "_time_name", lambda case, t: _name(times, t))
    out = post.quarter_turn_changes("drum", ["1"])
    assert out["pairs"] == 1
    assert out["variation"] > 0.02
    still, moving = ("lab", "drum") if frame == "lab" else ("drum", "lab")
    assert out[still] < 1e-12
    assert out[moving] > 0.1 * out["variation"]


def _name(times, t):
    """The written time named t, as _time_name (AssertionError if none)."""
    names = [k for k, v in times.items() if abs(v - t) < 1e-9]
    assert names, f"no time directory at t = {t}"
    return names[0]


@pytest.mark.parametrize("folder", ["measured", "etaMax", "N100", "Krylov",
                                    "fill"])
def test_readme_tables_are_rendered_from_drum_json(folder):
    """Each results table of the drum README is what its drum.json holds,
    rendered by granularfoam.post.drum (--readme)."""
    project = Path(__file__).resolve().parents[2]
    numbers = json.loads((project / "validation" / "squareDrum" / "measured"
                          / ("" if folder == "measured" else folder)
                          / "drum.json").read_text())
    text = (project / "tutorials" / "squareDrum" / "README.md").read_text()
    begin = post.README_BEGIN.format(folder)
    end = post.README_END.format(folder)
    assert begin in text and end in text, f"no {folder} table in the README"
    table = text[text.index(begin) + len(begin):text.index(end)].strip()
    assert table == post.results_table(numbers), (
        f"the README's {folder} table differs from its drum.json: run "
        "granularfoam.post.drum with --readme")


def test_J_series_keeps_the_finite_samples_on_its_step():
    """The monitor's J at the multiples of 0.25 s, the nan of a restart's
    first revolution left out."""
    t = np.round(np.arange(0.05, 2.0001, 0.05), 10)
    J = 0.1 * t
    J[(t > 0.9) & (t < 1.6)] = np.nan
    out = post.J_series({"t": t, "J": J})
    assert out["t"] == [0.25, 0.5, 0.75, 1.75, 2.0]
    assert out["J"] == pytest.approx([0.025, 0.05, 0.075, 0.175, 0.2])


def test_figure13_draws_every_run_of_the_results_file(tmp_path):
    """Figure 13 comes from drum.json: a run with its J series as a curve,
    one without it from J at each revolution (nulls left out); the other
    entries (the tension windows) are not runs."""
    numbers = {
        "N100_a": {"N": 100, "J_revolution": {"10": 0.1, "20": None,
                                              "30": 0.03}},
        "N50_b": {"N": 50, "J_revolution": {"10": 0.09},
                  "J_series": {"t": [0.25, 0.5], "J": [0.0, 0.01]}},
        "tension": {"N100K_CC20": {"lowest": -26}},
    }
    drawn = post.figure13(numbers, tmp_path / "figure13.png")
    assert (tmp_path / "figure13.png").stat().st_size > 0
    assert drawn == [("N50_b", [0.25, 0.5], [0.0, 0.01]),
                     ("N100_a", [10.0, 30.0], [0.1, 0.03])]


def test_figure_revolutions_draws_the_written_revolutions(monkeypatch,
                                                          tmp_path):
    """phi^s at the revolutions written (10 and 20 s of a run at 25 s);
    a run that has not reached 10 s has no such figure."""
    times = {"5": 5.0, "10": 10.0, "20": 20.0, "25": 25.0}

    def grid(case, name, names):
        X, Y = _turned_grid(0.0)
        x, _ = post.centres(X, Y)
        small = 0.5 + 2 * x
        return X, Y, {"alpha.small": small, "alpha.large": 1 - small,
                      "alpha.air": np.zeros((N, N)),
                      "I": np.full((N, N), 1e-4)}

    monkeypatch.setattr(post, "grid", grid)
    monkeypatch.setattr(post, "_time_name", lambda case, t: _name(times, t))
    monkeypatch.setattr(post, "label", lambda case: "N6_test")
    monkeypatch.setattr(post, "parameters", lambda case: {"L": 0.1})
    out = tmp_path / "revolutions.png"
    assert post.figure_revolutions("drum", out) == [10.0, 20.0]
    assert out.stat().st_size > 0
    del times["10"], times["20"]
    with pytest.raises(AssertionError, match="has not written"):
        post.figure_revolutions("drum", tmp_path / "none.png")


def test_lobe_angles_are_the_radial_arms_of_the_body():
    """Small-rich arms from a mixed core towards three corners of the
    drum and along a wall, joined at the core: the arms in the body are
    lobes at their angles; the arm whose outer part is in the avalanche
    (I > I_1) is not; an arm of one cell's width and 0.04 contrast is
    not."""
    n = 60
    edges = np.linspace(-0.1, 0.1, n + 1)
    X, Y = np.meshgrid(edges, edges)
    xc, yc = post.centres(X, Y)
    r, theta = np.hypot(xc, yc), np.arctan2(yc, xc)

    def arm(angle, height, width=0.35):
        d = np.angle(np.exp(1j * (theta - math.radians(angle))))
        return height * np.exp(-(d / width) ** 2) * (r > 0.02)
    small = (0.45 + arm(-135, 0.3) + arm(-45, 0.3) + arm(135, 0.3)
             + arm(45, 0.3) + arm(180, 0.04, width=0.02))
    inertial = np.full((n, n), 1e-4)
    inertial[(r > 0.03) & (np.abs(theta - math.pi / 4) < 0.6)] = 1.0
    air = np.zeros((n, n))
    f = {"alpha.small": small, "alpha.large": 1 - small,
         "alpha.air": air, "I": inertial}
    angles = np.degrees(post.lobe_angles(X, Y, f))
    assert sorted(np.mod(angles, 360)) == pytest.approx([135, 225, 315],
                                                        abs=5)
    assert math.degrees(post.lobe_spacing(np.radians(angles))) == \
        pytest.approx(90, abs=5)


def test_lobe_spacing_leaves_out_the_gap_across_the_air():
    """Lobes at -150, -60 and 30 degrees: 90 degrees apart, the gap of 180
    across the top left out; one lobe has no spacing."""
    a = np.radians([30.0, -150.0, -60.0])
    assert math.degrees(post.lobe_spacing(a)) == pytest.approx(90.0)
    assert post.lobe_spacing(a[:1]) is None


def test_readme_compares_with_the_paper_from_drum_json():
    """The drum README's comparison with the paper is what the Krylov
    drum.json holds, rendered by granularfoam.post.drum (--readme)."""
    project = Path(__file__).resolve().parents[2]
    numbers = json.loads((project / "validation" / "squareDrum" / "measured"
                          / "Krylov" / "drum.json").read_text())
    text = (project / "tutorials" / "squareDrum" / "README.md").read_text()
    begin = post.PAPER_BEGIN.format("Krylov")
    end = post.PAPER_END.format("Krylov")
    assert begin in text and end in text, "no comparison with the paper"
    table = text[text.index(begin) + len(begin):text.index(end)].strip()
    assert table == post.paper_table(numbers)
    assert post.PAPER["lobes"] in table


def test_sidewall_reads_the_end_walls_of_fvOptions(tmp_path):
    """The gap and friction of the tutorial's fvOptions.sidewall once
    ./Allrun -sidewall has copied it; None without constant/fvOptions."""
    project = Path(__file__).resolve().parents[2]
    (tmp_path / "constant").mkdir()
    assert post.sidewall(tmp_path) is None
    text = (project / "tutorials" / "squareDrum" / "constant"
            / "fvOptions.sidewall").read_text()
    (tmp_path / "constant" / "fvOptions").write_text(
        text.replace("0.25;", "0.3;"))
    assert post.sidewall(tmp_path) == {"W": 0.01, "muW": 0.3}


def test_fill_is_the_tutorials_70_percent_and_follows_the_surface(tmp_path):
    """The tutorial's initial surface at H = 0.04 m fills 70 % of the
    drum; moved to H = 0 (a copy's setGranularFieldsDict edited) 50 %,
    which the run's key and title carry."""
    project = Path(__file__).resolve().parents[2]
    system = tmp_path / "system"
    system.mkdir()
    tutorial = project / "tutorials" / "squareDrum" / "system"
    for name in ("drumParameters", "setGranularFieldsDict"):
        (system / name).write_text((tutorial / name).read_text())
    assert post.fill(tmp_path) == pytest.approx(0.7)
    text = (system / "setGranularFieldsDict").read_text()
    assert "(0 0.04 0)" in text
    (system / "setGranularFieldsDict").write_text(
        text.replace("(0 0.04 0)", "(0 0 0)"))
    assert post.fill(tmp_path) == pytest.approx(0.5)
    assert post._run_title({"N": 50, "coupling": "Krylov BFBt 20",
                            "nCorrectors": 30,
                            "etaMax": 3000, "fill": 0.5}).endswith(
        ", fill 50 %")
    assert "fill" not in post._run_title({"N": 50, "etaMax": 3000,
                                          "nCorrectors": 30,
                                          "coupling": "Krylov BFBt 20",
                                          "fill": 0.7})


def test_readme_sidewall_table_is_rendered_from_sidewall_json():
    """The drum README's sidewall table is what sidewall.json holds,
    rendered by granularfoam.post.drumSidewall (--readme)."""
    from granularfoam.post import drumSidewall
    project = Path(__file__).resolve().parents[2]
    numbers = json.loads((project / "validation" / "squareDrum" / "measured"
                          / "sidewall.json").read_text())
    text = (project / "tutorials" / "squareDrum" / "README.md").read_text()
    begin, end = drumSidewall.README_BEGIN, drumSidewall.README_END
    assert begin in text and end in text, "no sidewall table in the README"
    table = text[text.index(begin) + len(begin):text.index(end)].strip()
    assert table == drumSidewall.table(numbers)


def test_flat_surface_holds_the_area_below_it():
    """Level walls and a level surface: d = A/(2L) - L; half the square
    below a surface through the axis at any turn and inclination; the
    drum turned by 45 degrees, a level surface cutting off the lower
    corner's triangle of area a = h^2: d = -sqrt(2) L + sqrt(a)."""
    L = 0.1
    assert post.flat_surface(0.0, 0.0, 0.7 * 4 * L * L, L) == \
        pytest.approx(0.04)
    for theta, angle in ((0.3, 20.0), (-1.0, 35.0), (2.0, 5.0)):
        assert post.flat_surface(theta, angle, 2 * L * L, L) == \
            pytest.approx(0.0, abs=1e-8)
    a = 0.005                       # a triangle at the lower corner
    assert post.flat_surface(math.pi / 4, 0.0, a, L) == \
        pytest.approx(-math.sqrt(2) * L + math.sqrt(a))


def test_lobe_drift_follows_the_lobes_against_the_drum():
    """Three lobes 90 degrees apart turning 12 degrees/s faster than the
    drum, one of them leaving and another forming 90 degrees away at the
    third write: the drift is -12 degrees/s; lobes that turn with the
    drum have none."""
    omega = -360 / post.PERIOD              # degrees/s
    times = [70.0, 70.625, 71.25, 71.875]
    angles = []
    for k, t in enumerate(times):
        base = (omega - 12) * (t - 70)
        lobes = [base + 180, base + 270] + ([base + 360] if k < 2 else
                                            [base + 90])
        angles.append(np.radians(lobes))
    drift, matches = post.lobe_drift(angles, times)
    assert math.degrees(drift) == pytest.approx(-12)
    assert matches == 2 * 3 + 2
    still = [np.radians([omega * (t - 70) + 45, omega * (t - 70) + 135])
             for t in times]
    assert post.lobe_drift(still, times)[0] == pytest.approx(0, abs=1e-9)


def test_lobe_lives_are_the_lobes_seen_to_form_and_to_leave():
    """Lobes turning with the drum, 90 degrees apart: one seen over the
    whole window (its life unknown, left out), one that forms at the
    third write at -30 degrees and leaves after the seventh, 2.5 s later,
    at -120 degrees; a lobe that splits in two keeps one track."""
    omega = -360 / post.PERIOD              # degrees/s
    times = [70 + 0.625 * k for k in range(9)]
    angles = []
    for k, t in enumerate(times):
        turn = omega * (t - 70)
        lobes = [turn + 10]
        if 2 <= k <= 6:
            lobes.append(turn + 15)                 # -30 degrees at 71.25 s
        if k == 4:
            lobes.append(turn + 17)                 # the split, 2 degrees on
        angles.append(np.radians(lobes))
    lives = post.lobe_lives(angles, times)
    assert len(lives) == 2
    main = max(lives, key=lambda x: x["life_s"])
    assert main["life_s"] == pytest.approx(2.5)
    assert main["first_deg"] == pytest.approx(330)
    assert main["last_deg"] == pytest.approx(240)
    assert min(x["life_s"] for x in lives) == pytest.approx(0)
    tracks = post.lobe_tracks(angles, times)
    assert sorted(len(t) for t in tracks) == [1, 5, 9]


def test_lobe_lives_cell_averages_the_angles_round_the_circle():
    """Lobes forming at 350 and 10 degrees form at 0 on average, not 180;
    a run without lobe lives shows none."""
    run = {"lobe_life_s_median": 5.0,
           "lobe_lives_last_revolution": [
               {"life_s": 5.0, "first_deg": 350.0, "last_deg": 170.0},
               {"life_s": 5.0, "first_deg": 10.0, "last_deg": 190.0}]}
    cell = post._lives_cell(run)
    assert cell.startswith("5.00 / 5.00 s (2), ")
    first, last = (float(x.strip().rstrip("°"))
                   for x in cell.split(", ")[1].split("→"))
    assert min(first, 360 - first) == pytest.approx(0, abs=1e-6)
    assert last == pytest.approx(180)
    assert post._lives_cell({}) == "–"
