"""Maps from Python: the same places as `omninav explore`, and the same best place and
dissimilarity as `omninav localise`, for the same input."""

import csv
import io
import math

import pytest

import omninav
from conftest import run_omninav


def test_localisation_equals_the_command_lines(route_map, query_db):
    printed = list(csv.DictReader(io.StringIO(
        run_omninav("localise", route_map, query_db, "--format", "csv"))))
    localiser = omninav.Localiser(omninav.Map.open(route_map))
    queries = list(omninav.open_sequence(query_db))
    assert len(queries) == len(printed) >= 4
    matched = 0
    for frame, row in zip(queries, printed):
        result = localiser.localise(frame.image)
        if row["best_place"] == "":  # the command line found no match
            assert localiser.no_match_reason(result) is not None
            continue
        assert localiser.no_match_reason(result) is None
        matched += 1
        best = result.best[0]
        assert str(best.place) == row["best_place"]
        assert f"{best.dissimilarity:.3f}" == row["dissimilarity"]
        assert f"{best.similarity:.1f}" == row["similarity"]
    assert matched >= len(queries) // 2


def test_python_exploration_makes_the_command_lines_map(route_map, route_db, tmp_path):
    theirs = omninav.Map.open(route_map)
    ours = omninav.Map()
    run = ours.explore(route_db)
    assert run.frames == len(omninav.open_sequence(route_db)) > 20
    assert run.places == ours.place_count == theirs.place_count > 3
    for a, b in zip(ours.places(), theirs.places()):
        assert a.frame_index == b.frame_index
        assert math.isclose(a.heading_rad, b.heading_rad, abs_tol=1e-12)
    assert [(f, t) for f, t, _ in ours.edges()] == [(f, t) for f, t, _ in theirs.edges()]
    ours.save(tmp_path / "ours.vmem")
    assert omninav.Map.open(tmp_path / "ours.vmem").place_count == ours.place_count


def test_a_query_at_a_place_finds_the_nearest_place(route_db):
    frames = list(omninav.open_sequence(route_db))
    memory = omninav.Map()
    memory.explore(frames[::2])  # the frames as Python objects, every other one
    localiser = omninav.Localiser(memory)
    places = memory.places()
    for frame in frames[1::8]:
        best = places[localiser.localise(frame.image).best[0].place]
        distance = math.hypot(best.truth.x_m - frame.truth.x_m, best.truth.y_m - frame.truth.y_m)
        assert distance < 0.3, f"{frame.source}: best place {distance:.2f} m away"


def test_coarse_to_fine_keeps_fewer_candidates_and_the_oracles_best(route_map, query_db):
    memory = omninav.Map.open(route_map)
    localiser = omninav.Localiser(memory)
    config = omninav.MemoryConfig.load()
    for frame in omninav.open_sequence(query_db):
        pruned = localiser.localise(frame.image)
        oracle = localiser.localise(frame.image, exhaustive=True)
        levels = pruned.candidates_per_level
        assert len(levels) == len(config.localisation.levels) == 3
        assert all(len(finer) <= len(coarser) for coarser, finer in zip(levels, levels[1:]))
        assert set(levels[-1]) <= set(levels[0])
        assert pruned.best[0].place == oracle.best[0].place
        assert pruned.position_frame == "truth"  # the map's places have ground truth
        place = memory.place(pruned.best[0].place).truth
        assert pruned.position == (place.x_m, place.y_m)


def test_a_value_out_of_range_set_from_python_is_refused_as_in_memory_yaml(route_db):
    config = omninav.MemoryConfig.load()
    config.exploration.new_place_plateau_share = 2.0  # memory.yaml allows 0.01..1
    with pytest.raises(omninav.UsageError, match="exploration.new_place_plateau_share"):
        omninav.Map().explore(route_db, config=config)
