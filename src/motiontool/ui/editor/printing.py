"""File ▸ Print of a program (DG 2229-2231): long lines wrap at the page's width instead of being cut off, and
every page has a header with the file name, "Page n of N" and the date of printing (issue 23 item 9: the
editor's own print clipped long lines and printed no header). What went on each page is returned, so a caller
(and a test) can see it without reading the printer's output back."""

from __future__ import annotations

import datetime
from dataclasses import dataclass, field

from PySide6.QtCore import QPointF, QRectF, QSizeF, Qt
from PySide6.QtGui import QFont, QFontMetricsF, QPainter, QPen, QTextDocument, QTextOption

HEADER_GAP = 0.6  # of a line: between the header's rule and the program text


@dataclass
class PrintedPage:
    header: tuple[str, str, str]              # file name, "Page n of N", date
    lines: list[str] = field(default_factory=list)  # the program's text as laid out on this page, line by line
    widest: float = 0.0                       # the widest of those lines, in printer pixels
    width: float = 0.0                        # the width they had to fit


def print_program(text: str, font: QFont, printer, name: str,
                  when: datetime.datetime | None = None) -> list[PrintedPage]:
    """Print `text` in `font` on `printer` (a QPrinter) with a header on every page; returns what each page got."""
    when = when or datetime.datetime.now()
    date = when.strftime("%Y-%m-%d %H:%M")
    painter = QPainter()
    if not painter.begin(printer):
        raise OSError(f"cannot print to {printer.printerName() or printer.outputFileName() or 'the printer'}")
    try:
        area = printer.pageLayout().paintRectPixels(printer.resolution())
        header_font = QFont(font)
        header_font.setBold(True)
        painter.setFont(header_font)
        metrics = QFontMetricsF(header_font, printer)
        header_height = metrics.lineSpacing() * (1 + HEADER_GAP)
        document = QTextDocument()
        document.documentLayout().setPaintDevice(printer)  # lay out at the printer's resolution
        document.setDefaultFont(font)
        option = QTextOption()
        option.setWrapMode(QTextOption.WrapMode.WrapAtWordBoundaryOrAnywhere)  # a long name breaks anywhere
        document.setDefaultTextOption(option)
        document.setDocumentMargin(0)
        document.setPlainText(text)
        body = QSizeF(area.width(), area.height() - header_height)
        document.setPageSize(body)  # paginated: no line is cut by a page's end
        count = document.pageCount()
        pages = [PrintedPage((name, f"Page {n + 1} of {count}", date), width=body.width()) for n in range(count)]
        _collect_lines(document, body.height(), pages)
        for n, page in enumerate(pages):
            if n:
                printer.newPage()
            painter.save()
            painter.setFont(header_font)
            line = QRectF(0, 0, area.width(), metrics.lineSpacing())
            for part, align in zip(page.header, (Qt.AlignmentFlag.AlignLeft, Qt.AlignmentFlag.AlignHCenter,
                                                 Qt.AlignmentFlag.AlignRight), strict=True):
                painter.drawText(line, int(align | Qt.AlignmentFlag.AlignVCenter), part)
            painter.setPen(QPen(Qt.GlobalColor.black, max(1.0, printer.resolution() / 150)))
            painter.drawLine(QPointF(0, line.bottom()), QPointF(area.width(), line.bottom()))
            painter.translate(0, header_height - n * body.height())
            document.drawContents(painter, QRectF(0, n * body.height(), body.width(), body.height()))
            painter.restore()
    finally:
        painter.end()
    return pages


def _collect_lines(document: QTextDocument, page_height: float, pages: list[PrintedPage]) -> None:
    layout = document.documentLayout()
    block = document.begin()
    while block.isValid():
        top = layout.blockBoundingRect(block).top()
        text = block.text()
        for i in range(block.layout().lineCount()):
            line = block.layout().lineAt(i)
            page = pages[min(int((top + line.y()) // page_height), len(pages) - 1)]
            page.lines.append(text[line.textStart():line.textStart() + line.textLength()])
            page.widest = max(page.widest, line.naturalTextWidth())
        block = block.next()



def print_editor(editor, printer) -> None:
    """File ▸ Print of a CodeEditor: its text under its file name; what went on each page is kept as
    `editor.printed`. A printer that cannot start is said in a message box; the program is untouched."""
    from pathlib import Path

    path = editor.property("path")
    name = Path(path).name if path else editor.property("sample") or "Untitled"
    try:
        editor.printed = print_program(editor.toPlainText(), editor.font(), printer, name)
    except OSError as exc:
        editor.prompts.warn("Print", f"{exc}.")
