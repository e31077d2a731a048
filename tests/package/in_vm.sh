#!/bin/bash
# `make test-package-vm` (and the end of `make test-package` on a machine that cannot raise
# RLIMIT_RTPRIO): apt_install_as_lab_user.sh run inside a fresh Debian 12 virtual machine, with its
# own kernel, so that the one step a container cannot show is shown for real: the package's
# limits.d file applied by pam_limits at the lab user's login, and `palprig run --realtime` holding
# SCHED_FIFO 80 as that user, without root. A container's root may lack CAP_SYS_RESOURCE (this
# project's build machine does: its hard RLIMIT_RTPRIO is 0 and no process may raise it); a
# VM's root has every capability, as a rig PC's has.
#
# How: debootstrap a minimal Debian 12 (the kernel, Xvfb, man-db) into a cached folder, download
# into it the .deb's dependencies (so the VM needs no network: it has none, and apt installs
# from the cache), copy the .deb and the test script in, make a fresh ext4 image from the folder
# (mkfs.ext4 -d: no loop mount), boot it with QEMU (KVM where there is one, else TCG) with the
# test as init, read the serial console, power off. The VM starts from a fresh image every run;
# the cache folder (root's, default /var/cache/palprig-test-vm) keeps only the base system
# between runs (delete it to refresh).
#   tests/package/in_vm.sh PACKAGE.deb [CACHE_DIR]
# Needs root, qemu-system-x86, debootstrap, e2fsprogs and Debian's archive (for the first
# debootstrap and the dependencies). Figures (2-core AMD EPYC VM without KVM, TCG): debootstrap
# 3 min 34 s the first time; `make test-package-vm` with it cached 3 min 29 s (the VM about 3 min);
# the whole `make test-package` 4-5 min.
set -euo pipefail
deb=$(realpath "${1:?usage: in_vm.sh PACKAGE.deb [CACHE_DIR]}")
cache=$(realpath -m "${2:-/var/cache/palprig-test-vm}")
here=$(dirname "$(realpath "$0")")
fail() { echo "vm package test: FAILED: $*" >&2; exit 1; }
step() { echo "vm package test: $*"; }
[[ $(id -u) == 0 ]] || fail "run as root (debootstrap and chroot need it)"
for tool in qemu-system-x86_64 debootstrap mkfs.ext4; do
  command -v "$tool" >/dev/null || fail "$tool is missing (make test-package-vm installs qemu-system-x86, debootstrap, e2fsprogs)"
done
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
root=$cache/rootfs
mkdir -p "$cache"
# One run at a time per cache: two would share the image and the console log.
exec 9>"$cache/lock"
flock -n 9 || fail "another in_vm.sh is running with $cache"

# The base system is kept once debootstrap finished (its stamp); a run it did not finish starts again.
if [[ ! -f $cache/rootfs.done ]]; then
  step "debootstrap bookworm into $root (once; minutes)"
  rm -rf "$root"
  debootstrap --variant=minbase --include=linux-image-amd64,xvfb,xauth,man-db,systemd-sysv \
    bookworm "$root" "$mirror" >"$cache/debootstrap.log" 2>&1 || fail "debootstrap (log: $cache/debootstrap.log)"
  # The point releases' and security updates' packages too, as a rig PC has them.
  security=${DEBIAN_SECURITY_MIRROR:-http://deb.debian.org/debian-security}
  printf 'deb %s bookworm main\ndeb %s bookworm-updates main\ndeb %s bookworm-security main\n' \
    "$mirror" "$mirror" "$security" >"$root/etc/apt/sources.list"
  touch "$cache/rootfs.done"
fi
kernel=$(printf "%s\n" "$root"/boot/vmlinuz-* | sort -V | tail -n 1)
initrd=$(printf "%s\n" "$root"/boot/initrd.img-* | sort -V | tail -n 1)
[[ -f $kernel && -f $initrd ]] || fail "no kernel or initrd in $root/boot (delete $cache to start again)"

# The .deb's dependencies into the VM's apt cache (the VM itself has no network).
cp "$deb" "$root/root/palprig.deb"
chroot "$root" apt-get update -qq >"$cache/apt.log" 2>&1 || fail "apt-get update in $root (log: $cache/apt.log)"
chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --download-only /root/palprig.deb \
  >>"$cache/apt.log" 2>&1 || fail "downloading the package's dependencies (log: $cache/apt.log)"
cp "$here/apt_install_as_lab_user.sh" "$root/root/"
cat >"$root/root/vm-init.sh" <<'EOF'
#!/bin/bash
# init of the test VM (tests/package/in_vm.sh): the mounts a login needs, the test, power off.
export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
mountpoint -q /proc || mount -t proc proc /proc
mountpoint -q /sys || mount -t sysfs sys /sys
mountpoint -q /dev || mount -t devtmpfs dev /dev
mkdir -p /dev/pts /dev/shm
mount -t devpts devpts /dev/pts; mount -t tmpfs tmpfs /dev/shm; mount -t tmpfs tmpfs /run; mount -t tmpfs tmpfs /tmp
echo "vm: kernel $(uname -r), $(nproc) cpus, root's hard rtprio $(ulimit -Hr) (raisable: $(bash -c 'ulimit -Hr 90 && echo yes' 2>/dev/null || echo no))"
/root/apt_install_as_lab_user.sh /root/palprig.deb
echo "VM-TEST-EXIT $?"
sync
# Power off (QEMU then exits: -no-reboot). The request is asynchronous: init waits for it, since
# an init that ends makes the kernel panic (which panic=1 on the command line also ends).
echo o >/proc/sysrq-trigger
sleep 600
EOF
chmod +x "$root/root/vm-init.sh"

image=$cache/vm.img
rm -f "$image"
trap 'rm -f "$image"' EXIT  # 4 GB, sparse: not left behind by a failed run
mkfs.ext4 -q -F -d "$root" "$image" 4G || fail "mkfs.ext4 -d $root"
step "booting $(basename "$kernel") with QEMU ($( [[ -w /dev/kvm ]] && echo KVM || echo TCG, no KVM here: slow))"
log=$cache/console.log
timeout "${VM_TIMEOUT_S:-1800}" qemu-system-x86_64 -accel kvm -accel tcg,thread=multi -cpu max -m 2048 -smp "$(nproc)" \
  -nographic -no-reboot -nic none -kernel "$kernel" -initrd "$initrd" \
  -append "root=/dev/vda rw console=ttyS0 quiet panic=1 init=/root/vm-init.sh" \
  -drive "file=$image,format=raw,if=virtio" </dev/null >"$log" 2>&1 || fail "QEMU exited non-zero or timed out (console: $log)"
# The console without the firmware's and the kernel's lines: the test's own.
# (The console's escape sequences, which may lead a line, are removed first.)
console=$(tr -d '\0' <"$log" | sed -e 's/\x1b\[[0-9;?]*[A-Za-z]//g' -e 's/\x1bc//g' -e 's/\r$//')
grep -E '^(vm: |system package test: )' <<<"$console" || true
rc=$(sed -n 's/^VM-TEST-EXIT \([0-9]*\)$/\1/p' <<<"$console")
[[ -n $rc ]] || fail "the VM stopped before the test ended (console: $log)"
[[ $rc == 0 ]] || fail "the test in the VM exited $rc (console: $log)"
grep -q "SCHED_FIFO 80 held without root" <<<"$console" || fail "the VM did not check the real-time limits (console: $log)"
step "passed: installed with apt, run as a lab user (SCHED_FIFO without root), purged, in a Debian 12 VM"
