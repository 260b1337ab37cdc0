"""Ctrl-C (SIGINT) interrupts a long sweep and a long vehicle–bridge run: the extension polls
Python's signal handlers every 50 ms while the Rust code runs with the GIL released, and the
library stops between passages (sweep) or after the current step (run)."""

import signal
import subprocess
import sys
import time

import pytest

from conftest import ROOT

SWEEP = r"""
import sys, time, tomllib
import dyncontact
with open("examples/sweep_hslm.toml", "rb") as f:
    case = tomllib.load(f)
case["speeds"]["step"] = 0.001   # about 780 000 passages: minutes of work
print("start", flush=True)
t0 = time.perf_counter()
try:
    dyncontact.sweep(case)
except KeyboardInterrupt as e:
    print(f"interrupted after {time.perf_counter() - t0:.2f} s: {e}", flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


RUN = r"""
import sys, time, tomllib
import dyncontact
with open("examples/vehicle_bridge_default.toml", "rb") as f:
    case = tomllib.load(f)
case["integrator"]["dt"] = 2.5e-6   # 100 x the example's steps: minutes of work
case["output"] = {"every": 1000}
print("start", flush=True)
t0 = time.perf_counter()
try:
    dyncontact.run(case)
except KeyboardInterrupt as e:
    print(f"interrupted after {time.perf_counter() - t0:.2f} s: {e}", flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


@pytest.mark.parametrize("script", [SWEEP, RUN], ids=["sweep", "vehicle_bridge_run"])
def test_ctrl_c_stops_a_long_run(script):
    p = subprocess.Popen(
        [sys.executable, "-c", script], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert p.stdout.readline().strip() == "start"
    time.sleep(1.5)
    sent = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    stopped = time.perf_counter() - sent
    assert p.returncode == 3, (out, err)
    assert "interrupted" in out and "KeyboardInterrupt" not in err
    # A passage or a step takes milliseconds; 30 s leaves room for a loaded machine.
    assert stopped < 30, stopped
