"""Maps, patterns and the common scorer against `covga eval` and `covga maps`."""

import json
import warnings

import numpy as np
import pytest

import covga


@pytest.mark.parametrize(
    "preset,shape,resolution",
    [("thesis-1", (55, 55), 0.2), ("thesis-2", (55, 55), 0.2), ("office", None, None)],
)
def test_presets_load_with_their_frame(preset, shape, resolution):
    m = covga.load_map(preset)
    assert m.name == preset
    if shape is not None:
        assert m.shape == shape and m.resolution == resolution
    assert m.free.shape == m.shape and m.free.dtype == bool
    assert int(m.free.sum()) == m.free_cells
    x0, x1, y0, y1 = m.extent
    assert x1 - x0 == pytest.approx(m.shape[1] * m.resolution)
    assert y1 - y0 == pytest.approx(m.shape[0] * m.resolution)


def test_image_is_the_map_upside_down_in_map_server_values():
    m = covga.load_map("office")
    image = m.to_image()
    states = m.states
    assert image.shape == m.shape and image.dtype == np.uint8
    expected = np.choose(states, [254, 0, 205])[::-1]
    assert np.array_equal(image, expected)


def test_map_from_arrays_and_ros_files_agree(tmp_path, cli):
    cli("maps", "--out", tmp_path)
    from_file = covga.load_map(tmp_path / "office.yaml")
    office = covga.load_map("office")
    assert np.array_equal(from_file.states, office.states)
    occupied = office.states == 1
    with pytest.raises(covga.ConfigError, match="dtype bool"):
        covga.load_map(occupied, resolution=office.resolution, origin=office.origin)
    from_mask = covga.load_map(np.where(occupied, 100, 0), resolution=office.resolution, origin=office.origin)
    assert np.array_equal(from_mask.free, ~occupied)
    percent = np.where(office.states == 0, 0, np.where(office.states == 1, 100, -1))
    from_percent = covga.load_map(percent, resolution=office.resolution, origin=office.origin)
    assert np.array_equal(from_percent.states, office.states)


def test_an_array_map_beyond_the_image_files_cap_is_refused_before_it_is_copied():
    # A broadcast view: 2^28 + 1 cells described without holding them.
    huge = np.broadcast_to(np.zeros(1, dtype=np.bool_), (16385, 16385))
    with pytest.raises(covga.ConfigError, match=r"\(16385, 16385\) has 268468225 cells; a map has at most 268435456"):
        covga.load_map(huge, resolution=0.05)
    with pytest.raises(covga.ConfigError, match="at most 268435456"):
        covga._covga.map_from_states(np.broadcast_to(np.zeros(1, dtype=np.int8), (16385, 16385)), 0.05)


@pytest.mark.parametrize(
    "value,state",
    [(0, 0), (19, 0), (19.6, 2), (50, 2), (65, 2), (66, 1), (100, 1), (-1, 2)],
)
def test_occupancy_percent_thresholds(value, state):
    grid = np.zeros((4, 4))
    grid[1, 2] = value
    assert covga.load_map(grid, resolution=0.5).states[1, 2] == state


@pytest.mark.parametrize(
    "source,kwargs,message",
    [
        (np.zeros((3, 3)), {}, "resolution: an occupancy array needs"),
        (np.zeros((3, 3, 3)), {"resolution": 0.1}, "expected 2-D"),
        (np.full((3, 3), 150.0), {"resolution": 0.1}, "occupancy 150.0 at [0, 0] is out of range"),
        (np.full((3, 3), np.nan), {"resolution": 0.1}, "occupancy nan at [0, 0]"),
        (np.full((3, 3), 100), {"resolution": 0.1}, "no free cell"),
        (np.zeros((3, 3)), {"resolution": -0.1}, "resolution"),
        ("no-such-map", {}, "unknown map `no-such-map`"),
        ("room.png", {}, "the bare image `room.png` needs its metres per pixel"),
    ],
)
def test_bad_maps_raise_config_error(source, kwargs, message):
    with pytest.raises(covga.ConfigError) as e:
        covga.load_map(source, **kwargs)
    assert message in str(e.value)
    assert isinstance(e.value, ValueError)


@pytest.mark.parametrize("kind,angle", [("boustrophedon", 0.0), ("boustrophedon", 45.0), ("spiral", 0.0)])
def test_pattern_and_score_equal_covga_eval(tmp_path, cli, kind, angle):
    m = covga.load_map("thesis-2")
    path = covga.pattern(m, kind, start=(1.3, 1.3), width=0.6, angle=angle)
    out = tmp_path / "eval"
    done = cli("eval", "--map", "thesis-2", "--pattern", kind, "--angle", angle, "--json", "--out", out)
    report = json.loads(done.stdout)
    eval_path = np.genfromtxt(out / "path.csv", delimiter=",", names=True)
    assert np.array_equal(path, np.column_stack([eval_path["x_m"], eval_path["y_m"]]))
    assert covga.score(m, path, width=0.6) == report["common"]


