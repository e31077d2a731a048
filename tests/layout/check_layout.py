#!/usr/bin/env python3
"""The layout rule of docs/architecture.md, "Floors", checked on the sources: every #include "folder/..." of a
code folder names a folder it may depend on (arrows point down), and no header is included from
a folder that is not a code folder; each code folder's README.md names every source file and
script of the folder (by its name without the extension), so a folder's README cannot fall
behind its files; and each README's "May depend on:" paragraph names the folders this table
allows (with what they stand on), so a README cannot promise another layout than the one
checked. Prints one line per offence and exits 1.

Run: python3 tests/layout/check_layout.py [SOURCE_DIR]   (ctest: layout.IncludesPointDown)
"""
import pathlib
import re
import sys

# What each folder may include besides itself (docs/architecture.md, "Floors"; keep the two in step).
DATA = {"io", "models", "formats", "statistics", "study"}
RIG_BASE = {"io", "models", "runtime", "formats"}
ALLOWED = {
    "core": set(),  # the error root: every folder may include it
    "io": set(),    # the doors to files: floor 1, every folder above may include it
    "models": set(),
    "runtime": set(),
    "formats": {"io", "models"},
    "statistics": {"io", "models"},
    "study": {"models", "formats", "statistics"},
    "store": DATA,
    "charts": DATA | {"store"},
    "rigs": RIG_BASE,
    "inputs": RIG_BASE,
    "mechanics": {"models", "formats"},
    "controller": RIG_BASE | {"rigs", "inputs"},
    "calibration": RIG_BASE | {"rigs", "inputs", "controller", "statistics"},
    "experiments": RIG_BASE | {"rigs", "inputs", "controller", "statistics", "study"},
    "sessions": RIG_BASE | DATA | {"rigs", "inputs", "controller", "calibration", "experiments", "store"},
    "diagnostics": RIG_BASE | {"rigs", "inputs", "controller"},
    "gui": RIG_BASE | DATA | {"rigs", "inputs", "controller", "calibration", "experiments", "store", "sessions", "charts"},
    "cli": None,    # the top: anything but bench
    "bench": None,
}
# Files whose job puts them above their folder's floor, with the reason.
EXCEPTIONS = {
    # Calibration charts draw sweeps and fits: built only in a rig build (charts/CMakeLists.txt).
    "charts/calibration_charts.hpp": {"calibration"},
    "charts/calibration_charts.cpp": {"calibration"},
    # The finite-element figures draw mechanics' runs: built only in a rig build (charts/CMakeLists.txt).
    "charts/fe_charts.hpp": {"mechanics"},
    "charts/fe_charts.cpp": {"mechanics"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"', re.M)
# The README's paragraph "May depend on: ..." (up to the next blank line) and the folder names in it.
DEPENDS = re.compile(r"^May depend on:(.*?)(?:\n\s*\n|\Z)", re.M | re.S)
FOLDER_WORD = re.compile(r"(?<![\w/.-])(" + "|".join(sorted(ALLOWED, key=len, reverse=True)) + r")(?![\w-]|\.\w)")


def stands_on(folders: set) -> set:
    """The folders named and everything they may depend on, floor by floor down."""
    seen, todo = set(), list(folders)
    while todo:
        f = todo.pop()
        if f in seen:
            continue
        seen.add(f)
        todo.extend(ALLOWED.get(f) or ())
    return seen


def depends_offence(folder: str, text: str) -> str:
    """Why a README's "May depend on:" paragraph disagrees with ALLOWED, or ""."""
    m = DEPENDS.search(text)
    if not m:
        return f"{folder}/README.md: has no paragraph starting \"May depend on:\" (docs/architecture.md, \"Floors\")"
    said = " ".join(m.group(1).split())
    allowed = ALLOWED[folder]
    if allowed is None:
        return "" if "everything" in said else f"{folder}/README.md: \"May depend on:{m.group(1).strip()}\" should say everything"
    named = set(FOLDER_WORD.findall(said)) - {folder, "core"}
    got, want = stands_on(named) - {folder}, stands_on(allowed)
    if got == want:
        return ""
    parts = []
    if want - got:
        parts.append("leaves out " + ", ".join(sorted(want - got)))
    if got - want:
        parts.append("names " + ", ".join(sorted(got - want)) + ", which it may not depend on")
    return (f"{folder}/README.md: \"May depend on: {said}\" {' and '.join(parts)} "
            f"(tests/layout/check_layout.py allows {', '.join(sorted(allowed)) or 'nothing of palprig but core'})")


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    bad = []
    checked = 0
    for folder, allowed in ALLOWED.items():
        for path in sorted((root / folder).glob("*.[ch]pp")):
            rel = path.relative_to(root).as_posix()
            checked += 1
            for target in INCLUDE.findall(path.read_text(errors="replace")):
                if target == folder or target == "core":
                    continue
                if target not in ALLOWED:
                    bad.append(f"{rel}: includes {target}/, which is not a code folder")
                elif allowed is None:
                    if target == "bench":
                        bad.append(f"{rel}: includes bench/")
                elif target not in allowed and target not in EXCEPTIONS.get(rel, set()):
                    bad.append(f"{rel}: includes {target}/, but {folder}/ may depend only on "
                               f"{', '.join(sorted(allowed)) or 'nothing of palprig'}")
    for folder in ALLOWED:
        readme = root / folder / "README.md"
        if not readme.is_file():
            bad.append(f"{folder}/: has no README.md saying its role and its files")
            continue
        text = readme.read_text(errors="replace")
        offence = depends_offence(folder, text)
        if offence:
            bad.append(offence)
        for path in sorted((root / folder).iterdir()):
            if path.suffix in (".cpp", ".hpp", ".sh", ".py") and path.stem not in text:
                bad.append(f"{folder}/README.md: does not name {path.name}")
    for line in bad:
        print(line)
    print(f"layout: {checked} files checked, {len(bad)} offences (includes against the layout, files a README does not "
          f"name, READMEs whose \"May depend on:\" disagrees)")
    return 1 if bad or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
