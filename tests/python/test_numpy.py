"""Images in and out as numpy arrays: shape, dtype and pixels survive, and large data is shared,
not copied."""

import numpy as np
import pytest
from PIL import Image

import omninav


def known_image(height=7, width=11, channels=3):
    rng = np.random.default_rng(5)
    shape = (height, width, channels) if channels else (height, width)
    return rng.integers(0, 256, size=shape, dtype=np.uint8)


@pytest.mark.parametrize("channels", [3, 0])
def test_frame_round_trip_keeps_shape_dtype_and_pixels(channels):
    image = known_image(channels=channels)
    frame = omninav.Frame(image, index=4, source="mine")
    out = frame.image
    assert out.shape == image.shape
    assert out.dtype == np.uint8
    np.testing.assert_array_equal(out, image)
    assert frame.index == 4 and frame.source == "mine" and frame.truth is None


def test_frame_image_is_a_view_of_the_frame_pixels():
    frame = omninav.Frame(known_image())
    first, second = frame.image, frame.image
    assert np.shares_memory(first, second)  # both view the frame's own pixels
    first[0, 0, 0] = 255 - first[0, 0, 0]
    assert second[0, 0, 0] == first[0, 0, 0]


def test_frame_copies_the_callers_array():
    image = known_image()
    frame = omninav.Frame(image)
    assert not np.shares_memory(frame.image, image)


def test_strided_and_reversed_arrays_are_read_as_they_look():
    image = known_image(height=8, width=20)
    for view in (image[:, ::2], image[::-1], image[1:6, 3:17], np.asfortranarray(image)):
        np.testing.assert_array_equal(omninav.Frame(view).image, view)


@pytest.mark.parametrize("shift", [0, 1, 5, -3, 13])
def test_roll_columns_is_numpys_roll_along_the_columns(shift):
    image = known_image(height=5, width=12)
    np.testing.assert_array_equal(omninav.roll_columns(image, shift), np.roll(image, shift, axis=1))


def test_read_image_gives_bgr_pixels_of_the_file(tmp_path):
    rgb = known_image(height=9, width=13)
    Image.fromarray(rgb, "RGB").save(tmp_path / "a.png")
    bgr = omninav.read_image(tmp_path / "a.png")
    assert bgr.shape == (9, 13, 3) and bgr.dtype == np.uint8
    np.testing.assert_array_equal(bgr, rgb[:, :, ::-1])


def test_folder_sequence_yields_its_images_in_natural_order(tmp_path):
    images = [known_image(height=4, width=6) + i for i in range(3)]
    for i, name in enumerate(["img2.png", "img10.png", "img1.png"]):
        Image.fromarray(images[i], "RGB").save(tmp_path / name)
    sequence = omninav.open_sequence(tmp_path)
    assert len(sequence) == 3
    frames = list(sequence)
    assert [f.index for f in frames] == [0, 1, 2]
    # Natural order: img1, img2, img10.
    for frame, expected in zip(frames, [images[2], images[0], images[1]]):
        np.testing.assert_array_equal(frame.image, expected[:, :, ::-1])
        assert frame.truth is None


def test_signature_matrices_are_views_of_the_signature():
    panorama = known_image(height=6, width=40)
    signature = omninav.SignatureExtractor().compute(panorama)
    magnitude = signature.magnitude
    assert magnitude.shape == (signature.lines, signature.components) == (6, 15)
    assert magnitude.dtype == np.float32
    assert np.shares_memory(magnitude, signature.magnitude)
    # Component 0 is each row's mean grey level (the signature's own convention), before the
    # brightness normalisation: checked with it off.
    params = omninav.SignatureParams()
    params.normalise_brightness = False
    raw = omninav.SignatureExtractor(params).compute(panorama)
    grey = panorama[:, :, 0] * 0.114 + panorama[:, :, 1] * 0.587 + panorama[:, :, 2] * 0.299
    np.testing.assert_allclose(raw.magnitude[:, 0], grey.mean(axis=1), atol=0.6)


def test_a_turn_leaves_the_magnitudes_and_dissimilarity_unchanged():
    panorama = known_image(height=6, width=40)
    extractor = omninav.SignatureExtractor()
    a = extractor.compute(panorama)
    b = extractor.compute(np.roll(panorama, 7, axis=1))
    other = extractor.compute(known_image(height=6, width=40)[::-1].copy())
    assert omninav.dissimilarity(a, b) < 1e-3 * omninav.dissimilarity(a, other)
