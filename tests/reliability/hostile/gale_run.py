"""The hostile-case runner's tools: run the gale program, look at what it leaves behind.

Python standard library only. Nothing here trusts a number the program computes about its own
success: exit codes and signals come from the kernel (os.wait4), file contents are read back
and decoded here (PNG chunks and CRCs, JSON), .vdb files are opened by OpenVDB's own vdb_print.
"""

import hashlib
import json
import os
import re
import shutil
import signal
import struct
import subprocess
import tempfile
import time
import zlib


class Result:
    """How one run of the program ended."""

    def __init__(self, rc, sig, out, err, seconds, peak_kib, timed_out):
        self.rc = rc  # exit code, or None when ended by a signal
        self.sig = sig  # the signal that ended it, or 0
        self.out = out
        self.err = err
        self.seconds = seconds
        self.peak_kib = peak_kib  # ru_maxrss of the child, KiB (the kernel's count)
        self.timed_out = timed_out

    def ended(self):
        """'exit N' or 'killed by SIGX' or 'timed out'."""
        if self.timed_out:
            return "timed out"
        if self.sig:
            return "killed by " + signal.Signals(self.sig).name
        return "exit %d" % self.rc

    def error_lines(self):
        return [l for l in self.err.splitlines() if l.startswith("gale: error:")]


class Gale:
    """Starts the program: `gale` is its path, `shim` the full-disk LD_PRELOAD library."""

    def __init__(self, gale, shim, scratch):
        self.gale = os.path.abspath(gale)
        self.shim = os.path.abspath(shim) if shim else None
        self.scratch = scratch
        self.count = 0

    def folder(self, name):
        """A fresh empty working folder for one case."""
        self.count += 1
        path = os.path.join(self.scratch, "%03d-%s" % (self.count, re.sub(r"[^\w.-]", "_", name)))
        os.makedirs(path)
        return path

    def start(self, args, cwd, env=None, stdin=None):
        """Starts gale ARGS in cwd (stdout and stderr to files there, .gale-run-*); returns a Run."""
        e = dict(os.environ)
        e.update(env or {})
        self.count += 1
        base = os.path.join(self.scratch, "log-%03d" % self.count)
        out, err = open(base + ".out", "wb"), open(base + ".err", "wb")
        p = subprocess.Popen([self.gale] + list(args), cwd=cwd, env=e, stdout=out, stderr=err,
                             stdin=stdin if stdin is not None else subprocess.DEVNULL)
        out.close()
        err.close()
        return Run(p, base)

    def run(self, args, cwd, env=None, timeout=120, stdin=None):
        return self.start(args, cwd, env, stdin).wait(timeout)

    def full_disk_env(self, folder, free_bytes, report_free=False):
        """The shim's settings: free_bytes may be written under folder, then ENOSPC; with
        report_free, statvfs there reports free_bytes free as well."""
        env = {"LD_PRELOAD": self.shim, "GALE_FULL_DISK_FOLDER": folder,
               "GALE_FULL_DISK_BYTES": str(free_bytes),
               "ASAN_OPTIONS": os.environ.get("ASAN_OPTIONS", "") + ":verify_asan_link_order=0"}
        if report_free:
            env["GALE_FULL_DISK_STATVFS"] = "1"
        return env


