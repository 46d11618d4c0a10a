"""sheetgen_tools: the Python tooling around the `sheetgen` CLI, one package
that scripts/, bench/ and tests/ import.

Put tools/ on the import path: `PYTHONPATH=tools python3 ...` from the
repository root (ctest sets it for every Python test; the shell scripts export
it). Entry files that Blender runs by path (`blender -b --python scripts/X.py`)
cannot be given PYTHONPATH that way and add tools/ to sys.path themselves, in
one line at the top.

Modules:
  paths            where the checkout, the sample scenes and the default binary are
  runner           `sheetgen solve` as a function (SolveOptions -> SolveRun)
  problem          reading a problem, its meshes, load cases, limits and eigen requirements; problem variants
  geometry         distances, box meshes, sampling, both faces of a part's sheet
  findings         what a check measured and what failed
  clearance        brute-force clearance and flush rivet flanges
  ccx_check        every load case of a part by CalculiX: compliance, margin of safety, buckling, frequency
  ccx_deck         reading the decks `sheetgen export-ccx` writes and ccx's .dat; adding *BUCKLE steps
  ccx_stress       the stress rule on CalculiX's S4 mesh
  solid_reference  the CalculiX solid model the compliance is checked against
  dxf_check        the flat.dxf outline and rivet holes (ezdxf)
  verify           all checks of an output folder; `python3 -m sheetgen_tools.verify OUT_DIR`
  scenes           the scene library generator; `python3 -m sheetgen_tools.scenes [SCENE ...]`
  pictures         the matplotlib figures of the reports
  addon_loader     enabling the add-on of this checkout inside a running Blender
"""
