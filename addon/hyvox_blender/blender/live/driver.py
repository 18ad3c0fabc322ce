# SPDX-License-Identifier: GPL-3.0-or-later
"""Live: hyvox volumes that follow their sources (the design: core/live_scheduler.py).

Triggers, all on the thread Blender calls them on:
- depsgraph_update_post: which sources changed (geometry, transform, material, a
  collection's content); the volumes' own swaps change no source, so they trigger nothing;
- frame_change_post: a new frame in the viewport (animated sources: the depsgraph says
  which objects the frame changed) and, with a render depsgraph, before each rendered frame
  (F12, Render Animation, `blender -b -a`): then the run is synchronous and its export is
  the render's own evaluation (modifiers at render settings), so every frame renders with
  its own voxels and nothing needs a bake;
- undo_post / redo_post: the state returned to (its voxels come from the cache, or a run);
- load_pre, unregister and the end of the session: every run cancelled, the cache's files
  deleted except those shown or kept by a saved .blend (save_post).
In the UI a timer (bpy.app.timers) polls the worker and does every export and swap on the
main thread; the worker touches no Blender data. A render in the window calls its handlers
on Blender's render thread: there Live registers no timer and touches no window (the
timer, kept while live volumes exist, does that on the main thread), and it swaps a
frame's voxels in only while the interface is locked (Render > Lock Interface, which
turning Live on sets). That is Blender's documented condition for handlers that change
data while it renders: unlocked, the main thread evaluates the same volume meanwhile.
In background mode (`blender -b`, the bpy module) there is no event loop: the run happens
inside the handler, and the swap in the handler is evaluated by Blender's second pass over
what handlers changed, so when view_layer.update() or frame_set() returns the volume shows
the voxels of the new state."""

import atexit
import os
import sys
import threading
import time
import traceback

import bpy
from bpy.app.handlers import persistent

from ...core import live_key
from ...core.errors import HyvoxError
from ...core.live_cache import CacheEntry, LiveCache
from ...core.live_run import LiveInput, LiveRun
from ...core.live_scheduler import FAILED, SHOWN, LiveScheduler
from . import dependencies as live_dependencies, volumes as live_volumes
from ..export import render_depsgraph
from .volumes import LIVE_ID, SourcesUnavailable

POLL_SECONDS = 0.01  # the timer's interval while a run is on (Blender's loop sleeps ~5 ms)
IDLE_POLL_SECONDS = 0.2  # while live volumes exist and nothing runs (the tick reads flags only)
RENDER_POLL_SECONDS = 0.05  # while a render owns the volumes
UNLOCKED_RENDER = (
    "hyvox Live: this render shows the viewport's voxels: Render > Lock Interface is off, and Blender "
    "cannot swap a volume's file safely while it renders with the interface unlocked"
)
# Updates of these ID types may change what a coloured volume shows.
SHADING_TYPES = {"Material", "Image", "ShaderNodeTree", "Texture", "World"}


class _Live:
    """The session's Live state: one scheduler and cache, what the main thread last saw."""

    scheduler = LiveScheduler(threaded=not bpy.app.background)
    shown = frozenset()  # files shown by volumes, refreshed on the main thread (cache.in_use)
    kept_by_saves = set()  # files a saved .blend refers to: never deleted by the cache
    cache = LiveCache(in_use=lambda: _Live.shown | _Live.kept_by_saves)
    rendering = False
    unlocked_render_said = False  # this render's frames were left as they are, and it was said
    status = {}  # live id -> the line the panel shows
    timings = {}  # live id -> the last run's stage timings (ms), swap and main thread included
    started = {}  # live id -> the main thread's (wall, CPU) ms of starting the run
    warnings = {}  # live id -> the running run's export warnings
    runs_started = {}  # live id -> runs started (tests and the bench read it)
    status_bar_text = None  # the last text given to the status bar (tests read it)
    status_bar_later = []  # a text given off the main thread: the next tick shows it


def scheduler() -> LiveScheduler:
    return _Live.scheduler


def cache() -> LiveCache:
    return _Live.cache


def status_line(obj) -> str:
    ident = obj.get(LIVE_ID)
    volume = _Live.scheduler.get(ident) if ident else None
    if volume is not None and volume.state in ("running", "dirty"):
        return "Updating..."
    return _Live.status.get(ident, "Up to date" if obj.get(live_volumes.LIVE_KEY) else "Waiting for an edit")


