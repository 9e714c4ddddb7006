#!/usr/bin/env python3
"""`cavity history` against a real PostgreSQL server: Debian's postgresql-15,
started by this test in a temporary folder (as the postgres user when run as
root: initdb refuses root), on a free port, with password authentication
over TCP, and stopped and removed at the end even on failure.

    test_history_postgres.py CAVITY SOURCE_DIR

Real files go into both PostgreSQL and an SQLite file, each with the same
commit and date: a history of cavity_bench files made from a recorded H200
sweep with planted steps (tests/history_series.py), the recorded H100 and
H200 sweeps, two recorded gate.json files (copies in tests/data/) and a
results.json that `cavity run` writes here. Then show --json and alerts --json must be the
same from both, and alerts must find the planted steps. Also: the same file
twice is one run; a kill -9 halfway through an ingest leaves the whole run
or nothing; a newer schema is refused (exit 2); a wrong password, a server
that is down and a URL for a database that does not exist give exit 5 and
one line without the password.
"""
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

CAVITY, SOURCE = sys.argv[1:3]
PG = "/usr/lib/postgresql/15/bin"
PASSWORD = "hist-Secret-5d1"
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def as_postgres(args, **kw):
    """Runs a server program as the postgres user when we are root."""
    if os.getuid() == 0:
        args = ["runuser", "-u", "postgres", "--"] + args
    return subprocess.run(args, capture_output=True, text=True, **kw)


def cavity(*args, env=None):
    e = {k: v for k, v in os.environ.items() if not k.startswith("PG")}
    e.update(env or {})
    return subprocess.run([CAVITY, "history", *args], capture_output=True, text=True, env=e)


def one_line(p, code, what, *needles):
    lines = p.stderr.strip().splitlines()
    ok = p.returncode == code and len(lines) == 1 and all(n in p.stderr for n in needles)
    ok = ok and PASSWORD not in p.stderr + p.stdout
    check(ok, f"{what}: exit {p.returncode} (want {code}), {len(lines)} line(s): {p.stderr.strip()[:300]}")


class Server:
    def __init__(self, root):
        self.root = os.path.join(root, "pg")
        self.data, self.sock = os.path.join(self.root, "data"), os.path.join(self.root, "sock")
        os.makedirs(self.sock)
        with open(os.path.join(self.root, "pw"), "w") as f:
            f.write(PASSWORD + "\n")
        if os.getuid() == 0:
            os.chmod(root, 0o755)
            shutil.chown(self.root, "postgres")
            shutil.chown(self.sock, "postgres")
            shutil.chown(os.path.join(self.root, "pw"), "postgres")
        self.port = free_port()
        p = as_postgres([f"{PG}/initdb", "-D", self.data, "-U", "cavity", "--auth-local=trust",
                         "--auth-host=scram-sha-256", "--pwfile", os.path.join(self.root, "pw"), "-E", "UTF8"])
        if p.returncode:
            raise RuntimeError("initdb: " + p.stderr)
        self.started = False

    def start(self):
        opts = f"-p {self.port} -k {self.sock} -c listen_addresses=127.0.0.1 -c fsync=off"
        p = as_postgres([f"{PG}/pg_ctl", "-D", self.data, "-o", opts, "-l", os.path.join(self.root, "log"), "-w", "start"])
        if p.returncode:
            raise RuntimeError("pg_ctl start: " + p.stdout + p.stderr)
        self.started = True

    def stop(self):
        if self.started:
            as_postgres([f"{PG}/pg_ctl", "-D", self.data, "-m", "immediate", "-w", "stop"])
            self.started = False

    def psql(self, sql, db="cavity"):
        p = subprocess.run(["psql", "-h", self.sock, "-p", str(self.port), "-U", "cavity", "-d", db, "-Atc", sql],
                           capture_output=True, text=True)
        if p.returncode:
            raise RuntimeError("psql: " + p.stderr)
        return p.stdout.strip()

    def url(self, password=PASSWORD, db="cavity"):
        return f"postgresql://cavity:{password}@127.0.0.1:{self.port}/{db}"


