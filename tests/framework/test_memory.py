"""framework.memory: after keep_freed_memory, a freed step-sized array is reused, not faulted in again."""
import resource
import subprocess
import sys

import pytest

from tests.conftest import ROOT

PROBE = """
import resource, sys
import numpy as np
sys.path.insert(0, {root!r})
from framework.memory import keep_freed_memory
ok = keep_freed_memory() if {keep} else False
def faults_of_second_round():
    for r in range(2):
        f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        a = [np.empty(3 << 20, np.uint8) for _ in range(8)]     # eight 3 MiB arrays, written
        for x in a:
            x[:] = 1
        del a
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
print(ok, faults_of_second_round())
"""


def _probe(keep):
    out = subprocess.run([sys.executable, "-c", PROBE.format(root=str(ROOT), keep=keep)],
                         capture_output=True, text=True, check=True).stdout.split()
    return out[0] == "True", int(out[1])


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's mallopt")
def test_freed_arrays_are_reused_without_page_faults():
    ok, faults = _probe(True)
    if not ok:
        pytest.skip("mallopt not available (not glibc)")
    _, faults_default = _probe(False)
    # 24 MiB written is ~6,000 pages; with the thresholds set they come back from the heap
    assert faults < 1536, faults                         # measured 768 (6,144 without)
    assert faults_default > 3000, faults_default        # the probe does measure what it should