def _on_main_thread() -> bool:
    """False in the handlers of a render in the window (Blender's render thread)."""
    return threading.current_thread() is threading.main_thread()


# -- the status bar -------------------------------------------------------------------
def _status_bar(text):
    _Live.status_bar_text = text
    if bpy.app.background:
        if text:
            print(text)
        return
    if not _on_main_thread():  # windows are the main thread's
        if text:
            print(text)
        _Live.status_bar_later[:] = [text]
        return
    window_manager = bpy.context.window_manager
    for window in window_manager.windows if window_manager is not None else ():
        try:
            with bpy.context.temp_override(window=window):
                window.workspace.status_text_set(text)
        except (AttributeError, RuntimeError, TypeError):  # no temp_override, a closing window
            pass


# -- driving the state machines -------------------------------------------------------
def _refresh_shown():
    files = set()
    for volume in bpy.data.volumes:
        if volume.filepath:
            files.add(bpy.path.abspath(volume.filepath))
    for obj in bpy.data.objects:
        if live_volumes.LIVE_FILES in obj:
            files.update(bpy.path.abspath(p) for p in obj[live_volumes.LIVE_FILES])
    _Live.shown = frozenset(os.path.normcase(os.path.realpath(p)) for p in files)


def _report_error(obj, ident, error):
    _Live.status[ident] = f"Error: {error}"
    _status_bar(f"hyvox Live: {obj.name}: {error} (the last good voxels stay)")


STAGES = ("export", "key", "voxelize", "write", "swap")


def _apply(obj, ident, outcome):
    if outcome.kind == SHOWN:
        wall, cpu = time.perf_counter(), time.thread_time()
        swap_ms = live_volumes.swap(obj, outcome.output)
        _refresh_shown()
        was_error = _Live.status.get(ident, "").startswith("Error")
        timings = dict(outcome.output.timings_ms, swap=swap_ms)
        _Live.status[ident] = (
            "Up to date (from the cache)"
            if outcome.output.cached
            else f"Up to date ({sum(timings.get(s, 0.0) for s in STAGES):.0f} ms)"
        )
        warnings = _Live.warnings.pop(ident, [])
        if warnings:  # what the export had to say (objects without faces, colour sources)
            _Live.status[ident] += f"; {warnings[0]}"
        if was_error:
            _status_bar(None)
        # The main thread's share (in the UI the rest runs on the worker): the start (export,
        # settings, the run's set-up) and this swap, by the wall clock and by its own CPU time.
        started = _Live.started.pop(ident, (0.0, 0.0))
        timings["main"] = started[0] + (time.perf_counter() - wall) * 1000.0
        timings["main_cpu"] = started[1] + (time.thread_time() - cpu) * 1000.0
        _Live.timings[ident] = timings
    elif outcome.kind == FAILED:
        _report_error(obj, ident, outcome.error)
    else:
        _discard(outcome)


def _discard(outcome):
    """A dropped run (cancelled: its volume switched off or gone, a source deleted, an undo
    step, Esc) that finished all the same: what it wrote goes, unless something shows it
    (a state it found in the cache stays there)."""
    if outcome.output is not None and not outcome.output.cached:
        _Live.cache.remove(outcome.output.key, protected=_Live.shown | _Live.kept_by_saves)


def _start(obj, ident, depsgraph, synchronous):
    scene = depsgraph.scene_eval if depsgraph is not None else bpy.context.scene
    warnings = []
    wall, cpu = time.perf_counter(), time.thread_time()
    try:
        group = live_volumes.group_of(obj)
        settings, folder, fingerprint = live_volumes.settings_of(bpy.context, obj)
        start = time.perf_counter()
        meshes = live_volumes.export_meshes(obj, group, depsgraph, settings.color, warnings.append)
        export_ms = (time.perf_counter() - start) * 1000.0
        run = LiveRun(
            LiveInput(
                meshes, settings, folder, fingerprint, owner=ident, frame=scene.frame_current, export_ms=export_ms
            ),
            _Live.cache,
        )
    except SourcesUnavailable as exc:
        _Live.scheduler.fail(ident, str(exc))
        _Live.status[ident] = f"Waiting: {exc}"
        return
    except HyvoxError as exc:  # an empty mesh after an edit, bad settings...
        _Live.scheduler.fail(ident, str(exc))
        _report_error(obj, ident, str(exc))
        return
    _Live.runs_started[ident] = _Live.runs_started.get(ident, 0) + 1
    _Live.warnings[ident] = warnings
    _Live.started[ident] = ((time.perf_counter() - wall) * 1000.0, (time.thread_time() - cpu) * 1000.0)
    _Live.scheduler.start(ident, run, synchronous=synchronous)


