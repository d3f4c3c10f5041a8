"""File ▸ Print (DG 2229-2231) wraps long lines and puts a header on every page: the file name, "Page n of N" and
the date (issue 23 item 9: a long line was cut at the page's edge and no page said what it was). Printed as a
user does: the menu action, the print dialog answered with its Print button; the printer writes a PDF file."""

from __future__ import annotations

import datetime
import re

from PySide6.QtPrintSupport import QPrinter

from tests.modal import answering, ok_reply

LONG = "PRINT " + "+".join(f"value_{k}" for k in range(60))  # ~600 characters: several printed lines


def test_print_wraps_long_lines_and_heads_every_page(window, qtbot, tmp_path):
    lines = [f'PRINT "line {k}"' for k in range(150)]
    lines[3] = LONG
    program = tmp_path / "ctl2.m"
    program.write_text("\n".join(lines) + "\n", encoding="utf-8")
    editor = window.open_file(program)
    printer = QPrinter(QPrinter.PrinterMode.HighResolution)  # Print setup's printer: a PDF file here
    printer.setOutputFormat(QPrinter.OutputFormat.PdfFormat)
    printer.setOutputFileName(str(tmp_path / "ctl2.pdf"))
    window.printer = printer
    with answering(qtbot, ok_reply()):
        window.actions_by_text["Print..."].trigger()

    pages = editor.printed
    pdf = (tmp_path / "ctl2.pdf").read_bytes()
    assert len(pages) >= 3 and len(re.findall(rb"/Type\s*/Page\b", pdf)) == len(pages)
    today = datetime.date.today().isoformat()
    for n, page in enumerate(pages, start=1):
        name, number, date = page.header
        assert (name, number) == ("ctl2.m", f"Page {n} of {len(pages)}") and date.startswith(today)
        assert page.widest <= page.width  # nothing runs past the page's edge
    printed = [line for page in pages for line in page.lines]
    assert "".join(printed) == "".join(lines)  # every character, in order: nothing clipped
    assert len(printed) - len(lines) >= 3  # the long line took several printed lines
