#!/usr/bin/env python3
"""The ecosystem check: botsim on the public student repositories of ../shared/corpus/repos.toml.

As rustc's crater and ruff's ecosystem check do for theirs, this runs every repository of the
corpus as its entry says and writes a table of what happened against what must happen.

    corpus.py restore [--mirrors DIR] [--into DIR]
        Restores each repository's commit into DIR/<name> (default ../corpus beside the repo,
        outside it) from the bare mirrors the `fetch` tool gives (DIR/<owner>+<name>/repo, with
        or without a .git inside). Files a mirror lacks (4 MiB and more, LFS) are left out and
        counted. Restoring again keeps what is there.

    corpus.py table --json FILE [--table FILE]
        Writes the table again from a check's JSON record.

    corpus.py check [--into DIR] [--only NAME,...] [--no-speed] [--seed N] [--table FILE] [--json FILE]
        Runs `botsim board` (target/release/botsim) on each restored clone: first as committed
        (with `--param SIMULATE=1` where the top has it), checked against `first`; then with
        `args`, checked against `expect`; then, for every design that runs, `--bench` at `hw`
        timing with SIMULATE 1 and 0 (where the top has it), and `--live --speed max` for
        15 s of wall time with no page attached (its pace against real time, and the VGA
        frames it shows a second where it has VGA); and the differential check: the run of
        `expect` again under a random stimulus of the design's inputs (`--random-stimulus`,
        seeded by --seed and the repository's name) with `--check` (the default board beside
        the all-RTL board, every record compared byte for byte), and with `--cpu lockstep`
        (every KCPSM6's RTL and ISS compared every cycle). Writes the table as Markdown (default docs/ECOSYSTEM.md's
        table between its markers) and every run's words as JSON.

The corpus's code is third-party of unknown licence: nothing of it enters this repository; the
clones live outside it, and only facts (outcomes, figures, our own messages) reach the table.
"""
import argparse
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CORPUS = os.path.join(os.path.dirname(ROOT), "shared", "corpus", "repos.toml")
BOTSIM = os.environ.get("BOTSIM") or os.path.join(ROOT, "target", "release", "botsim")
MAP = os.path.join(os.path.dirname(ROOT), "shared", "reference", "maps", "world_map_part1.txt")
# Every run's budget: a design that hangs is a row, not a stuck check.
RUN_SECONDS = 600
# The end of the course's line on world_map_part1 (repos.toml's "line-end").
LINE_END = (59, 63)
TABLE_BEGIN = "<!-- ecosystem table: begin (scripts/dev/corpus.py check) -->"
TABLE_END = "<!-- ecosystem table: end -->"


def load_corpus(path):
    with open(path, "rb") as f:
        return tomllib.load(f)["repo"]


def mirror_of(mirrors, repository):
    owner, name = repository.split("/")
    base = os.path.join(mirrors, f"{owner}+{name}", "repo")
    for cand in (os.path.join(base, ".git"), base):
        if os.path.isdir(os.path.join(cand, "objects")):
            return cand
    return None


def git(mirror, *args, **kw):
    return subprocess.run(["git", "-C", mirror, *args], capture_output=True, **kw)


