"""Read worlds in the original Sim.I.am `settings.xml` format.

    <simulation>
      <app type="ControlApp"/>
      <robot type="QuickBot">
        <supervisor type="quickbot.QBSupervisor"/>
        <pose x="0" y="0" theta="0"/>
        <driver ip="..." port="..."/>      (optional, hardware only; ignored)
        <optitrack .../>                   (optional, weeks 1-2; ignored)
      </robot>
      <obstacle>
        <pose x="-1.6" y="-1.5" theta="0"/>
        <geometry><point x="0" y="0"/> ... at least 3 points ...</geometry>
      </obstacle>
      <goal x="1.1" y="1.1"/>              (extension of this port, optional: the world's goal)
    </simulation>

Obstacle world vertices are T(pose) * local points with the literal theta from the file (1.5708 is not
pi/2: the original's walls are skewed by ~4e-6 m/m, and we keep that).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from importlib import resources
from pathlib import Path
from xml.parsers import expat

from simiam.physics.transform import transform_point
from simiam.world.world import World

_CHILDREN = {
    "simulation": {"app", "robot", "obstacle", "goal"},
    "robot": {"supervisor", "pose", "driver", "optitrack"},
    "obstacle": {"pose", "geometry"},
    "geometry": {"point"},
    "app": set(), "supervisor": set(), "pose": set(), "driver": set(), "optitrack": set(),
    "point": set(), "goal": set(),
}
# The attributes each element may carry; a misspelt one (`thetaa`, a goal's `d_stop`) is refused rather
# than ignored. <driver> and <optitrack> are the original's hardware settings, ignored whatever they hold.
_ATTRIBUTES = {
    "simulation": (), "app": ("type",), "robot": ("type",), "supervisor": ("type",),
    "pose": ("x", "y", "theta"), "obstacle": (), "geometry": (), "point": ("x", "y"), "goal": ("x", "y"),
}


def _parse_xml(path: Path, text: str) -> tuple[ET.Element, dict[int, int]]:
    """A small ElementTree built with expat, remembering each element's line for error messages."""
    lines: dict[int, int] = {}
    stack: list[ET.Element] = []
    roots: list[ET.Element] = []
    p = expat.ParserCreate()

    def start(tag: str, attrs: dict[str, str]) -> None:
        el = ET.Element(tag, attrs)
        lines[id(el)] = p.CurrentLineNumber
        if stack:
            stack[-1].append(el)
        else:
            roots.append(el)
        stack.append(el)

    def end(tag: str) -> None:
        stack.pop()

    p.StartElementHandler = start
    p.EndElementHandler = end
    try:
        p.Parse(text, True)
    except expat.ExpatError as e:
        msg = f"XML syntax error: {expat.ErrorString(e.code)}"
        raise WorldFileError(path, "", msg, line=e.lineno) from None
    return roots[0], lines


class WorldFileError(Exception):
    """A world file that cannot be read: names the file, the element and what is wrong."""

    def __init__(self, file: str | Path, element: str, message: str, line: int | None = None) -> None:
        self.file = str(file)
        self.element = element
        self.message = message
        self.line = line
        super().__init__(str(self))

    def __str__(self) -> str:
        where = f"{self.file}, line {self.line}" if self.line is not None else self.file
        return f"{where}: <{self.element}>: {self.message}" if self.element else f"{where}: {self.message}"


def world_path(name: str) -> Path:
    """The packaged world file for a name such as "week3" or "final"."""
    return Path(str(resources.files("simiam.world") / "worlds" / f"{name}.xml"))


class _Reader:
    """Checks one parsed file and turns problems into WorldFileError with the element's line."""

    def __init__(self, path: Path, lines: dict[int, int]) -> None:
        self.path = path
        self.lines = lines

    def error(self, el: ET.Element, message: str) -> WorldFileError:
        return WorldFileError(self.path, el.tag, message, line=self.lines.get(id(el)))

    def number(self, el: ET.Element, attr: str) -> float:
        text = el.get(attr)
        if text is None:
            raise self.error(el, f"missing attribute {attr!r}")
        try:
            value = float(text.strip())
        except ValueError:
            raise self.error(el, f"attribute {attr}={text!r} is not a number") from None
        if not math.isfinite(value):
            raise self.error(el, f"attribute {attr}={text!r} is not a finite number")
        return value

    def check_children(self, el: ET.Element) -> None:
        known = _ATTRIBUTES.get(el.tag)
        for name in el.attrib:
            if known is not None and name not in known:
                from simiam.names import unknown_name

                raise self.error(el, unknown_name("attribute", name, known, of=f"<{el.tag}>"))
        allowed = _CHILDREN.get(el.tag, set())
        for child in el:
            if child.tag not in allowed:
                where = f" (allowed: {', '.join(sorted(allowed))})" if allowed else " (it takes none)"
                raise self.error(child, f"unknown element <{child.tag}> inside <{el.tag}>{where}")
            self.check_children(child)

    def one(self, parent: ET.Element, tag: str) -> ET.Element:
        found = parent.findall(tag)
        if len(found) != 1:
            what = "missing" if not found else f"appears {len(found)} times, expected once"
            raise self.error(parent, f"<{tag}> {what}")
        return found[0]

    def pose(self, parent: ET.Element) -> tuple[float, float, float]:
        p = self.one(parent, "pose")
        return (self.number(p, "x"), self.number(p, "y"), self.number(p, "theta"))


def parse_settings(path: Path, text: str | None = None, name: str | None = None) -> World:
    """Parse a settings.xml file (or its `text`) into a World; raises WorldFileError on bad input."""
    path = Path(path)
    if text is None:
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise WorldFileError(path, "", "no such world file") from None
        except (OSError, UnicodeDecodeError) as e:
            raise WorldFileError(path, "", f"cannot read the file ({e})") from None
    root, lines = _parse_xml(path, text)
    rd = _Reader(path, lines)
    if root.tag != "simulation":
        raise rd.error(root, "the root element must be <simulation>")
    rd.check_children(root)

    starts = [rd.pose(r) for r in root.findall("robot")]
    obstacles = []
    for k, ob in enumerate(root.findall("obstacle"), start=1):
        pose = rd.pose(ob)
        geom = rd.one(ob, "geometry")
        points = [(rd.number(pt, "x"), rd.number(pt, "y")) for pt in geom.findall("point")]
        if len(points) < 3:
            raise rd.error(geom, f"obstacle {k} has {len(points)} point(s); a polygon needs at least 3")
        obstacles.append([transform_point(pose, px, py) for px, py in points])
    goals = root.findall("goal")
    if len(goals) > 1:
        raise rd.error(root, f"{len(goals)} <goal> elements, expected at most one")
    goal = (rd.number(goals[0], "x"), rd.number(goals[0], "y")) if goals else None
    return World(name=name or path.stem, obstacles=obstacles, starts=starts or [(0.0, 0.0, 0.0)],
                 goal=goal, source=path)


def load_world(name_or_path: str | Path) -> World:
    """A packaged world by name ("week1".."week5", "final") or a settings.xml file by path."""
    if (isinstance(name_or_path, str) and "/" not in name_or_path and not name_or_path.endswith(".xml")
            and not Path(name_or_path).is_file()):
        path = world_path(name_or_path)
        if not path.is_file():
            known = sorted(p.stem for p in path.parent.glob("*.xml"))
            msg = f"no packaged world of that name (known: {', '.join(known)})"
            raise WorldFileError(name_or_path, "", msg)
        return parse_settings(path, name=name_or_path)
    return parse_settings(Path(name_or_path))
