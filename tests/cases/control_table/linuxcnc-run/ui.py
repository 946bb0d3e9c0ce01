#!/usr/bin/python3
# The "display" of the simulator (tests/it/linuxcnc_table.rs): LinuxCNC starts it with the
# INI file; it records every servo period with halsampler (tagged, so a lost sample shows),
# takes the machine out of E-stop, runs part.ngc in AUTO mode, waits until it is done and
# in position, and stops; LinuxCNC then shuts down. Written for this test, driving the
# controller through LinuxCNC's Python interface (module `linuxcnc`).
import linuxcnc, subprocess, time, sys, os
c = linuxcnc.command(); s = linuxcnc.stat(); e = linuxcnc.error_channel()
def wait(pred, t=60):
    end = time.time() + t
    while time.time() < end:
        s.poll()
        if pred(): return
        msg = e.poll()
        if msg: print("linuxcnc error:", msg, file=sys.stderr)
        time.sleep(0.01)
    sys.exit("timeout: task_state=%s interp=%s" % (s.task_state, s.interp_state))
wait(lambda: s.task_state == linuxcnc.STATE_ESTOP)
sampler = subprocess.Popen(["halsampler", "-t", "-c", "0"], stdout=open("samples.txt", "w"))
c.state(linuxcnc.STATE_ESTOP_RESET); c.wait_complete()
c.state(linuxcnc.STATE_ON); c.wait_complete()
wait(lambda: s.task_state == linuxcnc.STATE_ON)
c.mode(linuxcnc.MODE_AUTO); c.wait_complete()
c.program_open(os.path.abspath("part.ngc")); c.wait_complete()
c.auto(linuxcnc.AUTO_RUN, 0)
wait(lambda: s.exec_state != linuxcnc.EXEC_DONE or s.interp_state != linuxcnc.INTERP_IDLE, 10)
wait(lambda: s.interp_state == linuxcnc.INTERP_IDLE and s.exec_state == linuxcnc.EXEC_DONE and s.inpos, 120)
time.sleep(0.3)
sampler.terminate(); sampler.wait()