def restore(args):
    os.makedirs(args.into, exist_ok=True)
    for repo in load_corpus(args.corpus):
        dst = os.path.join(args.into, repo["name"])
        if os.path.isdir(dst) and os.listdir(dst):
            print(f"{repo['name']}: kept ({dst})")
            continue
        mirror = mirror_of(args.mirrors, repo["repository"])
        if mirror is None:
            print(f"{repo['name']}: no mirror of {repo['repository']} in {args.mirrors} (fetch it)")
            continue
        tree = git(mirror, "ls-tree", "-r", "-z", repo["commit"])
        if tree.returncode != 0:
            print(f"{repo['name']}: commit {repo['commit'][:10]} not in the mirror")
            continue
        entries = [e for e in tree.stdout.decode("utf-8", "surrogateescape").split("\0") if e]
        blobs = [(e.split("\t", 1)[1], e.split()[2]) for e in entries if e.split()[1] == "blob"]
        check = git(mirror, "cat-file", "--batch-check", input="\n".join(o for _, o in blobs).encode())
        missing = {line.split()[0] for line in check.stdout.decode().splitlines() if line.endswith("missing")}
        absent = [p for p, o in blobs if o in missing]
        os.makedirs(dst, exist_ok=True)
        # A temporary index of the commit, checked out into the clone: every blob the mirror
        # has is written (checkout-index goes on past the ones it lacks), symlinks and modes
        # as committed.
        index = os.path.join(args.into, f".index-{repo['name']}")
        env = {**os.environ, "GIT_INDEX_FILE": index}
        git(mirror, "read-tree", repo["commit"], env=env)
        git(mirror, f"--work-tree={dst}", "checkout-index", "-a", f"--prefix={dst}/", env=env)
        os.remove(index)
        written = sum(len(files) for _, _, files in os.walk(dst))
        ok = written == len(blobs) - len(absent)
        said = f"{len(blobs) - len(absent)} files" + (f", {len(absent)} absent from the mirror" if absent else "")
        print(f"{repo['name']}: {'restored' if ok else 'FAILED'} ({said}) into {dst}")


def run_botsim(argv, cwd=None, timeout=RUN_SECONDS):
    t = time.monotonic()
    try:
        p = subprocess.run([BOTSIM, *argv], capture_output=True, text=True, timeout=timeout, cwd=cwd)
        return p.returncode, p.stdout, p.stderr, time.monotonic() - t
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        return None, out, f"(no end within {timeout} s)", time.monotonic() - t


def error_line(stderr):
    """The first line botsim said as an error (its own words), or the last line."""
    lines = [l for l in stderr.splitlines() if l.strip()]
    for l in lines:
        if l.startswith("error") or l.startswith("botsim"):
            return l
    return lines[-1] if lines else ""


def has_simulate(stderr):
    """Whether the top has a SIMULATE parameter: botsim's refusal of --param says it has not."""
    return "has no parameter SIMULATE" not in stderr and "has no parameter `SIMULATE`" not in stderr


def base_args(clone, repo, simulate):
    a = ["board", os.path.join(clone, repo["run"])]
    if simulate is not None:
        a += ["--param", f"SIMULATE={simulate}"]
    return a


def reached(trace):
    """The first sample at which the bot stood on the line's end, from a --trace-csv file."""
    try:
        with open(trace) as f:
            rows = list(csv.DictReader(f))
    except OSError:
        return None
    return next((int(r["sample"]) for r in rows if (int(r["loc_x"]), int(r["loc_y"])) == LINE_END), None)


def outcome(repo, code, out, err, trace):
    """(verdict, words): the run against the entry's `expect`."""
    expect = repo["expect"]
    if code is None:
        return "FAIL", "hung: " + err
    if expect == "refused":
        line = error_line(err)
        if code == 0:
            return "FAIL", "ran, must be refused"
        if "panicked" in err or "RUST_BACKTRACE" in err:
            return "FAIL", "panic: " + line
        missing = [n for n in repo.get("names", []) if n not in err]
        return ("ok" if not missing else "FAIL"), line + (f" (lacks {missing})" if missing else "")
    if code != 0:
        return "FAIL", error_line(err)
    try:
        s = json.loads(out)
    except json.JSONDecodeError:
        return "FAIL", "no JSON summary"
    if expect == "line-end":
        # The bot reaches the end: some sample stands on it (a team's follower may turn back).
        end = s.get("end") or {}
        loc = (end.get("loc_x"), end.get("loc_y"))
        at = reached(trace)
        if at is not None:
            return "ok", f"reached the line's end {LINE_END} at sample {at}"
        return "FAIL", f"never on the line's end {LINE_END}; ended at {loc} after {s.get('samples')} samples"
    if "uart" in repo:
        # "type -> echo": the text typed (expect_args) comes back, in order, among what the
        # design sends (a program may echo each character with more).
        text = (s.get("uart") or {}).get("text") or ""
        rest = iter(text)
        if not all(c in rest for c in TYPED):
            return "FAIL", f"typed {TYPED!r}, the UART said {text[-80:]!r}"
        return "ok", f"typed {TYPED!r}, echoed ({repo['uart']})"
    return "ok", "ran"


