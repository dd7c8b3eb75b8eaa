#!/usr/bin/env python3
"""Line and toggle coverage per RTL module from a merged Verilator coverage file.

A coverage point is identified by its module, kind, file, line, column and comment; points of
several instances of one module (the CPU in three harnesses and in `bot`) merge, and a point
counts as covered when any instance hit it. Line coverage counts Verilator's line and branch
points, toggle coverage its toggle points (one per signal bit and direction).

Usage: coverage_report.py MERGED.dat FLOORS.txt [--check] [--uncovered MODULE]
FLOORS.txt: lines "<module> <line %> <toggle %>"; --check exits 1 when a module is below.
"""
import collections
import sys


def points(path):
    """Yield (module, kind, key, count) for every point of a Verilator coverage file."""
    with open(path, encoding="latin-1") as f:
        for line in f:
            if not line.startswith("C '"):
                continue
            body, count = line[3:].rstrip("\n").rsplit("' ", 1)
            fields = dict(kv.split("\x02", 1) for kv in body.split("\x01") if "\x02" in kv)
            kind, _, module = fields.get("page", "/").partition("/")
            module = module.split("__")[0]  # parameterised copies (kcpsm6__Hz1_...) are one module
            key = (fields.get("f", ""), fields.get("l", ""), fields.get("n", ""), fields.get("o", ""))
            yield module, kind, key, int(count)


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    hit = collections.defaultdict(dict)  # (module, group) -> {key: covered}
    for module, kind, key, count in points(sys.argv[1]):
        group = "toggle" if kind == "v_toggle" else "line"
        table = hit[(module, group)]
        table[key] = table.get(key, False) or count > 0
    floors = {}
    with open(sys.argv[2]) as f:
        for line in f:
            words = line.split("#")[0].split()
            if len(words) == 3:
                floors[words[0]] = (float(words[1]), float(words[2]))
    modules = sorted({m for m, _ in hit})
    print(f"{'module':<16} {'line':>18} {'toggle':>18}   floor (line, toggle)")
    failed = []
    for m in modules:
        cells = []
        pct = {}
        for g in ("line", "toggle"):
            t = hit.get((m, g), {})
            n, c = len(t), sum(t.values())
            pct[g] = 100.0 * c / n if n else 100.0
            cells.append(f"{c:5}/{n:<5} {pct[g]:5.1f}%")
        floor = floors.get(m)
        note = f"{floor[0]:.0f}%, {floor[1]:.0f}%" if floor else "-"
        if floor and (pct["line"] < floor[0] or pct["toggle"] < floor[1]):
            failed.append(m)
            note += "  BELOW"
        print(f"{m:<16} {cells[0]:>18} {cells[1]:>18}   {note}")
    if "--uncovered" in sys.argv:
        want = sys.argv[sys.argv.index("--uncovered") + 1]
        for (m, g), t in sorted(hit.items()):
            if m == want:
                for (f, l, n, o), c in sorted(t.items()):
                    if not c:
                        print(f"  uncovered {g}: {f}:{l} {o}")
    missing = [m for m in floors if m not in modules]
    if "--check" in sys.argv and (failed or missing):
        for m in missing:
            print(f"coverage: no points for module {m}", file=sys.stderr)
        for m in failed:
            print(f"coverage: {m} is below its floor", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
