"""Checks a screenshot: PNG of the expected size, not blank, and (with --report) the ground and the
bodies drawn where the scene puts them.

Decodes the PNG with zlib alone (the machines have no Pillow or numpy): 8-bit RGB or RGBA,
non-interlaced, every scanline filter.

"Not blank": the grey-level standard deviation is above 10 (of 255) and over 10% of the pixels
differ from the background colour, taken at the top-left corner (the sky above the scene).

With --report FILE (written by collide-viewer --camera-json), the checker projects points itself,
from the camera the viewer reports (eye, target, up, vertical field of view: a standard look-at
and perspective, so the renderer's own matrices are not trusted), and looks at the pixels there:
- bodies: every dynamic or kinematic convex body whose centre of mass projects into the image, is
  at least 2 pixels across and is not possibly hidden by another body (the ray from the eye through
  that pixel enters another body's bounding box before the centre) must be drawn in its own colour
  there. The shading only
  scales the colour (lighting is a scalar factor), so the pixel must be k times the body's colour,
  up to 10% of its length: that tells an orange box from a blue one, the grey ground or the sky;
- ground: the largest level static box or plane. Points of its top face on a 1 m lattice within
  25 m of the camera's target, in the image and not possibly hidden by a body, must have
  the ground's colour (grey, the same 10%) and be lit: at least twice as bright as the sky, as a
  face turned to the light (which comes from above) is;
- enough of both were checked (at least 3 bodies and 20 ground points), so that a camera looking
  away from the scene cannot pass.
Usage: check_png.py FILE WIDTH HEIGHT [--report FILE]; check_png.py --self-test
"""
import json
import math
import struct
import sys
import zlib

CONVEX = {"sphere", "capsule", "box", "cylinder", "ellipsoid", "convex_hull", "hull", "kdop"}


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


def blank_check(rows, width, channels):
    """Returns (deviation, fraction not background)."""
    background = tuple(rows[0][:3])
    grey, differing = [], 0
    for line in rows:
        for x in range(width):
            pixel = tuple(line[x * channels:x * channels + 3])
            grey.append(sum(pixel) / 3.0)
            differing += max(abs(a - b) for a, b in zip(pixel, background)) > 8
    mean = sum(grey) / len(grey)
    deviation = (sum((g - mean) ** 2 for g in grey) / len(grey)) ** 0.5
    return deviation, differing / len(grey)


# ---- vectors ----
def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(a):
    length = math.sqrt(dot(a, a))
    return [a[0] / length, a[1] / length, a[2] / length]


class Camera:
    """gluLookAt + gluPerspective, from the report's numbers."""

    def __init__(self, report):
        self.eye = report["eye"]
        self.forward = normalize(sub(report["target"], self.eye))
        self.side = normalize(cross(self.forward, report["up"]))
        self.up = cross(self.side, self.forward)
        self.tan_half = math.tan(0.5 * report["fov_y"])
        self.width, self.height = report["width"], report["height"]
        self.aspect = self.width / self.height

    def depth(self, point):
        return dot(sub(point, self.eye), self.forward)

    def project(self, point):
        """(x, y) in pixels, y down, or None behind the eye."""
        d = sub(point, self.eye)
        z = dot(d, self.forward)
        if z <= 1e-3:
            return None
        x = dot(d, self.side) / (z * self.tan_half * self.aspect)
        y = dot(d, self.up) / (z * self.tan_half)
        return (x + 1.0) * 0.5 * self.width, (1.0 - y) * 0.5 * self.height

    def pixels_per_metre(self, depth):
        return 0.5 * self.height / (depth * self.tan_half)


def colour_matches(pixel, colour):
    """The pixel is k times the colour (0.1 < k), up to 10% of the pixel's length."""
    reference = [255.0 * c for c in colour]
    k = dot(pixel, reference) / dot(reference, reference)
    residual = sub(pixel, [k * c for c in reference])
    length = math.sqrt(dot(pixel, pixel))
    return k > 0.1 and length > 0.0 and math.sqrt(dot(residual, residual)) <= 0.1 * length


def ray_through(camera, pixel):
    """The unit ray from the eye through the centre of the pixel the point falls in."""
    x, y = int(pixel[0]) + 0.5, int(pixel[1]) + 0.5
    ndc_x, ndc_y = 2.0 * x / camera.width - 1.0, 1.0 - 2.0 * y / camera.height
    return normalize([camera.forward[i] + ndc_x * camera.tan_half * camera.aspect * camera.side[i] +
                      ndc_y * camera.tan_half * camera.up[i] for i in range(3)])