def run_files(work):
    """(commit, date, path) of every real file both databases get."""
    p = subprocess.run([sys.executable, os.path.join(SOURCE, "tests/history_series.py"), SOURCE,
                        os.path.join(work, "series"), "--commits", "20"], capture_output=True, text=True, check=True)
    files = [tuple(line.split(" ", 2)) for line in p.stdout.strip().splitlines()]
    rec = os.path.join(SOURCE, "tests/data")
    files += [("aa11" * 10, "2026-10-01T00:00:00Z", os.path.join(rec, "2026-11-24_h100_full_sweep.json.gz")),
              ("bb22" * 10, "2026-10-02T00:00:00Z", os.path.join(rec, "2026-11-24_h100_first_look_5reps.json.gz")),
              ("cc33" * 10, "2026-10-03T00:00:00Z", os.path.join(rec, "2026-12-02_h200_gate2/gate_ci.json.gz")),
              ("dd44" * 10, "2026-10-04T00:00:00Z", os.path.join(rec, "2026-12-02_h200_gate2/gate_gc.json.gz"))]
    out = os.path.join(work, "run")
    r = subprocess.run([CAVITY, "run", "--backend", "gl", "--kernel", "alchemy", "--res", "64x36", "--frames", "8",
                        "--out", out], capture_output=True, text=True)
    if r.returncode == 0:
        files.append(("ee55" * 10, "2026-10-05T00:00:00Z", os.path.join(out, "results.json")))
    else:
        print("note: cavity run could not write a results.json here (exit %d); left out" % r.returncode)
    return files


def same_answers(server, sqlite, work):
    for case, (sub, extra) in enumerate((("show", ["--id", "corner/alchemy/n16/b4/full/1920x1080"]), ("show", ["--pass", "ao"]),
                       ("alerts", []), ("alerts", ["--since", "2026-11-05", "--min-change", "1"]))):
        outs = []
        for db in (server.url(), sqlite):
            path = os.path.join(work, f"{sub}-{case}-{len(outs)}.json")
            p = cavity(sub, "--db", db, *extra, "--json", path)
            check(p.returncode == 0, f"{sub} {' '.join(extra)} on {db.split(':')[0]}: exit {p.returncode} {p.stderr.strip()}")
            outs.append(json.load(open(path)) if p.returncode == 0 else None)
        check(outs[0] == outs[1] and outs[0] is not None, f"{sub} {' '.join(extra)}: PostgreSQL and SQLite give the same JSON")
    alerts = json.load(open(os.path.join(work, "alerts-2-0.json")))["alerts"]
    found = {(a["id"], a["pass"]): a for a in alerts}
    gl, vk = "corner/alchemy/n16/b4/full/1920x1080/gl/compute", "corner/alchemy/n16/b4/full/1920x1080/vk/compute"
    series = [line.split(" ", 2) for line in open(os.path.join(work, "series.txt")).read().splitlines()]
    a = found.get((gl, "ao"))
    check(a is not None and a["commit"] == series[12][0] and a["previous_commit"] == series[11][0]
          and a["direction"] == "slower" and 8 < a["change_pct"] < 12, f"the planted +10% in {gl} ao at commit 12: {a}")
    b = found.get((vk, "blur"))
    check(b is not None and b["commit"] == series[7][0] and b["direction"] == "faster" and -8 < b["change_pct"] < -4,
          f"the planted -6% in {vk} blur at commit 7: {b}")
    planted = {(gl, "ao"), (gl, "pipeline"), (vk, "blur"), (vk, "pipeline")}
    stray = [k for k in found if k[0] in (gl, vk, "corner/alchemy/n4/b4/full/1920x1080/gl/compute") and k not in planted]
    check(not stray, f"no change point where none was planted: {stray}")


