"""JSON files that may be gzip-compressed, read the same way as plain ones.

Recorded runs keep their large benchmark JSON as X.json.gz (gzip -9 -n). A
file is decompressed when its name ends in .gz or its first two bytes are
gzip's magic (1f 8b), so a compressed file under a .json name reads too.
Where a name given does not exist but the same name plus .gz does (a command
in a note written before the file was compressed), that one is read.

    import cavity_json
    doc = cavity_json.load(path)          # OSError, ValueError (bad gzip, bad JSON)
    raw = cavity_json.read_bytes(path)    # the decompressed bytes

Standard library only; used by scripts/charts/charts.py (cavity_charts/) and the
table scripts beside it (sys.path: this folder).
"""
import gzip
import json
import os
import zlib

GZIP_MAGIC = b"\x1f\x8b"


class BadGzip(ValueError):
    """A file that should be gzip (its name or its first bytes say so) and is not whole."""


def resolve(path):
    """path, or path + ".gz" when only that exists."""
    path = os.fspath(path)
    if not os.path.exists(path) and os.path.isfile(path + ".gz"):
        return path + ".gz"
    return path


def is_gzip(path, head):
    return os.fspath(path).endswith(".gz") or head[:2] == GZIP_MAGIC


def read_bytes(path):
    """The file's bytes, decompressed where it is gzip. OSError when it cannot be
    read, BadGzip when it is gzip and broken."""
    path = resolve(path)
    with open(path, "rb") as f:
        raw = f.read()
    if is_gzip(path, raw):
        try:
            raw = gzip.decompress(raw)
        except (OSError, EOFError, zlib.error) as e:
            raise BadGzip(f"not a whole gzip file ({e or type(e).__name__})") from None
    return raw


def read_text(path):
    return read_bytes(path).decode("utf-8")


def load(path):
    """json.load of a plain or gzip file (OSError, BadGzip, UnicodeDecodeError or JSONDecodeError)."""
    return json.loads(read_text(path))


def merge_rounds(files):
    """One Google Benchmark document from one process per round, as `cavity
    ab` merges them: every round's iteration entries, repetition k = round k
    (files in round order), the first round's context."""
    merged = {"benchmarks": []}
    for k, f in enumerate(files):
        doc = load(f)
        merged.setdefault("context", doc.get("context", {}))
        for b in doc.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration":
                continue
            b["repetition_index"], b["repetitions"] = k, len(files)
            merged["benchmarks"].append(b)
    return merged
