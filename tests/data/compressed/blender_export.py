# Usage: python blender_export.py SRC.glb OUTDIR STEM
# Imports SRC with Blender's glTF importer and exports it twice from the same session:
# STEM_blender.glb (no compression) and STEM_draco.glb (KHR_draco_mesh_compression, Blender defaults).
import sys, bpy
src, outdir, stem = sys.argv[1:4]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=src)
common = dict(export_format='GLB', export_cameras=True, export_lights=True, export_extras=True)
bpy.ops.export_scene.gltf(filepath=f"{outdir}/{stem}_blender.glb", export_draco_mesh_compression_enable=False, **common)
bpy.ops.export_scene.gltf(filepath=f"{outdir}/{stem}_draco.glb", export_draco_mesh_compression_enable=True, **common)
bpy.ops.export_scene.gltf(filepath=f"{outdir}/{stem}_draco_q20.glb", export_draco_mesh_compression_enable=True,
    export_draco_position_quantization=20, export_draco_normal_quantization=16, export_draco_texcoord_quantization=16, **common)
print("blender", bpy.app.version_string)
