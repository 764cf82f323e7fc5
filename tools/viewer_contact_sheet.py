#!/usr/bin/env python3
"""Screenshots of gridrt --view's seven views (keys 1..7) under a virtual display, laid
out as one contact sheet, each named (docs/viewer.md's picture):

    tools/viewer_contact_sheet.py OUT.png [SCENE] [--width 240 --height 180]

Needs Xvfb, xdotool and xwd (tools/setup.sh installs xvfb, xdotool, x11-apps) and
oiiotool (openimageio-tools). Python's standard library only.
"""
import argparse
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VIEWS = ["image", "depth", "normal", "albedo", "pe", "tests", "listlen"]
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
WAIT_S = 60  # the first window of a run may compile the kernels


def fail(message):
    sys.exit("viewer_contact_sheet: " + message)


def start_xvfb():
    read_end, write_end = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                               "1024x768x24", "-noreset", "-ardelay", "600000", "-nolisten", "tcp"], pass_fds=[write_end],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_end)
    with os.fdopen(read_end) as pipe:
        number = pipe.readline().strip()
    if not number:
        fail("Xvfb did not start")
    return server, ":" + number


def x(display, *args):
    env = dict(os.environ, DISPLAY=display)
    return subprocess.run(args, env=env, capture_output=True).stdout


def wait_for(what, test):
    start = time.time()
    while time.time() - start < WAIT_S:
        got = test()
        if got:
            return got
        time.sleep(0.05)
    fail("timed out waiting for " + what)


def xwd_to_ppm(data, path):
    """An xwd dump of a 24-bit TrueColor window (32-bit pixels) as a binary PPM."""
    fields = struct.unpack(">25I", data[:100])
    header, width, height = fields[0], fields[4], fields[5]
    byte_order, bits, line = fields[7], fields[11], fields[12]
    masks, colours = fields[14:17], fields[19]
    if fields[2] != 2 or bits != 32:
        fail("unexpected xwd layout (format %d, %d bits a pixel)" % (fields[2], bits))
    start = header + 12 * colours
    order = "<" if byte_order == 0 else ">"
    shifts = [(m & -m).bit_length() - 1 for m in masks]
    rgb = bytearray()
    for y in range(height):
        row = struct.unpack_from(order + "%dI" % width, data, start + y * line)
        for v in row:
            rgb += bytes(((v & m) >> s) & 255 for m, s in zip(masks, shifts))
    with open(path, "wb") as out:
        out.write(b"P6\n%d %d\n255\n" % (width, height) + bytes(rgb))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out")
    parser.add_argument("scene", nargs="?", default="")
    parser.add_argument("--width", type=int, default=240)
    parser.add_argument("--height", type=int, default=180)
    args = parser.parse_args()
    for tool in ("Xvfb", "xdotool", "xwd", "oiiotool"):
        if not shutil.which(tool):
            fail(tool + " is missing (tools/setup.sh installs it)")
    gridrt = os.environ.get("GRIDRT", os.path.join(ROOT, "build", "gridrt"))
    server, display = start_xvfb()
    work = tempfile.mkdtemp()
    viewer = None
    try:
        command = [gridrt, "--view", "-q", "--width", str(args.width), "--height", str(args.height)]
        if args.scene:
            command.insert(2, os.path.abspath(args.scene))
        viewer = subprocess.Popen(command, cwd=work, env=dict(os.environ, DISPLAY=display),
                                  stdout=subprocess.DEVNULL)
        window = wait_for("the window", lambda: x(display, "xdotool", "search", "--onlyvisible",
                                                  "--name", "^gridrt").split()[:1])[0].decode()
        x(display, "xdotool", "windowfocus", "--sync", window)
        pictures = []
        for number, view in enumerate(VIEWS):
            # P's note in the title comes with the first frame after it: the view is shown.
            x(display, "xdotool", "key", "--delay", "20", str(number + 1), "p")
            note = "wrote %s_view_%04d.png" % (
                os.path.splitext(os.path.basename(args.scene))[0] if args.scene else "gridrt", number)
            wait_for(view, lambda: note in x(display, "xdotool", "getwindowname", window).decode())
            path = os.path.join(work, view + ".ppm")
            xwd_to_ppm(x(display, "xwd", "-silent", "-id", window), path)
            pictures += [path, "--ch", "R,G,B", "--cut", "0,0,%d,%d" % (args.width - 1, args.height + 17)]
            if os.path.exists(FONT):
                pictures += ["--text:x=4:y=%d:size=14:font=%s" % (args.height + 14, FONT), view]
        x(display, "xdotool", "key", "q")
        viewer.wait(WAIT_S)
        subprocess.run(["oiiotool"] + pictures + ["--mosaic:pad=4", "4x2", "-o", args.out], check=True)
        print("viewer_contact_sheet: %d views -> %s" % (len(VIEWS), args.out))
    finally:
        if viewer and viewer.poll() is None:
            viewer.kill()
        server.terminate()
        server.wait()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
