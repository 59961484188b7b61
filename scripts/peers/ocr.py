"""Reads the text of part of a screenshot with Tesseract OCR (a third-party reader, run as a
separate process): the rows from TOP down, light text on a dark background, enlarged 3x first.

Usage: ocr.py IMAGE TOP
Prints the text Tesseract reads, one line per line of text.
"""

import subprocess
import sys
import tempfile

from PIL import Image, ImageOps


def main():
    path, top = sys.argv[1], int(sys.argv[2])
    image = Image.open(path).convert("L")
    image = image.crop((0, top, image.width, image.height))
    image = ImageOps.invert(image)
    image = image.resize((image.width * 3, image.height * 3), Image.LANCZOS)
    with tempfile.NamedTemporaryFile(suffix=".png") as enlarged:
        image.save(enlarged.name)
        # --psm 6: one uniform block of text.
        text = subprocess.run(
            ["tesseract", enlarged.name, "-", "--psm", "6"],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
    for line in text.splitlines():
        if line.strip():
            print(line)


if __name__ == "__main__":
    main()
