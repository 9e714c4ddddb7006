#!/usr/bin/env python3
"""The HTTP image store against a real server: Debian's nginx with its WebDAV
module (PUT), basic authentication (a writer, and a reader who may not write)
and TLS with a certificate of our own CA. No mock: the requests go through
libcurl to nginx over a socket.

    test_store_http.py CAVITY CAVITY_RENDER SOURCE_DIR

Cases: approve with upload (PUT), store check (GET, digest verified, cache
filled), the judge fetching a class reference over HTTP, a wrong password, a
reader without write access, credentials in the URL, the server down, a
digest mismatch on the server, a half download, a damaged cache entry, TLS
refused without the CA and accepted with it. Each failure: the documented
exit code, one line, no secret in it, nothing half-written.
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

CAVITY, RENDER, SOURCE = sys.argv[1:4]
CONFIG = "^corner/alchemy/n16/b4/full/160x90/gl/compute$"
SECRET_W, SECRET_R = "w-Secret-91f", "r-Secret-37a"
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run(args, env=None, **kw):
    e = dict(os.environ)
    for k in ("CAVITY_STORE", "CAVITY_STORE_TOKEN", "CAVITY_STORE_USER", "CAVITY_STORE_PASSWORD", "CAVITY_STORE_CA",
              "CAVITY_STORE_NETRC", "CAVITY_STORE_TIMEOUT", "CAVITY_STORE_STALL"):
        e.pop(k, None)
    e["CAVITY_STORE_CACHE"] = CACHE
    e.update(env or {})
    return subprocess.run(args, env=e, capture_output=True, text=True, **kw)


def one_line(p, code, what, *needles):
    lines = p.stderr.strip().splitlines()
    ok = p.returncode == code and len(lines) == 1 and all(n in p.stderr for n in needles)
    ok = ok and SECRET_W not in p.stderr + p.stdout and SECRET_R not in p.stderr + p.stdout
    check(ok, f"{what}: exit {p.returncode} (want {code}), {len(lines)} line(s): {p.stderr.strip()[:300]}")


def cache_files():
    out = []
    for base, _, names in os.walk(CACHE):
        out += [os.path.join(base, n) for n in names]
    return sorted(out)


def stalling_server(reply):
    """A TCP server on a free port that accepts, sends `reply` and then
    nothing, holding the connection open. Returns (port, stop)."""
    import threading
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held, done = [], threading.Event()

    def serve():
        srv.settimeout(0.2)
        while not done.is_set():
            try:
                conn, _ = srv.accept()
            except OSError:
                continue
            conn.recv(65536)
            if reply:
                conn.sendall(reply)
            held.append(conn)

    threading.Thread(target=serve, daemon=True).start()

    def stop():
        done.set()
        for c in held:
            c.close()
        srv.close()
    return srv.getsockname()[1], stop


def htpasswd(path, users):
    with open(path, "w") as f:
        for user, pw in users:
            h = subprocess.run(["openssl", "passwd", "-apr1", pw], capture_output=True, text=True, check=True)
            f.write(f"{user}:{h.stdout.strip()}\n")


def start_nginx(work):
    """nginx as this user: http on one port, https on another, the objects
    under work/www/cavity, PUT only for the writer, a rate-limited alias."""
    www = os.path.join(work, "www")
    os.makedirs(os.path.join(www, "cavity"))
    htpasswd(os.path.join(work, "all.htpasswd"), [("writer", SECRET_W), ("reader", SECRET_R)])
    htpasswd(os.path.join(work, "writers.htpasswd"), [("writer", SECRET_W)])
    ca_key, ca = os.path.join(work, "ca.key"), os.path.join(work, "ca.pem")
    key, csr, cert = (os.path.join(work, n) for n in ("srv.key", "srv.csr", "srv.pem"))
    ext = os.path.join(work, "ext.cnf")
    with open(ext, "w") as f:
        f.write("subjectAltName=DNS:localhost,IP:127.0.0.1\n")
    q = dict(capture_output=True, check=True)
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", ca_key, "-out", ca,
                    "-days", "2", "-subj", "/CN=cavity test CA"], **q)
    subprocess.run(["openssl", "req", "-newkey", "rsa:2048", "-nodes", "-keyout", key, "-out", csr,
                    "-subj", "/CN=localhost"], **q)
    subprocess.run(["openssl", "x509", "-req", "-in", csr, "-CA", ca, "-CAkey", ca_key, "-CAcreateserial",
                    "-out", cert, "-days", "2", "-extfile", ext], **q)
    http, https = free_port(), free_port()
    for d in ("tmp", "logs"):
        os.makedirs(os.path.join(work, d))
    auth = f"""
            auth_basic "cavity";
            auth_basic_user_file {work}/all.htpasswd;
            limit_except GET HEAD {{
                auth_basic "cavity-write";
                auth_basic_user_file {work}/writers.htpasswd;
            }}
            dav_methods PUT;
            create_full_put_path on;
            dav_access user:rw;
            client_max_body_size 64m;"""
    # A root master would run its workers as nobody, who cannot read this
    # private folder: they run as root then (a plain user's nginx ignores it).
    user = "user root root;" if os.geteuid() == 0 else ""
    conf = f"""
{user}
daemon off;
worker_processes 1;
pid {work}/nginx.pid;
error_log {work}/logs/error.log;
events {{ worker_connections 64; }}
http {{
    access_log {work}/logs/access.log;
    client_body_temp_path {work}/tmp;
    proxy_temp_path {work}/tmp;
    fastcgi_temp_path {work}/tmp;
    uwsgi_temp_path {work}/tmp;
    scgi_temp_path {work}/tmp;
    server {{
        listen 127.0.0.1:{http};
        root {www};
        location /cavity/ {{ {auth} }}
        location /slow/ {{
            alias {www}/cavity/;
            limit_rate 4k;
        }}
    }}
    server {{
        listen 127.0.0.1:{https} ssl;
        ssl_certificate {cert};
        ssl_certificate_key {key};
        root {www};
        location /cavity/ {{ {auth} }}
    }}
}}
"""
    path = os.path.join(work, "nginx.conf")
    with open(path, "w") as f:
        f.write(conf)
    proc = subprocess.Popen(["nginx", "-p", work, "-e", os.path.join(work, "logs", "error.log"), "-c", path],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    for _ in range(100):
        try:
            socket.create_connection(("127.0.0.1", http), timeout=0.2).close()
            break
        except OSError:
            time.sleep(0.05)
    else:
        sys.exit("nginx did not start: " + proc.stderr.read().decode())
    return proc, http, https, ca, www


def main():
    global CACHE
    if not shutil.which("nginx"):
        sys.exit("nginx is not installed (scripts/setup.sh installs nginx-light)")
    work = tempfile.mkdtemp(prefix="cavity-store-")
    CACHE = os.path.join(work, "cache")
    nginx, http, https, ca, www = start_nginx(os.path.join(work, "srv"))
    try:
        cases(work, http, https, ca, www)
    finally:
        nginx.send_signal(signal.SIGQUIT)
        nginx.wait(timeout=10)
        shutil.rmtree(work, ignore_errors=True)
    print(f"test_store_http: {len(failures)} failed")
    sys.exit(1 if failures else 0)


def cases(work, http, https, ca, www):
    url = f"http://127.0.0.1:{http}/cavity"
    writer = {"CAVITY_STORE_USER": "writer", "CAVITY_STORE_PASSWORD": SECRET_W}
    reader = {"CAVITY_STORE_USER": "reader", "CAVITY_STORE_PASSWORD": SECRET_R}
    base = os.path.join(work, "baselines")
    os.makedirs(base)
    for f in ("matrices.json", "manifest.json", "budgets.json", "images", "expectations"):
        os.symlink(os.path.join(SOURCE, "baselines", f), os.path.join(base, f))
    approvals = os.path.join(base, "approvals.json")
    good, planted = os.path.join(work, "good"), os.path.join(work, "planted")
    p = run([RENDER, "--matrix", "ci", "--filter", CONFIG, "--baselines", base, "--out", good])
    check(p.returncode == 0, f"render: {p.stderr.strip()[-200:]}")

    # A reader may not write: nothing approved, nothing stored.
    p = run([CAVITY, "baselines", "approve", "--from", good, "--baselines", base, "--store", url, "--why", "t"], reader)
    one_line(p, 5, "reader PUT refused", "PUT", "HTTP 401", "may not" if "403" in p.stderr else "credentials")
    check(not os.path.exists(approvals), "reader: approvals.json not written")
    p = run([CAVITY, "baselines", "approve", "--from", good, "--baselines", base, "--store", url, "--why", "t"],
            {"CAVITY_STORE_USER": "writer", "CAVITY_STORE_PASSWORD": "wrong"})
    one_line(p, 5, "wrong password refused", "HTTP 401", "credentials")
    check(not os.path.exists(approvals), "wrong password: approvals.json not written")
    p = run([CAVITY, "baselines", "approve", "--from", good, "--baselines", base, "--why", "t",
             "--store", f"http://writer:{SECRET_W}@127.0.0.1:{http}/cavity"])
    one_line(p, 2, "credentials in the URL refused", "credentials in the URL")

    # The writer puts the three images; approvals.json names their digests.
    p = run([CAVITY, "baselines", "approve", "--from", good, "--baselines", base, "--store", url, "--why", "t"], writer)
    check(p.returncode == 0 and "3 distinct images in the store" in p.stdout, f"writer approves: {p.stdout.strip()} {p.stderr.strip()}")
    digests = [a["digest"] for a in json.load(open(approvals))["approvals"]]
    on_server = sorted(os.listdir(os.path.join(www, "cavity", "sha256")))
    check(sorted(d.split(":")[1] + ".f32z" for d in digests) == on_server, f"objects on the server: {on_server}")

    # Reading needs credentials too (any user).
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", url])
    one_line(p, 5, "anonymous GET refused", "HTTP 401")
    check(cache_files() == [], "refused GET: cache empty")
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", url], reader)
    check(p.returncode == 0 and "3 approved images" in p.stdout, f"reader checks the store: {p.stdout.strip()} {p.stderr.strip()}")
    check(len(cache_files()) == 3, f"cache filled: {cache_files()}")
    # The cache answers with the server down, and a damaged entry is fetched again.
    down = f"http://127.0.0.1:{free_port()}/cavity"
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", down], reader)
    check(p.returncode == 0, f"cached objects need no server: {p.stderr.strip()}")
    victim = cache_files()[0]
    with open(victim, "r+b") as f:
        f.seek(40)
        f.write(b"\xff\xff\xff\xff")
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", url], reader)
    check(p.returncode == 0 and len(cache_files()) == 3, "damaged cache entry fetched again")
    shutil.rmtree(CACHE)
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", down], reader)
    one_line(p, 5, "server down", "127.0.0.1")
    check(cache_files() == [], "server down: nothing cached")

    # The judge fetches the class reference over HTTP: a planted defect fails
    # by tolerance against it, the unchanged render passes by digest.
    src = open(os.path.join(SOURCE, "kernels", "ao", "alchemy", "ssao_alchemy.glsl")).read()
    edit = os.path.join(work, "planted.glsl")
    open(edit, "w").write(src.replace("dot(N, omega) - P.bias", "dot(N, omega) - 0.9 * P.bias"))
    p = run([RENDER, "--matrix", "ci", "--filter", CONFIG, "--baselines", base, "--out", planted,
             "--kernel-source", "ssao_alchemy.glsl=" + edit])
    check(p.returncode == 0, "render planted")
    out = os.path.join(work, "judged")
    p = run([CAVITY, "gate", "judge", "--baselines", base, "--store", url, "--out", out, "--quiet", planted], reader)
    gate = json.load(open(os.path.join(out, "gate.json"))) if os.path.exists(os.path.join(out, "gate.json")) else {}
    imgs = [i for r in gate.get("results", []) for i in r["images"]]
    check(p.returncode == 1 and imgs and all(i["route"] == "tolerance" and i["reference"] == "llvmpipe gl/compute"
                                             and i["baseline"].startswith("store:") for i in imgs),
          f"planted defect judged against the class reference over HTTP: exit {p.returncode} {p.stderr.strip()[-200:]}")
    check(any(not i["passed"] for i in imgs), "planted defect fails")
    report = "".join(open(os.path.join(out, n)).read() for n in ("gate.json", "summary.md", "junit.xml", "index.html"))
    check(SECRET_R not in report and SECRET_W not in report, "no credential in any report")

    # A digest mismatch on the server: the object of one digest holds another
    # image. The judge refuses (exit 6) and caches nothing.
    shutil.rmtree(CACHE)
    obj = lambda d: os.path.join(www, "cavity", "sha256", d.split(":")[1] + ".f32z")
    ao = next(a["digest"] for a in json.load(open(approvals))["approvals"] if a["image"] == "ao")
    other = next(d for d in digests if d != ao)
    saved = open(obj(ao), "rb").read()
    shutil.copy(obj(other), obj(ao))
    p = run([CAVITY, "gate", "judge", "--baselines", base, "--store", url, "--out", os.path.join(work, "j2"), "--quiet",
             planted], reader)
    one_line(p, 6, "digest mismatch", ao, "corrupt")
    check(not any(ao.split(":")[1] in f for f in cache_files()), "mismatch: not cached")
    whole = lambda d: json.load(open(os.path.join(d, "gate.json"))) if os.path.exists(os.path.join(d, "gate.json")) else {}
    g = whole(os.path.join(work, "j2"))
    check(any(r.get("verdict") == "error" and "corrupt" in r.get("error", "") for r in g.get("results", [])),
          "digest mismatch: a whole gate.json says the store's object is corrupt")
    # The store down during the judge: exit 5, one line, and a whole report
    # that says so (no half-written images without a gate.json).
    down = f"http://127.0.0.1:{free_port()}/cavity"
    shutil.rmtree(CACHE, ignore_errors=True)
    p = run([CAVITY, "gate", "judge", "--baselines", base, "--store", down, "--out", os.path.join(work, "j3"), "--quiet",
             planted], reader)
    one_line(p, 5, "store down during the judge", "127.0.0.1")
    g = whole(os.path.join(work, "j3"))
    check(g.get("results") and all(r.get("verdict") == "error" for r in g["results"]) and
          all(os.path.exists(os.path.join(work, "j3", n)) for n in ("summary.md", "index.html", "junit.xml")),
          "store down: a whole report, every configuration an error")
    open(obj(ao), "wb").write(saved)

    # A half download: the transfer stops after a second at 4 KiB/s.
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", f"http://127.0.0.1:{http}/slow"],
            {"CAVITY_STORE_TIMEOUT": "1"})
    one_line(p, 5, "half download", "CAVITY_STORE_TIMEOUT")
    leftovers = [f for f in cache_files()]
    check(leftovers == [], f"half download: nothing in the cache {leftovers}")

    # Servers that stall: one accepts and never answers, one sends 16 bytes
    # of a response and stops. Each is cut off after CAVITY_STORE_STALL
    # seconds, not the whole request's limit.
    for name, reply in (("silent", b""), ("stops after 16 bytes", b"HTTP/1.1 200 OK\r\n")):
        port, stop = stalling_server(reply[:16])
        t0 = time.monotonic()
        p = run([CAVITY, "store", "check", "--baselines", base, "--store", f"http://127.0.0.1:{port}/cavity"],
                {"CAVITY_STORE_STALL": "2"}, timeout=60)
        took = time.monotonic() - t0
        stop()
        one_line(p, 5, f"stalled server, {name}", "stalled", "CAVITY_STORE_STALL")
        check(took < 20, f"stalled server, {name}: cut off in {took:.1f} s (CAVITY_STORE_STALL=2)")
        check(cache_files() == [], f"stalled server, {name}: nothing cached")
    # Limits that are not whole seconds in range: bad input, naming the variable.
    for var, value in (("CAVITY_STORE_TIMEOUT", "abc"), ("CAVITY_STORE_TIMEOUT", "-5"), ("CAVITY_STORE_STALL", "0"),
                       ("CAVITY_STORE_STALL", "1.5")):
        p = run([CAVITY, "store", "check", "--baselines", base, "--store", url], dict(reader, **{var: value}))
        one_line(p, 2, f"{var}={value} refused", f"{var}={value}", "whole seconds")

    # TLS: refused with no CA given (no way to turn verification off), accepted with it.
    tls = f"https://localhost:{https}/cavity"
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", tls], reader)
    one_line(p, 5, "TLS certificate not trusted", "TLS", "CAVITY_STORE_CA")
    check(cache_files() == [], "TLS refused: nothing cached")
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", tls], dict(reader, CAVITY_STORE_CA=ca))
    check(p.returncode == 0, f"TLS with the CA: {p.stderr.strip()}")
    # A bearer token nginx does not know is a refused credential as well.
    shutil.rmtree(CACHE)
    p = run([CAVITY, "store", "check", "--baselines", base, "--store", url], {"CAVITY_STORE_TOKEN": SECRET_R})
    one_line(p, 5, "unknown token refused", "HTTP 401")


if __name__ == "__main__":
    main()