def box_entry(origin, direction, low, high):
    """Where the ray enters the box (0 from inside), or None if it misses."""
    near, far = 0.0, math.inf
    for i in range(3):
        if abs(direction[i]) < 1e-12:
            if not low[i] <= origin[i] <= high[i]:
                return None
            continue
        t0, t1 = (low[i] - origin[i]) / direction[i], (high[i] - origin[i]) / direction[i]
        near, far = max(near, min(t0, t1)), min(far, max(t0, t1))
        if near > far:
            return None
    return near


def hidden(camera, occluders, pixel, point, skip=None):
    """Could a body other than `skip` hide `point` from the eye along the ray through the pixel? Its
    box (which holds the body) would have to be entered before the point's distance."""
    direction = ray_through(camera, pixel)
    distance = dot(sub(point, camera.eye), direction)
    for body in occluders:
        if body is skip:
            continue
        entry = box_entry(camera.eye, direction, body["min"], body["max"])
        if entry is not None and entry < distance:
            return True
    return False


def find_ground(bodies):
    best, best_area = None, 0.0
    for b in bodies:
        level = b["shape"] == "plane" or (b["shape"] == "box" and abs(abs(b["rotation"][0]) - 1.0) < 1e-6)
        if b["type"] != "static" or not level:
            continue
        area = (b["max"][0] - b["min"][0]) * (b["max"][2] - b["min"][2])
        if area > best_area:
            best, best_area = b, area
    return best


def check_report(rows, channels, report):
    """Returns (bodies checked, ground points checked, failures)."""
    camera = Camera(report)
    width, height = report["width"], report["height"]
    sky = [255.0 * c for c in report["background"]]
    bodies = report["bodies"]
    ground = find_ground(bodies)
    occluders = [b for b in bodies if b is not ground and b["shape"] != "plane"]
    failures = []

    def pixel_at(point):
        x, y = int(point[0]), int(point[1])
        return [float(v) for v in rows[y][x * channels:x * channels + 3]]

    def in_image(point):
        return point is not None and 1.0 <= point[0] < width - 1.0 and 1.0 <= point[1] < height - 1.0

    body_count = 0
    for body in occluders:
        if body["type"] == "static" or body["shape"] not in CONVEX:
            continue
        at = camera.project(body["center"])
        if not in_image(at):
            continue
        depth = camera.depth(body["center"])
        smallest = 0.5 * min(b - a for a, b in zip(body["min"], body["max"]))
        if smallest * camera.pixels_per_metre(depth) < 2.0:
            continue
        if hidden(camera, occluders, at, body["center"], skip=body):
            continue
        body_count += 1
        pixel = pixel_at(at)
        if not colour_matches(pixel, body["colour"]):
            failures.append(f"body {body['name']} at pixel ({int(at[0])}, {int(at[1])}): {pixel}, "
                            f"expected a shade of {[round(255 * c) for c in body['colour']]}")

    ground_count = 0
    if ground is None:
        failures.append("no level static box or plane to check the ground on")
    elif camera.eye[1] <= ground["max"][1]:
        failures.append("the camera is below the ground's top")
    else:
        top = ground["max"][1]
        target = report["target"]
        for i in range(-25, 26):
            for j in range(-25, 26):
                point = [target[0] + i + 0.37, top, target[2] + j + 0.37]
                if not (ground["min"][0] <= point[0] <= ground["max"][0] and
                        ground["min"][2] <= point[2] <= ground["max"][2]):
                    continue
                at = camera.project(point)
                if not in_image(at) or hidden(camera, occluders, at, point):
                    continue
                ground_count += 1
                pixel = pixel_at(at)
                if not colour_matches(pixel, ground["colour"]) or sum(pixel) < 2.0 * sum(sky):
                    failures.append(f"ground at pixel ({int(at[0])}, {int(at[1])}): {pixel}, expected a lit shade "
                                    f"of {[round(255 * c) for c in ground['colour']]}")
    if body_count < 3:
        failures.append(f"only {body_count} bodies could be checked (at least 3)")
    if ground_count < 20:
        failures.append(f"only {ground_count} ground points could be checked (at least 20)")
    return body_count, ground_count, failures


