#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Every fenced code block of the user documentation, run or checked (CTest docs/code_blocks).

usage: run_doc_blocks.py REPO_ROOT ARTCAM_DIR [--only FILE] [--keep] [--verbose] [--python PATH]

REPO_ROOT is the checkout; ARTCAM_DIR the folder holding the built `artcam` (the build's app/).
The files: README.md, docs/user-guide.md, docs/python.md, docs/performance.md,
docs/robustness.md. Each fenced
block's language (the word after the opening fence) says what happens to it:

  sh       run. The blocks of one file run in order, each as `bash -euo pipefail BLOCK` with
           standard input empty, all in one temporary folder per file that holds a copy of the
           repository's resources/ (so a block says `resources/coffee.png` as a user in a
           checkout would, and nothing a block writes reaches the checkout). PATH starts with
           ARTCAM_DIR. A block passes when it exits 0 within 120 s.
  python   run the same way with /usr/bin/python3 (or --python). When a module it imports is
           not installed the block is skipped, saying which module and Debian package; with
           ARTCAM_DOCS_STRICT=1 in the environment a skip is a failure.
  install, studio, long
           not run (they install packages, open the GUI, or take minutes); every command in
           them is checked instead. Commands are split at ; && || | and newlines; VAR=value
           prefixes, sudo and setarch [ARCH] -R are looked through to the command they run:
             apt-get/apt install|remove NAME: NAME is a package of packaging/install-deps.sh
               (or the project's own package); a .deb is one packaging/build-deb.sh writes
               (./build-deb/...); apt-get update passes;
             bash/sh/python3 SCRIPT, or a command written as a path (fuzz/run_fuzzers.sh): the
               script exists in the checkout (a path under a build*/ folder is checked as the
               program it names);
             cmake: every -D variable is CMAKE_* or one the project's CMake files declare
               (option() or a cache variable), -S names a folder of the checkout; -B folders
               are remembered for cd; ctest passes;
             cd DIR: DIR is a folder of the checkout or a build folder named before;
             artcam SUB ...: `artcam SUB --help` exits 0 (artcam --help/--version pass);
             artcam-studio ARGS: every argument that is not an option is an existing file;
             man PAGE: docs/man/PAGE.1 exists.
           Any other command is a failure: a block cannot escape by using one.
  console, text
           output or prose; not run, not counted.

Any other language, or a fence without one, is a failure; so is a top-level indented code
block (four spaces after a blank line, outside a list), which would escape the fences.
A failure prints the block's file:line, why, and its stderr. The last line is
"N passed, N failed"; the exit status is 1 when anything failed.
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

DOC_FILES = ["README.md", "docs/user-guide.md", "docs/python.md", "docs/performance.md",
             "docs/robustness.md"]
RUN_LANGS = {"sh", "python"}
CHECK_LANGS = {"install", "studio", "long"}
PROSE_LANGS = {"console", "text"}
BLOCK_TIMEOUT_S = 120
# Debian packages of the modules a python block may import, for the skip message.
PY_PACKAGES = {"numpy": "python3-numpy", "OpenImageIO": "python3-openimageio", "cv2": "python3-opencv",
               "artcam": "artcam-studio (a build's python/ folder)",
               "distributed": "python3-distributed"}

FENCE_OPEN = re.compile(r"^( {0,3}|\s*)(`{3,}|~{3,})\s*([^\s`]*)\s*$")
LIST_ITEM = re.compile(r"^\s*([-*+]|\d+[.)])\s")


class Block:
    def __init__(self, path, line, lang, text):
        self.path, self.line, self.lang, self.text = path, line, lang, text

    def where(self):
        return "%s:%d" % (self.path, self.line)


def parse_blocks(rel, text):
    """The fenced blocks of one file, and the problems of its fences."""
    blocks, problems = [], []
    lines = text.split("\n")
    i = 0
    prev_blank = True
    last_text = ""  # the last non-blank line outside a fence
    while i < len(lines):
        line = lines[i]
        m = FENCE_OPEN.match(line)
        if m:
            indent, fence, lang = len(m.group(1)), m.group(2), m.group(3)
            body, j = [], i + 1
            close = re.compile(r"^\s*" + re.escape(fence[0]) + "{%d,}\\s*$" % len(fence))
            while j < len(lines) and not close.match(lines[j]):
                body.append(lines[j][indent:] if lines[j][:indent].strip() == "" else lines[j])
                j += 1
            if j == len(lines):
                problems.append(("%s:%d" % (rel, i + 1), "fence never closed"))
            blocks.append(Block(rel, i + 1, lang, "\n".join(body) + "\n"))
            i = j + 1
            prev_blank, last_text = False, line
            continue
        if line.strip() == "":
            prev_blank = True
        else:
            indented = line.startswith("    ") or line.startswith("\t")
            in_list = LIST_ITEM.match(last_text) or last_text.startswith(" ")
            if indented and prev_blank and not in_list:
                problems.append(("%s:%d" % (rel, i + 1),
                                 "indented code block: put it in a fence with a language"))
            prev_blank, last_text = False, line
        i += 1
    return blocks, problems


def install_deps_packages(root):
    """Every package packaging/install-deps.sh can install (both of its lists)."""
    text = open(os.path.join(root, "packaging/install-deps.sh"), encoding="utf-8").read()
    text = re.sub(r"(^|\s)#.*", r"\1", text)  # comments may hold parentheses
    names = set()
    for m in re.finditer(r"packages\+?=\((.*?)\)", text, re.S):
        names.update(m.group(1).split())
    return names


def project_package(root):
    text = open(os.path.join(root, "cmake/Packaging.cmake"), encoding="utf-8").read()
    m = re.search(r"CPACK_PACKAGE_NAME\s+\"?([A-Za-z0-9.+-]+)", text)
    return m.group(1) if m else "artcam-studio"


def cmake_variables(root):
    """Variables the project's CMake files declare: option(NAME ...) or set(NAME ... CACHE ...)."""
    names = set()
    for base, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if not d.startswith((".", "build"))]
        for f in files:
            if f == "CMakeLists.txt" or f.endswith(".cmake"):
                try:
                    text = open(os.path.join(base, f), encoding="utf-8").read()
                except (OSError, UnicodeDecodeError):
                    continue
                names.update(re.findall(r"\boption\(\s*([A-Za-z0-9_]+)", text))
                names.update(re.findall(r"\bset\(\s*([A-Za-z0-9_]+)[^)]*\bCACHE\b", text))
    return names


