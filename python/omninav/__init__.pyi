# Type stubs of the omninav Python module (python/src/*.cpp): what an editor completes and a
# type checker checks. Images are numpy arrays: H x W x 3 uint8 BGR, or H x W grey.
from os import PathLike
from pathlib import Path
from typing import Iterable, Iterator, Optional, Protocol, Sequence as _Seq, Union

import numpy as np
import numpy.typing as npt

Image = npt.NDArray[np.uint8]
PathArg = Union[str, PathLike]

__version__: str  # the project's version (the file VERSION)

class Error(RuntimeError): ...
class ConfigError(Error): ...
class InputError(Error): ...
class UsageError(Error): ...

def default_config_dir() -> Path: ...
def set_log_level(level: str) -> None: ...  # "error" | "warning" | "info" | "debug"
def set_channel_order(order: str) -> None: ...  # "bgr" (default) | "rgb": colour images handed in
def channel_order() -> str: ...
def azimuth_of_column(column: float, width_px: int) -> float: ...
def column_of_azimuth(azimuth_rad: float, width_px: int) -> float: ...
def roll_columns(panorama: Image, shift_px: int) -> Image: ...

class Pose2:
    x_m: float
    y_m: float
    heading_rad: float
    def __init__(self, x_m: float = 0.0, y_m: float = 0.0, heading_rad: float = 0.0) -> None: ...

class CameraPose:
    x_m: float
    y_m: float
    z_m: float
    heading_rad: float
    pitch_rad: float
    roll_rad: float
    def __init__(self, x_m: float = 0.0, y_m: float = 0.0, z_m: float = 0.0,
                 heading_rad: float = 0.0, pitch_rad: float = 0.0,
                 roll_rad: float = 0.0) -> None: ...
    def on_floor(self) -> Pose2: ...

# Configuration: fields are the YAML keys.
class SamplingParams:
    policy: str  # "threshold" | "fixed_skip"
    threshold_norm_amp: float
    fixed_skip_frames: int
    max_reference_rotation_rad: float
    max_reference_rotation_deg: float
    parallax_step_ratio: float

class MinimiserParams:
    kind: str  # "local_scan" | "exhaustive" | "fft" | "phase"

class CompassConfig:
    def __init__(self) -> None: ...
    @staticmethod
    def load(config_dir: Optional[PathArg] = None) -> CompassConfig: ...
    @property
    def sampling(self) -> SamplingParams: ...
    @property
    def minimiser(self) -> MinimiserParams: ...
    global_fallback: bool
    width_px: Optional[int]

class SignatureParams:
    components: int
    colour: str  # "luminance" | "per_channel"
    normalise_brightness: bool
    def __init__(self) -> None: ...

class ExplorationParams:
    new_place_dissimilarity: Optional[float]  # None: "auto", a share of the stream's plateau
    new_place_plateau_share: float
    every_n_frames: int
    every_m: float
    thumbnail_width_px: int
    heading_source: str  # "auto" | "compass" | "truth" | "none"
    motion_components: int

class LocalisationParams:
    levels: list[int]
    candidate_similarity: float
    max_probes: int
    top_k: int
    fine_candidates: int
    fine_rotational_weight: float

class MemoryConfig:
    def __init__(self) -> None: ...
    @staticmethod
    def load(config_dir: Optional[PathArg] = None) -> MemoryConfig: ...
    @property
    def signature(self) -> SignatureParams: ...
    weights: list[float]
    exploration: ExplorationParams
    localisation: LocalisationParams

class RouteParams:
    match_dissimilarity_ratio: float
    goal_shortlist_ratio: float

class LinkParams:
    grid_agreement_ratio: float
    grid_direction_deg: float
    revisit_run: int
    revisit_ratio: float
    revisit_image_ratio: float
    revisit_disagreement_deg: float
    revisits_per_place: int
    revisit_candidates: int
    odometry_noise: float
    neighbour_spacings: float

