#!/usr/bin/env python3
"""Man pages and bash completion generated from palprig's own --help (CLI11), at build time, so
that they cannot drift from the commands: palprig.1 (the overview: every command, the shipped
data, the environment, exit codes) and palprig-COMMAND.1 for each command (its options and its
subcommands' options), gzipped as Debian wants them; and a bash completion script that completes
commands, subcommands, options and the names of shipped files (palprig data list KIND).

    cli_docs.py --palprig BUILD/bin/palprig --man-dir OUT/man1 --completion OUT/palprig [--date YYYY-MM-DD]
"""
from __future__ import annotations

import argparse
import datetime
import gzip
import os
import pathlib
import re
import subprocess
import sys

SECTION = re.compile(r"^([A-Z][A-Za-z ]*):\s*$")
ENTRY = re.compile(r"^  (\S.*?)(?:\s{2,}(\S.*))?$")
# Options whose value is a shipped file, by the kind palprig data list takes (cli/data_files.cpp).
DATA_OPTIONS = {"--protocol": "protocols", "--scene": "scenes", "--rig": "rigs", "--cal": "calibration",
                "--tracking": "tracking", "--curriculum": "curricula", "--fingertip": "fe", "--tissue": "fe",
                "--actuator": "fe", "--stress-model": "fe"}


class Command:
    def __init__(self, path: list[str], summary: str, usage: str, options: list, subcommands: list):
        self.path, self.summary, self.usage = path, summary, usage
        self.options = options          # [(names, description)]
        self.subcommands = subcommands  # [(name, description)]
        self.children: list[Command] = []


def run_help(palprig: str, path: list[str]) -> str:
    env = dict(os.environ, COLUMNS="200")
    r = subprocess.run([palprig, *path, "--help"], capture_output=True, text=True, env=env, check=False)
    if r.returncode != 0:
        sys.exit(f"cli_docs.py: {' '.join(['palprig', *path, '--help'])} exited {r.returncode}: {r.stderr.strip()}")
    return r.stdout


def split_entry(line: str, column: int):
    """An entry line of CLI11's help: (name, description), or None for a continued description.
    CLI11 pads the name to a fixed column; a name that fills it is followed by one space, and a
    longer one stands alone with its description on the next lines."""
    if not line.startswith("  ") or line.startswith("   "):
        return None
    if len(line) > column and line[column - 1] == " " and line[column] != " ":
        return line[:column].strip(), line[column:].strip()
    m = ENTRY.match(line)
    return (m.group(1).strip(), (m.group(2) or "").strip()) if m else None


def parse(text: str, path: list[str]) -> Command:
    summary, usage, section = [], "", None
    options, subcommands = [], []
    help_line = next((l for l in text.splitlines() if "Print this help message" in l), "")
    column = help_line.index("Print this help message") if help_line else 30
    for line in text.splitlines():
        if line.startswith("Usage:"):
            # CLI11 names the program as it was started (a build folder's path): name it palprig.
            usage = re.sub(r"^\S*palprig", "palprig", line[len("Usage:"):].strip())
            section = "after-usage"
            continue
        m = SECTION.match(line)
        if m and not line.startswith(" "):
            section = m.group(1).lower()
            continue
        if section is None:
            if line.strip():
                summary.append(line.strip())
            continue
        if not line.strip():
            continue
        target = options if section in ("options", "positionals") or section.endswith("options") else (
            subcommands if section == "subcommands" else None)
        if target is None:
            continue
        e = split_entry(line, column)
        if e:
            target.append(list(e))
        elif target:  # a description on its own line, or continued
            target[-1][1] = (target[-1][1] + " " + line.strip()).strip()
    return Command(path, " ".join(summary), usage, options, subcommands)


def walk(palprig: str, path: list[str]) -> Command:
    c = parse(run_help(palprig, path), path)
    for name, _ in c.subcommands:
        c.children.append(walk(palprig, [*path, name]))
    return c


def roff(text: str) -> str:
    text = text.replace("\\", "\\e").replace("-", "\\-")
    return "\n".join(("\\&" + l if l.startswith((".", "'")) else l) for l in text.split("\n"))


def header(name: str, version: str, date: str, what: str) -> list[str]:
    return [f'.TH {roff(name.upper())} 1 "{date}" "palprig {version}" "palprig manual"', ".SH NAME",
            f"{roff(name)} \\- {roff(what)}"]


def options_block(c: Command) -> list[str]:
    out = []
    for names, desc in c.options:
        out += [".TP", f"\\fB{roff(names)}\\fR", roff(desc or "")]
    return out


def command_page(c: Command, version: str, date: str) -> str:
    name = "palprig-" + "-".join(c.path)
    lines = header(name, version, date, c.summary or " ".join(c.path))
    lines += [".SH SYNOPSIS", f"\\fB{roff(c.usage)}\\fR", ".SH DESCRIPTION", roff(c.summary)]
    if c.options:
        lines += [".SH OPTIONS", *options_block(c)]

    def sub(cmd: Command, depth: int):
        nonlocal lines
        lines += [".SH " + roff(("COMMAND " if depth == 1 else "") + " ".join(["palprig", *cmd.path]).upper()),
                  f"\\fB{roff(cmd.usage)}\\fR", ".PP", roff(cmd.summary), *options_block(cmd)]
        for ch in cmd.children:
            sub(ch, depth + 1)

    for ch in c.children:
        sub(ch, 1)
    lines += [".SH SEE ALSO", "\\fBpalprig\\fR(1)"]
    return "\n".join(lines) + "\n"


