#!/usr/bin/env python3
"""scripts/hooks/commit-msg, as git runs it: in a scratch repository whose
core.hooksPath is scripts/hooks (what scripts/setup.sh sets), a commit with
a subject over 72 characters is refused with a line that says so, one
without a blank second line is refused, and a short subject with a body of
measurements is taken.

    commit_msg_hook.py SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile


def git(repo, *args, **kw):
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.invalid",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.invalid")
    return subprocess.run(["git", "-C", repo, *args], capture_output=True, text=True, env=env, **kw)


def main():
    hooks = os.path.join(os.path.abspath(sys.argv[1]), "scripts", "hooks")
    with tempfile.TemporaryDirectory() as repo:
        assert git(repo, "init", "-q").returncode == 0
        assert git(repo, "config", "core.hooksPath", hooks).returncode == 0
        open(os.path.join(repo, "f"), "w").write("x\n")
        assert git(repo, "add", "f").returncode == 0

        long_subject = "kernels: " + "a" * 64   # 73 characters
        r = git(repo, "commit", "-q", "-m", long_subject)
        assert r.returncode != 0, "a 73-character subject was committed"
        assert "73 characters" in r.stderr and "at most 72" in r.stderr, r.stderr
        assert git(repo, "rev-parse", "--verify", "-q", "HEAD").returncode != 0, "a commit was made"

        r = git(repo, "commit", "-q", "-F", "-", input="subject\nno blank line before the body\n")
        assert r.returncode != 0 and "line 2 must be blank" in r.stderr, r.stderr

        exact = "x" * 72
        body = "H200, Vulkan: 0.1458 ms against 0.1531 ms (-4.8%), 10 repetitions."
        r = git(repo, "commit", "-q", "-m", exact, "-m", body)
        assert r.returncode == 0, r.stderr
        log = git(repo, "log", "-1", "--format=%s%n%b").stdout
        assert log.startswith(exact + "\n") and body in log, log
    print("commit-msg hook: 3 messages judged as git runs it")


if __name__ == "__main__":
    main()