def test_score_of_a_path_file_and_of_agents_equals_covga_eval(tmp_path, cli):
    m = covga.load_map("thesis-1")
    a = covga.pattern(m, "boustrophedon", start=(1.3, 1.3), width=0.6)
    b = covga.pattern(m, "spiral", start=(9.7, 9.7), width=0.6)
    csv = tmp_path / "plan.csv"
    rows = ["agent,index,x_m,y_m"] + [
        f"{k},{i},{float(x)!r},{float(y)!r}" for k, p in enumerate([a, b]) for i, (x, y) in enumerate(p)
    ]
    csv.write_text("\n".join(rows) + "\n")
    args = ("eval", "--map", "thesis-1", "--path", csv, "--rot-speed", 0.5, "--projection", "f2", "--json")
    report = json.loads(cli(*args, "--out", tmp_path / "e").stdout)
    mine = covga.score(m, [a, b], width=0.6, rot_speed=0.5, projection="f2")
    assert mine == report["common"]
    assert mine["agents"] == 2 and len(mine["agent_time_s"]) == 2


def test_a_plan_through_a_wall_is_not_executable():
    m = covga.load_map("thesis-2")
    straight = np.array([[1.3, 1.3], [9.7, 9.7], [1.3, 1.3]])
    s = covga.score(m, straight)
    assert s["executable"] is False and s["obstacle_cells"] > 0


def test_camera_keys_are_checked_and_change_the_camera_metrics():
    m = covga.load_map("thesis-1")
    p = covga.pattern(m, "boustrophedon", start=(1.3, 1.3))
    narrow = covga.score(m, p, camera={"fov_deg": 10.0, "d_max": 1.0})
    wide = covga.score(m, p, camera={"fov_deg": 120.0, "d_max": 1.0})
    assert narrow["cam_walls_free"] < wide["cam_walls_free"]
    with pytest.raises(covga.ConfigError, match="fov_deg"):
        covga.score(m, p, camera={"fov_deg": 720.0})
    with pytest.raises(covga.ConfigError, match="unknown field `zoom`"):
        covga.score(m, p, camera={"zoom": 2})


@pytest.mark.parametrize(
    "call,message",
    [
        (lambda m, p: covga.score(m, p, width=0.0), "width = 0 is out of range"),
        (lambda m, p: covga.score(m, p, speed=float("nan")), "speed = NaN is out of range"),
        (lambda m, p: covga.score(m, p, rot_speed=-1), "rot_speed = -1 is out of range"),
        (lambda m, p: covga.score(m, p, projection="f3"), "projection = 'f3'"),
        (lambda m, p: covga.score(m, p[:, :1]), "path 0: shape (32, 1)"),
        (lambda m, p: covga.score(m, np.array([[50.0, 50.0]])), "path 0 start (50, 50) m is outside map"),
        (lambda m, p: covga.score(m, np.array([[1.0, np.inf]])), "path 0 point 0"),
        (lambda m, p: covga.score(m, p, width=20.0), "wider than the map"),
        (lambda m, p: covga.pattern(m, "zigzag"), "pattern 'zigzag'"),
        (lambda m, p: covga.pattern(m, start=(0.0, 0.0)), "start (0, 0)"),
        (lambda m, p: covga.pattern(m, width=1e-5), "width: a robot 1e-5 m wide"),
    ],
)
def test_bad_arguments_raise_config_error(call, message):
    m = covga.load_map("thesis-1")
    p = covga.pattern(m, "boustrophedon", start=(1.3, 1.3))
    with pytest.raises(covga.ConfigError) as e:
        call(m, p)
    assert message in str(e.value)


def test_a_bare_image_is_read_with_map_servers_thresholds_or_a_free_threshold(tmp_path):
    greys = [0, 89, 90, 205, 206, 249, 250, 255]
    image = tmp_path / "row.pgm"
    image.write_bytes(b"P5\n%d 1\n255\n" % len(greys) + bytes(greys))
    # 0 free, 1 occupied, 2 unknown
    ros = covga.load_map(image, resolution=0.1).states[0].tolist()
    assert ros == [1, 1, 2, 2, 0, 0, 0, 0]
    ipa = covga.load_map(image, resolution=0.1, free_threshold=250).states[0].tolist()
    assert ipa == [1, 1, 1, 1, 1, 1, 0, 0]
    for bad in (0, 256, -1):
        with pytest.raises(ValueError, match="free_threshold"):
            covga.load_map(image, resolution=0.1, free_threshold=bad)
    with pytest.raises(ValueError, match="applies to a bare PGM/PNG image only"):
        covga.load_map("office", free_threshold=250)


def test_a_path_too_long_to_score_is_refused_with_the_bound():
    m = covga.load_map("thesis-1")
    xs = np.linspace(1.5, 9.5, 150_001)
    path = np.column_stack([xs, np.full_like(xs, 2.0)])
    with pytest.raises(ValueError, match="would pose the camera 300000 times.*at most 200000 poses"):
        covga.score(m, path)


def _free_cells_of(m):
    return m.free_cells


