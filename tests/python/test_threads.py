"""Long computations release the GIL: a second Python thread makes progress meanwhile."""

import threading
import time

import omninav


def longest_pause_while(work):
    """Runs work() in a thread; returns how long it took and the longest the main thread went
    without running a Python statement meanwhile."""
    done = threading.Event()
    took = []

    def worker():
        start = time.perf_counter()
        work()
        took.append(time.perf_counter() - start)
        done.set()

    thread = threading.Thread(target=worker)
    last = time.perf_counter()
    longest = 0.0
    thread.start()
    while not done.is_set():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
    thread.join()
    return took[0], longest


def test_rendering_lets_another_thread_run():
    world = omninav.World("room:seed=6,boxes=6", width_px=2160, height_px=540, rays_per_pixel=4)
    renderer = omninav.Renderer(world)
    pose = omninav.CameraPose(3.0, 2.5, 1.0)
    took, longest = longest_pause_while(lambda: renderer.render(pose))
    # One call into C++ (0.2 s on an idle machine); holding the GIL it would stop the main thread for all of it. (Half of
    # it leaves room for a loaded machine's scheduling.)
    assert took > 0.1, "the render was too quick to tell"
    assert longest < took / 2, f"main thread stalled {longest:.3f} s of {took:.3f} s"


def line_frames():
    """The frames of a short line across the room, rendered with their true poses."""
    world = omninav.World("room:seed=6,boxes=6", width_px=360, height_px=45, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    return [omninav.Frame(renderer.render(pose), index=i, truth=pose)
            for i, (_, pose) in enumerate(world.trajectory("line:x0=2,y0=2,x1=4,y1=2.6"))]


def test_exploring_lets_another_thread_run():
    frames = line_frames()
    memory = omninav.Map()
    # The route there and back, five times: one call long enough to time.
    took, longest = longest_pause_while(lambda: memory.explore((frames + frames[::-1]) * 5))
    assert memory.place_count > 1
    assert took > 0.1, "the exploration was too quick to tell"
    assert longest < took / 2, f"main thread stalled {longest:.3f} s of {took:.3f} s"


def calls_from_threads(call, threads=4):
    """call() from `threads` threads at once; returns the exceptions they raised."""
    start = threading.Barrier(threads)
    raised = []

    def worker():
        start.wait()
        try:
            call()
        except Exception as error:  # noqa: BLE001 - collected and checked by the caller
            raised.append(error)

    workers = [threading.Thread(target=worker) for _ in range(threads)]
    for worker_thread in workers:
        worker_thread.start()
    for worker_thread in workers:
        worker_thread.join()
    return raised


def test_one_map_explored_from_four_threads_raises_instead_of_crashing():
    frames = line_frames()
    memory = omninav.Map()
    for _ in range(3):
        raised = calls_from_threads(lambda: (memory.explore(frames * 3), memory.place_count))
        assert all(isinstance(error, omninav.UsageError) for error in raised), raised
        assert all("in use by another thread" in str(error) for error in raised)
    assert memory.place_count > 0


def test_one_compass_pushed_from_four_threads_raises_instead_of_crashing():
    world = omninav.World("room:seed=6,boxes=6", width_px=360, height_px=45, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    panoramas = [renderer.render(pose)
                 for _, pose in world.trajectory("rotate:x=3,y=2.5,turns=0.2")]
    compass = omninav.Compass()

    def push_all():
        for panorama in panoramas:
            compass.push(panorama)

    for _ in range(3):
        raised = calls_from_threads(push_all)
        assert all(isinstance(error, omninav.UsageError) for error in raised), raised
    assert compass.started