class BeliefParams:
    view_scale: float
    direction_sigma_deg: float
    uniform_share: float
    confident_share: float

class NavigatorParams:
    step_m: float
    max_steps: int
    home_on_goal_image: bool
    homing_step_m: float
    homing_stop_m: float
    homing_step_spacings: float
    homing_stop_spacings: float
    homing_max_steps: int

class NavigationConfig:
    def __init__(self) -> None: ...
    @staticmethod
    def load(config_dir: Optional[PathArg] = None) -> NavigationConfig: ...
    route: RouteParams
    links: LinkParams
    belief: BeliefParams
    navigator: NavigatorParams

# Reading sequences.
class Frame:
    index: int
    time_s: Optional[float]
    truth: Optional[CameraPose]
    source: str
    odometry: Optional[CameraPose]
    image: Image  # a view of the frame's pixels
    def __init__(self, image: Image, index: int = 0, truth: Optional[CameraPose] = None,
                 time_s: Optional[float] = None, source: str = "") -> None: ...

class Sequence(Iterator[Frame]):
    def __iter__(self) -> Sequence: ...
    def __next__(self) -> Frame: ...
    def __len__(self) -> int: ...
    def describe(self) -> str: ...
    @property
    def needs_unwrapping(self) -> bool: ...
    @property
    def is_grid(self) -> bool: ...
    @property
    def is_video(self) -> bool: ...

def open_sequence(path: PathArg) -> Sequence: ...

class Panoramas(Iterator[Frame]):
    def __init__(self, input: PathArg, unwrap: bool = False,
                 config_dir: Optional[PathArg] = None, absolute_sources: bool = True) -> None: ...
    def __iter__(self) -> Panoramas: ...
    def __next__(self) -> Frame: ...
    def __len__(self) -> int: ...
    def describe(self) -> str: ...
    @property
    def is_grid(self) -> bool: ...
    @property
    def unwraps(self) -> bool: ...

def read_image(file: PathArg) -> Image: ...

class Unwrapper:
    def __init__(self, first_raw: Image, config_dir: Optional[PathArg] = None) -> None: ...
    def unwrap(self, raw: Image) -> Image: ...
    @property
    def panorama_size(self) -> tuple[int, int]: ...  # (height, width)

# The visual compass.
class CompassEstimate:
    frame_index: int
    heading_rad: float  # unwrapped: turns accumulate
    rotation_rad: float
    amplitude_norm: float
    reference_index: int
    new_reference: bool
    shift_px: float
    evaluations: int
    heading_sigma_rad: float  # the heading's standard deviation
    realigned: bool  # the heading was re-aligned from outside (a recognised place of a map)
    confidence: str  # "ok" or flags joined by '+'
    featureless: bool
    competing_minima: bool
    low_amplitude: bool
    ok: bool

class PairMatch:
    shift_px: int
    subpixel_shift_px: float
    rotation_rad: float
    distance_min: float
    amplitude: float
    amplitude_norm: float
    amplitude_norm_px: float
    self_amplitude: float
    evaluations: int
    confidence: str
    featureless: bool
    competing_minima: bool
    low_amplitude: bool
    ok: bool

class PairMatcher:
    def __init__(self, config: Optional[CompassConfig] = None,
                 config_dir: Optional[PathArg] = None) -> None: ...
    def match(self, first: Image, second: Image, start_shift_px: int = 0) -> PairMatch: ...

class MinWarpingResult:
    rotation_rad: float
    travel_rad: float
    home_rad: float
    cost: float
    rotation_only_cost: float
    rotation_only_rad: float
    featureless: bool
    def travel_world_rad(self, first_heading_rad: float) -> float: ...

class MinWarping:
    def __init__(self, config_dir: Optional[PathArg] = None) -> None: ...
    def estimate(self, first: Image, second: Image) -> MinWarpingResult: ...