def test_a_map_pickles_copies_and_compares_bit_for_bit():
    import copy
    import multiprocessing
    import pickle

    m = covga.load_map("office")
    odd = covga.load_map(np.array([[0, 1, 2], [0, 0, 1]], dtype=np.int8), resolution=0.05, origin=(-1.5, 2.25))
    for original in (m, odd):
        back = pickle.loads(pickle.dumps(original))
        assert back == original and hash(back) == hash(original)
        assert back.name == original.name and back.origin == original.origin
        assert back.resolution == original.resolution and np.array_equal(back.states, original.states)
        assert copy.deepcopy(original) == original and copy.copy(original) is original
    assert m != odd and m != "office"
    # A map crosses process boundaries (multiprocessing, joblib, pymoo's parallel runners).
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        assert pool.map(_free_cells_of, [m, odd]) == [m.free_cells, odd.free_cells]


@pytest.mark.parametrize(
    "call,message",
    [
        (lambda: covga.load_map("thesis-1", origin=(1.0, 2.0)), "origin= and name= apply to occupancy arrays only"),
        (lambda: covga.load_map("thesis-1", name="x"), "origin= and name= apply to occupancy arrays only"),
        (lambda: covga.load_map(np.zeros((3, 3)), resolution=0.1, origin=(0, 0, 0)), "two numbers"),
        (lambda: covga.load_map(np.zeros((3, 3)), resolution="0.1"), "resolution = '0.1': expected a number"),
        (lambda: covga.load_map(np.zeros((3, 3)), resolution=0.1, free_threshold=250), "bare PGM/PNG"),
        (lambda: covga.load_map("office", free_threshold=2.5), "free_threshold = 2.5: expected a whole number"),
        (lambda: covga.load_map("office", free_threshold="250"), "free_threshold = '250': expected a whole number"),
        (lambda: covga.thesis.evaluate("thesis-1", np.zeros((1, 3, 2)), start=1.0), "start = 1.0: expected a point"),
        (lambda: covga.grid("g.toml", jobs=1.5), "jobs = 1.5: expected a whole number"),
        (lambda: covga.thesis.evaluate("thesis-1", np.zeros((1, 3, 2), dtype=bool)), "genomes: an array of booleans"),
        (lambda: covga.thesis.evaluate("thesis-1", [np.zeros((3, 2), dtype=complex)]), "genome 0: an array of complex"),
        (lambda: covga.load_map(np.zeros((3, 3), dtype=complex), resolution=0.1), "expected bool or real numbers"),
        (lambda: covga.score("thesis-1", np.array([[1, 1], [2, 2]], dtype=bool)), "path 0: an array of booleans"),
    ],
)
def test_bad_python_arguments_raise_config_error_naming_the_key(call, message):
    with pytest.raises(covga.ConfigError, match=message.replace("(", r"\(").replace(")", r"\)")):
        call()


def test_pictures_of_maps_plans_and_runs(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    m = covga.load_map("thesis-1")
    png = m._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    plan = covga.pattern(m, "boustrophedon", start=(1.3, 1.3))
    ax = covga.plot.plot_plan(m, plan, title="boustrophedon")
    assert ax.get_aspect() == 1.0 and ax.get_xlabel() == "x [m]"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[:3] == ["path", "path start", "path end"] and "occupied" in labels
    assert ax.get_xlim() == (m.extent[0], m.extent[1])
    r = covga.run({"planner": "boustrophedon", "map": {"source": "thesis-1"}, "stations": {"start": [1.3, 1.3]}})
    assert r.map == m
    ax = r.plot()
    assert ax.get_title().startswith("boustrophedon, seed 1: coverage ")
    ax.figure.savefig(tmp_path / "run.png")
    assert (tmp_path / "run.png").stat().st_size > 1000


def test_score_names_the_robot_it_assumes_and_projects_as_files_do(tmp_path, cli):
    m = covga.load_map("thesis-1")
    path = covga.pattern(m, "boustrophedon", start=(1.3, 1.3))
    with pytest.warns(UserWarning, match=r"rot_speed = 0.0 rad/s .*turning .*free"):
        assumed = covga.score(m, path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        explicit = covga.score(m, path, width=0.6, speed=0.2, rot_speed=0.0)
    assert assumed == explicit
    # f2, as experiment files and covga eval project by default.
    done = cli("eval", "--map", "thesis-1", "--pattern", "boustrophedon", "--json", "--out", tmp_path / "e")
    assert json.loads(done.stdout)["projection"] == "f2"
    assert explicit["f_free"] == pytest.approx(explicit["cov_final_free"] * explicit["t_final"])


def test_a_batch_beyond_the_address_space_limit_is_refused_not_aborted(tmp_path):
    import subprocess
    import sys
    import textwrap

    code = textwrap.dedent(
        """
        import resource, numpy as np, covga
        resource.setrlimit(resource.RLIMIT_AS, (6_000_000_000, resource.RLIM_INFINITY))
        genomes = np.broadcast_to(np.array([0.0, 0.5]), (100_000, 5_000, 2))
        try:
            covga.thesis.evaluate("thesis-1", genomes)
        except ValueError as e:
            print("refused:", e)
        """
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "refused:" in done.stdout and "RLIMIT_AS" in done.stdout, done.stdout + done.stderr