def drive(scene, depsgraph=None, synchronous=None):
    """Collect finished runs and swap them in, then start a run for every dirty, idle live
    volume of the scene (main thread, or the render thread while it renders)."""
    synchronous = bpy.app.background if synchronous is None else synchronous
    live = live_volumes.live_objects(scene)
    for ident in _Live.scheduler.idents():
        if ident not in live:  # deleted, or Live switched off: cancelled, its other voxels go
            _forget(ident)
    for outcome in _Live.scheduler.collect_orphans():
        _discard(outcome)
    for ident, obj in live.items():
        if _Live.scheduler.busy(ident) and None in live_volumes.sources(obj):
            _Live.scheduler.cancel(ident)  # a source was deleted during the run
            _Live.scheduler.mark_dirty(ident)  # (the next export says why Live waits)
        outcome = _Live.scheduler.collect(ident)
        if outcome is not None:
            _apply(obj, ident, outcome)
        if _Live.scheduler.needs_run(ident):
            if depsgraph is None:
                depsgraph = bpy.context.evaluated_depsgraph_get()
            _start(obj, ident, depsgraph, synchronous)
            outcome = _Live.scheduler.collect(ident) if synchronous else None
            if outcome is not None:
                _apply(obj, ident, outcome)


def _tick():
    """The UI's timer: polls the workers, and does on the main thread what a render's
    handlers left for it (a status text, the viewport's voxels back after the render).
    It ends itself when no live volume is left."""
    if _Live.rendering:  # nothing here while it renders: not even a context override
        return RENDER_POLL_SECONDS
    if _Live.status_bar_later:
        _status_bar(_Live.status_bar_later.pop())
    if _Live.scheduler.active():
        try:
            drive(bpy.context.scene, synchronous=False)
        except Exception:  # a timer that raises is dropped by Blender: keep Live alive
            traceback.print_exc()
    if _Live.scheduler.active():
        return POLL_SECONDS
    return IDLE_POLL_SECONDS if _Live.scheduler.idents() else None


def _wake():
    """Make sure the timer runs. Off the main thread (a render's handlers) Blender's timer
    list must not be touched: the timer, which keeps ticking while live volumes exist,
    sees what the handler marked."""
    if bpy.app.background or not _on_main_thread():
        return
    if not bpy.app.timers.is_registered(_tick):
        bpy.app.timers.register(_tick, first_interval=0.0)


def request(obj) -> None:
    """Mark a live volume for a run (its switch turned on, a script's request)."""
    idents = live_volumes.live_objects(bpy.context.scene)
    ident = next((i for i, o in idents.items() if o == obj), None)
    if ident is None:
        return
    _Live.scheduler.mark_dirty(ident)
    if bpy.app.background:
        drive(bpy.context.scene)
    else:
        _wake()


def cancel_runs(reason="") -> int:
    """Cancel every running Live run (Esc); returns how many."""
    cancelled = 0
    for ident in _Live.scheduler.idents():
        if _Live.scheduler.busy(ident):
            _Live.scheduler.cancel(ident)
            _Live.status[ident] = f"Cancelled{': ' + reason if reason else ''} (the next edit updates it)"
            cancelled += 1
    if cancelled:
        _wake()
    return cancelled


# -- which volumes an update concerns ---------------------------------------------------
def _changes(depsgraph):
    objects, shading, collections = set(), False, False
    for update in depsgraph.updates:
        kind = type(update.id).__name__
        if kind == "Object":
            objects.add(update.id.name)
        elif kind in SHADING_TYPES:
            shading = True
            if kind == "Image":  # its pixels are read again at the next export
                live_volumes.ImagePixels.forget(update.id.name)
        elif kind == "Collection":
            collections = True
    return objects, shading, collections


def _mark_changed(scene, depsgraph) -> bool:
    objects, shading, collections = _changes(depsgraph)
    marked = False
    for ident, obj in live_volumes.live_objects(scene).items():
        watched = live_volumes.watched_names(obj)
        colour = shading and live_volumes.stored_used(obj, bpy.context).get("color", False)
        if watched & objects or colour or collections or len(watched) < len(live_volumes.sources(obj)):
            _Live.scheduler.mark_dirty(ident)
            marked = True
    return marked