def synthetic_scene():
    """A report and an image drawn to match it: sky on top, lit ground below the horizon, and three
    coloured disks where three spheres stand."""
    width, height = 160, 90
    report = {"width": width, "height": height, "eye": [0.0, 4.0, 12.0], "target": [0.0, 0.5, 0.0],
              "up": [0, 1, 0], "fov_y": 0.8, "background": [0.16, 0.18, 0.21], "bodies": [
                  {"name": "ground", "type": "static", "shape": "plane", "center": [0, 0, 0],
                   "min": [-1e30, -1e30, -1e30], "max": [1e30, 0.0, 1e30], "rotation": [1, 0, 0, 0],
                   "colour": [0.62, 0.64, 0.66], "checker": True}]}
    colours = [[0.9, 0.55, 0.3], [0.35, 0.65, 0.9], [0.55, 0.8, 0.4]]
    for i, colour in enumerate(colours):
        x = 3.0 * (i - 1)
        report["bodies"].append({"name": f"ball{i}", "type": "dynamic", "shape": "sphere", "center": [x, 0.5, 0.0],
                                 "min": [x - 0.5, 0.0, -0.5], "max": [x + 0.5, 1.0, 0.5], "rotation": [1, 0, 0, 0],
                                 "colour": colour, "checker": False})
    camera = Camera(report)
    sky = [round(255 * c) for c in report["background"]]
    lit_ground = [round(0.9 * 255 * c) for c in report["bodies"][0]["colour"]]
    rows = []
    for y in range(height):
        line = bytearray()
        for x in range(width):
            # Below the horizon when the ray through the pixel goes down.
            ndc_y = 1.0 - 2.0 * (y + 0.5) / height
            ray_y = camera.forward[1] + ndc_y * camera.tan_half * camera.up[1]
            line += bytes(lit_ground if ray_y < 0.0 else sky)
        rows.append(line)
    for body in report["bodies"][1:]:
        cx, cy = camera.project(body["center"])
        radius = 0.5 * camera.pixels_per_metre(camera.depth(body["center"]))
        shade = [round(0.7 * 255 * c) for c in body["colour"]]
        for y in range(height):
            for x in range(width):
                if math.hypot(x + 0.5 - cx, y + 0.5 - cy) <= radius:
                    rows[y][3 * x:3 * x + 3] = bytes(shade)
    return report, rows


def self_test():
    """The checks must fail on a flat image, a wrong size, a missing body and a missing ground."""
    import copy
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

    report, rows = synthetic_scene()
    bodies, ground, failures = check_report(rows, 3, report)
    if failures or bodies != 3:
        sys.exit(f"self-test: the matching synthetic image fails: {bodies} bodies, {ground} ground, {failures[:3]}")
    # A body missing (its disk painted over with the ground), or moved by the report.
    missing = copy.deepcopy(rows)
    cx, cy = Camera(report).project(report["bodies"][2]["center"])
    for y in range(int(cy) - 8, int(cy) + 9):
        for x in range(int(cx) - 8, int(cx) + 9):
            missing[y][3 * x:3 * x + 3] = missing[int(cy) + 20][3 * x:3 * x + 3]
    if not any("body ball1" in f for f in check_report(missing, 3, report)[2]):
        sys.exit("self-test: a missing body passed the check")
    swapped = copy.deepcopy(report)
    swapped["bodies"][1]["colour"], swapped["bodies"][3]["colour"] = report["bodies"][3]["colour"], \
        report["bodies"][1]["colour"]
    if not any("body ball0" in f for f in check_report(rows, 3, swapped)[2]):
        sys.exit("self-test: a body of the wrong colour passed the check")
    # No ground drawn: sky where the ground should be.
    skyless = [bytearray(rows[0]) for _ in rows]
    if not any(f.startswith("ground at") for f in check_report(skyless, 3, report)[2]):
        sys.exit("self-test: a missing ground passed the check")
    # A camera looking away: nothing to check.
    away = copy.deepcopy(report)
    away["target"] = [0.0, 4.0, 30.0]
    if not any("could be checked" in f for f in check_report(rows, 3, away)[2]):
        sys.exit("self-test: a camera looking away passed the check")
    print("self-test: flat image, wrong size, missing or miscoloured body, missing ground and a camera looking "
          "away rejected")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    path, want_width, want_height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    report_path = sys.argv[5] if len(sys.argv) > 5 and sys.argv[4] == "--report" else None
    width, height, channels, rows = read_png(path)
    if (width, height) != (want_width, want_height):
        sys.exit(f"{path}: {width}x{height}, expected {want_width}x{want_height}")
    deviation, fraction = blank_check(rows, width, channels)
    print(f"{path}: {width}x{height}, grey deviation {deviation:.1f}, {100 * fraction:.1f}% not background")
    if deviation <= 10.0 or fraction <= 0.10:
        sys.exit(f"{path}: looks blank")
    if report_path is None:
        return
    report = json.load(open(report_path))
    if (report["width"], report["height"]) != (width, height):
        sys.exit(f"{report_path}: for a {report['width']}x{report['height']} image, not {width}x{height}")
    bodies, ground, failures = check_report(rows, channels, report)
    print(f"{path}: {bodies} bodies and {ground} ground points checked against {report_path}")
    if failures:
        for failure in failures[:10]:
            print(failure, file=sys.stderr)
        sys.exit(f"{path}: {len(failures)} pixel checks failed")


if __name__ == "__main__":
    main()
