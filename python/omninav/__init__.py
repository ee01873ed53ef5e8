"""omninav: appearance-based topological mapping and navigation with omnidirectional cameras.

The C++ library from Python. Images are numpy arrays (H x W x 3 uint8 BGR, as OpenCV's
Python binding uses, or H x W grey); angles are radians and their names end in ``_rad``;
errors are :class:`Error` subclasses (:class:`InputError`, :class:`ConfigError`,
:class:`UsageError`) carrying the command line's one-line messages.

    import omninav
    world = omninav.World("room")
    renderer = omninav.Renderer(world)
    compass = omninav.Compass()
    for time_s, pose in world.trajectory("circle:radius_m=1,turns=0.25"):
        estimate = compass.push(renderer.render(pose), truth_heading_rad=pose.heading_rad)

Parameters are read from the configuration folder (``omninav.default_config_dir()``, or
``$OMNINAV_CONFIG_DIR``) by the same readers as the command line: ``CompassConfig.load()``,
``MemoryConfig.load()``; their fields are the YAML keys.
"""

from ._omninav import (  # noqa: F401 (re-exported)
    CameraPose,
    Compass,
    CompassConfig,
    CompassEstimate,
    ConfigError,
    Edge,
    Error,
    ExplorationParams,
    Frame,
    GoalRun,
    InputError,
    Localisation,
    LocalisationParams,
    Localiser,
    Map,
    NavigationStep,
    NavigatorParams,
    MemoryConfig,
    MinimiserParams,
    MinWarping,
    MinWarpingResult,
    NavigationConfig,
    PairMatch,
    PairMatcher,
    Panoramas,
    Place,
    PlaceMatch,
    Pose2,
    Renderer,
    RouteParams,
    RoutePlan,
    Run,
    SamplingParams,
    Sequence,
    Signature,
    SignatureExtractor,
    SignatureParams,
    Unwrapper,
    UsageError,
    WindowParams,
    World,
    azimuth_of_column,
    column_of_azimuth,
    default_config_dir,
    dissimilarity,
    open_sequence,
    read_image,
    roll_columns,
    set_log_level,
    similarities,
)

__all__ = [name for name in dir() if not name.startswith("_")]
