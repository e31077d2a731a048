#!/usr/bin/env python3
"""The style gate of `make test`: every C++ file formatted as .clang-format says, and clang-tidy
(.clang-tidy) clean on every .cpp the build compiles. Python 3 from Debian, no other package.

    python3 tools/check_style.py format [--repo ROOT] [--fix]
    python3 tools/check_style.py tidy   [--repo ROOT] --build BUILD [--jobs N] [--folders A,B] [FILE.cpp ...]

ctest runs them as style.ClangFormat and style.ClangTidy (tests/CMakeLists.txt); `make format`
runs `format --fix`. Each prints one line per offending file (clang-format's or clang-tidy's own
words below it) and exits 1 when there is any; 0 when the tree is clean.

clang-tidy parses each translation unit as a compiler does (several seconds each with Qt, Eigen
or Ceres), so `tidy` runs the build's own compile commands (BUILD/compile_commands.json) for every
.cpp of the repository the build compiles (libraries, programs, suites and benchmarks; `--folders`
for a subset of the top folders, FILE.cpp for single files), `--jobs` at a time. In a unity build
a target's batches are joined into one translation unit (BUILD/style-cache/batches/TARGET.cxx),
so the headers its sources share are parsed and walked once: clang-tidy spends most of a unit's
time walking the headers' syntax tree (Qt's, Eigen's, GoogleTest's), although it reports only
palprig's (the whole tree, cold: 437 sources one at a time about 2,000 s of CPU by sampling,
96 batches of eight 934 s, 62 targets 652 s; docs/benchmarks.md "The style gate"). It reports only
palprig's own files (the header filter is the source folders), and remembers a clean result per
translation unit in BUILD/style-cache/: the key is a hash of everything its preprocessed text
depends on (its compile command, the source, every header the compiler read for it, from the
build's dependency file), of .clang-tidy and of clang-tidy's version. A second run after a
one-file change re-checks only the translation units that include that file. Findings are never
cached: a unit with findings is checked again on the next run.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import hashlib
import json
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent.parent
# Folders of the tree that hold no C++ of palprig's (build folders are found by their CMakeCache).
NOT_CODE = {".git", "data", "docs", "tools"}


def source_folders(repo: pathlib.Path) -> list[str]:
    """Top-level folders holding palprig's C++ (not build folders, not data)."""
    out = []
    for d in sorted(repo.iterdir()):
        if not d.is_dir() or d.name in NOT_CODE or d.name.startswith("."):
            continue
        if (d / "CMakeCache.txt").exists() or d.name.startswith("build"):
            continue
        out.append(d.name)
    return out


def cxx_files(repo: pathlib.Path, suffixes=(".cpp", ".hpp")) -> list[pathlib.Path]:
    files = []
    for folder in source_folders(repo):
        for root, dirs, names in os.walk(repo / folder):
            dirs[:] = [d for d in dirs if not d.startswith(".")]
            files.extend(pathlib.Path(root) / n for n in names if n.endswith(suffixes))
    return sorted(files)


def need(tool: str) -> str:
    path = shutil.which(tool)
    if not path:
        sys.exit(f"style: {tool} is not installed (tools/debian-packages-test.txt lists it; `make deps-test` installs it)")
    return path


# ---------------------------------------------------------------------------------------- format
def check_format(repo: pathlib.Path, fix: bool) -> int:
    clang_format = need("clang-format")
    files = cxx_files(repo)
    if not files:
        print(f"style: no C++ files under {repo}")
        return 1
    bad = []
    for i in range(0, len(files), 50):
        batch = [str(f) for f in files[i:i + 50]]
        if fix:
            subprocess.run([clang_format, "-i", "--style=file", *batch], check=True)
            continue
        r = subprocess.run([clang_format, "--dry-run", "--Werror", "--style=file", *batch],
                           capture_output=True, text=True)
        if r.returncode != 0:
            seen = set()
            for line in r.stderr.splitlines():
                m = re.match(r"^(/[^:]+):(\d+):\d+: (error|warning):", line)
                if m and m.group(1) not in seen:
                    seen.add(m.group(1))
                    bad.append((m.group(1), m.group(2)))
            if not seen:  # clang-format itself failed
                print(r.stderr)
                return 1
    for path, line in bad:
        rel = pathlib.Path(path).relative_to(repo)
        print(f"{rel}:{line}: not formatted as .clang-format says (run `make format`, or clang-format -i {rel})")
    print(f"style: {len(files)} files checked with {clang_format}, {len(bad)} not formatted")
    return 1 if bad else 0


