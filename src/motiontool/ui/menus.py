"""The main window's menus with the manual's entries and shortcuts (ide-spec 1.26-1.50, 2.14-2.15); every entry
does what the manual says (tests/ui/test_menus_complete.py finds none disabled for want of code)."""

from __future__ import annotations

import operator
from pathlib import Path

from PySide6.QtGui import QKeySequence
from PySide6.QtWidgets import QMenu

from motiontool.resources import resources_path
from motiontool.ui import controller_menu as cm
from motiontool.ui import tool_windows


def _samples(pattern: str = "*.m") -> list[str]:
    return sorted(p.name for p in resources_path("samples").glob(pattern))


def build_menus(w) -> None:
    ed = w.current_editor
    dev = w.development

    def on_editor(method: str, *args):
        def run():
            editor = ed()
            if editor is not None:
                operator.attrgetter(method)(editor)(*args)  # "search.find_next": a method of the editor's part
        return run

    menus = [
        ("&File", [
            ("&New", "Ctrl+N", w.new_file), ("&Open...", "Ctrl+O", w.open_dialog), ("Recent &Files", None, "recent"),
            ("&Close", None, lambda: w.close_tab(w.tabs.currentIndex())), ("&Save", "Ctrl+S", lambda: w.save()),
            ("Save &as...", None, w.save_as),
            None, ("&Print...", "Ctrl+P", lambda: _print(w)), ("Print set&up...", None, lambda: _page_setup(w)), None,
            ("Sa&mple", None, "samples"), None, ("E&xit Program", None, w.close),
        ]),
        ("&Edit", [
            ("&Undo", "Ctrl+Z", on_editor("undo")), ("&Redo", "Ctrl+Shift+Z", on_editor("redo")),
            ("Cu&t", "Ctrl+X", on_editor("cut")), ("&Copy", "Ctrl+C", on_editor("copy")),
            ("&Paste", "Ctrl+V", on_editor("paste")), None,
            ("&Find...", "Ctrl+F", on_editor("search.show_find_dialog")),
            ("&Replace...", "Ctrl+R", on_editor("search.show_replace_dialog")),
            ("Find in F&iles...", None, on_editor("search.show_find_in_files")), None,
            ("Next Bookmark", "F2", on_editor("bookmarks.next_bookmark")),
            ("Previous Bookmark", "Shift+F2", on_editor("bookmarks.previous_bookmark")),
            ("Toggle Bookmark", "Ctrl+F2", on_editor("bookmarks.toggle_bookmark")),
            ("Clear All Bookmarks", None, on_editor("bookmarks.clear_bookmarks")), None,
            ("Convert Tabs", None, on_editor("edit.convert_tabs")), ("Clear Macros", None, lambda: _clear_macros(w)),
        ]),
        ("&Development", [
            ("&Execute", "F5", lambda: dev.execute()), ("&Break", "Esc", dev.break_program),
            ("C&ontinue", None, dev.continue_program), None, ("Messages", None, "messages"), None,
            ("Prepare Singlestep", None, w.debugger.prepare), ("Go", None, w.debugger.go),
            ("Singlestep", "F9", w.debugger.step), ("End Debug", None, w.debugger.end), None,
            ("Watch Add", None, w.debugger.watch_add), ("Watch Start", None, w.debugger.watch_start),
            ("Watch Stop", None, w.debugger.watch_stop), None, ("&Syntax Check", "F4", dev.syntax_check),
            ("Compile to file...", None, lambda: dev.compile_to_file()), None,
            ("Break all", None, dev.break_all), ("Start all", None, dev.start_all),
            ("Download all", None, lambda: _download_all(w)),
            ("Delete Programs all", None, dev.delete_programs_all), None,
            ("Select Controller...", None, lambda: _select_controller(w)),
            ("Close Interface", None, w.connection.close_interface),
            ("Close All Interfaces", None, w.connection.close_all), None,
            ("Command List...", "F12", lambda: _command_list(w)),
        ]),
        ("&Controller", [
            ("&Programs...", None, lambda: cm.show_programs(w)),
            ("P&arameters", None, [("Global...", None, lambda: _parameters(w, "global")),
                                   ("Axis...", None, lambda: _parameters(w, "axis")),
                                   ("Name...", None, lambda: _parameters(w, "name")),
                                   ("Drive (FC 300)...", None, lambda: _parameters(w, "drive")),
                                   ("APC (Unidrive SP)...", None, lambda: _apc_parameters(w)),
                                   ("Save to file...", None, lambda: cm.save_parameters(w)),
                                   ("Restore from file...", None, lambda: cm.restore_parameters(w))]),
            ("&Memory", None, [(title, None, lambda *, k=key: cm.memory(w, k))
                               for title, key, _effect in cm.MEMORY_ENTRIES]),
            ("&Reset", None, [(f"{title}...", None, lambda *, k=key: cm.reset(w, k))
                              for title, key, _effect in cm.RESET_ENTRIES]),
            None, ("Clear &Error", None, lambda: w.pending_error.clear()),
            ("Res&tart...", None, lambda: w.pending_error.restart()),
            None, ("Error &History...", None, lambda: _error_history(w)),
            ("&Diagnostic Report...", None, lambda: cm.diagnostic_report(w)),
        ]),
        ("&Tools", [("&CAM-Editor", None, lambda: _cam_editor(w)), ("&Array Editor", None, lambda: _array_editor(w)),
                    ("&Oscilloscope", None, lambda: _scope(w)), ("&I/O Panel", None, lambda: _io_panel(w)),
                    ("&Sweep Results...", None, lambda: _sweep_results(w))]),
        ("&Settings", [
            ("&Editor...", None, lambda: _editor_settings(w)), ("&Compiler...", None, lambda: _compiler_settings(w)),
            ("Open last file", None, "open_last"),
            ("&Interface...", None, lambda: _interface_settings(w)), ("&Language...", None, lambda: _language(w)),
        ]),
        ("&Window", [("&New APOSS Window", None, lambda: _new_window(w)),
                     ("&Cascade", None, lambda: _window_menu().cascade(w)),
                     ("Tile &vertically", None, lambda: _window_menu().tile(w, vertically=True)),
                     ("Tile &horizontally", None, lambda: _window_menu().tile(w, vertically=False))]),
        ("&Help", [
            ("&Contents", "F1", lambda: _help().show_help(w)), ("&Index", None, lambda: _help().show_index(w)),
            ("&SDO Dictionary", "F11", lambda: _help().show_dictionary(w)), None,
            ("&About Program", None, w.about),
        ]),
    ]
    for title, entries in menus:
        menu = w.menuBar().addMenu(title)
        if title == "&Window":  # the list of open windows follows the fixed entries (DG 3250)
            fixed = len(entries)
            menu.aboutToShow.connect(lambda *_, m=menu, n=fixed: _window_menu().fill(w, m, n))
        for entry in entries:
            if entry is None:
                menu.addSeparator()
                continue
            text, shortcut, slot = entry
            if slot == "samples":
                sub = menu.addMenu(text)
                for name in _samples():
                    sub.addAction(name, lambda *, n=name: w.open_sample(n))
                sub.addSeparator()
                # the APC user guide's complete DPL programs (seed 004 §7.1-7.6), for the simulated APC
                w.dpl_samples_menu = sub.addMenu("DPL (APC User Guide)")
                for name in _samples("*.dpl"):
                    w.dpl_samples_menu.addAction(name, lambda *, n=name: w.open_sample(n))
                w.samples_menu = sub
                continue
            if slot == "recent":
                w.recent_menu = menu.addMenu(text)
                fill_recent_menu(w)
                continue
            if slot == "open_last":  # Settings → Options: open the last file at start-up (DG 3156-3230)
                action = menu.addAction(text)
                action.setCheckable(True)
                action.setChecked(w.settings.value("options/open_last_file", False, type=bool))
                action.toggled.connect(lambda on: w.settings.setValue("options/open_last_file", on))
                w.actions_by_text[text] = action
                continue
            if slot == "messages":
                _messages_menu(w, menu.addMenu(text))
                continue
            if isinstance(slot, list):  # a submenu (Controller → Parameters ▸, Reset ▸)
                sub = menu.addMenu(text)
                for sub_text, _keys, sub_slot in slot:
                    action = sub.addAction(sub_text)
                    action.triggered.connect(lambda *_, s=sub_slot: s())
                    w.actions_by_text[sub_text.replace("&", "")] = action
                continue
            action = menu.addAction(text)
            if shortcut:
                action.setShortcut(QKeySequence(shortcut))
            if slot is None:
                action.setEnabled(False)  # not built yet; the entry shows where it will be
            else:
                action.triggered.connect(lambda *_, s=slot: s())
            w.actions_by_text[text.replace("&", "")] = action


