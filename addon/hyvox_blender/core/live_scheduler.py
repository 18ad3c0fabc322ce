# SPDX-License-Identifier: GPL-3.0-or-later
"""When Live runs happen: one small state machine per live volume.

    idle --edit--> dirty --export (main thread), start--> running --worker ends--> collect
      ^                                                                             |
      +------------- swap (main thread: the new file is shown) or drop -------------+

- At most one run per volume exists at any time: an edit during a run only marks the
  volume dirty, and one more run starts when the running one has been collected, with the
  state of the last edit (a burst of edits gives at most two runs; newest wins). The
  running run is not cancelled by an edit: its result is closer to the current state than
  what is shown (during a sculpt stroke or playback the voxels follow at the voxelizer's
  pace) and it is shown unless something newer already is.
- cancel() is for the cases where a result must not be shown: Live switched off, the volume
  or its sources gone, an undo step, a new file, Esc. The run's token is cancelled and its
  result dropped; the volume stays busy until its thread has ended, so a cancelled run
  never overlaps the next one.
- Threaded (the UI: the caller polls collect() from a timer) or synchronous (background
  mode and renders: start() returns when the run has ended).
Nothing here imports bpy; the Blender side (blender/live/driver.py) exports, swaps and reports."""

import threading
import traceback
from dataclasses import dataclass
from typing import Dict, List, Optional

from .errors import CancelledError, HyvoxError
from .live_run import LiveOutput, LiveRun

SHOWN, DROPPED, FAILED = "shown", "dropped", "failed"


@dataclass
class Outcome:
    kind: str  # SHOWN: swap it in; DROPPED: not to be shown; FAILED: error
    run: LiveRun
    output: Optional[LiveOutput] = None  # a dropped run may have finished all the same
    error: str = ""


class LiveVolume:
    """The state of one live volume (by its id)."""

    def __init__(self, ident: str):
        self.ident = ident
        self.dirty = False  # an edit came after the last export
        self.run: Optional[LiveRun] = None  # started and not yet collected
        self.thread: Optional[threading.Thread] = None
        self.generation = 0  # of the last run started
        self.shown_generation = 0  # of the last run shown
        self.dropping = False  # the current run was cancelled: drop its result
        self.error = ""  # the last run's error, until one succeeds
        self.runs_started = 0
        self.last_output: Optional[LiveOutput] = None
        self.finished = None  # (output, error) set when the run has ended

    @property
    def state(self) -> str:
        if self.run is None:
            return "dirty" if self.dirty else "idle"
        return "cancelling" if self.dropping else "running"