# What the check types to a design whose entry says `uart`: letters no banner has.
TYPED = "QZXJ"


def expect_args(repo, trace):
    if repo["expect"] == "line-end":
        return ["--timing", "fast", "--samples", "2000", "--map", MAP, "--stop-at-line-end", "--trace-csv", trace, "--json"]
    if repo["expect"] == "runs":
        seconds = repo.get("seconds", 0.05)
        args = ["--seconds", str(seconds), "--json"]
        if "uart" in repo:
            # Typed at 80 % of the run: after the program's start (which may empty the
            # UART's buffers), with time left for the echo.
            stim = os.path.join(tempfile.gettempdir(), f"corpus-{repo['name']}-typing.txt")
            with open(stim, "w") as f:
                f.write(f"{seconds * 0.8:.4f}s uart \"{TYPED}\"\n")
            args += ["--stimulus", stim]
        return args
    return []


BENCH_RE = {
    "rtl": re.compile(r"([0-9.]+)\s*x the all-RTL board"),
    "real": re.compile(r"([0-9.]+)\s*x real time"),
    "skipped": re.compile(r"skipped ([0-9.]+) %"),
}


def bench(clone, repo, simulate):
    args = base_args(clone, repo, simulate) + repo.get("args", [])
    code, out, err, secs = run_botsim(args + ["--timing", "hw", "--bench"])
    if code != 0 and "the design has no bot" in err:
        # A design without a bot has no firmware timing to choose.
        code, out, err, secs = run_botsim(args + ["--bench"])
    text = out + err
    got = {k: (float(m.group(1)) if (m := r.search(text)) else None) for k, r in BENCH_RE.items()}
    busy = next((l.split(":", 1)[1].strip() for l in text.splitlines() if "what kept it from skipping more" in l), "")
    got["busy"] = busy
    got["ok"] = code == 0
    got["said"] = "" if code == 0 else error_line(err)
    return got


# A live run's last line: its pace and, with VGA, its frames a second.
LIVE_RE = re.compile(r"\(([0-9.]+) x real time\)(?:, \d+ samples)?(?:, \d+ VGA frames \(([0-9.]+)/s\))?")
LIVE_SECONDS = 15