class Compass:
    def __init__(self, config: Optional[CompassConfig] = None,
                 config_dir: Optional[PathArg] = None) -> None: ...
    def push(self, panorama: Union[Image, Frame], index: Optional[int] = None,
             source: str = "", truth_heading_rad: Optional[float] = None) -> CompassEstimate: ...
    @property
    def started(self) -> bool: ...
    @property
    def reference_count(self) -> int: ...

# Signatures.
class Signature:
    rows: int
    channels: int
    components: int
    width_px: int
    lines: int
    magnitude: npt.NDArray[np.float32]  # lines x components, a view
    phase_rad: npt.NDArray[np.float32]  # lines x components, a view
    def truncated(self, components: int) -> Signature: ...

class SignatureExtractor:
    def __init__(self, params: Optional[SignatureParams] = None) -> None: ...
    def compute(self, panorama: Image, what: str = "panorama") -> Signature: ...
    @property
    def params(self) -> SignatureParams: ...

def dissimilarity(a: Signature, b: Signature, components: int = -1,
                  weights: Optional[_Seq[float]] = None) -> float: ...
def similarities(dissimilarities: _Seq[float]) -> list[float]: ...

# Maps.
class Place:
    signature: Signature
    heading_rad: Optional[float]
    heading_source: str
    source: str
    frame_index: int
    run: int
    time_s: Optional[float]
    truth: Optional[CameraPose]
    lattice_position: Optional[tuple[float, float]]
    thumbnail: Image

class Edge:
    kind: str
    dissimilarity: float
    relative_heading_rad: float
    heading_confidence: float
    motion_bearing_rad: Optional[float]
    motion_bearing_stddev_rad: float
    parallax_rad: float

class Run:
    id: int
    input: str
    frames: int
    places: int
    heading_source: str

class PlaceMatch:
    place: int
    dissimilarity: float
    similarity: float
    dissimilarity_per_value: float
    relative_heading_rad: float
    heading_confidence: float
    heading_rad: Optional[float]

class Localisation:
    best: list[PlaceMatch]
    candidates_per_level: list[list[int]]
    position_frame: Optional[str]  # "lattice" | "truth"
    position: Optional[tuple[float, float]]
    interpolated_position: Optional[tuple[float, float]]
    between_places: Optional[tuple[float, float]]

class RoutePlan:
    goal: int
    next: list[int]
    cost_m: list[float]
    direction_rad: list[float]
    direction_in_place_rad: list[float]
    def reaches_goal(self, place: int) -> bool: ...
    def route_from(self, start: int) -> list[int]: ...

class Map:
    def __init__(self, config: Optional[MemoryConfig] = None,
                 config_dir: Optional[PathArg] = None) -> None: ...
    @staticmethod
    def open(file: PathArg) -> Map: ...
    def save(self, file: Optional[PathArg] = None, overwrite: bool = False) -> None: ...
    def explore(self, input: Union[PathArg, Iterable[Union[Frame, Image]]],
                config: Optional[MemoryConfig] = None, config_dir: Optional[PathArg] = None,
                all_frames: bool = False, unwrap: bool = False) -> Run: ...
    def organise(self, step_m: float = 0.0, motion_constraints: bool = True,
                 config_dir: Optional[PathArg] = None) -> None: ...
    def plan_route(self, goal: int, config: Optional[NavigationConfig] = None,
                   config_dir: Optional[PathArg] = None) -> RoutePlan: ...
    def __len__(self) -> int: ...
    @property
    def place_count(self) -> int: ...
    @property
    def edge_count(self) -> int: ...
    def place(self, index: int) -> Place: ...
    def places(self) -> list[Place]: ...
    def edges(self) -> list[tuple[int, int, Edge]]: ...
    @property
    def runs(self) -> list[Run]: ...
    @property
    def signature_params(self) -> SignatureParams: ...
    @property
    def file(self) -> Optional[Path]: ...
    def navigate_to_image(self, robot: Robot, goal_image: Image,
                          config: Optional[NavigationConfig] = None,
                          config_dir: Optional[PathArg] = None,
                          max_steps: int = 0) -> GoalRun: ...