class Run:
    """A running child: its output so far, signals, and the end."""

    def __init__(self, popen, base):
        self.p = popen
        self.pid = popen.pid
        self.base = base
        self.t0 = time.monotonic()
        self.result = None

    def err_so_far(self):
        with open(self.base + ".err", "rb") as f:
            return f.read().decode("utf-8", "replace")

    def signal(self, sig):
        if self.result is None:
            try:
                os.kill(self.pid, sig)
            except ProcessLookupError:
                pass

    def wait_for(self, pattern, timeout):
        """Polls stderr until the regular expression matches (True), the child ends or the
        timeout passes (False)."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if re.search(pattern, self.err_so_far()):
                return True
            if self._reap(False):
                return bool(re.search(pattern, self.err_so_far()))
            time.sleep(0.005)
        return False

    def wait_for_temporary(self, folder, timeout):
        """Polls folder until a temporary appears in it (the run has started writing: True), the
        child ends or the timeout passes (False)."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if os.path.isdir(folder) and [f for f in leftovers(folder) if f != ".gale.lock"]:
                return True
            if self._reap(False):
                return False
            time.sleep(0.002)
        return False

    def _reap(self, block):
        if self.result is not None:
            return True
        pid, status, usage = os.wait4(self.pid, 0 if block else os.WNOHANG)
        if pid == 0:
            return False
        self.p.returncode = 0  # reaped here, not by Popen
        seconds = time.monotonic() - self.t0
        rc = os.WEXITSTATUS(status) if os.WIFEXITED(status) else None
        sig = os.WTERMSIG(status) if os.WIFSIGNALED(status) else 0
        self.result = Result(rc, sig, read_text(self.base + ".out"), read_text(self.base + ".err"),
                             seconds, usage.ru_maxrss, self._timed_out)
        return True

    _timed_out = False

    def wait(self, timeout=120):
        end = time.monotonic() + timeout
        while not self._reap(False):
            if time.monotonic() > end:
                self._timed_out = True
                os.kill(self.pid, signal.SIGKILL)
                self._reap(True)
                break
            time.sleep(0.005)
        return self.result


def read_text(path):
    with open(path, "rb") as f:
        return f.read().decode("utf-8", "replace")


def write_text(path, text):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def snapshot(folder):
    """Every regular file under folder (relative path) with the SHA-256 of its bytes."""
    out = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            if os.path.isfile(path) and not os.path.islink(path):
                with open(path, "rb") as f:
                    out[os.path.relpath(path, folder)] = hashlib.sha256(f.read()).hexdigest()
    return out


def leftovers(folder):
    """Temporaries and locks under folder: hidden files (.NAME.tmp-PID-N.ext, .gale.lock) and
    names holding '.tmp'."""
    found = []
    for root, _, files in os.walk(folder):
        for name in files:
            if name.startswith(".") or ".tmp" in name:
                found.append(os.path.relpath(os.path.join(root, name), folder))
    return sorted(found)


def png_check(path):
    """None if path is a whole PNG (signature, every chunk's CRC, IHDR, IDAT that inflates to
    exactly the rows IHDR promises, IEND last), else the reason."""
    try:
        data = open(path, "rb").read()
    except OSError as e:
        return str(e)
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return "no PNG signature"
    pos, idat, ihdr, ended = 8, b"", None, False
    while pos + 12 <= len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if len(body) < n or pos + 12 + n > len(data):
            return "chunk %r cut" % kind
        (crc,) = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            return "bad CRC in %r" % kind
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            ended = True
            break
        pos += 12 + n
    if not ihdr or not ended:
        return "no IHDR" if not ihdr else "no IEND (cut)"
    w, h, depth, colour = ihdr[:4]
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if channels is None or ihdr[6] != 0:
        return None  # palette or interlaced: chunks and CRCs were whole; good enough
    try:
        raw = zlib.decompress(idat)
    except zlib.error as e:
        return "IDAT does not inflate: %s" % e
    want = h * (1 + w * channels * depth // 8)
    return None if len(raw) == want else "IDAT holds %d bytes, IHDR promises %d" % (len(raw), want)


def png_rgb(path):
    """(width, height, [(r, g, b), ...]) of an 8-bit RGB or RGBA non-interlaced PNG."""
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    assert depth == 8 and colour in (2, 6), "8-bit RGB(A) expected"
    bpp = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    pixels = [tuple(r[x * bpp:x * bpp + 3]) for r in rows for x in range(w)]
    return w, h, pixels


def vdb_check(path):
    """None if OpenVDB's vdb_print reads the whole file, else the reason."""
    tool = shutil.which("vdb_print")
    if not tool:
        return None if os.path.getsize(path) > 0 else "empty"
    p = subprocess.run([tool, "-l", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    return None if p.returncode == 0 else "vdb_print: " + p.stderr.decode()[:120].strip()


def json_file(path):
    with open(path) as f:
        return json.load(f)


def scratch_folder():
    return tempfile.mkdtemp(prefix="gale-hostile-")
