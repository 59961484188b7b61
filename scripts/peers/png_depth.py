"""Reads a 16-bit depth PNG with Pillow (an independent reader of what yarok writes).

usage: png_depth.py FILE
Prints `mode MODE`, `size WIDTH HEIGHT`, `unit TEXT` (the `depth_unit_m` text chunk, `none`
without one) and `row V...`, the first row's values as Pillow decodes them.
"""

import sys

from PIL import Image


def main():
    image = Image.open(sys.argv[1])
    image.load()
    print("mode", image.mode)
    print("size", image.width, image.height)
    print("unit", image.text.get("depth_unit_m", "none"))
    print("row", *(image.getpixel((x, 0)) for x in range(image.width)))


if __name__ == "__main__":
    main()