class Robot(Protocol):
    """What the navigator drives: your robot or simulator."""
    def view(self, step: int) -> Image: ...
    def move(self, turn_rad: float, distance_m: float) -> float: ...
    def truth(self) -> CameraPose: ...

class NavigationStep:
    index: int
    truth: CameraPose
    match: Optional[PlaceMatch]
    heading_estimate_rad: float
    turn_rad: float
    jump: bool

class GoalRun:
    goal: PlaceMatch
    plan: RoutePlan
    reached: bool
    steps: list[NavigationStep]
    path_length_m: float
    jumps: int
    sidesteps: int
    replans: int
    homing_steps: int
    lost_events: int

# A robot's frames as they come (docs/ros.md: the ROS node runs the same session).
class LivePlace:
    place: int
    similarity: float  # Eq. 3 over the map's places, 0..1000
    dissimilarity_per_value: float
    probability: float
    confidence: float  # the belief on the place and the places linked to it
    lost: bool

class LiveCommand:
    state: str  # "driving", "reached" or "failed": stand still unless driving
    turn_rad: float  # still to turn on the spot, counter-clockwise positive
    distance_m: float  # still to drive forwards after the turn
    step: int  # the navigator's step (view) the command is of
    new_step: bool  # this frame was that step's view
    phase: str  # "route" or "homing"
    place: int  # the place the navigator acted on
    lost: bool  # the navigator's belief was spread then

class LiveOutput:
    frame: int
    stamp_s: float
    compass: CompassEstimate
    place: Optional[LivePlace]  # None without a map that has a lattice
    new_place: Optional[int]  # exploring: the place the frame became
    command: Optional[LiveCommand]  # navigating: the command toward the goal

class LiveSession:
    def __init__(self, map: Optional[PathArg] = None,
                 config_dir: Optional[PathArg] = None) -> None: ...
    def push(self, panorama: Image, stamp_s: float,
             odometry: Optional[Pose2] = None) -> Optional[LiveOutput]: ...
    def navigate_to(self, goal_image: Image) -> PlaceMatch: ...
    def stop_navigating(self) -> None: ...
    @property
    def navigating(self) -> bool: ...
    def start_exploring(self) -> None: ...
    def stop_exploring(self) -> None: ...
    def save(self) -> None: ...
    @property
    def exploring(self) -> bool: ...
    @property
    def place_count(self) -> int: ...
    @property
    def no_belief_reason(self) -> Optional[str]: ...
    @property
    def skipped(self) -> dict[str, int]: ...  # "bad image", "size change", "stamp not increasing"
    @property
    def last_skip(self) -> Optional[tuple[str, str]]: ...

class Localiser:
    def __init__(self, map: Map, config: Optional[MemoryConfig] = None,
                 config_dir: Optional[PathArg] = None,
                 navigation: Optional[NavigationConfig] = None) -> None: ...
    def localise(self, panorama: Image, exhaustive: bool = False,
                 what: str = "query") -> Localisation: ...
    def localise_signature(self, signature: Signature,
                           exhaustive: bool = False) -> Localisation: ...
    @property
    def match_limit(self) -> float: ...
    def no_match_reason(self, localisation: Localisation) -> Optional[str]: ...

# The renderer.
class World:
    def __init__(self, spec: str = "room", config_dir: Optional[PathArg] = None,
                 width_px: int = 0, height_px: int = 0, rays_per_pixel: int = 0) -> None: ...
    @property
    def name(self) -> str: ...
    def trajectory(self, spec: str) -> list[tuple[float, CameraPose]]: ...

class Renderer:
    def __init__(self, world: World) -> None: ...
    def render(self, pose: CameraPose, time_s: float = 0.0, frame_index: int = 0) -> Image: ...