def _evaluating_for_the_operator(scene) -> bool:
    """The operator's own render evaluation (render_depsgraph.py) is no render."""
    return scene.render.engine == render_depsgraph.ENGINE_ID


@persistent
def _on_depsgraph_update(scene, depsgraph=None):
    if depsgraph is None or _Live.rendering or _evaluating_for_the_operator(scene):
        return
    if _mark_changed(scene, depsgraph) or _Live.scheduler.active():
        if bpy.app.background:
            drive(scene, depsgraph)
        else:
            _wake()


@persistent
def _on_frame_change(scene, depsgraph=None):
    if depsgraph is None or _evaluating_for_the_operator(scene):
        return
    if depsgraph.mode == "RENDER":
        if not _on_main_thread() and not scene.render.use_lock_interface:
            if not _Live.unlocked_render_said:
                _Live.unlocked_render_said = True
                _status_bar(UNLOCKED_RENDER)
            return
        # Before this frame renders: every live volume of the scene gets this frame's voxels
        # from the render's evaluation, now (a cache hit when nothing changed).
        for ident in live_volumes.live_objects(scene):
            _Live.scheduler.mark_dirty(ident)
        drive(scene, depsgraph, synchronous=True)
        return
    if _Live.rendering:
        return
    _on_depsgraph_update(scene, depsgraph)


@persistent
def _on_render_init(scene, *_args):
    if not _evaluating_for_the_operator(scene):
        _Live.rendering = True
        _Live.unlocked_render_said = False


@persistent
def _on_render_end(scene, *_args):
    """After a render the viewport's own voxels come back (from the cache when unchanged)."""
    if _evaluating_for_the_operator(scene):
        return
    _Live.rendering = False
    for ident in live_volumes.live_objects(scene):
        _Live.scheduler.mark_dirty(ident)
    if not bpy.app.background:
        _wake()


@persistent
def _on_undo_redo(*_args):
    """The runs belong to the state left: cancelled; the state returned to gets its voxels
    (its volume's file is the one it showed then, when the cache still has it)."""
    follow_live_volumes()  # the state returned to may have live volumes, or none
    scene = bpy.context.scene
    for ident in live_volumes.live_objects(scene):
        _Live.scheduler.cancel(ident)
        _Live.scheduler.mark_dirty(ident)
    _refresh_shown()
    if bpy.app.background:
        drive(scene)
    else:
        _wake()


@persistent
def _on_load_pre(*_args):
    shutdown(session_ends=True)
    live_volumes.ImagePixels.forget()


@persistent
def _on_load_post(*_args):
    """A volume whose file is missing (the cache was not saved with the .blend) gets a run."""
    _refresh_shown()
    follow_live_volumes()
    scene = bpy.context.scene
    for ident, obj in live_volumes.live_objects(scene).items():
        _Live.scheduler.volume(ident)  # known: the timer keeps ticking for it
        if not all(os.path.exists(p) for p in live_volumes.shown_files(obj)):
            _Live.scheduler.mark_dirty(ident)
    if not bpy.app.background:
        _wake()


@persistent
def _on_save_post(*_args):
    _refresh_shown()
    _Live.kept_by_saves |= _Live.shown


def shutdown(session_ends=False):
    """Cancel every run and wait for them, then delete the files the cache wrote except those
    a saved .blend refers to and, while the session goes on (the add-on disabled), those
    the volumes show. When the file is closed (load_pre) or Blender quits, what only the
    unsaved session showed goes too."""
    for outcome in _Live.scheduler.shutdown():
        _discard(outcome)
    protected = set(_Live.kept_by_saves)
    if not session_ends:
        _refresh_shown()
        protected |= _Live.shown
    _Live.cache.clear(protected=protected)
    _Live.status.clear()


def _at_exit():
    shutdown(session_ends=True)


def _quitting() -> bool:
    """Whether Blender is quitting: it disables every add-on then (addon_utils.disable_all),
    while an artist disabling this one calls addon_utils.disable."""
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "disable_all" and frame.f_globals.get("__name__") == "addon_utils":
            return True
        frame = frame.f_back
    return False


def _forget(ident):
    _Live.scheduler.cancel(ident, forget=True)
    _refresh_shown()
    _Live.cache.drop_owner(ident, protected=_Live.shown | _Live.kept_by_saves)
    _Live.status.pop(ident, None)