def fill_recent_menu(w) -> None:
    menu: QMenu = w.recent_menu
    menu.clear()
    for path in w.recent_files():
        menu.addAction(path, lambda *, p=path: w.open_or_report(Path(p)))
    menu.setEnabled(bool(w.recent_files()))


def _messages_menu(w, menu: QMenu) -> None:
    """Development → Messages ▸ Log file / Stop logging / Update Log file (DG 2420-2426)."""
    start = menu.addAction("Log file...")
    stop = menu.addAction("Stop logging")
    update = menu.addAction("Update Log file")

    def refresh() -> None:
        stop.setEnabled(w.messages.logging)
        update.setEnabled(w.messages.logging)

    def choose() -> None:
        chosen = w.prompts.save_path("Log file", "messages.log", "Log files (*.log *.txt)")
        if chosen is not None:
            try:
                w.messages.start_log(chosen)
            except OSError as exc:
                from motiontool.ui.file_errors import save_failed

                save_failed(w, "Log file", chosen, exc, "Messages are not logged.")
        refresh()

    start.triggered.connect(choose)
    stop.triggered.connect(lambda: (w.messages.stop_log(), refresh()))
    update.triggered.connect(w.messages.update_log)
    refresh()


def _editor_settings(w) -> None:
    """Settings → Editor (DG 3117-3150): colours, tab size, convert tabs; kept in the settings file."""
    from motiontool.ui.editor.settings_dialog import EditorSettingsDialog

    dialog = EditorSettingsDialog(w.editor_settings(), w)
    if dialog.exec():
        w.set_editor_settings(dialog.settings())


