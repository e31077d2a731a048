#!/usr/bin/env python3
"""Executable docs: run every shell example of README.md and docs/**/*.md, compare the output the
page shows, and load every JSON and CSV example through palprig's reader for its kind.

Over 400 lines: one program (the page runner, the output matcher, the JSON and CSV loader, the
link checker and the self-test), which ctest runs as one.

    python3 tools/check_docs.py [--bin BUILD/bin] [--repo ROOT] [--keep] [PAGE.md ...]
    python3 tools/check_docs.py --self-test [--bin BUILD/bin] [--repo ROOT]

ctest runs the first as docs.ExamplesRun and the second as docs.SelfTestCatchesDrift (a rig
build only). Python 3 from Debian, no other package. The conventions a page follows are in
docs/developing.md, "Executable docs"; in short:

* Each page runs in a fresh temporary folder holding a symbolic link `data` to the repository's
  data/ (so `data/protocols/...` works as in a clone), with BUILD/bin first on PATH,
  QT_QPA_PLATFORM=offscreen, HOME inside the folder and standard input /dev/null. The page's
  blocks run in order in that folder, each ```sh block in one new bash, so a later block sees the
  files an earlier one wrote.
* In a ```sh block, comment lines that start with "#   " (a hash and three spaces) right under a
  command are the output it shows: its standard output followed by its standard error, blank
  lines left out. They must match the whole output, line for line, where a line "..." stands
  for any number of lines, "..." inside a line for any text, "~X" for a number within 10 % of X,
  and "[exit N]" (or "[exit N|M]") gives the exit status (0 when not shown). A command that
  shows no output is only required to exit 0. Other comments are comments.
* An HTML comment right before a fence steers it: `<!-- docs-test: skip: REASON -->` skips it
  (reported with the reason); `<!-- docs-test: file: NAME -->` writes a ```json / ```csv / ```text
  block to NAME in the page's folder; `kind: KIND` names its kind for `palprig check --kind`;
  `refused` says the example is one palprig must refuse; `needs: gui` skips the block in a build
  without the window; `timeout: S` (default 120 s); `starts: S` runs each command of a block that
  waits for a person (a window, a terminal session) and requires it to be still running after S
  seconds (then it is stopped with SIGTERM); `realtime` marks a block that runs the 1 kHz loop in
  real time: when the loop faulted in it because this machine stalled it beyond the rig's
  limits ("loop cannot hold its rate", or "pen input stale" when the input's reader was not run:
  the rig's own protection, working), the block runs once more and the report lists it under
  "retried"; any other failure, or a second stall, fails. Separate several with ";".
* Every ```json block (and every ```csv block with a file name) is loaded with `palprig check`
  (each JSON example is a complete file, never a fragment).
* Relative links ([text](path#anchor)) must name files that exist, and headings that exist.
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^( {0,3})(```+)\s*([A-Za-z0-9_+-]*)\s*$")
DIRECTIVE = re.compile(r"^\s*<!--\s*docs-test:\s*(.*?)\s*-->\s*$")
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
OUTPUT_PREFIX = "#   "
EXIT_LINE = re.compile(r"^\[exit ([0-9|]+)\]$")
NUMBER = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?"
TILDE = re.compile(r"~(" + NUMBER + ")")
HEREDOC = re.compile(r"<<-?\s*(['\"]?)([A-Za-z_][A-Za-z0-9_]*)\1")
TOLERANCE = 0.10
# What palprig says when the machine stalled the loop past the rig's limits (controller/fault.hpp):
# the loop lost more time than safety.max_lost_time_s, or the input's reader thread was not run
# for safety.max_input_age_s (a stalled virtual CPU), so its newest sample went stale.
LOOP_STALLED = "loop cannot hold its rate (lost time beyond safety.max_lost_time_s)"


@dataclasses.dataclass
class Block:
    page: pathlib.Path
    line: int            # 1-based line of the opening fence
    lang: str
    text: str
    directives: dict


@dataclasses.dataclass
class Command:
    line: int            # 1-based line in the page
    text: str
    expected: list       # shown output lines (prefix removed)


@dataclasses.dataclass
class Result:
    block: Block
    status: str          # passed, failed, skipped
    detail: str = ""


def parse_directives(lines: list) -> dict:
    out: dict = {}
    for raw in lines:
        for part in raw.split(";"):
            part = part.strip()
            if not part:
                continue
            key, _, value = part.partition(":")
            out[key.strip()] = value.strip() if value else True
    return out


def read_blocks(page: pathlib.Path) -> list:
    lines = page.read_text(encoding="utf-8").split("\n")
    blocks = []
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, ticks, lang = len(m.group(1)), m.group(2), m.group(3).lower()
        start = i
        # Directives: the comment lines right above the fence.
        d_lines = []
        j = i - 1
        while j >= 0 and DIRECTIVE.match(lines[j]):
            d_lines.insert(0, DIRECTIVE.match(lines[j]).group(1))
            j -= 1
        body = []
        i += 1
        while i < len(lines) and not re.match(r"^ {0,3}" + ticks + r"\s*$", lines[i]):
            body.append(lines[i][indent:] if lines[i][:indent].strip() == "" else lines[i])
            i += 1
        i += 1
        blocks.append(Block(page, start + 1, lang, "\n".join(body) + "\n", parse_directives(d_lines)))
    return blocks


def split_commands(block: Block) -> list:
    """The commands of a sh block with the output each one shows."""
    lines = block.text.split("\n")
    commands: list = []
    i = 0
    while i < len(lines):
        raw = lines[i]
        stripped = raw.strip()
        if not stripped:
            i += 1
            continue
        if raw.startswith(OUTPUT_PREFIX) or stripped == "#" and commands and commands[-1].expected:
            if not commands:
                raise ValueError(f"{block.page.name}:{block.line + 1 + i}: output shown before any command")
            commands[-1].expected.append(raw[len(OUTPUT_PREFIX):].rstrip() if raw.startswith(OUTPUT_PREFIX) else "")
            i += 1
            continue
        if stripped.startswith("#"):
            i += 1
            continue
        first = i
        text = [raw]
        while (text[-1].rstrip().endswith("\\") or text[-1].rstrip().endswith("&&")
               or text[-1].rstrip().endswith("|")) and i + 1 < len(lines):
            i += 1
            text.append(lines[i])
        heredoc = HEREDOC.search("\n".join(text))
        if heredoc:
            terminator = heredoc.group(2)
            while i + 1 < len(lines):
                i += 1
                text.append(lines[i])
                if lines[i].strip() == terminator:
                    break
        commands.append(Command(block.line + 1 + first, "\n".join(text), []))
        i += 1
    return commands


def line_pattern(expected: str) -> re.Pattern:
    parts = []
    pos = 0
    tokens = re.compile(r"\.\.\.|~" + NUMBER)
    for m in tokens.finditer(expected):
        parts.append(re.escape(expected[pos:m.start()]))
        if m.group(0) == "...":
            parts.append(".*?")
        else:
            parts.append("(" + NUMBER + ")")
        pos = m.end()
    parts.append(re.escape(expected[pos:]))
    return re.compile("^" + "".join(parts) + "$")


def line_matches(expected: str, actual: str) -> bool:
    m = line_pattern(expected).match(actual)
    if not m:
        return False
    wanted = [float(x) for x in TILDE.findall(expected)]
    got = [float(x) for x in m.groups()]
    return all(abs(g - w) <= TOLERANCE * abs(w) for g, w in zip(got, wanted))


def output_matches(expected: list, actual: list) -> bool:
    """expected (with "..." lines) against actual, whole output, blank lines left out."""
    expected = [e for e in expected if e.strip()]
    actual = [a.rstrip() for a in actual if a.strip()]
    memo: dict = {}

    def match(i: int, j: int) -> bool:
        key = (i, j)
        if key in memo:
            return memo[key]
        if i == len(expected):
            result = j == len(actual)
        elif expected[i].strip() == "...":
            result = any(match(i + 1, k) for k in range(j, len(actual) + 1))
        else:
            result = j < len(actual) and line_matches(expected[i], actual[j]) and match(i + 1, j + 1)
        memo[key] = result
        return result

    sys.setrecursionlimit(max(10000, 4 * (len(expected) + len(actual))))
    return match(0, 0)


def has_gui(bin_dir: pathlib.Path) -> bool:
    r = subprocess.run([str(bin_dir / "palprig"), "gui", "--help"], capture_output=True, text=True)
    return r.returncode == 0 and "not in this build" not in r.stdout + r.stderr


class PageRunner:
    def __init__(self, repo: pathlib.Path, bin_dir: pathlib.Path, path_prefix: list, gui: bool, keep: bool):
        self.repo, self.bin_dir, self.path_prefix, self.gui, self.keep = repo, bin_dir, path_prefix, gui, keep
        self.retried: list = []  # (page, block, why) of `realtime` blocks run a second time

    def environment(self, folder: pathlib.Path) -> dict:
        env = dict(os.environ)
        env["PATH"] = os.pathsep.join([str(p) for p in self.path_prefix] + [str(self.bin_dir), env.get("PATH", "")])
        env["QT_QPA_PLATFORM"] = "offscreen"
        env["HOME"] = str(folder / "home")
        env["PALPRIG_JOURNAL"] = str(folder / "home" / "journal.sqlite")
        env["TZ"] = "UTC"
        env["LC_ALL"] = "C.UTF-8"
        env.pop("PALPRIG_DATA", None)
        return env

    def run_page(self, page: pathlib.Path, fail_fast: bool = False) -> list:
        results = []
        folder = pathlib.Path(tempfile.mkdtemp(prefix="palprig-docs-"))
        try:
            (folder / "data").symlink_to(self.repo / "data")
            (folder / "home").mkdir()
            env = self.environment(folder)
            json_count = 0
            for block in read_blocks(page):
                if fail_fast and any(r.status == "failed" for r in results):
                    break
                d = block.directives
                if "skip" in d:
                    results.append(Result(block, "skipped", str(d["skip"])))
                    continue
                if d.get("needs") == "gui" and not self.gui:
                    results.append(Result(block, "skipped", "needs the window (a build without Qt)"))
                    continue
                if block.lang in ("sh", "bash", "shell") and "starts" in d:
                    results.append(self.run_starts(block, folder, env))
                elif block.lang in ("sh", "bash", "shell"):
                    before = files_under(folder) if d.get("realtime") else set()
                    result = self.run_sh(block, folder, env)
                    if result.status == "failed" and d.get("realtime") and stalled(result.detail):
                        # The machine, not the page: the loop vented as it must when it was
                        # stalled. Once more, from the files the page had before the block (a log
                        # the block waits on must not be the first run's); a second stall, or
                        # anything else, fails.
                        self.retried.append((page, block, result.detail.split("\n")[0]))
                        for made in sorted(files_under(folder) - before, reverse=True):
                            made.rmdir() if made.is_dir() and not made.is_symlink() else made.unlink()
                        result = self.run_sh(block, folder, env)
                    results.append(result)
                elif block.lang == "json" or "file" in d:
                    if block.lang == "json" and "file" not in d:
                        json_count += 1
                        d["file"] = f"example-{json_count}.json"
                    results.append(self.write_file(block, folder, env))
            return results
        finally:
            if self.keep:
                print(f"docs: {page.name}: kept {folder}")
            else:
                shutil.rmtree(folder, ignore_errors=True)

    def write_file(self, block: Block, folder: pathlib.Path, env: dict) -> Result:
        d = block.directives
        target = folder / str(d["file"])
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(block.text, encoding="utf-8")
        if block.lang not in ("json", "csv") or d.get("nocheck"):
            return Result(block, "passed", f"wrote {d['file']}")
        cmd = [str(self.bin_dir / "palprig"), "check", str(d["file"])]
        if "kind" in d:
            cmd += ["--kind", str(d["kind"])]
        r = subprocess.run(cmd, cwd=folder, env=env, capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, timeout=60)
        said = (r.stdout + r.stderr).strip()
        if d.get("refused"):
            if r.returncode == 2:
                return Result(block, "passed", f"{d['file']} refused as the page says: {said}")
            return Result(block, "failed", f"{d['file']}: the page says palprig refuses it, but `palprig check` "
                                           f"exited {r.returncode}: {said}")
        if r.returncode != 0:
            return Result(block, "failed", f"{d['file']}: `palprig check` refused the example: {said}")
        return Result(block, "passed", said)

    def run_starts(self, block: Block, folder: pathlib.Path, env: dict) -> Result:
        """A command that waits for a person (a window, a terminal session): it must accept its
        arguments and files and still be running after `starts: S` seconds; it is then sent
        SIGTERM (palprig vents and exits) and, if need be, killed."""
        try:
            commands = split_commands(block)
        except ValueError as e:
            return Result(block, "failed", str(e))
        wait = float(block.directives["starts"])
        for c in commands:
            log = folder / ".docs-test-starts.log"
            with open(log, "w") as out:
                proc = subprocess.Popen(["bash", "--noprofile", "--norc", "-c", "exec " + c.text], cwd=folder, env=env,
                                        stdin=subprocess.PIPE, stdout=out, stderr=subprocess.STDOUT,
                                        start_new_session=True)
                try:
                    status = proc.wait(timeout=wait)
                except subprocess.TimeoutExpired:
                    proc.terminate()
                    try:
                        proc.wait(timeout=15)
                    except subprocess.TimeoutExpired:
                        proc.kill()
                        proc.wait()
                    continue
            said = log.read_text(errors="replace").strip()
            return Result(block, "failed", f"line {c.line}: `{first_line(c.text)}` should wait for a person, but it "
                                           f"exited {status} within {wait:.0f} s; it printed:\n{indent(said)}")
        return Result(block, "passed", f"{len(commands)} commands started and waited {wait:.0f} s")

    def run_sh(self, block: Block, folder: pathlib.Path, env: dict) -> Result:
        try:
            commands = split_commands(block)
        except ValueError as e:
            return Result(block, "failed", str(e))
        work = folder / ".docs-test"
        work.mkdir(exist_ok=True)
        for old in work.iterdir():
            old.unlink()
        script = ["cd " + sh_quote(str(folder))]
        for n, c in enumerate(commands):
            script.append("{ " + c.text + "\n} >" + sh_quote(str(work / f"out.{n}")) + " 2>"
                          + sh_quote(str(work / f"err.{n}")))
            script.append(f"echo $? >{sh_quote(str(work / f'status.{n}'))}")
        timeout = float(block.directives.get("timeout", 120))
        started = time.monotonic()
        try:
            subprocess.run(["bash", "--noprofile", "--norc", "-c", "\n".join(script)], env=env, cwd=folder,
                           stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                           timeout=timeout, start_new_session=True)
        except subprocess.TimeoutExpired:
            return Result(block, "failed", f"timed out after {timeout:.0f} s")
        elapsed = time.monotonic() - started
        for n, c in enumerate(commands):
            status_file = work / f"status.{n}"
            if not status_file.exists():
                return Result(block, "failed", f"line {c.line}: `{first_line(c.text)}` did not run")
            status = int(status_file.read_text().strip() or "-1")
            out = (work / f"out.{n}").read_text(errors="replace").split("\n")
            err = (work / f"err.{n}").read_text(errors="replace").split("\n")
            expected = [e for e in c.expected if not EXIT_LINE.match(e.strip())]
            exits = [EXIT_LINE.match(e.strip()).group(1) for e in c.expected if EXIT_LINE.match(e.strip())]
            allowed = {int(x) for x in exits[0].split("|")} if exits else {0}
            shown = "\n".join(l for l in out + err if l.strip())
            if status not in allowed:
                return Result(block, "failed", f"line {c.line}: `{first_line(c.text)}` exited {status} "
                                               f"(the page says {sorted(allowed)}); it printed:\n{indent(shown)}")
            if expected and not output_matches(expected, out + err):
                return Result(block, "failed", f"line {c.line}: `{first_line(c.text)}` printed what the page does "
                                               f"not show.\n  the page shows:\n{indent(chr(10).join(expected))}\n"
                                               f"  it printed:\n{indent(shown)}")
        return Result(block, "passed", f"{len(commands)} commands, {elapsed:.1f} s")


def stalled(detail: str) -> bool:
    """The block failed because the machine stalled the loop: its run faulted for lost time, or for
    a stale input (the reader was not scheduled), and said so in palprig's fault line."""
    return LOOP_STALLED in detail or re.search(r"palprig: fault at t=[0-9.]+ s: pen input stale", detail) is not None


