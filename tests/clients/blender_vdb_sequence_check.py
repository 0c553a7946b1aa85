# Blender (Debian 12's 3.4) on an OpenVDB sequence written by `patina-texgen export`:
#   blender -b --factory-startup --python-exit-code 1 --python blender_vdb_sequence_check.py \
#       -- REPORT.json FIRST.vdb SECOND.vdb ...
# Imports the files as File > Import > OpenVDB does when the user selects them all, then
# steps the scene through every frame and loads the grids there, writing REPORT.json with
# whether Blender made a sequence of them, its length, and per frame the file it loaded and
# the grids it found.
import json
import os
import sys

import bpy


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    report_path, files = args[0], args[1:]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    directory = os.path.dirname(os.path.abspath(files[0]))
    bpy.ops.object.volume_import(
        filepath=os.path.abspath(files[0]), directory=directory,
        files=[{"name": os.path.basename(f)} for f in files])
    obj = bpy.context.active_object
    volume = obj.data
    report = {"objects": len([o for o in bpy.data.objects if o.type == "VOLUME"]),
              "is_sequence": volume.is_sequence,
              "frame_start": volume.frame_start,
              "frame_duration": volume.frame_duration,
              "frames": []}
    scene = bpy.context.scene
    for frame in range(volume.frame_start, volume.frame_start + volume.frame_duration):
        scene.frame_set(frame)
        volume.grids.load()
        report["frames"].append({
            "frame": frame,
            "file": os.path.basename(volume.grids.frame_filepath),
            "loaded": volume.grids.is_loaded,
            "grids": sorted(g.name for g in volume.grids)})
    with open(report_path, "w") as f:
        json.dump(report, f, indent=1)


main()
