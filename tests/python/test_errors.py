"""Bad input raises the typed exception with the command line's one-line message naming the
file."""

import numpy as np
import pytest

import omninav


def test_the_exceptions_are_typed_and_share_a_base():
    for error in (omninav.InputError, omninav.ConfigError, omninav.UsageError):
        assert issubclass(error, omninav.Error)
    assert issubclass(omninav.Error, RuntimeError)


def test_a_missing_image_raises_input_error_naming_it(tmp_path):
    missing = tmp_path / "nowhere.png"
    with pytest.raises(omninav.InputError, match="nowhere.png"):
        omninav.read_image(missing)


def test_a_corrupt_image_raises_input_error_naming_it(tmp_path):
    bad = tmp_path / "broken.png"
    bad.write_bytes(b"\x89PNG\r\n\x1a\n this is not a png")
    with pytest.raises(omninav.InputError, match="broken.png"):
        omninav.read_image(bad)


def test_a_folder_without_images_raises_input_error_naming_it(tmp_path):
    (tmp_path / "notes.txt").write_text("no images here")
    with pytest.raises(omninav.InputError, match=str(tmp_path.name)):
        omninav.open_sequence(tmp_path)


def test_a_csv_without_its_columns_raises_input_error_naming_it(tmp_path):
    csv = tmp_path / "poses.csv"
    csv.write_text("file,x_m\na.png,1\n")
    with pytest.raises(omninav.InputError, match="poses.csv"):
        omninav.open_sequence(csv)


def test_a_bad_map_file_raises_input_error_naming_it(tmp_path):
    bad = tmp_path / "not_a_map.vmem"
    bad.write_text("hello")
    with pytest.raises(omninav.InputError, match="not_a_map.vmem"):
        omninav.Map.open(bad)


def test_a_bad_config_key_raises_config_error_naming_the_file(tmp_path):
    source = omninav.default_config_dir()
    for name in ("camera.yaml", "compass.yaml"):
        (tmp_path / name).write_text((source / name).read_text())
    text = (tmp_path / "compass.yaml").read_text()
    (tmp_path / "compass.yaml").write_text(text.replace("threshold_norm_amp: 0.6055",
                                                        "threshold_norm_amp: 7"))
    with pytest.raises(omninav.ConfigError, match="compass.yaml.*threshold_norm_amp"):
        omninav.CompassConfig.load(tmp_path)


@pytest.mark.parametrize(
    "array",
    [np.zeros((4, 5), np.float64), np.zeros((4, 5, 2), np.uint8), np.zeros(5, np.uint8),
     np.zeros((0, 5), np.uint8)],
)
def test_an_array_that_is_no_image_raises_input_error(array):
    with pytest.raises(omninav.InputError, match="uint8"):
        omninav.Frame(array)


def test_panoramas_of_another_shape_raise_input_error_naming_the_frame():
    compass = omninav.Compass()
    compass.push(np.zeros((10, 40, 3), np.uint8) + 1, source="first.png")
    with pytest.raises(omninav.InputError, match="second.png"):
        compass.push(np.zeros((10, 48, 3), np.uint8), source="second.png")
