"""The formats room: files of other tools read into DH tables and written from them
(URDF, roboticstoolbox DH robots). May import model, notation, kinematics and geometry.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "UrdfImport": "urdf",
        "UrdfModel": "urdf",
        "table_from_rtb": "rtb",
        "chain_from_urdf": "urdf",
        "import_urdf": "urdf",
        "read_urdf": "urdf",
        "write_urdf": "urdf",
        "read_xml": "xmlsafe",
        "to_rtb": "rtb",
    },
)

__all__ = [
    "UrdfImport",
    "UrdfModel",
    "table_from_rtb",
    "chain_from_urdf",
    "import_urdf",
    "read_urdf",
    "read_xml",
    "to_rtb",
    "write_urdf",
]
