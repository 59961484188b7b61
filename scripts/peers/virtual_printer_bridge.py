"""Serves OctoPrint's VirtualPrinter (a Marlin emulator; AGPL, run here as a separate process and
never linked) on a pseudo-terminal, for yarok's integration tests.

Usage: virtual_printer_bridge.py [JSON_SETTINGS [REPLUG_SECONDS]]
Prints the device's path on its first line of standard output: a symbolic link to the
pseudo-terminal, stable as a /dev/serial/by-id/ name is. Then it shuttles bytes between the
device and the printer, and reports on standard output, a line each:
  > LINE      a line the printer received;
  closed      the client closed the device (after having used it);
  dropped     the printer dropped the connection (`!!DEBUG:drop_connection`): like an
              unplugged USB cable, the device and its link disappear;
  replugged   REPLUG_SECONDS later (when given), a freshly booted printer behind a new device,
              the link pointing at it: the cable plugged back in.
Each line written to its standard input goes to the printer as if it came down the line (a
fault injected through the `!!DEBUG:` channel while the client waits on a move). It ends when
standard input closes (the test ends), the client closes the device, or the printer drops the
connection and is not replugged.
  ~ LINE      a line the printer ignored while it booted.
JSON_SETTINGS overrides the plugin's default settings, e.g. '{"sendWait": false}'; its key
"bootSeconds" (the bridge's own) makes the board boot that long after the device is first
opened, as a bootloader or a slow SD card does: what it is sent meanwhile is lost, and what the
printer says (its start banner) comes only after.
"""

import json
import logging
import os
import select
import shutil
import sys
import tempfile
import threading
import time
import tty

from octoprint.plugins.virtual_printer import VirtualPrinterPlugin
from octoprint.plugins.virtual_printer import virtual


class NoPlugins:
    """OctoPrint's plugin manager, with no plugins: the printer asks it for action hooks."""

    def get_hooks(self, *_):
        return {}


virtual.plugin_manager = NoPlugins


class Settings:
    """The slice of OctoPrint's plugin settings the VirtualPrinter reads."""

    def __init__(self, values, folder):
        self._values = values
        self._folder = folder

    def get(self, path, merged=False, **_):
        value = self._values
        for key in path:
            if not isinstance(value, dict) or key not in value:
                return None
            value = value[key]
        return value

    def get_int(self, path, **_):
        value = self.get(path)
        return None if value is None else int(value)

    def get_float(self, path, **_):
        value = self.get(path)
        return None if value is None else float(value)

    def get_boolean(self, path, **_):
        return bool(self.get(path))

    def global_get_basefolder(self, name, **_):
        folder = os.path.join(self._folder, name)
        os.makedirs(folder, exist_ok=True)
        return folder

    def set(self, *_, **__):
        pass

    def save(self, *_, **__):
        pass


def report(line):
    try:
        print(line, flush=True)
    except BrokenPipeError:
        pass


class Device:
    """A pseudo-terminal for the client, reached through a stable link to it."""

    def __init__(self, link):
        self.link = link
        self.master, self._client_side = os.openpty()
        tty.setraw(self._client_side)
        os.symlink(os.ttyname(self._client_side), link + ".new")
        os.replace(link + ".new", link)

    def let_go_of_client_side(self):
        """Closes our hold on the client's side, so that the client closing it reaches us."""
        if self._client_side is not None:
            os.close(self._client_side)
            self._client_side = None

    def unplug(self):
        os.unlink(self.link)
        self.let_go_of_client_side()
        os.close(self.master)


def serve(printer, device, ended, boot_seconds):
    """Shuttles bytes until the test ends, the client closes the device, or the printer drops
    the connection; returns which. For the first boot_seconds the board boots: it takes no line
    and says nothing."""
    outcome = []
    done = threading.Event()
    booted_at = time.monotonic() + boot_seconds

    def finish(why):
        outcome.append(why)
        done.set()

    def write_all(data):
        # Its receive buffer is 64 bytes, like a board's: it takes what fits, the rest waits.
        while data and not done.is_set():
            written = printer.write(data)
            data = data[written:]
            if not written:
                time.sleep(0.001)

    def to_printer():
        pending = b""
        while not done.is_set():
            ready, _, _ = select.select([device.master], [], [], 0.1)
            if not ready:
                continue
            try:
                pending += os.read(device.master, 4096)
            except OSError:
                # Nobody holds the device open any more.
                return finish("closed")
            device.let_go_of_client_side()
            # One write a line: the printer takes one line from each write it queues, and
            # would leave a second line of the same write waiting for the next one.
            *lines, pending = pending.split(b"\n")
            try:
                for line in lines:
                    text = line.decode(errors="replace").strip()
                    if time.monotonic() < booted_at:
                        report("~ " + text)
                        continue
                    report("> " + text)
                    write_all(line + b"\n")
            except Exception:
                return finish("dropped")

    def from_printer():
        while time.monotonic() < booted_at and not done.is_set():
            time.sleep(0.01)
        while not done.is_set():
            try:
                line = printer.readline()
            except Exception:
                return finish("dropped")
            if line:
                # Its queue holds some lines with their ending and some without.
                os.write(device.master, line if line.endswith(b"\n") else line + b"\n")

    for work in (to_printer, from_printer):
        threading.Thread(target=work, daemon=True).start()
    while not done.wait(0.05):
        if ended.is_set():
            finish("ended")
    printer.close()
    return outcome[0]


def main():
    logging.basicConfig(level=logging.CRITICAL)
    values = VirtualPrinterPlugin().get_settings_defaults()
    if len(sys.argv) > 1:
        values.update(json.loads(sys.argv[1]))
    boot_seconds = float(values.pop("bootSeconds", 0.0))
    replug = float(sys.argv[2]) if len(sys.argv) > 2 else None
    folder = tempfile.mkdtemp(prefix="yarok-virtual-printer-")
    link = os.path.join(folder, "printer")
    ended = threading.Event()

    current = {}

    def until_stdin_closes():
        for line in sys.stdin:
            # A line the test injects, as if it came down the line (`!!DEBUG:…`).
            data = line.encode()
            try:
                while data:
                    data = data[current["printer"].write(data):]
            except Exception:
                pass  # an unplugged printer takes nothing
        ended.set()

    printed = False
    while True:
        printer = virtual.VirtualPrinter(Settings(values, folder), None, folder, read_timeout=0.1)
        current["printer"] = printer
        device = Device(link)
        report("replugged" if printed else link)
        if not printed:
            threading.Thread(target=until_stdin_closes, daemon=True).start()
        printed = True
        outcome = serve(printer, device, ended, boot_seconds)
        device.unplug()
        if outcome != "ended":
            report(outcome)
        if outcome != "dropped" or replug is None or ended.wait(replug):
            break
    shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
