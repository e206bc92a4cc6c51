#!/bin/bash
# Run one of the README's quick-start commands as a new user would: in a freshly bootstrapped minimal Debian 12
# (bookworm) root with only git, sudo and ca-certificates added, as an ordinary user with sudo, in a clean clone
# of this repository's HEAD with ../shared beside it.
#
# Usage: sudo scripts/fresh_machine_check.sh test|run [--keep] [--root DIR]
#   test   scripts/test.sh (set up, build, run every test)
#   run    scripts/run.sh  (set up, build, run the built-in synthetic sequence through roslaunch)
#   --keep leave the root in place afterwards (default: removed)
#   --root where to build the root (default /var/tmp/cosmo-fresh-<command>)
#
# Needs root and Debian's debootstrap (installed when missing). The mirror is the one this machine's apt uses.
# The bootstrapped base is cached in /var/tmp/cosmo-fresh-base.tar (delete it to bootstrap anew); every run
# starts from a copy of it, so nothing of an earlier run is reused. Not part of CI: it is a cold build (packages
# downloaded, nothing cached) and takes tens of minutes. Run it whenever scripts/debian-packages.txt or
# scripts/setup.sh changes. Prints the command's last lines, its wall time and its exit code.
set -eo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)

cmd=""; keep=0; root=""
while [ $# -gt 0 ]; do
  case "$1" in
    test|run) cmd=$1 ;;
    --keep) keep=1 ;;
    --root) root=$2; shift ;;
    *) echo "usage: $0 test|run [--keep] [--root DIR]"; exit 2 ;;
  esac
  shift
done
[ -n "$cmd" ] || { echo "usage: $0 test|run [--keep] [--root DIR]"; exit 2; }
[ "$(id -u)" -eq 0 ] || { echo "fresh_machine_check: needs root (debootstrap, chroot)"; exit 2; }
root=${root:-/var/tmp/cosmo-fresh-$cmd}
port=$([ "$cmd" = test ] && echo 11712 || echo 11711)  # its own ROS master port: a run and a test check can run side by side
base_tar=/var/tmp/cosmo-fresh-base.tar
shared="$here/../shared"
[ -d "$shared" ] || echo "fresh_machine_check: no $shared: the tests that need it will skip"
[ -z "$(git -C "$here" status --porcelain --untracked-files=no)" ] ||
  echo "fresh_machine_check: uncommitted changes are NOT part of the check (it clones HEAD)"

# The machine's own Debian mirror (deb822 sources first, then the one-line form).
mirror=$(grep -hs '^URIs:' /etc/apt/sources.list.d/*.sources | awk '{print $2}' | grep -v security | head -1)
[ -n "$mirror" ] || mirror=$(grep -hs '^deb ' /etc/apt/sources.list | awk '{print $2}' | grep -v security | head -1)
mirror=${mirror:-http://deb.debian.org/debian}

if [ ! -f "$base_tar" ]; then
  command -v debootstrap > /dev/null || {
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap; }
  echo "[fresh] bootstrapping Debian 12 from $mirror"
  tmp_root=$(mktemp -d /var/tmp/cosmo-fresh-bootstrap.XXXX)
  debootstrap --variant=minbase --include=git,sudo,ca-certificates bookworm "$tmp_root" "$mirror" \
    > /var/tmp/cosmo-fresh-debootstrap.log 2>&1 || {
      tail -20 /var/tmp/cosmo-fresh-debootstrap.log; echo "[fresh] debootstrap failed"; exit 1; }
  chmod 755 "$tmp_root"     # mktemp's 0700 would become the root's "/"
  tar -C "$tmp_root" -cf "$base_tar" .
  rm -rf "$tmp_root"
fi

unmount_all() {
  for m in dev/pts dev proc sys; do mountpoint -q "$root/$m" && umount -l "$root/$m"; done
  return 0
}
cleanup() {
  unmount_all
  if [ $keep -eq 0 ]; then rm -rf "$root"; fi
}
trap cleanup EXIT

unmount_all
rm -rf "$root"
mkdir -p "$root"
tar -C "$root" -xf "$base_tar"
chmod 755 "$root"
mount -t proc proc "$root/proc"
mount --rbind /sys "$root/sys"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
cp /etc/resolv.conf "$root/etc/resolv.conf"
cp /etc/hosts "$root/etc/hosts"; cp /etc/hostname "$root/etc/hostname" 2>/dev/null || true

# An ordinary user with sudo, as on a new machine.
chroot "$root" useradd -m -s /bin/bash cosmo
echo 'cosmo ALL=(ALL) NOPASSWD:ALL' > "$root/etc/sudoers.d/cosmo"
git clone -q "$here" "$root/home/cosmo/cosmo"
[ -d "$shared" ] && cp -a "$shared" "$root/home/cosmo/shared"
chroot "$root" chown -R cosmo:cosmo /home/cosmo

log="/var/tmp/cosmo-fresh-$cmd.log"
echo "[fresh] running scripts/$cmd.sh in $root as user cosmo (log: $log)"
start=$(date +%s)
set +e
# Its own ROS master port, so that a master running on this machine does not answer.
chroot "$root" su - cosmo -c "cd ~/cosmo && export ROS_MASTER_URI=http://localhost:$port && scripts/$cmd.sh" \
  < /dev/null > "$log" 2>&1
rc=$?
set -e
secs=$(( $(date +%s) - start ))
echo "[fresh] last lines of scripts/$cmd.sh:"
tail -15 "$log"
printf '[fresh] scripts/%s.sh exited %d after %d min %02d s\n' "$cmd" $rc $((secs / 60)) $((secs % 60))
exit $rc
