"""Meshes hertz-cylinder.geo into hertz-cylinder.msh (second order, format 4.1, ASCII).

usage:  python3 -m venv /tmp/gmsh-venv && /tmp/gmsh-venv/bin/pip install gmsh==4.15.2
        /tmp/gmsh-venv/bin/python crates/tribo-cli/examples/gmsh/make_mesh.py
"""
import os

import gmsh

here = os.path.dirname(os.path.abspath(__file__))
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(os.path.join(here, "hertz-cylinder.geo"))
gmsh.model.mesh.generate(2)
gmsh.model.mesh.setOrder(2)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.write(os.path.join(here, "hertz-cylinder.msh"))
gmsh.finalize()
