#!/usr/bin/env python3
"""A comment in a product source states a reason; it never quotes a
measurement. Measured figures live in the measurement notebook, one dated
folder per study, and a comment that wants them cites the study by its folder
name. This test fails a comment that quotes a percentage (a number followed by
a percent sign) or a time (a number followed by a time unit as a whole word:
ms, us, ns, s, sec, seconds, min, minutes and the like), and a comment that
names the notebook's folder or its old place under bench/. Multiplicative
factors are allowed: they state a ratio, not a reading; so is a confidence
level (a percentage followed by "interval" or "confidence", or after
"nominal", or closing a sentence after "at"), which is a choice.

Product sources are the git-tracked C++, GLSL, JavaScript, HTML, Python,
shell and CMake files outside the notebook and docs/. Comments are // and
/* */ in C-like files, <!-- --> in HTML, and # in Python, shell and CMake
(Python's docstrings count as comments too). Code and strings are not looked
at, so a format string or a unit in an identifier does not count.

    comment_rule.py               exit 0: no offence; 1: one line per offence
    comment_rule.py --self-test   checks the rule against inline examples
"""
import ast
import io
import os
import re
import subprocess
import sys
import tokenize

C_LIKE = (".cpp", ".h", ".glsl", ".js")
HASH = (".sh", ".cmake")
SUFFIXES = C_LIKE + HASH + (".py", ".html")
NOTEBOOK = "lab"  # the measurement notebook's top-level folder

NUMBER = r"(?<![\w.])\d+(?:[.,]\d+)*"
# A percentage; a digit after the sign (or an open parenthesis) is a modulo.
PERCENT = re.compile(NUMBER + r"\s?%(?!\s*[\d(])")
# A confidence level, blanked out before PERCENT looks.
LEVEL = re.compile(NUMBER + r"\s?%(?=\s+(?:[\w-]+\s+){0,2}(?:interval|confidence))"
                   r"|(?<=\bnominal )" + NUMBER + r"\s?%"
                   r"|(?<=\b[Aa]t )" + NUMBER + r"\s?%(?=[.,;:)]|$)")
TIME_UNITS = r"(?:ms|msec|us|usec|µs|ns|s|secs?|seconds?|mins?|minutes?)"
TIME = re.compile(NUMBER + r"\s?" + TIME_UNITS + r"(?!\w)")
OLD_PLACE = "bench" + "/results"  # spelled apart: this file must not name it either
PLACES = re.compile(OLD_PLACE + r"|(?<![\w-])" + NOTEBOOK + "/")


