#!/usr/bin/python3
"""The DISPLAY program of the bench configuration: machine on, home, run the program named by
BENCH_PROGRAM with optional stops off (an M0 resumed at once), sample the joints with halsampler
into BENCH_SAMPLES, wait for the end, write BENCH_DONE (its text: "ok" or the errors), and exit
(LinuxCNC then shuts down). Run by LinuxCNC's own Python (the linuxcnc module is Debian's)."""

import os
import subprocess
import sys
import time

import linuxcnc

program, done = os.environ["BENCH_PROGRAM"], os.environ["BENCH_DONE"]
s, c, e = linuxcnc.stat(), linuxcnc.command(), linuxcnc.error_channel()


def wait(cond, timeout_s):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        s.poll()
        if cond():
            return True
        time.sleep(0.01)
    return False


def finish(text):
    with open(done, "w") as f:
        f.write(text)
    sys.exit(0)


wait(lambda: True, 1)
c.state(linuxcnc.STATE_ESTOP_RESET)
c.state(linuxcnc.STATE_ON)
if not wait(lambda: s.task_state == linuxcnc.STATE_ON, 10):
    finish("machine did not come on")
c.mode(linuxcnc.MODE_MANUAL)
c.wait_complete()
c.teleop_enable(0)
c.home(-1)
if not wait(lambda: all(s.homed[:3]), 20):
    finish("not homed")
c.mode(linuxcnc.MODE_AUTO)
c.wait_complete()
c.program_open(program)
c.wait_complete()
c.set_optional_stop(0)                # M1 does not stop, as the planner reads it
c.wait_complete()
samples = open(os.environ["BENCH_SAMPLES"], "w")
sampler = subprocess.Popen(["halsampler", "-c", "0"], stdout=samples)
time.sleep(0.3)
c.auto(linuxcnc.AUTO_RUN, 0)
wait(lambda: s.interp_state != linuxcnc.INTERP_IDLE, 10)
errors = []
end = time.monotonic() + float(os.environ.get("BENCH_TIMEOUT_S", "3600"))
while True:
    if time.monotonic() > end:
        errors.append("timed out: the program did not end")
        break
    s.poll()
    err = e.poll()
    if err:
        errors.append(err[1])
    if s.interp_state == linuxcnc.INTERP_IDLE and s.queue == 0 and s.current_vel == 0.0:
        break
    if s.paused:                      # M0: go on at once (the planner does not wait either)
        c.auto(linuxcnc.AUTO_RESUME)
    time.sleep(0.05)
time.sleep(0.3)
sampler.terminate()
sampler.wait()
samples.close()
finish("ok" if not errors else "; ".join(errors))