# ------------------------------------------------------------------------------------------ tidy
PCH_ARGS = re.compile(r"^(-Winvalid-pch|-fpch-preprocess)$")


def compile_entries(repo: pathlib.Path, build: pathlib.Path, unity: bool = True) -> dict[pathlib.Path, dict]:
    """The build's translation units of palprig's sources, by file: each .cpp compiled on its own,
    and each unity file of a unity build (CMake's UNITY_BUILD) as one unit, or, with unity=False,
    each of its sources on its own with the unity file's command. A precompiled header of GCC's
    (which clang cannot read) is taken out of the command, its header included instead."""
    db = json.loads((build / "compile_commands.json").read_text())
    folders = tuple(str(repo / f) + os.sep for f in source_folders(repo))
    out: dict[pathlib.Path, dict] = {}
    for e in db:
        args = e["arguments"] if "arguments" in e else shlex.split(e["command"])
        kept, skip = [], False
        for i, a in enumerate(args):
            if skip:
                skip = False
                continue
            if PCH_ARGS.match(a):
                continue
            if a in ("-include", "--include") and i + 1 < len(args) and "cmake_pch" in args[i + 1]:
                hxx = args[i + 1]
                hxx = hxx[:-4] if hxx.endswith((".gch", ".pch")) else hxx
                kept += ["-include", hxx]
                skip = True
                continue
            kept.append(a)
        source = pathlib.Path(e["directory"], e["file"]).resolve()
        obj = None
        if "-o" in kept:
            obj = pathlib.Path(e["directory"], kept[kept.index("-o") + 1])
        entry = {"directory": e["directory"], "arguments": kept, "object": obj}
        if str(source).startswith(folders):
            out.setdefault(source, dict(entry, file=str(source), members=[source]))
        elif "unity_" in source.name:  # CMake's UNITY_BUILD: one file including several sources
            members = [pathlib.Path(inc).resolve()
                       for inc in re.findall(r'#include\s+"([^"]+)"', source.read_text(errors="replace"))]
            members = [m for m in members if str(m).startswith(folders)]
            if not members:
                continue
            if not unity:  # each source on its own, with the unity file's command
                for member in members:
                    args_m = [str(member) if a in (e["file"], str(source)) else a for a in kept]
                    out.setdefault(member, dict(entry, arguments=args_m, file=str(member), members=[member]))
                continue
            # The batch as the compiler sees it: its headers parsed and walked once for all its
            # sources (about five times less work than one source at a time). The unity file's
            # own `#include "x.cpp"` lines are what bugprone-suspicious-include flags: off for it.
            out.setdefault(source, dict(entry, file=str(source), members=members, objects=[obj], unity_files=[source],
                                        checks="-bugprone-suspicious-include"))
    return out


def whole_targets(entries: dict[pathlib.Path, dict], folder: pathlib.Path) -> dict[pathlib.Path, dict]:
    """A target's unity batches joined into one translation unit for clang-tidy (FOLDER/NAME.cxx
    including every source of the target): clang-tidy spends most of a unit's time walking the
    syntax tree of the headers (Qt's, Eigen's, GoogleTest's), so the fewer the units the less the
    work (the whole tree: 96 units of eight sources took 900 s of CPU, cold). The sources of a
    target already share a unit in the build, and their file-local names are unique within it."""
    groups: dict[str, list[pathlib.Path]] = {}
    for unit, e in entries.items():
        if e.get("unity_files") and e["objects"][0] is not None:
            groups.setdefault(str(e["objects"][0].parent.parent), []).append(unit)
    folder.mkdir(parents=True, exist_ok=True)
    out = {u: e for u, e in entries.items() if not e.get("unity_files")}
    for target_dir, units in sorted(groups.items()):
        units.sort(key=lambda u: int(re.search(r"unity_(\d+)_", u.name).group(1)))
        first = entries[units[0]]
        if len(units) == 1:
            out[units[0]] = first
            continue
        members = [m for u in units for m in entries[u]["members"]]
        batch = folder / (pathlib.Path(target_dir).name.removesuffix(".dir") + ".cxx")
        text = "// generated by tools/check_style.py: one target's unity batches as one unit\n" + "".join(
            f'#include "{m}"\n' for m in members)
        if not batch.exists() or batch.read_text() != text:  # unchanged keeps its time stamp
            batch.write_text(text)
        args = [str(batch) if a in (first["file"], str(units[0])) else a for a in first["arguments"]]
        out[batch] = dict(first, arguments=args, file=str(batch), members=members,
                          objects=[o for u in units for o in entries[u]["objects"]],
                          unity_files=[f for u in units for f in entries[u]["unity_files"]])
    return out


