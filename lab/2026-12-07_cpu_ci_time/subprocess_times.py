import subprocess, time, os
_orig = subprocess.Popen.__init__
_log = open(os.environ.get("PROF_LOG", "/tmp/prof/log.txt"), "a")
class _P(subprocess.Popen):
    pass
_run = subprocess.run
def run(*a, **k):
    t = time.time()
    try:
        return _run(*a, **k)
    finally:
        args = a[0] if a else k.get("args")
        _log.write("%.2f\t%s\n" % (time.time() - t, " ".join(map(str, args)) if isinstance(args, (list, tuple)) else args)[:400] + "\n")
        _log.flush()
subprocess.run = run