# -- the switch -------------------------------------------------------------------------
_quiet = []  # set while the operator turns Live on for volumes whose voxels are current


def _switched(obj, context):
    if obj.hyvox_live:
        live_volumes.prepare_for_live(obj, context)
        follow_live_volumes()
        # Renders in the window then lock it, so that Live may swap each frame's voxels in.
        context.scene.render.use_lock_interface = True
        _Live.scheduler.volume(obj[LIVE_ID])  # known: the timer keeps ticking for it
        if not _quiet:
            request(obj)
        else:
            _wake()
        return
    live_dependencies.unfollow(obj)
    ident = obj.get(LIVE_ID)
    if ident:  # the last voxels stay as a baked result
        _forget(ident)
    follow_live_volumes()


def take_over(objects, results, used) -> None:
    """The operator's finished run, handed over once. Every result records the settings and
    sources its Live switch will use (now or later). A run that made live volumes (live=True)
    turns Live on for them: their voxels are those of the current state, so they go into the
    cache under its key (the run's geometry digests) and no run follows until something
    changes."""
    for obj, result in zip(objects, results.values()):
        live_volumes.remember(obj, used, result.group, files=list(result.files) + list(result.vox_files))
    if not used["live"]:
        return
    for obj, result in zip(objects, results.values()):
        _, _, fingerprint = live_volumes.settings_of(bpy.context, obj)
        _quiet.append(obj)
        try:
            obj.hyvox_live = True
        finally:
            _quiet.pop()
        if not result.geometry_digest:
            request(obj)
            continue
        key = live_key.run_key(result.geometry_digest, fingerprint)
        obj[live_volumes.LIVE_KEY] = key
        _Live.cache.put(CacheEntry(key, result, owner=obj[LIVE_ID], frame=bpy.context.scene.frame_current))
    _refresh_shown()


# The handlers that follow the scene. Blender may call them on its render thread (a render
# in the window), where Python can crash Blender 3.4 (Python 3.11) while its main thread is
# inside an operator that Python called (bench/bench_window_render.py counts it). So they
# are registered only while a live volume exists: a session without one renders as if
# hyvox were not installed.
FOLLOWING = (
    ("depsgraph_update_post", _on_depsgraph_update),
    ("frame_change_post", _on_frame_change),
    ("render_init", _on_render_init),
    ("render_complete", _on_render_end),
    ("render_cancel", _on_render_end),
)
# The session's handlers, always registered (the main thread only).
SESSION = (
    ("undo_post", _on_undo_redo),
    ("redo_post", _on_undo_redo),
    ("load_pre", _on_load_pre),
    ("load_post", _on_load_post),
    ("save_post", _on_save_post),
)


def follow_live_volumes() -> bool:
    """Registers the FOLLOWING handlers while a live volume exists, removes them when none
    does; returns whether they are registered. Called where volumes go live or stop
    (the switch, undo and redo, a file loaded), never from inside a FOLLOWING handler:
    Blender walks those lists while it calls them."""
    try:
        wanted = any(obj.hyvox_live for obj in bpy.data.objects)
    except AttributeError:  # bpy.data is closed while add-ons register: follow until the next
        wanted = True  # load_post (Blender's start, a file opened) or switch decides
    for name, handler in FOLLOWING:
        handlers = getattr(bpy.app.handlers, name)
        if wanted and handler not in handlers:
            handlers.append(handler)
        elif not wanted and handler in handlers:
            handlers.remove(handler)
    return wanted


def register():
    bpy.types.Object.hyvox_live = bpy.props.BoolProperty(
        name="Live",
        default=False,
        update=_switched,
        description="Update the voxels by themselves when the sources change (edits, modifiers, transforms, "
        "materials, frames); off: they stay as they are",
    )
    for name, handler in SESSION:
        getattr(bpy.app.handlers, name).append(handler)
    follow_live_volumes()
    atexit.register(_at_exit)


def unregister():
    atexit.unregister(_at_exit)
    shutdown(session_ends=_quitting())
    if bpy.app.timers.is_registered(_tick):
        bpy.app.timers.unregister(_tick)
    for name, handler in FOLLOWING + SESSION:
        handlers = getattr(bpy.app.handlers, name)
        if handler in handlers:
            handlers.remove(handler)
    del bpy.types.Object.hyvox_live
