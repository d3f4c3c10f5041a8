"""The TESTSETP variant's Load and the curve list's Reload (DG 5326-5347, 4850-4876): the controller's answers come
on a thread while the scope window paints and says what it waits for (poll_job.wait, decision I34); the curves are
made in the GUI thread. A refused or lost request is said in the status bar; the curves shown stay."""

from __future__ import annotations

from motiontool.comms.protocol import LinkError
from motiontool.scope.acquisition import list_testsetp, load_testsetp, reload_testsetp
from motiontool.scope.ui.poll_job import wait


def load_recordings(window) -> None:
    """One recording is loaded at once; with several the user picks (DG 5326-5333)."""
    link = window.link
    if link is None:
        return
    bar = window.statusBar()
    try:
        found = wait(window, "Listing the TESTSETP recordings …", lambda: list_testsetp(link))
    except LinkError as exc:
        bar.showMessage(f"TESTSETP: {exc}", 10000)
        return
    if not found:
        bar.showMessage("No TESTSETP recording on the controller", 5000)
        return
    chosen = found[-1]
    if len(found) > 1 and window.ask:
        labels = [f"{r.index}: {r.name} ({r.samples} sets)" for r in found]
        text = window.prompts.pick("TESTSETP", "Recording to upload:", labels, len(labels) - 1)
        if text is None:
            return
        chosen = found[labels.index(text)]
    if any(c.source.method == "testsetp" and c.source.info.get("index") == chosen.index
           for c in window.scope.curves):   # a second Load added the same set again (issue 23 item 8)
        bar.showMessage(f"Recording {chosen.index} ({chosen.name}) is shown already; Reload in the curve list reads "
                        "it again", 10000)
        return
    label = "" if not window.scope.curves else f"#{chosen.index} "
    try:
        load_testsetp(window.scope, link, chosen.index, label=label,
                      run=lambda request: wait(window, f"Uploading recording {chosen.index} ({chosen.name}) …",
                                               request))
    except LinkError as exc:
        bar.showMessage(f"TESTSETP: {exc}", 10000)
        return
    window.list.rebuild()
    window.zoom_reset()


def reload_recording(window, name: str) -> None:
    """Reload & Redisplay: the curve's recording read again (after the program re-ran)."""
    link = window.link
    if link is None:
        return
    try:
        reload_testsetp(window.scope, link, window.scope.curve(name),
                        run=lambda request: wait(window, f"Reloading {name} …", request))
    except (LinkError, ValueError) as exc:   # no such recording any more, or the line failed
        window.statusBar().showMessage(f"Reload {name}: {exc}", 10000)
        return
    window.zoom_reset()