def files_under(folder: pathlib.Path) -> set:
    """Every file and folder under folder, symbolic links not followed (data/ is one)."""
    out = set()
    for top, dirs, files in os.walk(folder):
        out.update(pathlib.Path(top) / n for n in dirs + files)
    return out


def first_line(text: str) -> str:
    line = text.split("\n")[0].rstrip("\\ ")
    return line if len(line) <= 100 else line[:97] + "..."


def indent(text: str, prefix: str = "    | ") -> str:
    lines = text.split("\n")
    if len(lines) > 60:
        lines = lines[:30] + [f"... ({len(lines) - 60} lines) ..."] + lines[-30:]
    return "\n".join(prefix + l for l in lines)


def sh_quote(s: str) -> str:
    return "'" + s.replace("'", "'\\''") + "'"


def anchors_of(page: pathlib.Path) -> set:
    """GitHub's heading anchors: lower case, punctuation dropped, spaces to hyphens."""
    out = set()
    in_fence = False
    for line in page.read_text(encoding="utf-8").split("\n"):
        if FENCE.match(line):
            in_fence = not in_fence
        elif not in_fence and re.match(r"^#{1,6} ", line):
            text = line.lstrip("#").strip().lower()
            out.add(re.sub(r"[^\w\- ]", "", text).replace(" ", "-"))
    return out


