#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The hostile corpus: runs every case of cases.tsv against the built artcam (CTest hostile/corpus).

Each case runs in its own empty output folder, under a memory cap (RLIMIT_AS) and a timeout,
and must:
  - end by exit, not by a signal, within the timeout (no crash, no hang);
  - exit with the expected status: "ok" is 0, a number is that status;
  - on a refusal: print 1 to 3 lines on stderr (libpng's own "libpng ..." line aside), holding
    every expected fragment, and peak under 200 MiB of memory;
  - on success: satisfy every listed property of its outputs;
  - never show the standard library's internals (std::, bad_alloc, basic_string, vector::) nor
    a nan or inf as a number, on stdout or stderr;
  - leave every input byte for byte as it was, nothing new among the inputs, and no atomic
    save temporary anywhere.

cases.tsv and cases-<area>.tsv: one case per line, tab-separated: id, class, expect (ok | exit status), checks
(';'-separated; for a refusal, fragments stderr must hold; for ok: exists:P, image:P:WxHxC,
opaque:P, stdout:TEXT, stderr:TEXT, lines:P:N), command (artcam's arguments, shell-quoted).
Placeholders: {F} the generated inputs (make_files.py), {O} the case's output folder, {R} the
repository's resources/. Lines starting with # are comments.

Cases run one at a time unless --jobs N (or ARTCAM_HOSTILE_JOBS) says more: CI's sanitizer
job runs two, the normal test run one (CTest already runs other suites beside it).

usage: run_cases.py ARTCAM WORK_DIR [--only ID_REGEX] [--show] [--jobs N]
"""
import argparse
import collections
import concurrent.futures
import hashlib
import os
import re
import resource
import shlex
import shutil
import subprocess
import sys
import threading
import time

here = os.path.dirname(os.path.abspath(__file__))
repo = os.path.dirname(os.path.dirname(here))
parser = argparse.ArgumentParser()
parser.add_argument("artcam")
parser.add_argument("work")
parser.add_argument("--only", default="")
parser.add_argument("--show", action="store_true", help="print every case's outcome")
parser.add_argument("--jobs", type=int, default=int(os.environ.get("ARTCAM_HOSTILE_JOBS", "1")),
                    help="cases run at once")
opts = parser.parse_args()
opts.artcam = os.path.abspath(opts.artcam)

MEMORY_CAP = 1 << 30  # RLIMIT_AS: a run that tries to take more meets bad_alloc, not the OOM killer
REFUSAL_PEAK_MIB = 200
# Under a sanitizer (CI's ASan+UBSan tree, packaging/ci-sanitizers.sh) the shadow memory needs
# terabytes of address space and inflates every peak: no RLIMIT_AS and no peak assertion there;
# a sanitizer report makes the run exit with the sanitizer's status, which no case expects.
SANITIZED = os.environ.get("ARTCAM_HOSTILE_SANITIZED") == "1"
TIMEOUT_S = 120 if os.environ.get("ARTCAM_HOSTILE_SANITIZED") == "1" else 60
BANNED = re.compile(r"std::|bad_alloc|basic_string|vector::|length_error|(?<![\w.-])-?(nan|inf)(?![\w])",
                    re.IGNORECASE)
TEMPORARY = re.compile(r"^\..*\.tmp-\d+-\d+")

files = os.path.join(opts.work, "files")
outs = os.path.join(opts.work, "out")
shutil.rmtree(opts.work, ignore_errors=True)
subprocess.run([sys.executable, os.path.join(here, "make_files.py"), files,
                os.path.join(repo, "resources"), opts.artcam], check=True)
resources_dir = os.path.join(repo, "resources")


def snapshot(root):
    state = {}
    for folder, _, names in os.walk(root):
        for name in names:
            path = os.path.join(folder, name)
            if os.path.islink(path):
                state[path] = "link:" + os.readlink(path)
                continue
            if not os.path.isfile(path):  # a named pipe: opening it would wait for a writer
                state[path] = "special"
                continue
            with open(path, "rb") as f:
                state[path] = hashlib.sha256(f.read()).hexdigest()
    return state


def temporaries(root):
    found = []
    for folder, _, names in os.walk(root):
        found += [os.path.join(folder, n) for n in names if TEMPORARY.match(n)]
    return found


def image_info(path):
    r = subprocess.run(["oiiotool", "--info", "-v", path], capture_output=True, text=True)
    m = re.search(r"(\d+)\s*x\s*(\d+), (\d+) channel", r.stdout)
    return (int(m.group(1)), int(m.group(2)), int(m.group(3))) if m else None


def mean_alpha(path):
    # oiiotool prints per-channel averages; the last channel of a 2- or 4-channel image is alpha.
    r = subprocess.run(["oiiotool", path, "--printstats"], capture_output=True, text=True)
    m = re.search(r"Stats Avg:\s*([^\n]*)", r.stdout)
    if not m:
        return None
    values = [float(v) for v in m.group(1).split() if re.match(r"^-?[\d.e+-]+$", v)]
    return values[-1] if values and len(values) in (2, 4) else 1.0


# No core files from any case (inherited by every child). The address-space cap is set by
# prlimit(1) around the one command rather than in a preexec_fn, which is unsafe once cases
# run on several threads.
resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
LIMIT = [] if SANITIZED else ["prlimit", "--as=%d" % MEMORY_CAP, "--"]


def expand(text, out_dir):
    return text.replace("{F}", files).replace("{O}", out_dir).replace("{R}", resources_dir)


def run_case(case_id, expect, checks, command):
    out_dir = os.path.join(outs, case_id)
    os.makedirs(out_dir)
    argv = [expand(a, out_dir) for a in shlex.split(command)]
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", LC_ALL="C")
    # Leading NAME=VALUE words set the environment (a raised ARTCAM_MAX_MEMORY_MB lets a size
    # past the budget check reach the allocation, which RLIMIT_AS then refuses).
    while argv and re.match(r"^[A-Z_]+=", argv[0]):
        name, _, value = argv.pop(0).partition("=")
        env[name] = value
    before = snapshot(files)
    start = time.monotonic()
    proc = subprocess.Popen(LIMIT + [opts.artcam] + argv, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, env=env, cwd=out_dir)
    # Pipes drained by threads, the child reaped by wait4 for its own peak RSS.
    chunks = {"out": b"", "err": b""}

    def drain(stream, key):
        chunks[key] = stream.read()

    readers = [threading.Thread(target=drain, args=(proc.stdout, "out")),
               threading.Thread(target=drain, args=(proc.stderr, "err"))]
    for t in readers:
        t.start()
    timer = threading.Timer(TIMEOUT_S, proc.kill)
    timer.start()
    _, wait_status, usage = os.wait4(proc.pid, 0)
    timer.cancel()
    for t in readers:
        t.join()
    proc.returncode = 0  # reaped here; keeps Popen from waiting on a pid that is gone
    seconds = time.monotonic() - start
    if seconds >= TIMEOUT_S:
        return ["hang: no exit within %d s" % TIMEOUT_S], {}
    status = (os.WEXITSTATUS(wait_status) if os.WIFEXITED(wait_status)
              else -os.WTERMSIG(wait_status))
    peak_mib = usage.ru_maxrss / 1024
    stdout, stderr = chunks["out"], chunks["err"]
    out_text = stdout.decode("utf-8", "replace")
    err_text = stderr.decode("utf-8", "replace")
    problems = []
    if status < 0:
        problems.append("killed by signal %d" % -status)
    want = 0 if expect == "ok" else int(expect)
    if status != want:
        problems.append("exit %d, expected %d" % (status, want))
    # Names of the case's own files are not text the program made: mask them before looking
    # for nan/inf (a file may be called m-nan.csv).
    masked_err, masked_out = err_text, out_text
    for a in sorted(argv, key=len, reverse=True):
        for name in (a, os.path.basename(a)):
            if len(name) > 2:
                masked_err = masked_err.replace(name, "FILE")
                masked_out = masked_out.replace(name, "FILE")
    # A quoted value is the user's own text echoed back ("nan" in a CSV cell), not ours.
    quoted = re.compile(r'"[^"\n]*"')
    bad = BANNED.search(quoted.sub("Q", masked_err)) or BANNED.search(quoted.sub("Q", masked_out))
    if bad:
        problems.append("shows %r" % bad.group(0))
    lines = [l for l in err_text.splitlines() if l.strip() and not l.startswith("libpng ")]
    if expect != "ok":
        if not 1 <= len(lines) <= 3:
            problems.append("%d stderr lines, expected 1 to 3" % len(lines))
        for fragment in filter(None, checks.split(";")):
            if expand(fragment, out_dir) not in err_text:
                problems.append("stderr lacks %r" % fragment)
    else:
        for check in filter(None, checks.split(";")):
            kind, _, rest = check.partition(":")
            rest = expand(rest, out_dir)
            if kind == "exists" and not (os.path.isfile(rest) and os.path.getsize(rest) > 0):
                problems.append("no output %s" % rest)
            elif kind == "image":
                path, _, shape = rest.rpartition(":")
                got = image_info(path)
                if got is None or "%dx%dx%d" % got != shape:
                    problems.append("%s is %s, expected %s" % (path, got, shape))
            elif kind == "opaque":
                alpha = mean_alpha(rest)
                if alpha is None or alpha < 0.5:
                    problems.append("%s mean alpha %s: mostly transparent" % (rest, alpha))
            elif kind == "stdout" and rest not in out_text:
                problems.append("stdout lacks %r" % rest)
            elif kind == "stderr" and rest not in err_text:
                problems.append("stderr lacks %r" % rest)
            elif kind == "lines":
                path, _, n = rest.rpartition(":")
                if not os.path.isfile(path) or len(open(path).read().splitlines()) != int(n):
                    problems.append("%s does not have %s lines" % (path, n))
    after = snapshot(files)
    changed = [p for p in before if before[p] != after.get(p)]
    added = [p for p in after if p not in before]
    if changed:
        problems.append("inputs changed: %s" % ", ".join(os.path.basename(p) for p in changed))
    if added:
        problems.append("written among the inputs: %s" % ", ".join(added))
    stray = temporaries(out_dir) + temporaries(files)
    if stray:
        problems.append("temporaries left: %s" % ", ".join(stray))
    return problems, {"status": status, "err": err_text.strip(), "out": out_text.strip()[:300],
                      "peak_mib": peak_mib, "seconds": seconds}


# cases.tsv, then every cases-<area>.tsv beside it (one file per area keeps additions apart).
cases = []
case_files = ["cases.tsv"] + sorted(n for n in os.listdir(here)
                                    if n.startswith("cases-") and n.endswith(".tsv"))
for case_file in case_files:
    with open(os.path.join(here, case_file)) as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.split("\t")
            if len(fields) != 5:
                sys.exit("%s:%d: %d fields, expected 5 (id, class, expect, checks, command)"
                         % (case_file, number, len(fields)))
            cases.append(fields)
ids = collections.Counter(c[0] for c in cases)
duplicates = [i for i, n in ids.items() if n > 1]
if duplicates:
    sys.exit("%s: duplicate ids %s" % (", ".join(case_files), ", ".join(duplicates)))

os.makedirs(outs)
failed = []
totals = collections.defaultdict(lambda: collections.Counter())
peak_refusal = 0.0
chosen = []
for case in cases:
    case_id, command = case[0], case[4]
    if opts.only and not re.search(opts.only, case_id):
        continue
    # Without RLIMIT_AS (sanitized runs) a case that relies on it would really allocate.
    if SANITIZED and re.match(r"^[A-Z_]+=", command):
        print("skip %s: needs RLIMIT_AS, which sanitizers cannot run under" % case_id)
        continue
    chosen.append(case)
with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, opts.jobs)) as pool:
    outcomes = list(pool.map(lambda c: run_case(c[0], c[2], c[3], c[4]), chosen))
for (case_id, klass, expect, checks, command), (problems, result) in zip(chosen, outcomes):
    if expect != "ok" and result and result["peak_mib"] > REFUSAL_PEAK_MIB and not SANITIZED:
        problems.append("refusal peaked at %.0f MiB (cap %d)" % (result["peak_mib"],
                                                                 REFUSAL_PEAK_MIB))
    if expect != "ok" and result:
        peak_refusal = max(peak_refusal, result["peak_mib"])
    totals[klass]["cases"] += 1
    totals[klass]["refused" if expect != "ok" else "accepted"] += 1
    if problems:
        totals[klass]["failed"] += 1
        failed.append(case_id)
    if opts.show or problems:
        print("%s %s [%s] exit %s, %.2f s" % ("FAIL" if problems else "ok  ", case_id, klass,
                                             result.get("status", "-"), result.get("seconds", 0)))
        for p in problems:
            print("    - " + p)
        if result.get("err"):
            print("    stderr: " + result["err"].replace("\n", "\n            "))

print("\nclass        cases  refused  accepted  failed")
grand = collections.Counter()
for klass in sorted(totals):
    t = totals[klass]
    grand.update(t)
    print("%-12s %5d  %7d  %8d  %6d" % (klass, t["cases"], t["refused"], t["accepted"], t["failed"]))
print("%-12s %5d  %7d  %8d  %6d" % ("total", grand["cases"], grand["refused"], grand["accepted"],
                                    grand["failed"]))
print("largest peak of a refusal: %.0f MiB" % peak_refusal)
if failed:
    print("FAILED: " + " ".join(failed))
    sys.exit(1)
