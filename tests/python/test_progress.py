"""The progress bar: drawn on request or on a terminal, silent otherwise."""

import io

import hylo
from hylo._progress import Bar, make_progress
from test_ground import site


def test_the_bar_draws_counts_and_rates():
    stream = io.StringIO()
    bar = Bar("slam", "scans", stream=stream)
    bar(5, 0)
    bar(40, 100)
    bar.close()
    text = stream.getvalue()
    assert "\rslam 5 scans [" in text and "40/100 scans" in text and "|" in text
    assert text.endswith("\n") and "scans/s]" in text


def test_silent_unless_asked_or_on_a_terminal(capsys):
    hylo.ground_mask(site())  # pytest's captured stderr is not a terminal
    assert capsys.readouterr().err == ""
    hylo.ground_mask(site(), progress=True)
    err = capsys.readouterr().err
    assert "smrf |" in err and "steps" in err
    assert isinstance(make_progress(False, "x", "y"), type(make_progress(None, "x", "y")))
