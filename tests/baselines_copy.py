"""Helpers for the Python tests that work on a copy of baselines/."""
import json
import os


def drop_cpu_approvals(base):
    """The CPU renderers' approved digests out of a copied baselines folder:
    a test's images must take the tolerance route (a planted defect in a
    baseline file, or new digests to approve), which an approved digest
    would skip (docs/gate.md, "Changed is a state of its own")."""
    path = os.path.join(base, "approvals.json")
    with open(path) as f:
        doc = json.load(f)
    doc["approvals"] = [a for a in doc["approvals"] if a.get("device_class") != "llvmpipe"]
    with open(path, "w") as f:
        json.dump(doc, f, indent=2)
