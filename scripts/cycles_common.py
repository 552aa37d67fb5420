"""What `cycles_bake.py` and `cycles_cornell.py` set alike in Blender (bpy 5.0.1): Cycles on
the CPU with a fixed sample count and thread count, no adaptive sampling, denoising or
clamping, and a black world."""
import bpy


def cycles_settings(scene, samples, seed, bounces, threads):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.max_bounces = c.diffuse_bounces = bounces
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    return c


def black_world(scene):
    scene.world = bpy.data.worlds.new("black")
    scene.world.use_nodes = True  # deprecated in Blender 5 (always on), needed before it
    for n in scene.world.node_tree.nodes:
        if n.type == "BACKGROUND":
            n.inputs["Strength"].default_value = 0.0
    return scene.world
