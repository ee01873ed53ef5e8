"""omninav: appearance-based topological mapping and navigation with omnidirectional cameras.

The C++ library from Python. Images are numpy arrays (H x W x 3 uint8 BGR, as OpenCV's
Python binding uses, or RGB after ``set_channel_order("rgb")``, or H x W grey); angles are radians and their names end in ``_rad``;
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
    __version__,
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
    LiveCommand,
    LiveOutput,
    LivePlace,
    LiveSession,
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
    LinkParams,
    BeliefParams,
    Run,
    SamplingParams,
    Sequence,
    Signature,
    SignatureExtractor,
    SignatureParams,
    Unwrapper,
    UsageError,
    World,
    azimuth_of_column,
    channel_order,
    column_of_azimuth,
    default_config_dir,
    dissimilarity,
    open_sequence,
    read_image,
    roll_columns,
    set_channel_order,
    set_log_level,
    similarities,
)



def _short_repr(value):
    """A field's value in a repr: arrays and long lists by their size, so a repr stays a line."""
    if hasattr(value, "shape"):
        return f"<array {'x'.join(str(n) for n in value.shape)}>"
    if isinstance(value, (list, tuple)) and len(value) > 4:
        return f"[{len(value)} items]"
    return repr(value)


def _fields_repr(value):
    """ClassName(field=value, ...) over the class's properties in the order the binding defines
    them: what a result or a parameter set holds, readable at the prompt."""
    fields = []
    for name, member in vars(type(value)).items():
        if name.startswith("_") or not isinstance(member, property):
            continue
        try:
            fields.append(f"{name}={_short_repr(getattr(value, name))}")
        except Exception as error:  # a field that cannot be read says why, the rest still show
            fields.append(f"{name}=<{type(error).__name__}>")
    return f"{type(value).__name__}({', '.join(fields)})"


# The result and parameter types print their fields (the others keep their own __repr__).
for _type in (SamplingParams, MinimiserParams, CompassConfig, SignatureParams,
              ExplorationParams, LocalisationParams, MemoryConfig, RouteParams, LinkParams,
              BeliefParams, NavigatorParams,
              NavigationConfig, Place, Edge, Localisation, RoutePlan, Run, NavigationStep, GoalRun,
              LivePlace, LiveOutput, LiveCommand):
    _type.__repr__ = _fields_repr
del _type

__all__ = [name for name in dir() if not name.startswith("_")]