def kill_halfway(server, work, big):
    """A kill -9 while a big file goes in: afterwards the run is whole or absent."""
    before = int(server.psql("SELECT count(*) FROM runs"))
    p = subprocess.Popen([CAVITY, "history", "ingest", "--db", server.url(), "--commit", "ff66" * 10, big],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(0.15)
    p.send_signal(signal.SIGKILL)
    p.wait()
    time.sleep(0.3)   # the server notices the closed connection and rolls back
    runs = int(server.psql("SELECT count(*) FROM runs"))
    orphans = int(server.psql("SELECT count(*) FROM passes p LEFT JOIN runs r ON p.run_id = r.id WHERE r.id IS NULL"))
    passes = server.psql("SELECT count(*) FROM passes p JOIN runs r ON p.run_id = r.id WHERE r.commit_sha = '" + "ff66" * 10 + "'")
    whole = runs == before or (runs == before + 1 and int(passes) == 2518)
    check(whole and orphans == 0, f"kill -9 halfway: runs {before} -> {runs}, passes of it {passes}: all or nothing")


def errors(server, work, good):
    one_line(cavity("show", "--db", server.url(password="wrong")), 5, "a wrong password", "cannot connect",
             "password authentication failed")
    one_line(cavity("show", "--db", server.url(db="nosuch")), 5, "a database that does not exist", "nosuch")
    # The password from libpq's PGPASSWORD instead of the URL.
    p = cavity("show", "--db", f"postgresql://cavity@127.0.0.1:{server.port}/cavity", "--pass", "ao",
               env={"PGPASSWORD": PASSWORD})
    check(p.returncode == 0, f"credentials from PGPASSWORD: exit {p.returncode} {p.stderr.strip()}")
    server.psql("UPDATE schema_version SET version = 42")
    one_line(cavity("alerts", "--db", server.url()), 2, "a newer schema", "schema version 42 is newer")
    server.psql("UPDATE schema_version SET version = 2")
    server.stop()
    one_line(cavity("ingest", "--db", server.url(), "--commit", "abcd1234", good), 5, "the server down", "cannot connect")


def main():
    for prog in ("initdb", "pg_ctl"):
        if not os.path.exists(f"{PG}/{prog}"):
            if os.environ.get("CI") == "true":
                print(f"FAIL {PG}/{prog} missing (scripts/setup.sh installs postgresql)")
                sys.exit(1)
            print(f"skip: {PG}/{prog} missing (apt-get install postgresql)")
            sys.exit(0)
    work = tempfile.mkdtemp(prefix="cavity-history-pg-")
    server = None
    try:
        server = Server(work)
        server.start()
        server.psql("CREATE DATABASE cavity", db="postgres")
        files = run_files(work)
        with open(os.path.join(work, "series.txt"), "w") as f:
            f.write("\n".join(" ".join(x) for x in files[:20]) + "\n")
        sqlite = os.path.join(work, "h.sqlite")
        for commit, date, path in files:
            for db in (server.url(), sqlite):
                p = cavity("ingest", "--db", db, "--commit", commit, "--date", date, path)
                if p.returncode:
                    check(False, f"ingest {path} into {db.split(':')[0]}: {p.stderr.strip()}")
        again = cavity("ingest", "--db", server.url(), "--commit", files[0][0], "--date", files[0][1], files[0][2])
        check(again.returncode == 0 and "already stored" in again.stdout, f"the same file twice: {again.stdout.strip()}")
        check(server.psql("SELECT count(*) FROM runs") == str(len(files)), "one run per file in PostgreSQL")
        same_answers(server, sqlite, work)
        chart = cavity("chart", "--db", server.url(), "--pass", "ao", "--id", "1920x1080", "--out", os.path.join(work, "chart"))
        check(chart.returncode == 0 and os.path.exists(os.path.join(work, "chart/index.html")),
              f"chart from PostgreSQL: {chart.stdout.strip()} {chart.stderr.strip()}")
        kill_halfway(server, work, os.path.join(SOURCE, "tests/data/2026-11-30_h200_full_sweep.json.gz"))
        errors(server, work, files[0][2])
    finally:
        if server:
            server.stop()
        shutil.rmtree(work, ignore_errors=True)
    print(f"{len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
