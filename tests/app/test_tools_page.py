"""The Tools page: the table by touch, the tool in the spindle, touch-off, import; the header
always shows the tool in the spindle."""

from __future__ import annotations

from pathlib import Path

from planner.core.tools import Tool


def _setup(fake_controller) -> None:
    fake_controller.set_tool(Tool(1, 1, (("Z", 40.0),), 6.0, "6 mm flat"))
    fake_controller.set_tool(Tool(2, 7, (("Z", -3.5),), 3.0, "3 mm ball"))
    fake_controller.calls.clear()


def test_the_table_shows_every_tool_and_which_is_in_the_spindle(fake_window, fake_controller) -> None:
    page = fake_window.page("tools")
    _setup(fake_controller)
    assert page.table.rowCount() == 2
    assert [page.table.item(1, c).text() for c in range(5)] == ["T2", "7", "-3.500", "3.000", "3 mm ball"]
    assert "none" in page.spindle_label.text() and "none" in fake_window.header.tool_label.text()
    page.table.selectRow(1)
    page.buttons["spindle"].click()
    assert fake_controller.calls[-1] == ("set_tool_in_spindle", 2)
    assert page.table.item(1, 0).text() == "● T2" and page.table.item(1, 0).font().bold()
    assert fake_window.header.tool_label.text() == "Tool: T2 (3 mm ball)"


def test_tapping_a_value_changes_it_through_the_controller(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("tools")
    _setup(fake_controller)
    dialogs.answers.append(41.25)
    page.edit_cell(0, 2)
    assert fake_controller.calls[-1][0] == "set_tool"
    assert fake_controller.tool_table.get(1).length_mm == 41.25
    dialogs.answers.append(8.0)
    page.edit_cell(0, 3)
    assert fake_controller.tool_table.get(1).diameter_mm == 8.0
    dialogs.answers.append("8 mm rougher")
    page.edit_cell(0, 4)
    assert fake_controller.tool_table.get(1).description == "8 mm rougher"
    assert page.table.item(0, 2).text() == "41.250"
    dialogs.answers.append(None)                        # cancelled: nothing sent
    n = len(fake_controller.calls)
    page.edit_cell(0, 1)
    assert len(fake_controller.calls) == n


def test_add_delete_and_touch_off(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("tools")
    _setup(fake_controller)
    dialogs.answers.append(5.0)
    page.buttons["add"].click()
    assert fake_controller.tool_table.get(5) == Tool(5, 5)
    dialogs.answers.append(2.0)                         # already there: said, not replaced
    page.buttons["add"].click()
    assert dialogs.asked[-1] == ("inform", "T2 is already in the table.")
    page.table.selectRow(0)
    page.buttons["touch"].click()                       # the spindle is empty: said, nothing measured
    assert dialogs.asked[-1][0] == "inform" and "No tool is in the spindle" in dialogs.asked[-1][1]
    assert not any(c[0] == "touch_off_tool" for c in fake_controller.calls)
    fake_controller.set_tool_in_spindle(1)
    dialogs.answers.append(1.5)
    page.buttons["touch"].click()
    assert fake_controller.calls[-1] == ("touch_off_tool", 1, 1.5)
    page.table.selectRow(2)
    page.buttons["remove"].click()                      # confirmed
    assert fake_controller.calls[-1] == ("remove_tool", 5) and 5 not in fake_controller.tool_table


def test_import_stays_in_the_program_folders(fake_window, fake_controller, dialogs, tmp_path: Path) -> None:
    page = fake_window.page("tools")
    dialogs.answers.append("/etc/passwd")
    page.buttons["import"].click()
    assert dialogs.asked[-1][0] == "inform"
    assert not any(c[0] == "import_tool_table" for c in fake_controller.calls)
    folder = fake_window.context.folders.default
    tbl = Path(folder) / "shop.tbl"
    tbl.write_text("T3 P3 Z10 ;x\n")
    dialogs.answers.append(str(tbl))
    page.buttons["import"].click()
    assert fake_controller.calls[-1] == ("import_tool_table", str(tbl))


def test_measuring_on_the_setter_asks_first(fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("tools")
    _setup(fake_controller)
    page.table.selectRow(1)
    dialogs.answers.append(False)                       # declined: the machine does not move
    page.buttons["measure"].click()
    assert not any(c[0] == "measure_tool" for c in fake_controller.calls)
    assert "Keep clear of the machine" in dialogs.asked[-1][1]
    page.buttons["measure"].click()                     # confirmed
    assert fake_controller.calls[-1] == ("measure_tool", 2)


def test_touch_off_length_measures_the_tool_in_the_spindle_unless_told_otherwise(
        fake_window, fake_controller, dialogs) -> None:
    page = fake_window.page("tools")
    _setup(fake_controller)
    fake_controller.set_tool_in_spindle(1)
    page.table.selectRow(1)                              # T2 selected, T1 in the spindle
    dialogs.answers.extend([0, 2.0])                     # asked whose: the one in the spindle
    page.buttons["touch"].click()
    assert dialogs.asked[-2][0] == "choose" and "is in the spindle" in dialogs.asked[-2][1]
    assert fake_controller.calls[-1] == ("touch_off_tool", 1, 2.0)
    dialogs.answers.extend([1, 3.0])                     # the selected one, said explicitly
    page.buttons["touch"].click()
    assert fake_controller.calls[-1] == ("touch_off_tool", 2, 3.0)
    n = len(fake_controller.calls)
    dialogs.answers.append(-1)                           # cancelled: nothing measured
    page.buttons["touch"].click()
    assert len(fake_controller.calls) == n
