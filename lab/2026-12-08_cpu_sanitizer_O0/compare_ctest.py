"""Test time per program between two ctest logs (-j2 --output-on-failure).

    python3 compare_ctest.py before.ctest.log.gz after.ctest.log.gz test_programs.txt

test_programs.txt maps each GoogleTest test to its program (the
`--gtest_list_tests` of each, one "Suite.Test program" a line); a test with
no '.' in its name is a Python test."""
import collections
import gzip
import re
import sys


def lines(path):
    return gzip.open(path, "rt", errors="replace") if path.endswith(".gz") else open(path, errors="replace")


def load(path):
    times = {}
    for line in lines(path):
        m = re.search(r"Test\s+#\d+:\s+(\S+).*?Passed\s+([\d.]+) sec", line)
        if m:
            times[m.group(1)] = float(m.group(2))
    return times


before, after = load(sys.argv[1]), load(sys.argv[2])
program = dict(line.split() for line in open(sys.argv[3]))
groups = collections.defaultdict(lambda: [0.0, 0.0, 0])
for name in before.keys() & after.keys():
    g = groups[program.get(name, "python" if "." not in name else "other")]
    g[0] += before[name]
    g[1] += after[name]
    g[2] += 1
for name, (b, a, n) in sorted(groups.items()):
    print(f"{name:14s} {n:4d} tests  {b:7.1f} s -> {a:7.1f} s  x{a / b:.3f}")
print(f"{'all':14s} {sum(g[2] for g in groups.values()):4d} tests  "
      f"{sum(g[0] for g in groups.values()):7.1f} s -> {sum(g[1] for g in groups.values()):7.1f} s")
