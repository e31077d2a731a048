#!/bin/bash
# package.InstallAndRun (ctest) and `make test-package-scratch` (the first half of `make test-package`): the Debian package as a rig PC gets it.
# Builds the .deb with CPack from BUILD (unless one is given), unpacks it into a scratch root
# (dpkg -x: no root rights or apt needed, nothing touches this machine's /usr) and checks
#   - its control data: dependencies computed by dpkg-shlibdeps (Qt, libmodbus, comedilib, ...),
#     the postinst/postrm and the limits.d conffile;
#   - the files a lab expects: the program, the shipped data, man pages, bash completion, the
#     desktop entry, the group (sysusers), limits.d, udev rules, copyright and changelog;
#   - the installed program run from an empty folder far from the clone, with a bare PATH and
#     no PALPRIG_* variables: --version, `data list` (taken from the installed share/palprig,
#     not the source tree), the demo, a simulated session by protocol name and its statistics,
#     `man` on the installed page, the completion of "palprig ex";
#   - lintian on the .deb (when installed): no error, and no warning that is not listed with its
#     reason in tests/package/lintian-accepted.txt (other infos are printed).
# Exits non-zero at the first check that fails, naming it.
#   tests/package/install_and_run.sh BUILD_DIR [PACKAGE.deb]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: install_and_run.sh BUILD_DIR [PACKAGE.deb]}" && pwd)
deb=${2:-}
fail() { echo "package test: FAILED: $*" >&2; exit 1; }
step() { echo "package test: $*"; }

if [[ -z $deb ]]; then
  start=$(date +%s)
  (cd "$build" && cpack -G DEB >cpack.log 2>&1) || { cat "$build/cpack.log" >&2; fail "cpack -G DEB"; }
  deb=$(ls -t "$build"/palprig_*.deb | head -n 1)
  step "built $(basename "$deb") in $(($(date +%s) - start)) s, $(du -k "$deb" | cut -f1) KiB"
fi
[[ -f $deb ]] || fail "no package $deb"
deb=$(realpath "$deb")

root=$(mktemp -d /tmp/palprig-package-root.XXXXXX)
work=$(mktemp -d /tmp/palprig-package-run.XXXXXX)
trap 'rm -rf "$root" "$work"' EXIT

# Control data.
control=$(dpkg-deb -f "$deb")
depends=$(dpkg-deb -f "$deb" Depends)
for lib in libqt6widgets6 libmodbus5 libcomedi0 libevdev2 libsqlite3-0 libpq5 adduser; do
  [[ $depends == *"$lib"* ]] || fail "Depends lacks $lib (dpkg-shlibdeps): $depends"
done
dpkg-deb -e "$deb" "$work/control"
for f in postinst postrm conffiles; do [[ -f $work/control/$f ]] || fail "no $f in the control archive"; done
grep -qx /etc/security/limits.d/palprig.conf "$work/control/conffiles" || fail "limits.d file is not a conffile"
step "control: $(echo "$control" | grep -E '^(Package|Version|Architecture|Installed-Size):' | tr '\n' ' ')"

# Files.
dpkg -x "$deb" "$root"
for f in usr/bin/palprig \
         usr/share/palprig/protocols/discrimination_002.json usr/share/palprig/scenes/phantom_abc.json \
         usr/share/palprig/scenes/phantom_abc.pgm usr/share/palprig/rigs/simulated.json \
         usr/share/palprig/traces/phantom_abc_pass.csv usr/share/palprig/tracking/tracking_stylus.json \
         usr/share/palprig/calibration/paper002.json usr/share/palprig/waveforms/brachial_pressure.csv \
         usr/share/man/man1/palprig.1.gz usr/share/man/man1/palprig-experiment.1.gz \
         usr/share/bash-completion/completions/palprig usr/share/applications/palprig.desktop \
         usr/share/icons/hicolor/scalable/apps/palprig.svg \
         usr/share/doc/palprig/copyright usr/share/doc/palprig/changelog.gz \
         usr/share/doc/palprig/changelog.Debian.gz usr/share/doc/palprig/CITATION.cff \
         usr/lib/sysusers.d/palprig.conf usr/lib/udev/rules.d/70-palprig.rules etc/security/limits.d/palprig.conf; do
  [[ -e $root/$f ]] || fail "the package lacks /$f"
done
step "files: $(find "$root" -type f | wc -l) files, $(du -sk "$root" | cut -f1) KiB installed"