def _command_list(w) -> None:
    from motiontool.ui.command_list import CommandListDialog

    dialog = CommandListDialog(w)
    dialog.insert_requested.connect(lambda line: ed.insertPlainText(line) if (ed := w.current_editor()) else None)
    dialog.execute_requested.connect(w.development.execute_line)
    w.command_list = dialog
    dialog.show()


def _clear_macros(w) -> None:
    """Edit → Clear Macros (DG L2225): "All currently defined macros can be cleared" - the IDE's, in every tab,
    and in the settings file."""
    for editor in w.editors():
        editor.recorder.clear_macros()   # also the last recorded macro, which a tab plays without a shortcut
    w.macros.clear()


def _cam_editor(w) -> None:
    tool_windows.cam_editor(w)


def _scope(w) -> None:
    tool_windows.oscilloscope(w)


def _io_panel(w) -> None:
    from motiontool.ui.io_panel import io_panel

    io_panel(w)


def _sweep_results(w) -> None:
    from motiontool.ui.sweep_view import open_sweep_results

    open_sweep_results(w)


def _array_editor(w) -> None:
    tool_windows.array_editor(w)


def _select_controller(w) -> None:
    """Development → Select Controller (DG 2536-2546)."""
    from motiontool.ui.interface_dialog import SelectControllerDialog

    dialog = SelectControllerDialog(w, w.controllers, w.settings)
    if dialog.exec():
        key, cid = dialog.selected()
        w.development.select_controller(cid, interface=key)


def _interface_settings(w) -> None:
    """Settings → Interface (DG 3087-3111): new connections use it; connected controllers stay."""
    from motiontool.ui.interface_dialog import InterfaceSettingsDialog, load_interfaces

    if InterfaceSettingsDialog(w, w.settings).exec():
        configs, default = load_interfaces(w.settings)
        w.controllers.set_default(configs[default])
        w.messages.ide(f"Default interface: {configs[default].description} (controllers "
                       f"{configs[default].first}..{configs[default].last}); it is used for new connections")


def _new_window(w) -> None:
    from motiontool.ui.connection import new_window

    w.other_windows = [o for o in getattr(w, "other_windows", []) if o.isVisible()] + [new_window(w)]


def _error_history(w) -> None:
    from motiontool.ui.error_history import show_error_history

    show_error_history(w)


def _parameters(w, which: str) -> None:
    from motiontool.ui import parameter_dialogs

    {"global": parameter_dialogs.show_global, "axis": parameter_dialogs.show_axis,
     "name": parameter_dialogs.show_name, "drive": parameter_dialogs.show_drive}[which](w)


def _apc_parameters(w) -> None:
    from motiontool.ui.apc_parameters import show_apc_parameters

    show_apc_parameters(w)


def _download_all(w) -> None:
    from motiontool.ui.download_dialog import download_all

    download_all(w)


def _compiler_settings(w) -> None:
    from motiontool.ui.compiler_settings import edit_compiler_settings

    edit_compiler_settings(w)


def _language(w) -> None:
    from motiontool.ui.language import choose_language

    choose_language(w)


def _window_menu():
    from motiontool.ui import window_menu

    return window_menu


def _help():
    from motiontool.ui import help as help_module

    return help_module


def _page_setup(w) -> None:
    """Print setup (DG 2231): page size, orientation and margins for the next Print."""
    from PySide6.QtPrintSupport import QPageSetupDialog, QPrinter

    w.printer = getattr(w, "printer", None) or QPrinter()
    QPageSetupDialog(w.printer, w).exec()


def _print(w) -> None:
    editor = w.current_editor()
    if editor is None:
        return
    try:
        from PySide6.QtPrintSupport import QPrintDialog, QPrinter
    except ImportError:  # the Essentials wheel may lack print support on some platforms
        w.messages.ide("Printing is not available in this Qt installation")
        return
    printer = getattr(w, "printer", None) or QPrinter()  # Print setup's page, when it was set
    w.printer = printer
    if QPrintDialog(printer, w).exec():
        editor.print_(printer)
