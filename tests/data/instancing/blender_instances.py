# Usage: python blender_instances.py OUTDIR
# Five linked duplicates of one icosphere mesh (shared mesh data), exported by Blender 5.0.1
# twice: with EXT_mesh_gpu_instancing (export_gpu_instances=True) and without.
import sys, math, bpy
out = sys.argv[1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1, radius=0.5)
src = bpy.context.active_object
# Blender exports GPU instances only for mesh children of one empty.
bpy.ops.object.empty_add(location=(0.0, 0.0, 0.0))
root = bpy.context.active_object
src.parent = root
mat = bpy.data.materials.new("Glass")
src.data.materials.append(mat)
for i in range(1, 5):
    o = src.copy()  # shares src.data: a linked duplicate (keeps the parent)
    o.location = (1.5 * i, 0.3 * i, 0.0)
    o.rotation_euler = (0.0, 0.0, 0.4 * i)
    o.scale = (1.0, 1.0 + 0.25 * i, 1.0)
    bpy.context.collection.objects.link(o)
common = dict(export_format='GLB', export_cameras=False, export_lights=False)
bpy.ops.export_scene.gltf(filepath=f"{out}/spheres_instanced.glb", export_gpu_instances=True, **common)
bpy.ops.export_scene.gltf(filepath=f"{out}/spheres_plain.glb", export_gpu_instances=False, **common)
print("blender", bpy.app.version_string)