def main_page(root: Command, version: str, date: str) -> str:
    lines = header("palprig", version, date, "drive a pneumatic multi-finger palpation rig and run the studies done on it")
    lines += [".SH SYNOPSIS", "\\fBpalprig\\fR \\fICOMMAND\\fR [\\fIOPTIONS\\fR]", ".br",
              "\\fBpalprig\\fR \\fICOMMAND\\fR \\fB\\-\\-help\\fR", ".SH DESCRIPTION", roff(root.summary), ".PP",
              roff("Every command is described in its own page, palprig-COMMAND(1), generated from its --help.")]
    lines += [".SH OPTIONS", *options_block(root), ".SH COMMANDS"]
    for name, desc in root.subcommands:
        lines += [".TP", f"\\fBpalprig {roff(name)}\\fR", roff(desc), f"See \\fBpalprig\\-{roff(name)}\\fR(1)."]
    lines += [
        ".SH FILES",
        roff("Protocols, scenes, rig files, calibrations, pen traces, tracking examples, curricula and the "
             "finite-element model's files ship in "
             "/usr/share/palprig (share/palprig beside the program's bin folder). Options that take one "
             "(--protocol, --scene, --rig, --cal, --tracking, --curriculum, --fingertip, --tissue, --actuator, "
             "--stress-model, --input trace:NAME) also take its name: "
             "palprig experiment run --protocol discrimination_002 --participant sim:1 --db s.db. "
             "palprig data list shows the names."),
        ".TP", "\\fB/etc/security/limits.d/palprig.conf\\fR",
        roff("Real-time priority and locked memory for the palprig group."),
        ".TP", "\\fB/usr/lib/udev/rules.d/70\\-palprig.rules\\fR",
        roff("The comedi cards and pen tablets for the palprig group."),
        ".SH ENVIRONMENT", ".TP", "\\fBPALPRIG_DATA_DIR\\fR",
        roff("A folder searched first for shipped files by name (KIND/NAME.json, KIND/NAME.csv)."),
        ".SH EXIT STATUS", ".TP", "0", "Success.", ".TP", "1",
        roff("The rig faulted while running (every channel vented, the reason printed), or another failure."),
        ".TP", "2", roff("A file or argument was refused before anything moved (one line naming it)."),
        ".SH SEE ALSO",
        ", ".join(f"\\fBpalprig\\-{roff(n)}\\fR(1)" for n, _ in root.subcommands),
    ]
    return "\n".join(lines) + "\n"


def completion(root: Command) -> str:
    cases = []

    def visit(c: Command):
        words = [n for n, _ in c.subcommands]
        for names, _ in c.options:
            for part in re.sub(r"\{[^}]*\}", "", names.split(" ")[0]).split(","):
                if part.startswith("-"):
                    words.append(part)
        cases.append(f'    "{" ".join(c.path)}") words="{" ".join(words)}" ;;')
        for ch in c.children:
            visit(ch)

    visit(root)
    data = "\n".join(f'    {opt}) kind={kind} ;;' for opt, kind in DATA_OPTIONS.items())
    return f"""# bash completion for palprig, generated from its --help by packaging/cli_docs.py.
_palprig() {{
  local cur prev path="" words kind="" i w
  cur=${{COMP_WORDS[COMP_CWORD]}}
  prev=${{COMP_WORDS[COMP_CWORD-1]}}
  # The command path typed so far: the words before the cursor that are not options or their values.
  for ((i = 1; i < COMP_CWORD; i++)); do
    w=${{COMP_WORDS[i]}}
    case "$w" in -*) continue ;; esac
    case " $(_palprig_words "$path") " in *" $w "*) path="${{path:+$path }}$w" ;; esac
  done
  case "$prev" in
{data}
  esac
  if [[ -n $kind ]]; then
    COMPREPLY=($(compgen -W "$(palprig data list "$kind" 2>/dev/null | awk '{{print $1}}')" -- "$cur") $(compgen -f -- "$cur"))
    return
  fi
  COMPREPLY=($(compgen -W "$(_palprig_words "$path")" -- "$cur"))
  [[ ${{#COMPREPLY[@]}} -eq 0 ]] && COMPREPLY=($(compgen -f -- "$cur"))
}}
_palprig_words() {{
  local words=""
  case "$1" in
{chr(10).join(cases)}
  esac
  echo "$words"
}}
complete -F _palprig palprig
"""


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--palprig", required=True)
    ap.add_argument("--man-dir", required=True)
    ap.add_argument("--completion", required=True)
    epoch = os.environ.get("SOURCE_DATE_EPOCH")  # reproducible builds give the date; else today
    today = datetime.datetime.fromtimestamp(int(epoch), datetime.timezone.utc).date() if epoch else datetime.date.today()
    ap.add_argument("--date", default=today.isoformat())
    a = ap.parse_args()
    version_line = subprocess.run([a.palprig, "--version"], capture_output=True, text=True, check=True).stdout
    version = version_line.split()[1] if len(version_line.split()) > 1 else "unknown"
    root = walk(a.palprig, [])
    man = pathlib.Path(a.man_dir)
    man.mkdir(parents=True, exist_ok=True)
    for old in man.glob("*.1.gz"):
        old.unlink()
    pages = {"palprig.1": main_page(root, version, a.date)}
    for c in root.children:
        pages["palprig-" + "-".join(c.path) + ".1"] = command_page(c, version, a.date)
    for name, text in pages.items():
        # mtime 0 and no file name inside: the same help gives the same bytes (reproducible).
        with open(man / (name + ".gz"), "wb") as f, gzip.GzipFile(filename="", mode="wb", fileobj=f, mtime=0,
                                                                   compresslevel=9) as z:
            z.write(text.encode())
    pathlib.Path(a.completion).parent.mkdir(parents=True, exist_ok=True)
    pathlib.Path(a.completion).write_text(completion(root))
    print(f"cli_docs.py: {len(pages)} man pages in {man}, bash completion {a.completion}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
