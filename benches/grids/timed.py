"""One program run of a grid script with a wall-time limit and its CPU time (shared by
texture.py and dynamics.py)."""
import os, subprocess, tempfile, threading


def run_timed(cmd, timeout):
    """Runs `cmd`, killed after `timeout` seconds of wall time. Returns `(code, timed_out,
    stdout, stderr, cpu_s)`: the exit code, whether the limit killed it (a run that ended with
    code 0 just as the timer fired is not), its output, and its user + system CPU time
    (os.wait4)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err)
        timer = threading.Timer(timeout, p.kill)
        timer.start()
        _, status, ru = os.wait4(p.pid, 0)
        timed_out = not timer.is_alive()
        timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read().decode(), err.read().decode()
    return (p.returncode, timed_out and p.returncode != 0, stdout, stderr,
            ru.ru_utime + ru.ru_stime)