_NINJA_DEPS: dict[pathlib.Path, dict[pathlib.Path, list[pathlib.Path]]] = {}


def ninja_deps(build: pathlib.Path) -> dict[pathlib.Path, list[pathlib.Path]]:
    """A Ninja build's record of the files each object's compile read (`ninja -t deps`): Ninja
    reads the compiler's dependency files into its own log and deletes them. Only records Ninja
    calls VALID (newer than the object) count; read once per build folder."""
    if build not in _NINJA_DEPS:
        found: dict[pathlib.Path, list[pathlib.Path]] = {}
        ninja = shutil.which("ninja") or shutil.which("ninja-build")
        if ninja and (build / "build.ninja").exists():
            text = subprocess.run([ninja, "-C", str(build), "-t", "deps"], capture_output=True, text=True).stdout
            current: list[pathlib.Path] | None = None
            for line in text.splitlines():
                if line.startswith("    ") and current is not None:
                    current.append(pathlib.Path(build, line.strip()))
                elif line and not line.startswith(" "):
                    name, _, state = line.partition(": #deps")
                    current = [] if state.endswith("(VALID)") else None
                    if current is not None:
                        found[pathlib.Path(build, name).resolve()] = current
        _NINJA_DEPS[build] = found
    return _NINJA_DEPS[build]


def depfile_inputs(entry: dict) -> list[pathlib.Path] | None:
    """The files the compiler read for this unit, from the build's dependency file (NAME.o.d), or
    in a Ninja build from Ninja's log of them."""
    objects = entry.get("objects") or [entry["object"]]
    sources = entry.get("unity_files") or [pathlib.Path(entry["file"])]
    names: list[pathlib.Path] = []
    for obj, source in zip(objects, sources):
        if obj is None:
            return None
        logged = ninja_deps(pathlib.Path(entry["directory"]).resolve()).get(pathlib.Path(obj).resolve())
        if logged is not None:
            if not obj.exists() or obj.stat().st_mtime < pathlib.Path(source).stat().st_mtime:
                return None  # the source changed since it was compiled: its includes may have too
            names += logged
            continue
        dep = pathlib.Path(str(obj) + ".d")
        if not dep.exists() or dep.stat().st_mtime < pathlib.Path(source).stat().st_mtime:
            return None
        text = dep.read_text(errors="replace").replace("\\\n", " ")
        _, _, rest = text.partition(": ")
        names += [pathlib.Path(entry["directory"], n.replace("\\ ", " "))
                  for n in re.findall(r"(?:\\ |[^\s])+", rest)]
    return names


def preprocessed_inputs(entry: dict) -> list[pathlib.Path]:
    """Without a current dependency file: ask the compiler which files the unit reads (-M)."""
    args = [a for a in entry["arguments"]]
    if "-o" in args:
        i = args.index("-o")
        del args[i:i + 2]
    args = [a for a in args if a != "-c"] + ["-M", "-MG"]
    r = subprocess.run(args, cwd=entry["directory"], capture_output=True, text=True)
    text = r.stdout.replace("\\\n", " ")
    _, _, rest = text.partition(": ")
    return [pathlib.Path(entry["directory"], n) for n in re.findall(r"(?:\\ |[^\s])+", rest)]


def unit_key(entry: dict, salt: bytes) -> str:
    h = hashlib.sha256(salt)
    args = list(entry["arguments"])
    if "-o" in args:  # where the object goes does not change what is checked
        i = args.index("-o")
        del args[i:i + 2]
    h.update("\0".join(args).encode())
    inputs = depfile_inputs(entry) or preprocessed_inputs(entry)
    for path in sorted(set([pathlib.Path(entry["file"])] + inputs)):
        h.update(str(path).encode())
        try:
            h.update(hashlib.sha256(path.read_bytes()).digest())
        except OSError:
            h.update(b"missing")
    return h.hexdigest()


