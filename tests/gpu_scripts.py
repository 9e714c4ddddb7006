#!/usr/bin/env python3
"""The GPU machine's scripts (docs/gpu.md, docs/history.md), dry-run on the
CPU renderers as a user's device call runs them: from a repository root with
the bundle in .bundle/, each on one small configuration. Each must finish
with exit 0 and leave in $OUT what the docs say comes back, and what it
leaves must be what a later step reads: the render folder parts join into a
folder `cavity gate judge` judges, the approvals name the rendered
configurations, the history bundle's runs ingest into a database and a chart.

    gpu_scripts.py SOURCE_DIR BUILD_DIR

On a machine without nvidia-smi, scripts/gpu_env.sh leaves the system's
loaders as they are, so llvmpipe and lavapipe render.
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from baselines_copy import drop_cpu_approvals  # noqa: E402

# One small configuration: a screen-space kernel at the ci matrix's size.
ONE = "^corner/alchemy/n8/b0/full/160x90/vk/"


def run(cmd, cwd, env, timeout=600):
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0:
        raise AssertionError(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r


def git(repo, *args):
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.invalid",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.invalid")
    return run(["git", "-c", "core.hooksPath=/dev/null", *args], repo, env).stdout.strip()


def fresh_out(root, name):
    out = os.path.join(root, "out", name)
    os.makedirs(out)
    return out


def main():
    source, build = (os.path.abspath(p) for p in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as root:
        # The repository as the device tool lays it: scripts and baselines,
        # plus the bundle. A copy of baselines/: the scripts write approvals.
        os.symlink(os.path.join(source, "scripts"), os.path.join(root, "scripts"))
        os.symlink(os.path.join(source, "kernels"), os.path.join(root, "kernels"))
        shutil.copytree(os.path.join(source, "baselines"), os.path.join(root, "baselines"))
        drop_cpu_approvals(os.path.join(root, "baselines"))
        env = dict(os.environ, BUILD_DIR=build, BUNDLE_XZ="0", BUNDLE_MAX_MIB="4096",
                   BUNDLE_BINARIES="cavity_bench cavity_render cavity")
        run([os.path.join(source, "scripts", "bundle.sh"), os.path.join(root, ".bundle")], source, env)
        drop_cpu_approvals(os.path.join(root, ".bundle", "baselines"))
        # xz at its fastest preset: the history bundle's tar -J of two
        # sanitizer builds took half this test's time at the default.
        env = dict(os.environ, XZ_OPT="-0")

        # planted_defects.sh: the defect list the store run reads.
        defects = os.path.join(root, "defects")
        run(["scripts/planted_defects.sh", defects], root, env)
        names = [line.split()[0] for line in open(os.path.join(defects, "list.txt"))]
        assert len(names) >= 8, names

        # gpu_render.sh: the render folder in parts, joined and judged here.
        out = fresh_out(root, "render")
        run(["scripts/gpu_render.sh", "--matrix", "ci", "--filter", ONE], root, dict(env, OUT=out))
        parts = sorted(glob.glob(os.path.join(out, "render.tar.*")))
        assert parts, os.listdir(out)
        joined = os.path.join(root, "render.tar")
        with open(joined, "wb") as w:
            for p in parts:
                w.write(open(p, "rb").read())
        with tarfile.open(joined) as t:
            t.extractall(os.path.join(root, "back"))
        manifest = json.load(open(os.path.join(root, "back", "render", "manifest.json")))
        assert manifest, "an empty manifest"
        run([os.path.join(build, "harness", "cavity"), "gate", "judge", os.path.join(root, "back", "render"),
             "--baselines", os.path.join(root, "baselines"), "--out", os.path.join(root, "judged"), "--quiet"],
            root, env)

        # gpu_references.sh: approvals for what it rendered, then a clean render judged by digest.
        out = fresh_out(root, "references")
        run(["scripts/gpu_references.sh", "ci", "0", ONE], root, dict(env, OUT=out))
        approvals = open(os.path.join(out, "approvals.json")).read()
        assert "corner/alchemy/n8/b0/full/160x90/vk" in approvals, approvals[:500]
        gate = json.load(open(os.path.join(out, "gate1.json")))
        assert gate, "an empty gate.json"

        # gpu_store_run.sh: references into a folder store, the planted defects judged against them.
        out = fresh_out(root, "store")
        run(["scripts/gpu_store_run.sh", "ci", "vk", defects], root,
            dict(env, OUT=out, FILTER="^corner/alchemy_fast/n16/b4/full/160x90/", CLEAN="0"))
        with tarfile.open(os.path.join(out, "results.tgz")) as t:
            got = t.getnames()
        assert any(n.endswith("approvals.json") for n in got), got
        assert any("planted/" in n for n in got), got

        # gpu_sweep.sh: one benchmark of the gpu sweep.
        out = fresh_out(root, "sweep")
        listed = run([os.path.join(root, ".bundle", "run.sh"), "--sweep", "gpu", "--benchmark_list_tests"],
                     root, env).stdout.split()
        # The sweep's smallest Vulkan configuration: a software renderer takes
        # seconds a frame at 1920x1080.
        one = next(n for n in listed if "/320x180/vk/compute" in n)
        run(["scripts/gpu_sweep.sh", f"--benchmark_filter=^{one}$", "--max-time", "0.01"], root, dict(env, OUT=out))
        sweep = json.load(open(os.path.join(out, "gpu_sweep.json")))
        assert any(b["name"].startswith(one) for b in sweep["benchmarks"]), [b["name"] for b in sweep["benchmarks"]]

        # history_bundle.sh, gpu_history.sh, history_ingest.sh: two commits of a scratch
        # repository, their builds already in the cache (the current cavity_bench for both),
        # measured, ingested and charted.
        repo = os.path.join(root, "repo")
        os.makedirs(repo)
        os.symlink(os.path.join(source, "scripts"), os.path.join(repo, "scripts"))
        git(repo, "init", "-q")
        commits = []
        for i in range(2):
            open(os.path.join(repo, "f"), "w").write(f"{i}\n")
            git(repo, "add", "f")
            git(repo, "commit", "-q", "-m", f"commit {i}")
            commits.append(git(repo, "rev-parse", "HEAD"))
        os.makedirs(os.path.join(repo, ".history-builds", "worktree"))
        os.makedirs(os.path.join(repo, ".history-builds", "bin"))
        for c in commits:
            shutil.copy(os.path.join(build, "bench", "cavity_bench"), os.path.join(repo, ".history-builds", "bin", c[:12]))
        bundle = os.path.join(root, "history.tar.xz")
        run(["scripts/history_bundle.sh", bundle, *commits], repo, env)
        out = fresh_out(root, "history")
        run(["scripts/gpu_history.sh", bundle, "1", "0.01", f"^{one}$"], repo, dict(env, OUT=out))
        came = os.path.join(root, "history_back")
        with tarfile.open(os.path.join(out, "history.tgz")) as t:
            t.extractall(came)
        for c in commits:
            assert os.path.isfile(os.path.join(came, c[:12] + ".json")), os.listdir(came)
        db = os.path.join(root, "history.sqlite")
        run(["scripts/history_ingest.sh", came, db, os.path.join(root, "chart")], repo,
            dict(env, CAVITY=os.path.join(build, "harness", "cavity")))
        assert os.path.isfile(os.path.join(root, "chart", "index.html")), os.listdir(os.path.join(root, "chart"))
        shown = open(os.path.join(came, "show.txt")).read()
        assert commits[0][:7] in shown or commits[1][:7] in shown, shown[:1000]
    print("gpu scripts: bundle, planted_defects, gpu_render, gpu_references, gpu_store_run, gpu_sweep, "
          "history_bundle, gpu_history, history_ingest: dry runs passed")


if __name__ == "__main__":
    main()
