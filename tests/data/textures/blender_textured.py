# Usage: python blender_textured.py OUT.glb
# A unit plane with an 8x8 red/green checker as its base colour texture (PNG), for texture
# format tests; the image is generated here.
import sys, bpy
out = sys.argv[1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_plane_add(size=1.0)
plane = bpy.context.active_object
img = bpy.data.images.new("checker", 8, 8)
px = []
for y in range(8):
    for x in range(8):
        px += [1.0, 0.0, 0.0, 1.0] if (x + y) % 2 == 0 else [0.0, 1.0, 0.0, 1.0]
img.pixels = px
img.file_format = 'PNG'
img.pack()
mat = bpy.data.materials.new("Checker")
mat.use_nodes = True
bsdf = mat.node_tree.nodes["Principled BSDF"]
tex = mat.node_tree.nodes.new("ShaderNodeTexImage")
tex.image = img
tex.interpolation = 'Closest'
mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
plane.data.materials.append(mat)
bpy.ops.export_scene.gltf(filepath=out, export_format='GLB', export_image_format='AUTO')
print("blender", bpy.app.version_string)