def check_links(page: pathlib.Path) -> list:
    """Relative links name files that exist, and #anchors headings of the page they point at."""
    bad = []
    in_fence = False
    for n, line in enumerate(page.read_text(encoding="utf-8").split("\n"), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        for target in LINK.findall(re.sub(r"`[^`]*`", "", line)):  # not inside inline code
            if re.match(r"^[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            where = (page.parent / path) if path else page
            if not where.exists():
                bad.append(f"{page.name}:{n}: link to {target}, which does not exist")
            elif anchor and where.suffix == ".md" and anchor not in anchors_of(where):
                bad.append(f"{page.name}:{n}: link to {target}, but {where.name} has no heading #{anchor}")
    return bad


def pages_of(repo: pathlib.Path) -> list:
    return [repo / "README.md"] + sorted((repo / "docs").rglob("*.md"))


def run(repo: pathlib.Path, bin_dir: pathlib.Path, pages: list, keep: bool = False, path_prefix: list = (),
        quiet: bool = False, fail_fast: bool = False, failures_out: list = None) -> int:
    runner = PageRunner(repo, bin_dir, list(path_prefix), has_gui(bin_dir), keep)
    started = time.monotonic()
    counts = {"passed": 0, "failed": 0, "skipped": 0}
    skipped = []
    failures = []
    for page in pages:
        t0 = time.monotonic()
        links = check_links(page)
        for link in links:
            failures.append(link)
            counts["failed"] += 1
        results = [] if (fail_fast and links) else runner.run_page(page, fail_fast)
        for r in results:
            counts[r.status] += 1
            where = f"{page.relative_to(repo)}:{r.block.line}"
            if r.status == "failed":
                failures.append(f"{where}: {r.detail}")
            elif r.status == "skipped":
                skipped.append(f"{where}: {r.detail}")
        if not quiet:
            n_fail = sum(1 for r in results if r.status == "failed")
            print(f"docs: {page.relative_to(repo)}: {len(results)} blocks, {n_fail} failed "
                  f"({time.monotonic() - t0:.1f} s)", flush=True)
    retried = [f"{p.relative_to(repo)}:{b.line}: {why}" for p, b, why in runner.retried]
    if not quiet:
        for s in skipped:
            print(f"skipped {s}")
        for r in retried:
            print(f"retried {r} (this machine stalled the loop past the rig's limits; run once more)")
        for f in failures:
            print(f"FAILED {f}")
        print(f"docs: {counts['passed']} passed, {counts['failed']} failed, {counts['skipped']} skipped "
              f"in {time.monotonic() - started:.1f} s")
    if failures_out is not None:
        failures_out.extend(failures)
    return 1 if counts["failed"] else 0


# --self-test: the checker must fail on docs that drifted from the code.
def self_test(repo: pathlib.Path, bin_dir: pathlib.Path) -> int:
    problems = []
    with tempfile.TemporaryDirectory(prefix="palprig-docs-selftest-") as tmp:
        tmp = pathlib.Path(tmp)

        def copy_tree() -> pathlib.Path:
            root = pathlib.Path(tempfile.mkdtemp(dir=tmp))
            shutil.copy(repo / "README.md", root / "README.md")
            shutil.copytree(repo / "docs", root / "docs")
            (root / "data").symlink_to(repo / "data")
            for entry in repo.iterdir():
                if entry.name in ("README.md", "docs", "data", ".git") or entry.name.startswith("build"):
                    continue
                (root / entry.name).symlink_to(entry)
            return root

        def expect(name: str, root: pathlib.Path, page: str, should_fail: bool, path_prefix=()):
            failures: list = []
            code = run(root, bin_dir, [root / page], path_prefix=path_prefix, quiet=True, fail_fast=True,
                       failures_out=failures)
            ok = (code != 0) == should_fail
            print(f"self-test: {name}: {'failed' if code else 'passed'} "
                  f"({'as it must' if ok else 'WRONG: it must ' + ('fail' if should_fail else 'pass')})", flush=True)
            for f in failures[:1]:
                print(indent(f.split("\n")[0], "    "), flush=True)
            if not ok:
                problems.append(name)

        # 0. The control: the README as it is passes in the same set-up, so each failure below is
        # the mutation's doing.
        expect("README.md as it is", copy_tree(), "README.md", False)

        # 1. A documented flag deleted from the code: a palprig that no longer knows --by.
        wrapper_dir = tmp / "flagless"
        wrapper_dir.mkdir()
        wrapper = wrapper_dir / "palprig"
        wrapper.write_text("#!/bin/sh\nfor a in \"$@\"; do case \"$a\" in --by|--by=*) echo \"The following argument "
                           "was not expected: --by\" >&2; exit 109;; esac; done\nexec " + sh_quote(str(bin_dir / "palprig"))
                           + " \"$@\"\n")
        wrapper.chmod(0o755)
        readme = (repo / "README.md").read_text()
        if not re.search(r"^palprig [^\n]*--by", readme, re.M):
            problems.append("README.md shows no command with --by to delete")
        expect("README.md run by a palprig without --by", copy_tree(), "README.md", True, [wrapper_dir])

        # 2. A scene key renamed: the function scene example with radius_mm spelled radius.
        root = copy_tree()
        page = root / "docs" / "scene-authoring.md"
        text = page.read_text()
        mutated = text.replace('"radius_mm"', '"radius"', 1)
        if mutated == text:
            problems.append("docs/scene-authoring.md has no radius_mm key to rename")
        page.unlink()
        page.write_text(mutated)
        expect("scene-authoring.md with radius_mm renamed radius", root, "docs/scene-authoring.md", True)

        # 3. A shown figure changed: the first number of the README's shown output off by far.
        root = copy_tree()
        page = root / "README.md"
        lines = readme.split("\n")
        for n, line in enumerate(lines):
            if line.startswith(OUTPUT_PREFIX) and re.search(r"\d+\.\d+", line) and "~" not in line:
                lines[n] = re.sub(r"(\d+)\.(\d+)", lambda m: str(int(m.group(1)) + 7) + "." + m.group(2), line, 1)
                break
        else:
            problems.append("README.md shows no figure to change")
        page.unlink()
        page.write_text("\n".join(lines))
        expect("README.md with a shown figure changed", root, "README.md", True)

        # 4. A flag the code never had, typed in a documented command.
        root = copy_tree()
        page = root / "README.md"
        mutated = re.sub(r"^(palprig stats trials [^\n]*)$", r"\1 --by-participant", readme, count=1, flags=re.M)
        if mutated == readme:
            problems.append("README.md has no `palprig stats trials` line")
        page.unlink()
        page.write_text(mutated)
        expect("README.md with a flag palprig does not have", root, "README.md", True)

        # 5. A broken link.
        root = copy_tree()
        page = root / "README.md"
        page.unlink()
        page.write_text(readme + "\nSee [the missing page](docs/no-such-page.md).\n")
        expect("README.md with a link to a missing page", root, "README.md", True)

        # 6. A `realtime` block is run once more only when the loop stalled: a palprig that faults
        # so once passes on the second run; one that always does, or fails otherwise once, fails.
        page_text = ("# Real time\n\n<!-- docs-test: realtime -->\n```sh\npalprig --version\n#   palprig ...\n```\n")
        for name, say, always, should_fail in (
                ("a realtime block whose loop stalled once", f"palprig: fault at t=1.000 s: {LOOP_STALLED}", False, False),
                ("a realtime block whose input went stale once", "palprig: fault at t=1.840 s: pen input stale", False, False),
                ("a realtime block whose loop stalls every time", f"palprig: fault at t=1.000 s: {LOOP_STALLED}", True, True),
                ("a realtime block that failed otherwise once", "palprig: cannot open /dev/comedi0", False, True)):
            root = copy_tree()
            (root / "docs" / "realtime.md").write_text(page_text)
            stall_dir = pathlib.Path(tempfile.mkdtemp(dir=tmp))
            marker = stall_dir / "stalled-once"
            first = "" if always else f"[ -e {sh_quote(str(marker))} ] && exec {sh_quote(str(bin_dir / 'palprig'))} \"$@\"\n"
            (stall_dir / "palprig").write_text(f"#!/bin/sh\n{first}: > {sh_quote(str(marker))}\necho {sh_quote(say)} >&2\nexit 1\n")
            (stall_dir / "palprig").chmod(0o755)
            expect(name, root, "docs/realtime.md", should_fail, [stall_dir])

    print("self-test: 5 of 5 drifts made the check fail, 4 of 4 real-time retries went as they must, and the "
          "unchanged README passed" if not problems else "self-test: FAILED: " + "; ".join(problems))
    return 1 if problems else 0


def main() -> int:
    here = pathlib.Path(__file__).resolve().parent.parent
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repo", type=pathlib.Path, default=here)
    ap.add_argument("--bin", type=pathlib.Path, default=None, help="folder holding palprig (default REPO/build/bin)")
    ap.add_argument("--keep", action="store_true", help="keep each page's temporary folder")
    ap.add_argument("--self-test", action="store_true", help="check that drifted docs make the check fail")
    ap.add_argument("pages", nargs="*", type=pathlib.Path)
    a = ap.parse_args()
    repo = a.repo.resolve()
    bin_dir = (a.bin or repo / "build" / "bin").resolve()
    if not (bin_dir / "palprig").exists():
        print(f"docs: no palprig in {bin_dir} (build first)")
        return 1
    if a.self_test:
        return self_test(repo, bin_dir)
    pages = [p.resolve() for p in a.pages] if a.pages else pages_of(repo)
    return run(repo, bin_dir, pages, keep=a.keep)


if __name__ == "__main__":
    sys.exit(main())
