#!/usr/bin/env python3
"""The release files agree with the build: LICENSE is there, CITATION.cff is YAML with the fields
CFF 1.2.0 requires (cff-version, message, title, authors; each reference a type, a title and
authors) and its version is project(palprig VERSION ...) of CMakeLists.txt, it names the five
papers of docs/papers.md, and CHANGELOG.md has a section for that version or "Unreleased".
Prints one line per offence and exits 1.

Run: python3 tests/layout/check_release_files.py [SOURCE_DIR]   (ctest: layout.ReleaseFilesAgree)
"""
import pathlib
import re
import sys

import yaml  # python3-yaml (tools/debian-packages.txt)


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    bad = []
    cmake = (root / "CMakeLists.txt").read_text()
    m = re.search(r"project\(palprig VERSION ([0-9]+\.[0-9]+\.[0-9]+)", cmake)
    version = m.group(1) if m else None
    if not version:
        bad.append("CMakeLists.txt: no project(palprig VERSION X.Y.Z)")
    if "Permission is hereby granted" not in (root / "LICENSE").read_text(errors="replace"):
        bad.append("LICENSE: not the MIT licence the README and CITATION.cff name")
    cff = yaml.safe_load((root / "CITATION.cff").read_text())
    for key in ("cff-version", "message", "title", "authors", "version", "license", "references"):
        if not cff.get(key):
            bad.append(f"CITATION.cff: no {key}")
    if cff.get("cff-version") != "1.2.0":
        bad.append(f"CITATION.cff: cff-version {cff.get('cff-version')}, expected 1.2.0")
    if str(cff.get("version")) != version:
        bad.append(f"CITATION.cff: version {cff.get('version')} but CMakeLists.txt says {version}")
    if cff.get("license") != "MIT":
        bad.append(f"CITATION.cff: license {cff.get('license')}, but LICENSE is MIT")
    refs = cff.get("references") or []
    for i, r in enumerate(refs):
        for key in ("type", "title", "authors"):
            if not r.get(key):
                bad.append(f"CITATION.cff: reference {i + 1} has no {key}")
    papers = (root / "docs" / "papers.md").read_text().lower()
    titles = [str(r.get("title", "")).lower() for r in refs]
    if len(refs) != 5:
        bad.append(f"CITATION.cff: {len(refs)} references, expected the five papers of docs/papers.md")
    for t in titles:
        if t and t not in papers:
            bad.append(f"CITATION.cff: reference '{t}' is not one of docs/papers.md's papers")
    changelog = (root / "CHANGELOG.md").read_text()
    if f"## [{version}]" not in changelog and "## [Unreleased]" not in changelog:
        bad.append(f"CHANGELOG.md: no section for {version} or Unreleased")
    for line in bad:
        print(line)
    print(f"release files: version {version}, {len(refs)} references, {len(bad)} offences")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
