"""URDF in and out: a robot description's joint chain as a DH table, and a DH table as a URDF.

One idea a module, imported one way (``description`` ← ``read`` ← ``to_dh``; ``write`` apart):

- :mod:`.description`: the robot description as frozen values (:class:`UrdfModel`,
  :class:`UrdfJoint`, :class:`Origin`, :class:`Inertial`), numbers exactly as written, and
  the tree's questions (root, leaves, the chain from one link to another);
- :mod:`.read`: :func:`read_urdf`, a file or text through the safe XML reader
  (:mod:`dhsym.formats.xmlsafe`: no DTD, no entities, meshes never opened) into the model;
- :mod:`.to_dh`: :func:`import_urdf` and :func:`chain_from_urdf`, the chain's joint axes at
  home through the lectures' frame assignment into a DH table whose q means what the URDF's
  does, inertials merged into the DH links (:class:`UrdfImport`, :func:`table_yaml`);
- :mod:`.write`: :func:`write_urdf`, a DH table as one URDF link per DH frame, built with
  :mod:`xml.etree.ElementTree`.

Examples
--------
>>> text = '''<robot name="two">
...   <link name="base"/><link name="upper"/><link name="tip"/>
...   <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
...     <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
...     <limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint>
...   <joint name="elbow" type="continuous"><parent link="upper"/><child link="tip"/>
...     <origin xyz="0.25 0 0"/><axis xyz="0 0 1"/></joint>
... </robot>'''
>>> robot = chain_from_urdf(text)
>>> [(r.theta, r.d, r.a, r.alpha) for r in robot.table.rows]
[(theta1, 0, 1/4, 0), (theta2, 1/10, 0, 0)]
>>> robot.table.rows[0].limits, robot.table.rows[1].label
((-31/10, 31/10), 'elbow')
>>> again = chain_from_urdf(write_urdf(robot))
>>> bool(abs(again.fk([0.3, -0.2]) - robot.fk([0.3, -0.2])).max() < 1e-12)
True
"""

from .description import Inertial, Origin, UrdfJoint, UrdfModel
from .read import MAX_LINKS, is_urdf_source, read_urdf
from .to_dh import MAX_CHAIN, UrdfImport, chain_from_urdf, import_urdf, table_yaml
from .write import write_urdf

__all__ = [
    "MAX_CHAIN",
    "MAX_LINKS",
    "Inertial",
    "Origin",
    "UrdfImport",
    "UrdfJoint",
    "UrdfModel",
    "chain_from_urdf",
    "import_urdf",
    "is_urdf_source",
    "read_urdf",
    "table_yaml",
    "write_urdf",
]
