"""Tools: the tool table by touch (number, pocket, length, diameter, description), the tool in
the spindle, touch-off of a tool's length and import of a LinuxCNC ``.tbl`` file.

Every change goes through the controller, which refuses it while a program runs (a program
reads the offsets when it is checked) and says why in the status line.
"""

from __future__ import annotations

from PySide6.QtGui import QFont
from PySide6.QtWidgets import (
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from app.context import PanelContext
from app.controller_text import localize
from app.format import tool_text
from app.i18n import N_, tr
from app.widgets.touch import touch_rows
from planner.core.tools import Tool, ToolTable

COLUMNS = (N_("Tool"), N_("Pocket"), N_("Length Z (mm)"), N_("Diameter (mm)"), N_("Description"))


class ToolsPage(QWidget):
    def __init__(self, context: PanelContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("toolsPage")
        self.ctx = context
        c = context.controller
        i18n = context.i18n
        layout = QVBoxLayout(self)
        self.spindle_label = QLabel()
        self.spindle_label.setObjectName("toolInSpindle")
        layout.addWidget(self.spindle_label)
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        self.table.verticalHeader().setVisible(False)
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        touch_rows(self.table)
        self.table.cellClicked.connect(self.edit_cell)
        layout.addWidget(self.table, 1)
        hint = QLabel()
        hint.setWordWrap(True)
        i18n.bind(hint, N_("Tap a value to change it. Lengths are the tool's Z offset, used by G43. "
                           "Touch off: jog the tool tip onto a surface and enter its height in the "
                           "active work coordinates."))
        layout.addWidget(hint)
        row = QHBoxLayout()
        self.buttons: dict[str, QPushButton] = {}
        for name, label, slot in (
            ("add", N_("Add tool"), self.add_tool),
            ("remove", N_("Delete"), self.remove_tool),
            ("spindle", N_("In the spindle"), self.set_in_spindle),
            ("touch", N_("Touch off length"), self.touch_off),
            ("measure", N_("Measure on the setter"), self.measure),
            ("import", N_("Import .tbl"), self.import_table),
        ):
            button = QPushButton()
            i18n.bind(button, label)
            button.setMinimumHeight(56)
            button.clicked.connect(slot)
            row.addWidget(button)
            self.buttons[name] = button
        layout.addLayout(row)
        self._tools: ToolTable = c.tool_table
        self._in_spindle = c.tool_in_spindle
        c.toolsChanged.connect(self._on_tools)
        i18n.languageChanged.connect(lambda _lang: self._on_tools(self._tools, self._in_spindle))
        self._on_tools(self._tools, self._in_spindle)

    # --- display ---------------------------------------------------------------------------
    def _on_tools(self, table: object, in_spindle: int) -> None:
        assert isinstance(table, ToolTable)
        self._tools, self._in_spindle = table, int(in_spindle)
        self.table.setHorizontalHeaderLabels([tr(c) for c in COLUMNS])
        tools = list(table)
        self.table.setRowCount(len(tools))
        bold = QFont()
        bold.setBold(True)
        for r, t in enumerate(tools):
            cells = (f"T{t.number}", str(t.pocket), f"{t.length_mm:.3f}", f"{t.diameter_mm:.3f}",
                     t.description)
            for col, text in enumerate(cells):
                item = QTableWidgetItem(("● " if col == 0 and t.number == self._in_spindle else "") + text)
                if t.number == self._in_spindle:
                    item.setFont(bold)
                self.table.setItem(r, col, item)
        self.spindle_label.setText(tr("In the spindle: {0}").format(tool_text(table, self._in_spindle)))

    def selected_tool(self) -> Tool | None:
        row = self.table.currentRow()
        tools = list(self._tools)
        return tools[row] if 0 <= row < len(tools) else None

    # --- actions ---------------------------------------------------------------------------
    def edit_cell(self, row: int, col: int) -> None:
        tools = list(self._tools)
        if not 0 <= row < len(tools) or col == 0:
            return
        t = tools[row]
        c, d = self.ctx.controller, self.ctx.dialogs
        if col == 4:
            text = d.ask_text(self, tr("T{0}").format(t.number), tr("Description:"), text=t.description)
            if text is not None:
                c.set_tool(Tool(t.number, t.pocket, t.offsets_mm, t.diameter_mm, text.strip(), t.lathe))
            return
        title, value, lo = {
            1: (tr("T{0}: pocket").format(t.number), float(t.pocket), 0.0),
            2: (tr("T{0}: length Z (mm)").format(t.number), t.length_mm, -1e6),
            3: (tr("T{0}: diameter (mm)").format(t.number), t.diameter_mm, 0.0),
        }[col]
        new = d.ask_number(self, title, value, lo, 1e6, 0 if col == 1 else 4)
        if new is None:
            return
        if col == 1:
            c.set_tool(Tool(t.number, int(new), t.offsets_mm, t.diameter_mm, t.description, t.lathe))
        elif col == 2:
            c.set_tool(t.with_offset("Z", new))
        else:
            c.set_tool(Tool(t.number, t.pocket, t.offsets_mm, new, t.description, t.lathe))

    def add_tool(self) -> None:
        taken = [t.number for t in self._tools]
        proposal = max(taken, default=0) + 1
        number = self.ctx.dialogs.ask_number(self, tr("New tool number"), float(proposal), 1, 99_999, 0)
        if number is None:
            return
        n = int(number)
        if n in self._tools:
            self.ctx.dialogs.inform(self, tr("Add tool"), tr("T{0} is already in the table.").format(n))
            return
        self.ctx.controller.set_tool(Tool(n, n))

    def remove_tool(self) -> None:
        t = self.selected_tool()
        if t is None:
            return
        question = tr("Delete {0} from the tool table?").format(t.label())
        if self.ctx.dialogs.confirm(self, tr("Delete"), question):
            self.ctx.controller.remove_tool(t.number)

    def set_in_spindle(self) -> None:
        t = self.selected_tool()
        if t is not None:
            self.ctx.controller.set_tool_in_spindle(t.number)

    def touch_off(self) -> None:
        """The length of the tool in the spindle (the one touching the surface): another tool
        only when it is selected and the operator says so, naming it."""
        number = self._in_spindle
        selected = self.selected_tool()
        d = self.ctx.dialogs
        if selected is not None and selected.number != number:
            if not number:
                text = tr("No tool is in the spindle: put {0} in and set it (In the spindle) first.")
                d.inform(self, tr("Touch off length"), text.format(selected.label()))
                return
            spindle_tool = self._tools.get(number)
            label = spindle_tool.label() if spindle_tool is not None else f"T{number}"
            choice = d.choose(self, tr("Touch off length"),
                              tr("{0} is in the spindle, {1} is selected. Whose length is measured?").format(
                                  label, selected.label()),
                              [label, selected.label(), tr("Cancel")])
            if choice == 1:
                number = selected.number
            elif choice != 0:
                return
        if not number:
            d.inform(self, tr("Touch off length"), tr("No tool is in the spindle."))
            return
        tool = self._tools.get(number)
        label = tool.label() if tool is not None else f"T{number}"
        z = d.ask_number(self, tr("Touch off {0}: work Z of the surface the tip touches").format(label), 0.0)
        if z is not None:
            result = self.ctx.controller.touch_off_tool(number, z)
            if not result:
                d.inform(self, tr("Touch off length"), localize(result.reason))

    def measure(self) -> None:
        """The tool in the spindle measured on the tool setter: the operator confirms first,
        since the machine moves by itself (up, across, down onto the setter)."""
        t = self.selected_tool()
        if t is None:
            return
        question = tr("Measure {0} on the tool setter? The spindle goes up to the clearance height, "
                      "across to the setter and probes down onto it twice. Keep clear of the machine."
                      ).format(t.label())
        if self.ctx.dialogs.confirm(self, tr("Measure on the setter"), question):
            result = self.ctx.controller.measure_tool(t.number)
            if not result:
                self.ctx.dialogs.inform(self, tr("Measure on the setter"), result.reason)

    def import_table(self) -> None:
        folders = self.ctx.folders
        assert folders is not None
        path = self.ctx.dialogs.ask_open_file(self, str(folders.default), folders, (".tbl",))
        if not path:
            return
        if folders.root_of(path) is None or not path.lower().endswith(".tbl"):
            self.ctx.dialogs.inform(self, tr("Import .tbl"),
                                    tr("{0} is not a tool table in the program folders").format(path))
            return
        if self.ctx.dialogs.confirm(
                self, tr("Import .tbl"), tr("Replace the whole tool table by {0}?").format(path)):
            self.ctx.controller.import_tool_table(path)


def create_page(context: PanelContext) -> QWidget:
    return ToolsPage(context)
