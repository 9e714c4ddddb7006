import subprocess, time, sys, runpy, atexit
orig = subprocess.run
log = []
def timed(*a, **k):
    t = time.time(); r = orig(*a, **k); dt = time.time() - t
    args = a[0] if a else k.get('args')
    log.append((dt, ' '.join(args) if isinstance(args, list) else str(args)))
    return r
subprocess.run = timed
def dump():
    tot = sum(d for d, _ in log)
    print(f"TOTAL subprocess {tot:.1f}s in {len(log)} calls", file=sys.stderr)
    for d, c in sorted(log, reverse=True)[:25]:
        print(f"{d:7.2f} {c[:200]}", file=sys.stderr)
atexit.register(dump)
script = sys.argv[1]; sys.argv = sys.argv[1:]
runpy.run_path(script, run_name='__main__')
