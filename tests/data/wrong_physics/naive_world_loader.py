"""WRONG world loader: parses with ElementTree and float() and lets every exception escape."""
import xml.etree.ElementTree as ET


def load_world(path):
    root = ET.parse(path).getroot()
    obstacles = []
    for ob in root.iter("obstacle"):
        obstacles.append([(float(p.get("x")), float(p.get("y"))) for p in ob.iter("point")])
    return obstacles