def check_tidy(repo: pathlib.Path, build: pathlib.Path, jobs: int, only: list[str], folders: str) -> int:
    clang_tidy = need("clang-tidy")
    if not (build / "compile_commands.json").exists():
        print(f"style: no {build}/compile_commands.json (configure the build first)")
        return 1
    started = time.monotonic()
    # Named files are checked one by one (a quick look at a file being edited); otherwise a unity
    # build's batches are checked as the compiler builds them.
    entries = compile_entries(repo, build, unity=not only)
    cache = build / "style-cache"
    if not only:
        entries = whole_targets(entries, cache / "batches")
    if only:
        wanted = {pathlib.Path(f).resolve() for f in only}
        entries = {f: e for f, e in entries.items() if f in wanted}
    elif folders != "all":
        chosen = tuple(str(repo / f) + os.sep for f in folders.split(","))
        entries = {f: e for f, e in entries.items() if any(str(m).startswith(chosen) for m in e["members"])}
    if not entries:
        print("style: no translation unit of palprig's in the compile commands")
        return 1
    (cache / "tidy").mkdir(parents=True, exist_ok=True)
    # The commands clang-tidy sees: the build's, without what only GCC can read.
    (cache / "compile_commands.json").write_text(json.dumps(
        [{"directory": e["directory"], "arguments": e["arguments"], "file": e["file"]} for e in entries.values()]))
    version = subprocess.run([clang_tidy, "--version"], capture_output=True, text=True).stdout
    salt = (version + (repo / ".clang-tidy").read_text()).encode()
    header_filter = "^" + re.escape(str(repo)) + "/(" + "|".join(source_folders(repo)) + ")/"

    def one(item):
        path, entry = item
        key = unit_key(entry, salt)
        mark = cache / "tidy" / key
        if mark.exists():
            return path, True, 0, ""
        extra = [f"--checks={entry['checks']}"] if entry.get("checks") else []
        # The project's .clang-tidy by name: clang-tidy looks for one above the checked file, and
        # a unity file lives in the build folder, outside the repository.
        r = subprocess.run([clang_tidy, "-p", str(cache), "--quiet", f"--config-file={repo / '.clang-tidy'}",
                            f"--header-filter={header_filter}", *extra,
                            str(path)], capture_output=True, text=True)
        findings = [l for l in r.stdout.splitlines() if re.search(r": (warning|error): ", l)]
        if r.returncode == 0 and not findings:
            mark.write_text(str(path) + "\n")
            return path, False, 0, ""
        return path, False, max(1, len(findings)), r.stdout + r.stderr

    cached = ran = 0
    failed = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        # The units with the most sources first, so that a large one does not start last and
        # leave the other process idle at the end (a cold run is the longest test of make test).
        order = sorted(entries.items(), key=lambda kv: (-len(kv[1].get("members") or [kv[0]]), str(kv[0])))
        for path, was_cached, n, text in pool.map(one, order):
            cached += was_cached
            ran += not was_cached
            if n:
                failed.append((path, n, text))
    for path, n, text in failed:
        members = entries[path]["members"]
        name = (str(path.relative_to(repo)) if path.is_relative_to(repo) and members == [path]
                else "unity batch of " + ", ".join(str(m.relative_to(repo)) for m in members))
        print(f"{name}: {n} clang-tidy finding(s):")
        lines = [l for l in text.splitlines() if not re.match(r"^\d+ warnings? (generated|treated)", l)]
        print("\n".join("  " + l for l in lines if l.strip()))
    sources = sum(len(e["members"]) for e in entries.values())
    print(f"style: clang-tidy on {len(entries)} translation units of {sources} sources ({cached} unchanged since a clean check, "
          f"{ran} checked, -j{jobs}) in {time.monotonic() - started:.0f} s: {len(failed)} with findings")
    return 1 if failed else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("what", choices=["format", "tidy"])
    ap.add_argument("--repo", type=pathlib.Path, default=HERE)
    ap.add_argument("--build", type=pathlib.Path, default=None, help="the build folder (tidy; default REPO/build)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--folders", default="all",
                    help="tidy: comma-separated top folders to check (default 'all': every unit of the tree)")
    ap.add_argument("--fix", action="store_true", help="format: rewrite the files instead of checking")
    ap.add_argument("files", nargs="*", help="tidy: only these .cpp files")
    a = ap.parse_intermixed_args()
    repo = a.repo.resolve()
    if a.what == "format":
        return check_format(repo, a.fix)
    return check_tidy(repo, (a.build or repo / "build").resolve(), a.jobs, a.files, a.folders)


if __name__ == "__main__":
    sys.exit(main())
