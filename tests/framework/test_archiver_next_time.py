"""The next output / checkpoint time: Uintah's interval-by-interval sum, and a tiny interval
far below the step handled without looping over every interval."""
import time

from framework.archiver import _next_time


def test_next_time_matches_the_interval_sum():
    due, interval = 0.0, 0.1
    for t in (0.05, 0.1, 0.35, 1.0, 1.0000000000001):
        expect = due
        while expect <= t * (1 + 1e-12):
            expect += interval
        due = _next_time(due, interval, t)
        assert due == expect


def test_tiny_interval_is_quick_and_just_after_t():
    start = time.process_time()
    due = _next_time(0.0, 1e-12, 1e-3)              # 1e9 intervals behind
    assert time.process_time() - start < 0.5
    assert 1e-3 * (1 + 1e-12) < due <= 1e-3 * (1 + 1e-12) + 2e-12
