"""fognav.perception on analytic range data: a staircase seen from the humanoid's head, as a
float point image and as a 16-bit depth PNG with its intrinsics."""
import struct
import zlib

import numpy as np
import pytest

import fognav
from fognav import perception

# the staircase: floor, then treads of RISE each, DEPTH deep, from X0 on along +x; the last
# tread runs on to the end of the view; 4 m wide, so its sides are out of view
X0, DEPTH, RISE, STEPS = 1.0, 0.25, 0.04, 3
W, H, FX, FY = 640, 480, 500.0, 500.0
CX, CY = (W - 1) / 2, (H - 1) / 2
CAMERA_HEIGHT, PITCH = 0.55, np.radians(25)


def camera_pose():
    """X_GC: the camera 0.55 m over the grid origin, looking along +x, pitched down."""
    c, s = np.cos(PITCH), np.sin(PITCH)
    z_c = np.array([c, 0, -s])       # optical axis
    x_c = np.array([0.0, -1.0, 0.0])  # image right
    y_c = np.cross(z_c, x_c)          # image down
    X = np.eye(4)
    X[:3, :3] = np.column_stack([x_c, y_c, z_c])
    X[:3, 3] = [0, 0, CAMERA_HEIGHT]
    return X


def staircase_depth():
    """Depth along the optical axis per pixel (metres) and the surface each pixel sees: 0 the
    floor, 1..STEPS the treads, -1..-STEPS the risers."""
    X = camera_pose()
    u, v = np.meshgrid(np.arange(W), np.arange(H))
    d_c = np.stack([(u - CX) / FX, (v - CY) / FY, np.ones_like(u, dtype=float)], axis=-1)
    d = d_c @ X[:3, :3].T
    o = X[:3, 3]
    best = np.full((H, W), np.inf)
    surface = np.zeros((H, W), dtype=int)

    def offer(t, valid, sid):
        better = valid & (t > 0) & (t < best)
        best[better] = t[better]
        surface[better] = sid

    with np.errstate(divide="ignore", invalid="ignore"):
        t = (0 - o[2]) / d[..., 2]
        offer(t, o[0] + t * d[..., 0] < X0, 0)
        for k in range(STEPS):
            h = RISE * (k + 1)
            lo, hi = X0 + DEPTH * k, X0 + DEPTH * (k + 1) if k < STEPS - 1 else 1e9
            t = (h - o[2]) / d[..., 2]
            x = o[0] + t * d[..., 0]
            offer(t, (x >= lo) & (x < hi), k + 1)
            t = (lo - o[0]) / d[..., 0]
            z = o[2] + t * d[..., 2]
            offer(t, (z >= h - RISE) & (z <= h), -(k + 1))
    best[~np.isfinite(best)] = np.nan
    return best.astype(np.float32), surface


def check_staircase(labels, planes, surface, tolerance):
    """Each of the 2 * STEPS + 1 surfaces is one plane with the analytic normal and place, and
    the planes' pixels are the surfaces' own."""
    R = camera_pose()[:3, :3]
    t = camera_pose()[:3, 3]
    normals = planes["normal"] @ R.T
    centroids = planes["centroid"] @ R.T + t
    big = [k for k in range(len(planes["rms"])) if planes["num_points"][k] >= 500]
    found = {}
    for k in big:
        n = normals[k]
        if abs(n[2]) > np.cos(np.radians(3)):  # a tread or the floor: its height
            level = round(centroids[k][2] / RISE)
            assert abs(centroids[k][2] - level * RISE) < tolerance
            sid = level
        elif abs(n[0]) > np.cos(np.radians(3)):  # a riser: where it stands
            step = round((centroids[k][0] - X0) / DEPTH)
            assert abs(centroids[k][0] - (X0 + step * DEPTH)) < tolerance
            sid = -(step + 1)
        else:
            pytest.fail(f"plane {k} of {planes['num_points'][k]} points is neither level nor "
                        f"upright: normal {n}")
        assert sid not in found, f"surface {sid} split into planes {found[sid]} and {k}"
        found[sid] = k
    assert sorted(found) == list(range(-STEPS, 0)) + list(range(0, STEPS + 1))
    # pixel by pixel: the share of each surface's pixels that its plane holds
    for sid, k in found.items():
        mine = surface == sid
        share = np.mean(labels[mine] == k)
        assert share > 0.9, f"surface {sid}: {share:.2f} of its pixels in its plane"
    return found


def test_segment_finds_treads_and_risers_of_a_staircase():
    depth, surface = staircase_depth()
    points = perception.depth_to_points(depth, FX, FY, CX, CY)
    assert points.shape == (H, W, 3) and points.dtype == np.float32
    np.testing.assert_allclose(points[..., 2], depth, equal_nan=True)
    labels, planes = perception.segment(points)
    assert labels.shape == (H, W) and labels.dtype == np.int32
    check_staircase(labels, planes, surface, tolerance=0.003)


