"""The package as a user meets it: its version, the configuration it reads when none is named,
and objects that print what they hold."""

import re
from pathlib import Path

import pytest

import omninav

SOURCE = Path(__file__).resolve().parents[2]


def test_the_version_is_the_projects():
    assert omninav.__version__ == (SOURCE / "VERSION").read_text().strip()


def test_the_default_configuration_lies_inside_the_package(monkeypatch):
    monkeypatch.delenv("OMNINAV_CONFIG_DIR", raising=False)
    config = Path(omninav.default_config_dir())
    assert config == Path(omninav.__file__).parent / "config"
    assert (config / "memory.yaml").is_file()
    monkeypatch.setenv("OMNINAV_CONFIG_DIR", "/elsewhere")
    assert Path(omninav.default_config_dir()) == Path("/elsewhere")


def test_results_and_parameters_print_their_fields(route_map, query_db):
    memory = omninav.Map.open(route_map)
    localisation = omninav.Localiser(memory).localise(next(iter(omninav.open_sequence(query_db))).image)
    config = omninav.MemoryConfig.load()
    for value in (memory.places()[0], localisation, config, config.exploration,
                  omninav.CompassConfig.load(), omninav.NavigationConfig.load().navigator):
        text = repr(value)
        assert " object at 0x" not in text, text
        assert text.startswith(type(value).__name__ + "("), text
        assert "\n" not in text and len(text) < 4000, text
    place = repr(memory.places()[0])
    assert re.search(r"heading_rad=-?[0-9.e-]+", place), place
    assert "signature=Signature(" in place or "signature=<" in place, place
    # A parameter set shows its values, so a changed one is seen.
    exploration = config.exploration
    text = repr(exploration)
    assert "ExplorationParams(" in text and "=" in text, text


def test_rgb_images_said_to_be_rgb_give_the_bgr_results():
    world = omninav.World("room", width_px=120, height_px=24)
    bgr = omninav.Renderer(world).render(omninav.CameraPose(2.0, 1.5, 1.0, heading_rad=0.3))
    rgb = bgr[..., ::-1].copy()
    signature = omninav.SignatureExtractor().compute
    as_bgr = signature(bgr).magnitude.copy()
    assert omninav.channel_order() == "bgr"
    assert not (signature(rgb).magnitude == as_bgr).all(), "red and blue trade rows when unsaid"
    try:
        omninav.set_channel_order("rgb")
        assert omninav.channel_order() == "rgb"
        assert (signature(rgb).magnitude == as_bgr).all()
        assert (signature(bgr[..., 0]).magnitude == signature(bgr[..., 0]).magnitude).all()
        with pytest.raises(omninav.UsageError, match="expected bgr or rgb"):
            omninav.set_channel_order("rgba")
    finally:
        omninav.set_channel_order("bgr")
