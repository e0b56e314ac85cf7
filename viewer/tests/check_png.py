"""Checks a screenshot: PNG of the expected size, and not blank.

Decodes the PNG with zlib alone (the machines have no Pillow or numpy): 8-bit RGB or RGBA,
non-interlaced, every scanline filter. "Not blank" means the scene was drawn: the grey-level
standard deviation is above 10 (of 255) and over 10% of the pixels differ from the background
colour, taken at the top-left corner (the sky above the scene).
Usage: check_png.py FILE WIDTH HEIGHT
"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        sys.exit(f"{path}: unsupported PNG (depth {depth}, colour type {colour}, interlace {interlace})")
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous, pos = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[pos], bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            upper_left = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - upper_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - upper_left)
                predictor = left if pa <= pb and pa <= pc else up if pb <= pc else upper_left
                line[i] = (line[i] + predictor) & 255
        rows.append(line)
        previous = line
    return width, height, channels, rows


def write_flat_png(path, width, height, rgb):
    """A PNG of one colour (filter 0 on every row), for the self-test."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                  + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def self_test():
    """The check must fail on a flat image and on a wrong size: run it as a subprocess on both."""
    import os
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        flat = os.path.join(folder, "flat.png")
        write_flat_png(flat, 64, 32, (41, 46, 54))
        blank = subprocess.run([sys.executable, __file__, flat, "64", "32"], capture_output=True, text=True)
        size = subprocess.run([sys.executable, __file__, flat, "65", "32"], capture_output=True, text=True)
    if blank.returncode == 0 or "looks blank" not in blank.stderr:
        sys.exit("self-test: a flat image passed the check")
    if size.returncode == 0 or "expected 65x32" not in size.stderr:
        sys.exit("self-test: a wrong size passed the check")
    print("self-test: flat image and wrong size rejected")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    path, want_width, want_height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    width, height, channels, rows = read_png(path)
    if (width, height) != (want_width, want_height):
        sys.exit(f"{path}: {width}x{height}, expected {want_width}x{want_height}")
    background = tuple(rows[0][:3])
    grey, differing = [], 0
    for line in rows:
        for x in range(width):
            pixel = tuple(line[x * channels:x * channels + 3])
            grey.append(sum(pixel) / 3.0)
            differing += max(abs(a - b) for a, b in zip(pixel, background)) > 8
    mean = sum(grey) / len(grey)
    deviation = (sum((g - mean) ** 2 for g in grey) / len(grey)) ** 0.5
    fraction = differing / len(grey)
    print(f"{path}: {width}x{height}, grey deviation {deviation:.1f}, {100 * fraction:.1f}% not background")
    if deviation <= 10.0 or fraction <= 0.10:
        sys.exit(f"{path}: looks blank")


if __name__ == "__main__":
    main()