def c_comments(text):
    """(line, text) of each // and /* */ comment, skipping strings, character
    literals (a quote after a digit is a C++ digit separator) and raw strings."""
    out, i, n, line = [], 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            out.append((line, text[i + 2:end]))
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end
            out.append((line, text[i + 2:end]))
            line += text.count("\n", i, end)
            i = end + 2
        elif c == "R" and text.startswith('"', i + 1) and (i == 0 or not (text[i - 1].isalnum() and
                                                                        text[i - 1] not in "uUL8")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            end = n if end < 0 else end + len(m.group(1)) + 2
            line += text.count("\n", i, end)
            i = end
        elif c in "\"'`" and not (c == "'" and i > 0 and text[i - 1].isalnum()):
            j = i + 1
            while j < n and text[j] != c and (c == "`" or text[j] != "\n"):
                j += 2 if text[j] == "\\" else 1
            line += text.count("\n", i, min(j, n))
            i = j + 1
        else:
            i += 1
    return out


def hash_comments(text):
    """(line, text) of each # comment: a # that starts a word outside quotes
    (so that $# and ${#x} in shell are not comments). The quote state starts
    afresh on each line, which is enough for these scripts."""
    out = []
    for number, row in enumerate(text.split("\n"), 1):
        quote, i = None, 0
        while i < len(row):
            c = row[i]
            if quote:
                if c == "\\" and quote == '"':
                    i += 1
                elif c == quote:
                    quote = None
            elif c in "\"'":
                quote = c
            elif c == "#" and (i == 0 or row[i - 1].isspace()):
                out.append((number, row[i + 1:]))
                break
            i += 1
    return out


def python_comments(text):
    """(line, text) of each # comment and docstring, read by Python's own
    tokenizer and parser; the # heuristic where the file does not parse."""
    try:
        out = [(tok.start[0], tok.string[1:])
               for tok in tokenize.generate_tokens(io.StringIO(text).readline)
               if tok.type == tokenize.COMMENT]
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                body = node.body
                if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                        and isinstance(body[0].value.value, str):
                    out.append((body[0].lineno, body[0].value.value))
        return out
    except (SyntaxError, tokenize.TokenError):
        return hash_comments(text)


def html_comments(text):
    """(line, text) of each <!-- --> comment, and the C-like comments of the
    page's <script> and <style> blocks."""
    out = []
    for m in re.finditer(r"<!--(.*?)-->", text, re.S):
        out.append((text.count("\n", 0, m.start()) + 1, m.group(1)))
    for m in re.finditer(r"<(script|style)\b[^>]*>(.*?)</\1>", text, re.S | re.I):
        base = text.count("\n", 0, m.start(2))
        out += [(base + line, body) for line, body in c_comments(m.group(2))]
    return out


def comments(name, text):
    if name.endswith(C_LIKE):
        return c_comments(text)
    if name.endswith(".py"):
        return python_comments(text)
    if name.endswith(".html"):
        return html_comments(text)
    return hash_comments(text)


def offences(name, text):
    """(line, comment line) of each comment line that quotes a measured figure
    or names the notebook, in order."""
    found = set()
    for first, body in comments(name, text):
        for k, row in enumerate(body.split("\n")):
            if PERCENT.search(LEVEL.sub("", row)) or TIME.search(row) or PLACES.search(row):
                found.add((first + k, row.strip(" \t*/#")))
    return sorted(found)


def product_files(root):
    names = subprocess.run(["git", "ls-files", "-z"], cwd=root, capture_output=True, text=True,
                           check=True).stdout.split("\0")
    for name in names:
        parts = name.split("/")
        if not name or parts[0] in (NOTEBOOK, "docs") or name.endswith(".md"):
            continue
        if name.endswith(SUFFIXES) or parts[-1] == "CMakeLists.txt":
            yield name


# (file name, source, number of offending lines): a failing and a passing
# example for each pattern and each comment syntax.
EXAMPLES = [
    ("a.cpp", "int x; // the loop was 12-13% slower\n", 1),
    ("a.cpp", "int x; // the loop was 7 % slower\n", 1),
    ("a.cpp", 'printf("%d took 12%", x); // prints %s and %d\n', 0),
    ("a.cpp", "int y = i % 4; // wraps: k % (n + 1), 2 % 3\n", 0),
    ("a.cpp", "// the median's 95% distribution-free interval, nominal 95%, at 95%.\n", 0),
    ("a.cpp", "// at 5% noise; 99% of the pixels\n", 1),
    ("a.cpp", "/* one pass took\n   0.45 s on the GPU */\n", 1),
    ("a.cpp", "double max_time_s = 3; // the limit in seconds, max_time_s\n", 0),
    ("a.cpp", "// a dispatch costs 3 ms\n// and 164 s in all, 2 minutes\n", 2),
    ("a.cpp", "// 1.72x faster, 64x4 tiles, 3 samples\n", 0),
    ("a.cpp", "// see " + OLD_PLACE + "/2026-12-01_x\n", 1),
    ("a.cpp", "// see lab" "/2026-12-01_x\n", 1),
    ("a.cpp", "// (study 2026-12-01_h200_gate), a collab/ folder\n", 0),
    ("a.cpp", 'auto s = R"(// 12% )"; char c = \'"\'; int n = 1\'000; // fine\n', 0),
    ("a.glsl", "float a = 0.5; /* 20% slower on the H200 */\n", 1),
    ("a.glsl", "float a = 0.5; // the second ray's weight\n", 0),
    ("a.js", "const r = /x/; // took 30 ms\n", 1),
    ("a.js", "const s = '50%'; // half width\n", 0),
    ("a.html", "<!-- loads in 2 s -->\n<script>// 10% more\n</script>\n", 2),
    ("a.html", "<p>50%</p><!-- half width -->\n", 0),
    ("a.py", "x = 1  # took 5 sec\n", 1),
    ("a.py", 'x = "%d%%" % 5  # a percentage\n', 0),
    ("a.py", 'def f():\n    """Runs 3 minutes."""\n', 1),
    ("a.py", 's = """not a docstring: 3 s"""\n', 0),
    ("a.sh", 'echo "# 5 s" ${#x} $# # counted\n', 0),
    ("a.sh", "sleep 5  # the fleet is 9% faster\n", 1),
    ("CMakeLists.txt", "set(T 600) # waits 600 s\n", 1),
    ("CMakeLists.txt", 'set(T "#600 s") # the bundle builds the whole project\n', 0),
]


def self_test():
    bad = 0
    for name, source, want in EXAMPLES:
        got = offences(name, source)
        if len(got) != want:
            bad += 1
            print(f"self-test: {name} {source!r}: {len(got)} offences, want {want}: {got}")
    print(f"self-test: {len(EXAMPLES) - bad} of {len(EXAMPLES)} examples as expected")
    return 1 if bad else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    failures = 0
    for name in product_files(root):
        with open(os.path.join(root, name), encoding="utf-8") as f:
            text = f.read()
        for line, row in offences(name, text):
            print(f"{name}:{line}: comment quotes a measured figure: {row}")
            failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