class LiveScheduler:
    def __init__(self, threaded: bool):
        self.threaded = threaded
        self._volumes: Dict[str, LiveVolume] = {}
        self._orphans: List[LiveVolume] = []  # forgotten while a run was still ending
        self._lock = threading.RLock()

    # -- state ------------------------------------------------------------------------
    def volume(self, ident: str) -> LiveVolume:
        with self._lock:
            if ident not in self._volumes:
                self._volumes[ident] = LiveVolume(ident)
            return self._volumes[ident]

    def get(self, ident: str) -> Optional[LiveVolume]:
        with self._lock:
            return self._volumes.get(ident)

    def idents(self) -> List[str]:
        with self._lock:
            return list(self._volumes)

    def mark_dirty(self, ident: str) -> None:
        with self._lock:
            self.volume(ident).dirty = True

    def needs_run(self, ident: str) -> bool:
        """Dirty and idle: the caller should export now and start()."""
        with self._lock:
            volume = self._volumes.get(ident)
            return volume is not None and volume.dirty and volume.run is None

    def busy(self, ident: str) -> bool:
        with self._lock:
            volume = self._volumes.get(ident)
            return volume is not None and volume.run is not None

    def active(self) -> bool:
        """Whether anything is left to do (a timer keeps polling while it is)."""
        with self._lock:
            return bool(self._orphans) or any(v.dirty or v.run is not None for v in self._volumes.values())

    def fail(self, ident: str, error: str) -> None:
        """An export that failed (on the main thread): the volume keeps its voxels."""
        with self._lock:
            volume = self.volume(ident)
            volume.dirty = False
            volume.error = error

    # -- runs -------------------------------------------------------------------------
    def start(self, ident: str, run: LiveRun, synchronous: Optional[bool] = None) -> None:
        """Start run for the volume (its export is done). Synchronous (the default unless
        threaded): the run happens now, on this thread; a threaded run of the same volume
        still going is cancelled and waited for first."""
        synchronous = (not self.threaded) if synchronous is None else synchronous
        volume = self.volume(ident)
        if volume.run is not None:
            if not synchronous:
                raise RuntimeError(f"live volume {ident} already has a run")
            self.cancel(ident)
            self.wait(ident)
            self.collect(ident)
        with self._lock:
            volume.dirty = False
            volume.generation += 1
            volume.runs_started += 1
            volume.run, volume.finished, volume.dropping = run, None, False
            generation = volume.generation
            if not synchronous:
                volume.thread = threading.Thread(
                    target=self._work, args=(volume, run), name=f"hyvox-live-{generation}", daemon=True
                )
                volume.thread.start()
        if synchronous:
            self._work(volume, run)

    @staticmethod
    def _work(volume: LiveVolume, run: LiveRun) -> None:
        output, error = None, ""
        try:
            output = run()
        except CancelledError:
            error = "cancelled"
        except HyvoxError as exc:
            error = str(exc)
        except BaseException as exc:  # a bug: reported, never left running or half-done
            traceback.print_exception(type(exc), exc, exc.__traceback__)
            error = f"hyvox failed unexpectedly ({type(exc).__name__}: {exc}); see the console"
        volume.finished = (output, error)

    def collect(self, ident: str) -> Optional[Outcome]:
        """The outcome of the volume's run once it has ended (None while it runs or when
        there is none); the volume is idle again."""
        with self._lock:
            volume = self._volumes.get(ident)
            if volume is None or volume.run is None or volume.finished is None:
                return None
            return self._settle(volume)

    def _settle(self, volume: LiveVolume) -> Outcome:
        output, error = volume.finished
        run = volume.run
        generation = volume.generation
        dropped = volume.dropping or run.cancelled
        volume.run, volume.thread, volume.finished, volume.dropping = None, None, None, False
        if dropped:
            return Outcome(DROPPED, run, output)
        if error:
            volume.error = error
            return Outcome(FAILED, run, None, error)
        if generation <= volume.shown_generation:
            return Outcome(DROPPED, run, output)
        volume.shown_generation = generation
        volume.error = ""
        volume.last_output = output
        return Outcome(SHOWN, run, output)

    def cancel(self, ident: str, forget: bool = False) -> None:
        """Cancel the volume's run, if any: its result is dropped. forget: the volume is gone
        too (its run, still ending, is collected by collect_orphans())."""
        with self._lock:
            volume = self._volumes.get(ident)
            if volume is None:
                return
            if volume.run is not None:
                volume.dropping = True
                volume.run.cancel()
            if forget:
                del self._volumes[ident]
                if volume.run is not None:
                    self._orphans.append(volume)
            else:
                volume.dirty = False

    def collect_orphans(self) -> List[Outcome]:
        """The outcomes of runs of forgotten volumes that have ended (all dropped)."""
        with self._lock:
            done = [v for v in self._orphans if v.finished is not None]
            self._orphans = [v for v in self._orphans if v.finished is None]
            return [self._settle(v) for v in done]

    def wait(self, ident: str, timeout: Optional[float] = None) -> bool:
        """Block until the volume's run has ended (tests, renders, shutdown)."""
        with self._lock:
            volume = self._volumes.get(ident)
            thread = volume.thread if volume is not None else None
        if thread is not None:
            thread.join(timeout)
            return not thread.is_alive()
        return True

    def shutdown(self, timeout: float = 5.0) -> List[Outcome]:
        """Cancel every run, wait for their threads (each stops at its next check) and
        return every outcome (all dropped): nothing runs on once this returns."""
        with self._lock:
            idents = list(self._volumes)
        for ident in idents:
            self.cancel(ident, forget=True)
        with self._lock:
            threads = [v.thread for v in self._orphans if v.thread is not None]
        for thread in threads:
            thread.join(timeout)
        return self.collect_orphans()