def live(clone, repo, simulate):
    """`--live --speed max` for LIVE_SECONDS of wall time with no page attached, stopped as
    Ctrl-C stops it: its pace against real time, and its VGA frames a second (None without
    VGA)."""
    args = base_args(clone, repo, simulate) + repo.get("args", []) + ["--live", "--speed", "max", "--port", "0"]
    p = subprocess.Popen([BOTSIM, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        out, err = p.communicate(timeout=LIVE_SECONDS)
    except subprocess.TimeoutExpired:
        p.send_signal(signal.SIGINT)
        try:
            out, err = p.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            p.kill()
            out, err = p.communicate()
    m = LIVE_RE.search(out + err)
    if not m:
        return {"ok": False, "said": error_line(err)}
    return {"ok": True, "real": float(m.group(1)), "frames": float(m.group(2)) if m.group(2) else None}


FRAMES_SECONDS = "0.1"


def frames(clone, repo, simulate):
    """`--frames` for FRAMES_SECONDS of board time under `--bench`: the VGA frames a second
    this run simulates and writes, and the all-RTL board's, side by side."""
    out_dir = tempfile.mkdtemp(prefix=f"corpus-frames-{repo['name']}-")
    try:
        args = base_args(clone, repo, simulate) + repo.get("args", [])
        code, out, err, secs = run_botsim(args + ["--seconds", FRAMES_SECONDS, "--frames", out_dir, "--bench", "--json"])
        if code != 0:
            return {"ok": False, "said": error_line(err)}
        j = json.loads(out.strip().splitlines()[-1])
        return {"ok": True, "frames": j.get("vga_frames"), "per_s": j.get("frames_per_s"), "rtl_per_s": j.get("rtl_frames_per_s")}
    finally:
        shutil.rmtree(out_dir, ignore_errors=True)


def seed_of(seed, name):
    """The random stimulus's seed for a repository: the check's seed and its name."""
    return (seed * 1_000_003 + zlib.crc32(name.encode())) % (1 << 32)


def differential(clone, repo, simulate, seed):
    """`expect`'s run under a random stimulus, with `--check` and with `--cpu lockstep`:
    ("ok" or "DIFFERS" or "FAIL", words) for each."""
    trace = os.path.join(tempfile.gettempdir(), f"corpus-{repo['name']}-check.csv")
    args = base_args(clone, repo, simulate) + repo.get("args", []) + expect_args(repo, trace)
    args = [a for a in args if a != "--json"] + ["--random-stimulus", str(seed)]
    code, out, err, secs = run_botsim(args + ["--check"])
    said = next((l for l in err.splitlines() if re.match(r"^(\w+: )?check: ", l) and "the same run on" not in l), "")
    if code == 0 and "check: equal" in said:
        check = ["ok", said.split(", every record: ")[-1]]
    elif said:
        check = ["DIFFERS", said]
    else:
        check = ["FAIL", error_line(err)]
    code, out, err, _ = run_botsim(args + ["--cpu", "lockstep", "-q"])
    lockstep = ["ok", "every cycle equal"] if code == 0 else ["FAIL", error_line(err)]
    return {"seed": seed, "check": check, "lockstep": lockstep, "seconds": round(secs, 1)}


def check(args):
    repos = load_corpus(args.corpus)
    if args.only:
        keep = set(args.only.split(","))
        repos = [r for r in repos if r["name"] in keep]
    rows, record = [], []
    for repo in repos:
        clone = os.path.join(args.into, repo["name"])
        if not os.path.isdir(clone):
            rows.append((repo, "FAIL", "not restored", "", None))
            continue
        # First, as committed: with SIMULATE=1 where the top has it.
        code, out, err, _ = run_botsim(base_args(clone, repo, 1) + ["--seconds", "0.001"])
        simulate = 1
        if code != 0 and not has_simulate(err):
            simulate = None
            code, out, err, _ = run_botsim(base_args(clone, repo, None) + ["--seconds", "0.001"])
        first = repo.get("first")
        if first:
            lacks = [f for f in first if f not in err]
            first_verdict = "ok" if code != 0 and not lacks else "FAIL"
            first_words = error_line(err) + (f" (lacks {lacks})" if lacks else "")
        else:
            first_verdict = "ok" if (code == 0) == (repo["expect"] != "refused") else "FAIL"
            first_words = "ran" if code == 0 else error_line(err)
        # Then with its one step, against `expect`.
        trace = os.path.join(tempfile.gettempdir(), f"corpus-{repo['name']}.csv")
        code, out, err, secs = run_botsim(base_args(clone, repo, simulate) + repo.get("args", []) + expect_args(repo, trace))
        verdict, words = outcome(repo, code, out, err, trace)
        entry = {"name": repo["name"], "first": [first_verdict, first_words], "expect": [verdict, words], "seconds": round(secs, 1)}
        if verdict == "ok" and repo["expect"] != "refused" and not args.no_speed:
            entry["speed"] = {str(s): bench(clone, repo, s) for s in ([1, 0] if simulate is not None else [None])}
            entry["live"] = live(clone, repo, simulate)
            if entry["live"].get("frames") is not None:
                entry["frames"] = frames(clone, repo, simulate)
        if verdict == "ok" and repo["expect"] != "refused":
            entry["differential"] = differential(clone, repo, simulate, seed_of(args.seed, repo["name"]))
        record.append(entry)
        print(json.dumps(entry), flush=True)
    if args.merge:
        record = merged(args.merge, record)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(record, f, indent=1)
    write_table(args.table, record)


def merged(path, record):
    """An earlier run's record (`check --json`) with this run's entries in place of theirs:
    a run with --no-speed keeps the earlier speed of an entry whose verdict it confirms."""
    with open(path) as f:
        old = json.load(f)
    new = {e["name"]: e for e in record}
    out = []
    for e in old:
        n = new.pop(e["name"], None)
        if n is None:
            out.append(e)
            continue
        if "differential" not in n and "differential" in e:
            n["differential"] = e["differential"]
        if "speed" not in n and "speed" in e and n["expect"][0] == e["expect"][0] == "ok":
            n["speed"] = e["speed"]
            if "live" in e:
                n["live"] = e["live"]
            if "frames" in e:
                n["frames"] = e["frames"]
        out.append(n)
    return out + list(new.values())


def table(args):
    """The table again from a check's JSON record (`check --json`), without running."""
    with open(args.json) as f:
        write_table(args.table, json.load(f))


def fmt(v, unit=""):
    return "-" if v is None else f"{v:g}{unit}"


def write_table(path, record):
    head = "| repository | first run | expect | = all-RTL | x all-RTL (S=1 / S=0) | x real time | skipped | live `--speed max`; frames simulated | what kept it busy |\n|---|---|---|---|---|---|---|---|---|\n"
    body = ""
    for e in record:
        sp = e.get("speed", {})
        cols = []
        for key in ("rtl", "real", "skipped"):
            cols.append(" / ".join(fmt(v.get(key), "%" if key == "skipped" else "") for v in sp.values()) or "-")
        busy = "; ".join(v["busy"] for v in sp.values() if v.get("busy"))
        # Paths below the clone, as its team knows them.
        here = re.compile(r"[^\s(`']*/" + re.escape(e["name"]) + "/")
        cell = lambda p: here.sub("", f"{p[0]}: {p[1]}").replace("|", "\\|").replace("\n", " ")[:160]
        lv = e.get("live")
        if not lv:
            live_cell = "-"
        elif not lv.get("ok"):
            live_cell = "did not run: " + here.sub("", lv.get("said", "")).replace("|", "/")[:60]
        else:
            live_cell = f"{lv['real']:g} x" + (f", {lv['frames']:g} VGA frames/s" if lv.get("frames") is not None else "")
        fr = e.get("frames")
        if fr and fr.get("ok") and fr.get("per_s") is not None:
            live_cell += f"; `--frames` {fr['per_s']:.3g}/s (all-RTL {fr['rtl_per_s']:.3g}/s)"
        df = e.get("differential")
        if not df:
            same = "-"
        else:
            same = "yes" if df["check"][0] == "ok" else f"**no**: {here.sub('', df['check'][1])}"
            same += "; lock-step " + ("equal" if df["lockstep"][0] == "ok" else "**failed**: " + here.sub("", df["lockstep"][1]))
            same = same.replace("|", "/")[:200]
        body += f"| {e['name']} | {cell(e['first'])} | {cell(e['expect'])} | {same} | {cols[0]} | {cols[1]} | {cols[2]} | {live_cell} | {here.sub('', busy).replace('|', '/')[:120]} |\n"
    table = head + body
    if not os.path.exists(path):
        with open(path, "w") as f:
            f.write(f"{TABLE_BEGIN}\n{table}{TABLE_END}\n")
        return
    text = open(path).read()
    if TABLE_BEGIN in text and TABLE_END in text:
        pre, rest = text.split(TABLE_BEGIN, 1)
        _, post = rest.split(TABLE_END, 1)
        text = f"{pre}{TABLE_BEGIN}\n{table}{TABLE_END}{post}"
    else:
        text += f"\n{TABLE_BEGIN}\n{table}{TABLE_END}\n"
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--corpus", default=CORPUS)
    p.add_argument("--into", default=os.path.join(os.path.dirname(ROOT), "corpus"))
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("restore")
    r.add_argument("--mirrors", default="/work/.mirror")
    c = sub.add_parser("check")
    c.add_argument("--only")
    c.add_argument("--no-speed", action="store_true")
    c.add_argument("--seed", type=int, default=540, help="the random stimuli's seed (with each repository's name)")
    c.add_argument("--table", default=os.path.join(ROOT, "docs", "ECOSYSTEM.md"))
    c.add_argument("--json")
    c.add_argument("--merge", help="an earlier run's JSON: its entries for the repositories not run here are kept")
    t = sub.add_parser("table")
    t.add_argument("--json", required=True)
    t.add_argument("--table", default=os.path.join(ROOT, "docs", "ECOSYSTEM.md"))
    args = p.parse_args()
    {"restore": restore, "check": check, "table": table}[args.cmd](args)


if __name__ == "__main__":
    sys.exit(main())
