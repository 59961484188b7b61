"""Drives a window on an X server as a user would, with python-xlib (a third-party X client, run
as a separate process): waits for it, reads its title, takes a screenshot, presses a key, closes
it the way a window manager's close button does (WM_DELETE_WINDOW).

Usage: x11_window.py DISPLAY TITLE_PREFIX COMMAND [ARG]
  wait SECONDS      wait until a window whose title starts with TITLE_PREFIX is mapped
  title             print its title
  screenshot FILE   save what it shows as PNG and print `size WIDTH HEIGHT`
  key KEYSYM        press and release a key (an X keysym name: space, Right, h)
  drag BUTTON X0 Y0 X1 Y1
                    press a mouse button (1 left, 3 right) at window pixel (X0, Y0), move to
                    (X1, Y1) in steps, release
  close             ask it to close
"""

import sys
import time

from PIL import Image
from Xlib import X, XK, display, protocol
from Xlib.ext import xtest


def find(conn, prefix):
    for window in conn.screen().root.query_tree().children:
        try:
            name = window.get_wm_name()
            attributes = window.get_attributes()
        except Exception:
            continue
        if isinstance(name, bytes):
            name = name.decode("utf-8", "replace")
        if name and name.startswith(prefix) and attributes.map_state == X.IsViewable:
            return window
    return None


def title(window):
    name = window.get_wm_name()
    return name.decode("utf-8", "replace") if isinstance(name, bytes) else str(name or "")


def main():
    display_name, prefix, command = sys.argv[1:4]
    arg = sys.argv[4] if len(sys.argv) > 4 else None
    conn = display.Display(display_name)
    if command == "wait":
        deadline = time.monotonic() + float(arg)
        while find(conn, prefix) is None:
            if time.monotonic() > deadline:
                sys.exit(f"no window titled {prefix}… within {arg} s")
            time.sleep(0.05)
        return
    window = find(conn, prefix)
    if window is None:
        sys.exit(f"no window titled {prefix}…")
    if command == "title":
        print(title(window))
    elif command == "screenshot":
        geometry = window.get_geometry()
        raw = window.get_image(0, 0, geometry.width, geometry.height, X.ZPixmap, 0xFFFFFFFF)
        image = Image.frombytes("RGB", (geometry.width, geometry.height), raw.data, "raw", "BGRX")
        image.save(arg)
        print("size", geometry.width, geometry.height)
    elif command == "key":
        window.set_input_focus(X.RevertToParent, X.CurrentTime)
        conn.sync()
        code = conn.keysym_to_keycode(XK.string_to_keysym(arg))
        xtest.fake_input(conn, X.KeyPress, code)
        xtest.fake_input(conn, X.KeyRelease, code)
        conn.sync()
    elif command == "drag":
        button, x0, y0, x1, y1 = (int(v) for v in sys.argv[4:9])
        origin = window.translate_coords(conn.screen().root, 0, 0)
        left, top = -origin.x, -origin.y

        def move(x, y):
            xtest.fake_input(conn, X.MotionNotify, x=left + x, y=top + y)
            conn.sync()
            time.sleep(0.02)

        move(x0, y0)
        xtest.fake_input(conn, X.ButtonPress, button)
        for step in range(1, 11):
            move(x0 + (x1 - x0) * step // 10, y0 + (y1 - y0) * step // 10)
        xtest.fake_input(conn, X.ButtonRelease, button)
        conn.sync()
    elif command == "close":
        protocols = conn.intern_atom("WM_PROTOCOLS")
        delete = conn.intern_atom("WM_DELETE_WINDOW")
        event = protocol.event.ClientMessage(
            window=window, client_type=protocols, data=(32, [delete, X.CurrentTime, 0, 0, 0])
        )
        window.send_event(event, event_mask=X.NoEventMask)
        conn.sync()
    else:
        sys.exit(f"unknown command {command}")


if __name__ == "__main__":
    main()
