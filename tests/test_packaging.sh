#!/usr/bin/env bash
# The Debian package (cmake/Packaging.cmake, packaging/), checked without installing it: the ctest
# cases packaging_* run one step each, after packaging_deb_build (their fixture).
#   test_packaging.sh build     SOURCE BUILD WORK  cpack from the build tree into WORK, extracted into WORK/root
#   test_packaging.sh contents  SOURCE BUILD WORK  control fields, maintainer scripts, the file list
#   test_packaging.sh units     SOURCE BUILD WORK  the units and the user, read by systemd's own offline tools
#   test_packaging.sh installed SOURCE BUILD WORK  the extracted programs run and read their installed data
#   test_packaging.sh node      SOURCE BUILD WORK  the node config template starts a slave (port 47690)
#   test_packaging.sh loopback  SOURCE BUILD WORK  the installed loopback runs an installed config (ports 47692-47693)
# Needs the programs built (ctest runs after the build), dpkg-dev, file and systemd (scripts/setup.sh).
# node and loopback open UDP ports 47690-47693 on 127.0.0.1 (run ctest under flock /tmp/cupola-ctest.lock).
set -euo pipefail
step="$1" src="$2" build="$3" work="$4"
deb="$work/cupola.deb" root="$work/root"
fail() {
    echo "test_packaging $step: $*" >&2
    exit 1
}
export LC_ALL=C

# cupola-* programs declared in master/, slave/ and tools/, read from their CMakeLists.txt files
# (independently of the install rule that collects them).
declared_programs() {
    find "$src/master" "$src/slave" "$src/tools" -name CMakeLists.txt -exec cat {} + |
        sed -n 's/^[[:space:]]*add_executable(\(cupola-[A-Za-z0-9_-]*\).*/\1/p' | sort -u
}