# The installed program, from an empty folder, with nothing of the clone in its environment.
cd "$work"
run() { env -i PATH="$root/usr/bin:/usr/bin:/bin" HOME="$work" QT_QPA_PLATFORM=offscreen LANG=C.UTF-8 "$@"; }
version=$(run palprig --version) || fail "palprig --version exited $?"
[[ $version =~ ^palprig\ [0-9]+\.[0-9]+\.[0-9]+\ \(commit\ [0-9a-f]{7,}(-dirty)?\)$ ]] || fail "--version printed '$version'"
step "$version"
list=$(run palprig data list) || fail "palprig data list exited $?"
[[ $(head -n 1 <<<"$list") == "palprig data: $root/usr/share/palprig (installed)" ]] ||
  fail "data list does not read the installed share/palprig: $(head -n 1 <<<"$list")"
grep -q "protocols:.* discrimination_002 " <<<"$list" || fail "data list does not name discrimination_002: $list"
demo=$(run palprig demo --out "$work/demo" 2>&1) || fail "palprig demo exited $?: $demo"
grep -q "Every tumor got higher pressure than soft tissue." <<<"$demo" || fail "the demo: $demo"
session=$(run palprig experiment run --protocol discrimination_002 --participant sim:1 --db s.db 2>&1) ||
  fail "the session by protocol name exited $?: $session"
grep -q "session 1 completed: 32 trials in s.db" <<<"$session" || fail "the session by protocol name: $session"
stats=$(run palprig stats trials s.db 2>&1) || fail "stats trials exited $?: $stats"
grep -q "^three-finger " <<<"$stats" || fail "stats trials: $stats"
missing=$(run palprig experiment run --protocol no_such_protocol --participant sim:1 --db t.db 2>&1) && fail "an unknown name was taken"
grep -q "no_such_protocol' is neither a file nor the name of a shipped file in $root/usr/share/palprig/protocols" <<<"$missing" ||
  fail "an unknown protocol name: $missing"
step "ran --version, data list, demo, experiment run --protocol discrimination_002, stats trials from $work"

# man, completion, desktop entry.
page=$(MANWIDTH=100 man -l "$root/usr/share/man/man1/palprig-experiment.1.gz" 2>&1 | col -b)
grep -q -- "--protocol" <<<"$page" || fail "man palprig-experiment does not show --protocol"
warnings=$(LC_ALL=C.UTF-8 MANROFFSEQ='' man --warnings -l "$root/usr/share/man/man1/palprig.1.gz" 2>&1 >/dev/null || true)
[[ -z $warnings ]] || fail "man palprig gives warnings: $warnings"
completed=$(run bash -c "source '$root/usr/share/bash-completion/completions/palprig'
  COMP_WORDS=(palprig ex); COMP_CWORD=1; _palprig; echo \${COMPREPLY[*]}
  COMP_WORDS=(palprig experiment run --protocol disc); COMP_CWORD=4; _palprig; echo \${COMPREPLY[*]}")
[[ $(sed -n 1p <<<"$completed") == "experiment export" ]] || fail "completion of 'palprig ex': $completed"
[[ $(sed -n 2p <<<"$completed") == *discrimination_002* ]] || fail "completion of '--protocol disc': $completed"
if command -v desktop-file-validate >/dev/null; then
  desktop-file-validate "$root/usr/share/applications/palprig.desktop" || fail "desktop-file-validate"
fi
step "man pages render, completion completes commands and protocol names, the desktop entry is valid"

# lintian: errors fail; warnings and infos not listed as accepted are printed.
if command -v lintian >/dev/null; then
  findings=$(lintian --tag-display-limit 0 -I "$deb" 2>&1) || [[ $? -le 2 ]] || fail "lintian could not run: $findings"
  errors=$(grep '^E: ' <<<"$findings" || true)
  [[ -z $errors ]] || fail "lintian errors:
$errors"
  accepted=$(grep -v '^#' "$here/lintian-accepted.txt" | awk 'NF{print ": " $1 " "}')
  others=$(grep '^[WI]: ' <<<"$findings" | grep -v -F "${accepted:-no such tag}" || true)
  step "lintian: no error; $(grep -c '^[WI]: ' <<<"$findings" || true) warnings/infos, accepted ones in tests/package/lintian-accepted.txt"
  unlisted=$(grep '^W: ' <<<"$others" || true)
  [[ -z $unlisted ]] || fail "lintian warnings not in tests/package/lintian-accepted.txt (fix them, or list them with the reason):
$unlisted"
  [[ -z $others ]] || echo "$others"
fi
step "passed"
