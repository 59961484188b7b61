"""Serves OctoPrint's VirtualPrinter (a Marlin emulator; AGPL, run here as a separate process and
never linked) on a pseudo-terminal, for yarok's integration tests.

Usage: virtual_printer_bridge.py [JSON_SETTINGS]
Prints the pseudo-terminal's device path on its first line of standard output, then shuttles
bytes between the device and the printer until standard input closes (the test ends) or the
printer drops the connection (`!!DEBUG:drop_connection`), when it closes the device side.
JSON_SETTINGS overrides the plugin's default settings, e.g. '{"sendWait": false}'.
"""

import json
import logging
import os
import select
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


def main():
    logging.basicConfig(level=logging.CRITICAL)
    values = VirtualPrinterPlugin().get_settings_defaults()
    if len(sys.argv) > 1:
        values.update(json.loads(sys.argv[1]))
    folder = tempfile.mkdtemp(prefix="yarok-virtual-printer-")
    printer = virtual.VirtualPrinter(Settings(values, folder), None, folder, read_timeout=0.1)

    master, slave = os.openpty()
    tty.setraw(slave)
    print(os.ttyname(slave), flush=True)
    done = threading.Event()

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
            ready, _, _ = select.select([master], [], [], 0.1)
            if not ready:
                continue
            try:
                pending += os.read(master, 4096)
                # One write a line: the printer takes one line from each write it queues, and
                # would leave a second line of the same write waiting for the next one.
                *lines, pending = pending.split(b"\n")
                for line in lines:
                    write_all(line + b"\n")
            except Exception:
                break
        done.set()

    def from_printer():
        while not done.is_set():
            try:
                line = printer.readline()
            except Exception:
                break
            if line:
                # Its queue holds some lines with their ending and some without.
                os.write(master, line if line.endswith(b"\n") else line + b"\n")
        done.set()

    def until_stdin_closes():
        sys.stdin.read()
        done.set()

    threads = [threading.Thread(target=work, daemon=True)
               for work in (to_printer, from_printer, until_stdin_closes)]
    for thread in threads:
        thread.start()
    done.wait()
    printer.close()
    # Closing both sides ends the device: the driver reads the end of the stream.
    os.close(slave)
    os.close(master)


if __name__ == "__main__":
    main()