step_build() {
    rm -rf "$work"
    mkdir -p "$work"
    cpack --config "$build/CPackConfig.cmake" -B "$work/cpack" >"$work/cpack.log" 2>&1 ||
        fail "cpack failed: $(tail -20 "$work/cpack.log")"
    local made=("$work"/cpack/cupola_*.deb)
    [ ${#made[@]} -eq 1 ] && [ -f "${made[0]}" ] || fail "cpack made no single cupola_*.deb in $work/cpack"
    mv "${made[0]}" "$deb"
    rm -rf "$work/cpack/_CPack_Packages"
    dpkg-deb -x "$deb" "$root"
    echo "test_packaging build: $(basename "${made[0]}"), $(stat -c %s "$deb") bytes, extracted into $root"
}

check_control() {
    local version depends
    [ "$(dpkg-deb -f "$deb" Package)" = cupola ] || fail "Package is '$(dpkg-deb -f "$deb" Package)', not cupola"
    version="$(sed -n 's/^project(Cupola VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")"
    [ -n "$version" ] && [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] ||
        fail "Version is '$(dpkg-deb -f "$deb" Version)', project() says '$version'"
    [ -n "$(dpkg-deb -f "$deb" Maintainer)" ] || fail "no Maintainer"
    depends="$(dpkg-deb -f "$deb" Depends)"
    # From dpkg-shlibdeps (libc6, libsodium23...) and the ones named in cmake/Packaging.cmake.
    for d in libc6 libsodium23 libopenimageio liberfa1 libusb-1.0-0 libegl1 libegl-mesa0 libgl1-mesa-dri; do
        grep -qE "(^|[ ,|])$d" <<<"$depends" || fail "Depends lacks $d: $depends"
    done
}

check_maintainer_scripts() {
    local ctl="$work/control"
    rm -rf "$ctl"
    mkdir -p "$ctl"
    dpkg-deb -e "$deb" "$ctl"
    for s in postinst prerm postrm; do
        [ -x "$ctl/$s" ] || fail "no executable $s in the control archive"
        sh -n "$ctl/$s" || fail "$s: syntax error"
    done
    grep -q 'systemd-sysusers cupola.conf' "$ctl/postinst" || fail "postinst does not create the user from sysusers.d"
}

check_file_list() {
    local list="$work/contents.txt" rel
    dpkg-deb --contents "$deb" | awk '{print $1, $6}' >"$list"
    has() { grep -q " \./$1\$" "$list" || fail "the package lacks /$1"; }
    for p in $(declared_programs); do
        grep -q "^-rwxr-xr-x \./usr/bin/$p\$" "$list" || fail "the package lacks the program /usr/bin/$p (mode 755)"
    done
    [ "$(declared_programs | wc -l)" -ge 8 ] || fail "found only $(declared_programs | wc -l) programs in the CMakeLists.txt"
    has usr/lib/systemd/system/cupola-slave@.service
    has usr/lib/systemd/system/cupola-master.service
    has usr/lib/udev/rules.d/70-cupola-navigation.rules
    has usr/lib/sysusers.d/cupola.conf
    has usr/share/cupola/node/cluster.json
    has usr/share/doc/cupola/DEPLOYMENT.md
    while IFS= read -r rel; do has "usr/share/cupola/data/$rel"; done < <(cd "$src/data" && find . -type f | sed 's|^\./||')
    while IFS= read -r rel; do has "usr/share/cupola/configs/$rel"; done < <(cd "$src/configs" && find . -name '*.json' | sed 's|^\./||')
    # Everything lives under /usr: /etc/cupola is made by postinst and filled by the operator.
    if grep -v ' \./usr/\| \./$' "$list" | grep -q .; then fail "files outside /usr: $(grep -v ' \./usr/\| \./$' "$list")"; fi
}

step_contents() {
    check_control
    check_maintainer_scripts
    check_file_list
    echo "test_packaging contents: cupola $(dpkg-deb -f "$deb" Version); Depends: $(dpkg-deb -f "$deb" Depends)"
}

# systemd 252's `systemctl cat` needs a running manager; offline, systemd-analyze reads the same
# unit files under --root (the verify step also needs the targets the units order themselves after).
check_units_offline() {
    local r="$1" units="$1/usr/lib/systemd/system" out
    out="$(systemd-analyze --root="$r" cat-config systemd/system/cupola-slave@.service)"
    grep -q "^ExecStart=/usr/bin/cupola-slave --config /etc/cupola/cluster.json --channel %i" <<<"$out" ||
        fail "cupola-slave@.service does not start /usr/bin/cupola-slave on /etc/cupola/cluster.json: $out"
    for u in "$units"/cupola-slave@.service "$units"/cupola-master.service; do
        grep -qx 'User=cupola' "$u" || fail "$u does not run as cupola"
    done
    for t in /usr/lib/systemd/system/*.target /lib/systemd/system/*.target; do
        [ -e "$units/$(basename "$t")" ] || cp "$t" "$units/"
    done
    # Unknown keys and missing programs are warnings with exit code 0: any output fails.
    out="$(systemd-analyze verify --root="$r" cupola-slave@0.service cupola-slave@front.service \
        cupola-master.service 2>&1)" || fail "systemd-analyze verify: $out"
    [ -z "$out" ] || fail "systemd-analyze verify warns: $out"
    systemctl --root="$r" enable cupola-slave@0.service cupola-master.service >/dev/null 2>&1 ||
        fail "systemctl --root enable cupola-slave@0.service failed"
    [ "$(readlink "$r/etc/systemd/system/multi-user.target.wants/cupola-slave@0.service")" = \
        /usr/lib/systemd/system/cupola-slave@.service ] || fail "enabling cupola-slave@0 made no multi-user.target link"
    [ "$(systemctl --root="$r" is-enabled cupola-slave@0.service)" = enabled ] || fail "cupola-slave@0 is not enabled"
}

# The sysusers.d file, applied to the scratch root: the user the units name, in every group they name.
check_user_offline() {
    local r="$1" groups
    mkdir -p "$r/etc"
    systemd-sysusers --root="$r" cupola.conf >/dev/null 2>&1 || fail "systemd-sysusers --root rejected cupola.conf"
    grep -q '^cupola:x:[0-9]*:[0-9]*:[^:]*:/var/lib/cupola:' "$r/etc/passwd" ||
        fail "no system user cupola with home /var/lib/cupola: $(cat "$r/etc/passwd")"
    groups="$(sed -n 's/^SupplementaryGroups=//p' "$r"/usr/lib/systemd/system/cupola-*.service | tr ' ' '\n' | sort -u)"
    [ -n "$groups" ] || fail "the units name no SupplementaryGroups"
    for g in $groups; do
        grep -q "^$g:x:[0-9]*:\(.*,\)\?cupola\(,.*\)\?\$" "$r/etc/group" || fail "cupola is not in group $g: $(cat "$r/etc/group")"
    done
}

step_units() {
    local r="$work/units-root"
    rm -rf "$r"
    cp -a "$root" "$r"
    check_units_offline "$r"
    check_user_offline "$r"
    echo "test_packaging units: cupola-slave@0 and cupola-master verify, enable and run as cupola (groups video render plugdev)"
}

# The installed ΔT table is the one read (a broken copy of it is the error), not the source tree's.
check_installed_data() {
    local b="$work/broken" out
    out="$("$root/usr/bin/cupola-slave" --help)" || fail "/usr/bin/cupola-slave --help failed"
    grep -q -- '--channel' <<<"$out" || fail "/usr/bin/cupola-slave --help does not list --channel: $out"
    out="$("$root/usr/bin/cupola-sky" position sun 1900-01-01T00:00:00Z)" || fail "cupola-sky in 1900: $out"
    grep -q '"ra_deg"' <<<"$out" || fail "cupola-sky printed no position: $out"
    rm -rf "$b"
    mkdir -p "$b/usr/bin" "$b/usr/share/cupola"
    cp "$root/usr/bin/cupola-sky" "$b/usr/bin/"
    cp -r "$root/usr/share/cupola/data" "$b/usr/share/cupola/"
    printf 'year,delta_t_s\n1700,1\n1600,2\n' >"$b/usr/share/cupola/data/time/delta_t.csv"
    if out="$("$b/usr/bin/cupola-sky" position sun 1900-01-01T00:00:00Z 2>&1)"; then
        fail "cupola-sky ignored its installed (broken) data/time/delta_t.csv: $out"
    fi
    grep -q "$b/usr/share/cupola/data/time/delta_t.csv: years must increase" <<<"$out" ||
        fail "cupola-sky did not read $b/usr/share/cupola/data: $out"
}

# A config of the package with its paths into the extracted root and its ports moved.
relocated_config() {
    python3 - "$1" "$2" "$root" "$3" <<'EOF'
import json, os, sys
source, target, root, port = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
c = json.load(open(source))
for k in ("scene", "show", "key_file"):  # absolute: the package's /usr/...; relative: next to the source
    p = root + c[k] if os.path.isabs(c[k]) else os.path.join(os.path.dirname(source), c[k])
    c[k] = os.path.normpath(p)
n = c.setdefault("network", {})
n.update(master_address="127.0.0.1", snapshot_port=port, report_port=port + 1)
if n.get("transport") == "broadcast":
    n["broadcast_address"] = "127.255.255.255"
for ch in c["channels"]:
    if "unicast_address" in ch:
        ch["unicast_address"] = "127.0.0.1:%d" % port
json.dump(c, open(target, "w"), indent=1)
EOF
}

# The render node's config with a key made as docs/DEPLOYMENT.md says: the slave loads the scene,
# show and key (strict permissions), starts EGL and, with no master, exits 3 after its idle timeout.
check_node_config() {
    local n="$work/node" rc=0
    rm -rf "$n"
    mkdir -p "$n"
    install -m 0600 /dev/null "$n/cluster.key"
    head -c32 /dev/urandom | od -An -tx1 >"$n/cluster.key"
    relocated_config "$root/usr/share/cupola/node/cluster.json" "$n/cluster.json" 47690
    sed -i "s|\"key_file\": \"[^\"]*\"|\"key_file\": \"cluster.key\"|" "$n/cluster.json"
    "$root/usr/bin/cupola-slave" --config "$n/cluster.json" --channel front --out "$n/out" --idle-timeout 1 \
        >"$n/slave.log" 2>&1 || rc=$?
    [ "$rc" -eq 3 ] || fail "the node config: cupola-slave exited $rc, not 3 (idle): $(tail -5 "$n/slave.log")"
}

# The installed example loopback-1ch.json run by the installed loopback launcher, which starts the
# installed master and slave: two frames and a domemaster.
check_installed_loopback() {
    local l="$work/loopback"
    rm -rf "$l"
    mkdir -p "$l"
    relocated_config "$root/usr/share/cupola/configs/loopback-1ch.json" "$l/loopback.json" 47692
    "$root/usr/bin/cupola-loopback" --config "$l/loopback.json" --frames 2 --out "$l/out" >"$l/loopback.log" 2>&1 ||
        fail "installed cupola-loopback failed: $(tail -5 "$l/loopback.log")"
    [ -s "$l/out/zenith/frame_000001.png" ] || fail "no frame 1 from the installed slave: $(ls -R "$l/out")"
    ls "$l/out/dome/"frame_*.png >/dev/null 2>&1 || fail "no domemaster from the installed loopback: $(ls -R "$l/out")"
}

# What the installed programs run with: their own cache, no data folder override, no display.
installed_environment() {
    export CUPOLA_CACHE_DIR="$work/cache-$step"
    unset CUPOLA_DATA_DIR DISPLAY WAYLAND_DISPLAY
}

step_installed() {
    installed_environment
    check_installed_data
    echo "test_packaging installed: the extracted programs run and read their own data"
}

step_node() {
    installed_environment
    check_node_config
    echo "test_packaging node: the node config and a key made as documented start a slave"
}

step_loopback() {
    installed_environment
    check_installed_loopback
    echo "test_packaging loopback: the installed loopback-1ch.json ran on the installed master and slave"
}

case "$step" in
    build) step_build ;;
    contents) step_contents ;;
    units) step_units ;;
    installed) step_installed ;;
    node) step_node ;;
    loopback) step_loopback ;;
    *) fail "unknown step (build, contents, units, installed, node, loopback)" ;;
esac
