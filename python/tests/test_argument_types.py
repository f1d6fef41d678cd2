"""Arguments of the wrong type are refused naming the argument (issue 100, item 9), never
converted: a bool occupancy array has no meaning of its own, text where a number is wanted is
not read as the number it spells, a truthy value is not a flag."""

import numpy as np
import pytest

import covga

PATH = np.array([[1.3, 1.3], [4.0, 1.3]])


def test_a_bool_occupancy_array_is_refused_naming_its_dtype_and_what_to_pass():
    free = covga.load_map("thesis-1").free
    with pytest.raises(covga.ConfigError, match=r"dtype bool.*np\.where\(occupied, 100, 0\).*np\.where\(free, 0, 100\)"):
        covga.load_map(free, resolution=0.2)
    # ConfigError is a ValueError: `except ValueError` catches it.
    with pytest.raises(ValueError):
        covga.load_map(np.zeros((3, 3), dtype=bool), resolution=0.1)
    # What the message says to pass loads the map the mask describes.
    m = covga.load_map(np.where(free, 0, 100), resolution=0.2)
    assert np.array_equal(m.free, free)


@pytest.mark.parametrize(
    "call,key",
    [
        (lambda: covga.score("thesis-1", PATH, width="0.6", speed=0.2, rot_speed=0.0), "width"),
        (lambda: covga.score("thesis-1", PATH, width=0.6, speed="0.2", rot_speed=0.0), "speed"),
        (lambda: covga.score("thesis-1", PATH, width=0.6, speed=0.2, rot_speed="0"), "rot_speed"),
        (lambda: covga.score("thesis-1", PATH, width=True, speed=0.2, rot_speed=0.0), "width"),
        (lambda: covga.score("thesis-1", PATH, width=0.6, speed=0.2, rot_speed=0.0, raster="yes"), "raster"),
        (lambda: covga.score("thesis-1", PATH, width=0.6, speed=0.2, rot_speed=0.0, projection=2), "projection"),
        (lambda: covga.pattern("thesis-1", width="0.6"), "width"),
        (lambda: covga.pattern("thesis-1", angle="90"), "angle"),
        (lambda: covga.pattern("thesis-1", complete="no"), "complete"),
        (lambda: covga.pattern("thesis-1", kind=1), "kind"),
        (lambda: covga.pattern("thesis-1", start=("1.3", 1.3)), "start"),
        (lambda: covga.thesis.evaluate("thesis-1", np.zeros((1, 3, 2)), width="0.6"), "width"),
        (lambda: covga.thesis.evaluate("thesis-1", np.zeros((1, 3, 2)), speed="0.2"), "speed"),
        (lambda: covga.thesis.evaluate("thesis-1", np.zeros((1, 3, 2)), rot_speed="0"), "rot_speed"),
        (lambda: covga.thesis.decode("thesis-1", np.zeros((3, 2)), width="0.6"), "width"),
        (lambda: covga.load_map(np.zeros((3, 3)), resolution="0.1"), "resolution"),
        (lambda: covga.stats.sign_test([1.0, 2.0], against="0"), "against"),
        (lambda: covga.stats.bootstrap_ci([1.0, 2.0], [1.0, 3.0], paired="yes"), "paired"),
        (lambda: covga.stats.bootstrap_ci([1.0, 2.0], [1.0, 3.0], level="0.9"), "level"),
        (lambda: covga.run({"planner": "boustrophedon"}, figures="no"), "figures"),
    ],
)
def test_a_number_or_flag_of_the_wrong_type_is_refused_naming_the_argument(call, key):
    with pytest.raises(covga.ConfigError, match=rf"^{key} = "):
        call()


def test_numbers_of_every_numeric_type_are_still_accepted():
    a = covga.score("thesis-1", PATH, width=np.float32(0.6), speed=np.int64(1), rot_speed=0)
    b = covga.score("thesis-1", PATH, width=0.6, speed=1.0, rot_speed=0.0)
    assert a["cov_final_reach"] == pytest.approx(b["cov_final_reach"])
    plan = covga.pattern("thesis-1", start=(3, 3), width=1, angle=np.float64(0.0), complete=np.bool_(True))
    assert plan.shape[1] == 2
