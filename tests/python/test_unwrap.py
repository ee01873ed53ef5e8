"""Unwrapping a constructed raw omnidirectional image: the mirror is found, and what varies
around and across the ring becomes what varies along and down the panorama."""

import numpy as np

import omninav

CENTRE_X, CENTRE_Y, RADIUS = 120.5, 118.5, 100.0


def raw_image():
    """A ring on black: green goes round four times (sin 4θ), red grows with the radius."""
    yy, xx = np.mgrid[0:240, 0:240]
    radius = np.hypot(xx - CENTRE_X, yy - CENTRE_Y)
    angle = np.arctan2(yy - CENTRE_Y, xx - CENTRE_X)
    raw = np.zeros((240, 240, 3), np.uint8)
    inside = radius < RADIUS
    raw[inside, 0] = 200
    raw[inside, 1] = (128 + 100 * np.sin(4 * angle[inside])).astype(np.uint8)
    raw[inside, 2] = (2 * radius[inside]).astype(np.uint8)
    return raw


def test_the_ring_becomes_the_panorama_of_camera_yaml():
    raw = raw_image()
    unwrapper = omninav.Unwrapper(raw)
    panorama = unwrapper.unwrap(raw)
    assert panorama.shape == (45, 360, 3)  # camera.yaml's panorama size
    assert unwrapper.panorama_size == (45, 360)
    middle = panorama[22].astype(float)
    # Around the ring: four cycles of green along every row, and nothing else of note.
    spectrum = np.abs(np.fft.rfft(middle[:, 1] - middle[:, 1].mean()))
    assert spectrum.argmax() == 4
    assert spectrum[4] > 5 * np.delete(spectrum, 4).max()
    # Across the ring: the outer circle at the top (camera.yaml), so red falls row by row.
    red = panorama[:, :, 2].astype(float).mean(axis=1)
    assert (np.diff(red) < 0).all()
    assert red[0] > 180 and red[-1] < 60  # 2r: about 2x95 at the top, 2x25 at the bottom