def write_png16(path, image):
    """A 16-bit greyscale PNG, written by hand (zlib, no filter)."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    h, w = image.shape
    rows = b"".join(b"\x00" + image[v].astype(">u2").tobytes() for v in range(h))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows)))
        f.write(chunk(b"IEND", b""))


def read_png16(path):
    """Reads a PNG as a 16-bit depth camera writes it: with OpenCV where it is installed, else
    the unfiltered 16-bit greyscale PNG that write_png16 writes."""
    try:
        import cv2
        image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
        assert image is not None and image.dtype == np.uint16
        return image
    except ImportError:
        data = open(path, "rb").read()
        w, h = struct.unpack(">II", data[16:24])
        idat, pos = b"", 8
        while pos < len(data):
            n, kind = struct.unpack(">I4s", data[pos:pos + 8])
            if kind == b"IDAT":
                idat += data[pos + 8:pos + 8 + n]
            pos += 12 + n
        raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 1 + 2 * w)
        return raw[:, 1:].copy().view(">u2").astype(np.uint16)


def test_depth_png_with_intrinsics_gives_staircase_and_its_fog(tmp_path):
    depth, surface = staircase_depth()
    millimetres = np.where(np.isfinite(depth), np.round(depth * 1000), 0).astype(np.uint16)
    png = tmp_path / "depth.png"
    write_png16(png, millimetres)
    depth_mm = read_png16(png)
    np.testing.assert_array_equal(depth_mm, millimetres)

    points = perception.depth_to_points(depth_mm, FX, FY, CX, CY, scale=0.001)
    # millimetre depth: the paper's settings for precise range data
    labels, planes = perception.segment(points, {"c_max": 10, "sigma_min": 0.0003})
    check_staircase(labels, planes, surface, tolerance=0.005)

    maps = perception.Maps()
    maps.insert(points, (labels, planes), camera_pose())
    fog = maps.fog()
    res = fog["resolution"]
    x0, y0 = fog["origin"]
    assert fog["types"].dtype == np.uint8 and fog["heights"].dtype == np.float32
    assert fog["types"].shape == fog["heights"].shape == (100, 100)

    def cell(x, y):
        return int(np.floor((y - y0) / res)), int(np.floor((x - x0) / res))

    # the middle of the floor before the stairs and of each tread: standable, at its height
    for level, x in [(0, 0.8)] + [(k + 1, X0 + DEPTH * (k + 0.5)) for k in range(STEPS)]:
        for y in (-0.2, 0.0, 0.2):
            i = cell(x, y)
            assert fog["types"][i] in (fognav.FLOOR, fognav.STAIRS), (x, y, fog["types"][i])
            assert abs(fog["heights"][i] - level * RISE) < 0.01
    # a riser between treads: a change of 4 cm is stairs, not a border
    riser_types = {int(fog["types"][cell(X0 + DEPTH, y)]) for y in (-0.2, 0.0, 0.2)} | \
        {int(fog["types"][cell(X0 + DEPTH - res, y)]) for y in (-0.2, 0.0, 0.2)}
    assert fognav.STAIRS in riser_types
    # behind the camera nothing was seen
    assert fog["types"][cell(-1.0, 0.0)] == fognav.UNKNOWN


@pytest.mark.parametrize("bad, expected", [
    (np.zeros((4, 5)), "H x W x 3"),
    (np.zeros((4, 5, 2), dtype=np.float32), "got shape (4, 5, 2)"),
    (np.zeros((0, 5, 3), dtype=np.float32), "got shape (0, 5, 3)"),
    (np.zeros((4, 5, 3), dtype=bool), "of bool"),
    ([[1.0, 2.0, 3.0]], "numpy array"),
])
def test_wrongly_shaped_points_raise_naming_the_argument(bad, expected):
    with pytest.raises(ValueError, match="points") as error:
        perception.segment(bad)
    assert expected in str(error.value)


def test_bad_segmentation_params_raise_naming_the_key():
    points = np.zeros((8, 8, 3), dtype=np.float32)
    with pytest.raises(fognav.InputError, match="segmentation.n_mn: unknown parameter"):
        perception.segment(points, {"n_mn": 3})
    with pytest.raises(ValueError, match="segmentation.c_max"):
        perception.segment(points, {"c_max": -4})
    with pytest.raises(ValueError, match="planner.h_floor: not a parameter here"):
        perception.segment(points, {"planner.h_floor": 0.01})


def test_maps_insert_checks_its_arrays():
    depth, _ = staircase_depth()
    points = perception.depth_to_points(depth, FX, FY, CX, CY)
    labels, planes = perception.segment(points)
    maps = perception.Maps()
    with pytest.raises(ValueError, match="labels: expected an H x W integer array"):
        maps.insert(points, labels[:10], camera_pose(), planes)
    with pytest.raises(ValueError, match="camera_pose: expected a 4 x 4"):
        maps.insert(points, labels, np.eye(3), planes)
    with pytest.raises(ValueError, match="camera_pose: expected a rigid transform"):
        maps.insert(points, labels, 2 * np.eye(4), planes)
    with pytest.raises(ValueError, match="planes: required"):
        maps.insert(points, labels, camera_pose())
    with pytest.raises(ValueError, match="fog: nothing inserted yet"):
        maps.fog()
    with pytest.raises(fognav.InputError, match="grid.size_q: unknown parameter"):
        perception.Maps({"grid.size_q": 3})