def unwrap(words):
    """The command a line runs, after VAR=value prefixes and the wrappers sudo and
    setarch [ARCH] -R (which run the rest of the line as a command)."""
    while True:
        while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0]):
            words = words[1:]
        if words and words[0] == "sudo":
            words = words[1:]
        elif words and words[0] == "setarch":
            words = words[1:]
            while words and (words[0].startswith("-") or words[0] in ("x86_64", "i386", "i686")):
                words = words[1:]
        else:
            return words


class Checker:
    """The static checks of install/studio/long blocks."""

    def __init__(self, root, artcam_dir):
        self.root, self.artcam_dir = root, artcam_dir
        self.packages = install_deps_packages(root)
        self.own_package = project_package(root)
        self.cmake_vars = cmake_variables(root)
        self.help_ok = {}

    def artcam_sub(self, sub):
        if sub not in self.help_ok:
            exe = os.path.join(self.artcam_dir, "artcam")
            r = subprocess.run([exe, sub, "--help"], stdin=subprocess.DEVNULL,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            self.help_ok[sub] = r.returncode == 0
        return self.help_ok[sub]

    def exists(self, rel):
        return os.path.exists(os.path.join(self.root, rel))

    def commands(self, text):
        """The simple commands of a block: lists of words, split at ; && || | and newlines."""
        joined = re.sub(r"\\\n", " ", text)
        out = []
        for line in joined.split("\n"):
            lex = shlex.shlex(line, posix=True, punctuation_chars=";&|<>()")
            lex.whitespace_split = True
            cmd, skip_next = [], False
            for tok in lex:
                if skip_next:
                    skip_next = False
                    continue
                if tok and all(c in ";&|()" for c in tok):
                    if cmd:
                        out.append(cmd)
                    cmd = []
                elif tok and all(c in "<>&" for c in tok):
                    skip_next = True  # a redirection's file
                else:
                    cmd.append(tok)
            if cmd:
                out.append(cmd)
        return out

    def check(self, block):
        """A list of problems (empty: the block passes)."""
        problems, build_dirs = [], set()
        for words in self.commands(block.text):
            words = unwrap(words)
            if not words:
                continue
            problems += self.check_command(words, build_dirs)
        return problems

    def check_command(self, words, build_dirs):
        cmd, args = words[0], words[1:]
        plain = [a for a in args if not a.startswith("-")]
        shown = " ".join(words)
        if "/" in cmd:
            first = cmd.split("/", 1)[0]
            if first.startswith("build"):
                return self.check_command([os.path.basename(cmd)] + args, build_dirs)
            return [] if self.exists(cmd) else ["%s: no such script in the checkout" % cmd]
        if cmd in ("apt-get", "apt"):
            if not plain:
                return ["%s: no subcommand" % shown]
            sub, names = plain[0], plain[1:]
            if sub == "update":
                return []
            if sub not in ("install", "remove", "purge"):
                return ["%s: apt subcommand %s has no check" % (shown, sub)]
            problems = []
            for n in names:
                if n.endswith(".deb"):
                    if not (n.startswith("./build-deb/") and self.exists("packaging/build-deb.sh")):
                        problems.append("%s: not a package packaging/build-deb.sh writes" % n)
                elif n not in self.packages and n != self.own_package:
                    problems.append("%s: not in packaging/install-deps.sh" % n)
            if not names:
                problems.append("%s: names no package" % shown)
            return problems
        if cmd in ("bash", "sh", "python3"):
            if not plain:
                return ["%s: names no script" % shown]
            return [] if self.exists(plain[0]) else ["%s: no such script" % plain[0]]
        if cmd == "cmake":
            problems = []
            for k, a in enumerate(args):
                var = None
                if a.startswith("-D"):
                    var = (a[2:] if len(a) > 2 else (args[k + 1] if k + 1 < len(args) else ""))
                    var = var.split("=", 1)[0].split(":", 1)[0]
                if var is not None and not var.startswith("CMAKE_") and var not in self.cmake_vars:
                    problems.append("cmake -D%s: no such option in the project's CMake files" % var)
                if a == "-S" and k + 1 < len(args) and not os.path.isdir(
                        os.path.join(self.root, args[k + 1])):
                    problems.append("cmake -S %s: no such folder" % args[k + 1])
                if a in ("-B", "--build", "--install") and k + 1 < len(args):
                    build_dirs.add(args[k + 1])
            return problems
        if cmd == "ctest":
            return []
        if cmd == "cd":
            d = plain[0] if plain else ""
            if d in build_dirs or d.startswith("build") or os.path.isdir(os.path.join(self.root, d)):
                return []
            return ["cd %s: no such folder, nor a build folder named before" % d]
        if cmd == "artcam":
            if not plain or args[0].startswith("-"):
                return [] if args and args[0] in ("--help", "-h", "--version") else [
                    "%s: no subcommand" % shown]
            return [] if self.artcam_sub(args[0]) else ["artcam %s: not a subcommand" % args[0]]
        if cmd == "artcam-studio":
            return ["artcam-studio %s: no such file" % a for a in plain if not self.exists(a)]
        if cmd == "dask":
            # dask.distributed's own command line (the cluster pages): python3-distributed.
            if "python3-distributed" not in self.packages:
                return ["%s: python3-distributed is not in packaging/install-deps.sh" % shown]
            return [] if plain and plain[0] in ("scheduler", "worker", "ssh") else [
                "%s: dask subcommand %s has no check" % (shown, plain[0] if plain else "")]
        if cmd == "man":
            return [] if plain and self.exists("docs/man/%s.1" % plain[-1]) else [
                "%s: no such manual page in docs/man" % shown]
        return ["%s: no check for the command %s in a not-run block" % (shown, cmd)]


def python_imports(text):
    mods = set()
    for m in re.finditer(r"^\s*(?:import|from)\s+([A-Za-z_][A-Za-z0-9_]*)", text, re.M):
        mods.add(m.group(1))
    return sorted(mods)


def tail(text, n=40):
    lines = text.rstrip("\n").split("\n")
    return "\n".join(("    " + l) for l in lines[-n:]) if text.strip() else "    (empty)"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("root")
    ap.add_argument("artcam_dir")
    ap.add_argument("--only", help="one of the files, e.g. README.md")
    ap.add_argument("--keep", action="store_true", help="keep the temporary folders")
    ap.add_argument("--verbose", action="store_true", help="print every block and its time")
    ap.add_argument("--python", default="/usr/bin/python3" if os.path.exists("/usr/bin/python3")
                    else sys.executable)
    a = ap.parse_args()
    root = os.path.abspath(a.root)
    artcam_dir = os.path.abspath(a.artcam_dir)
    if not os.access(os.path.join(artcam_dir, "artcam"), os.X_OK):
        print("run_doc_blocks: no artcam in %s" % artcam_dir)
        return 2
    strict = os.environ.get("ARTCAM_DOCS_STRICT") == "1"
    checker = Checker(root, artcam_dir)
    env = dict(os.environ)
    env["PATH"] = artcam_dir + os.pathsep + env.get("PATH", "")
    env["QT_QPA_PLATFORM"] = "offscreen"
    # `import artcam` from the same build as the artcam program (<build>/python beside <build>/app).
    build_python = os.path.join(os.path.dirname(artcam_dir), "python")
    if os.path.isdir(os.path.join(build_python, "artcam")):
        for e in (env, os.environ):
            e["PYTHONPATH"] = build_python + (os.pathsep + e["PYTHONPATH"] if e.get("PYTHONPATH") else "")
    scripts = tempfile.mkdtemp(prefix="artcam-doc-blocks-")

    passed, failed, skipped = 0, 0, []

    def fail(where, why, stderr=None):
        nonlocal failed
        failed += 1
        print("FAIL %s: %s" % (where, why))
        if stderr is not None:
            print(tail(stderr))

    files = [a.only] if a.only else DOC_FILES
    for rel in files:
        path = os.path.join(root, rel)
        if not os.path.exists(path):
            fail(rel, "file missing")
            continue
        blocks, problems = parse_blocks(rel, open(path, encoding="utf-8").read())
        for where, why in problems:
            fail(where, why)
        work = None
        for n, b in enumerate(blocks):
            if b.lang in PROSE_LANGS:
                continue
            if b.lang in CHECK_LANGS:
                probs = checker.check(b)
                if probs:
                    fail(b.where(), "(%s) %s" % (b.lang, "; ".join(probs)))
                else:
                    passed += 1
                    if a.verbose:
                        print("ok   %s (%s) checked" % (b.where(), b.lang))
                continue
            if b.lang not in RUN_LANGS:
                fail(b.where(), "fence language %r is none of %s" % (
                    b.lang, ", ".join(sorted(RUN_LANGS | CHECK_LANGS | PROSE_LANGS))))
                continue
            if work is None:
                work = tempfile.mkdtemp(prefix="artcam-docs-%s-" % re.sub(r"\W", "_", rel))
                shutil.copytree(os.path.join(root, "resources"), os.path.join(work, "resources"),
                                symlinks=True)
            script = os.path.join(scripts, "block-%s-%d" % (re.sub(r"\W", "_", rel), n))
            with open(script, "w", encoding="utf-8") as f:
                f.write(b.text)
            if b.lang == "sh":
                argv = ["bash", "-euo", "pipefail", script]
            else:
                missing = [m for m in python_imports(b.text) if subprocess.run(
                    [a.python, "-c", "import " + m], stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL).returncode != 0]
                if missing:
                    why = "%s cannot import %s (Debian: %s)" % (a.python, ", ".join(missing), " ".join(
                        PY_PACKAGES.get(m, "?") for m in missing))
                    if strict:
                        fail(b.where(), why)
                    else:
                        skipped.append("%s: %s" % (b.where(), why))
                    continue
                argv = [a.python, script]
            start = time.monotonic()
            try:
                r = subprocess.run(argv, cwd=work, env=env, stdin=subprocess.DEVNULL,
                                   capture_output=True, text=True, timeout=BLOCK_TIMEOUT_S)
            except subprocess.TimeoutExpired as e:
                fail(b.where(), "(%s) still running after %d s" % (b.lang, BLOCK_TIMEOUT_S),
                     (e.stderr or b"").decode(errors="replace") if isinstance(e.stderr, bytes)
                     else (e.stderr or ""))
                continue
            if r.returncode != 0:
                fail(b.where(), "(%s) exit status %d; stderr:" % (b.lang, r.returncode), r.stderr)
            else:
                passed += 1
                if a.verbose:
                    print("ok   %s (%s) %.1f s" % (b.where(), b.lang, time.monotonic() - start))
        if work is not None:
            if a.keep:
                print("kept %s's folder: %s" % (rel, work))
            else:
                shutil.rmtree(work, ignore_errors=True)
    shutil.rmtree(scripts, ignore_errors=True)
    for s in skipped:
        print("SKIP " + s)
    if skipped:
        print("%d skipped (ARTCAM_DOCS_STRICT=1 makes a skip a failure)" % len(skipped))
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
